"""From an LF time series to the events table PAS screens: one event per wave.

Your LF run (e.g. the linear relative wave elevation at the bow) is one or
several records; each is cut into its zero-up-crossing waves
(:func:`pas.stats.peaks.zero_upcrossings`), and every complete wave is one
*event*: its crest is the LF peak (:func:`pas.stats.peaks.wave_crests`), its
window runs from its up-crossing to the next (times interpolated between
samples, :func:`pas.stats.peaks.upcrossing_times`).  The parts before a
record's first and after its last up-crossing are not waves.

``n_waves`` is the number of these waves over all records, the mean period is
their mean length (the counted mean zero-up-crossing period of the record,
in the encounter frame when the record is), and ``p_exp`` is that period
over the exposure (Eq. 11, :func:`pas.stats.exceedance.p_exp_from_duration`).
A ``threshold`` keeps only the events whose LF peak is above it in the
table while ``n_waves`` still counts every wave, as PAS needs (Eq. 2-3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .._support.checks import check_finite, check_positive
from ..stats.exceedance import p_exp_from_duration
from ..stats.peaks import upcrossing_times, wave_crests, zero_upcrossings

__all__ = ["LFEvents", "lf_events", "wave_events", "EVENT_COLUMNS"]

#: Columns of :attr:`LFEvents.table`: ``id`` and ``lf`` for :func:`pas.run_pas`,
#: the rest the event's ``meta`` (``{record}``, ``{t_start}`` ... in a
#: :class:`pas.CommandOracle`).
EVENT_COLUMNS = ("id", "lf", "record", "wave", "t_start", "t_peak", "t_end")


@dataclass(frozen=True)
class LFEvents:
    """The events of an LF run and what :func:`pas.run_pas` needs with them.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per wave whose LF peak is above ``threshold`` (every wave
        without one), columns :data:`EVENT_COLUMNS`: ``id`` (``<record>-w<wave>``),
        ``lf`` (the wave's crest), ``record`` (the record it came from),
        ``wave`` (its number in that record, counting every wave),
        ``t_start``/``t_end`` (its up-crossing and the next one, s) and
        ``t_peak`` (time of the crest, s), in the record's own time.
    n_waves : int
        Every complete wave of every record, below the threshold included.
    mean_period : float
        Mean length of those waves, s (counted mean zero-up-crossing period).
    duration : float
        Total length of the records, s.
    records : pandas.DataFrame
        Per record: ``record``, ``duration``, ``n_waves``, ``mean_period``.
    threshold : float or None
        The LF threshold the table was cut at; pass it on to :func:`pas.run_pas`.
    exposure : float or None
        Exposure duration, s.
    p_exp : float or None
        ``mean_period / exposure`` (Eq. 11), None without ``exposure``.
    """

    table: pd.DataFrame
    n_waves: int
    mean_period: float
    duration: float
    records: pd.DataFrame
    threshold: float | None = None
    exposure: float | None = None
    p_exp: float | None = None

    def summary(self) -> str:
        """One line: waves, mean period, events over the threshold, ``p_exp``."""
        cut = ("" if self.threshold is None else
               f", {len(self.table)} over threshold {self.threshold:g}")
        p = "" if self.p_exp is None else f", p_exp {self.p_exp:.4g} ({self.exposure:g} s)"
        return (f"{self.n_waves} waves in {self.duration:g} s ({len(self.records)} record(s)), "
                f"mean period {self.mean_period:.4g} s{cut}{p}")


def lf_events(series, *, dt=None, threshold=None, exposure=None) -> LFEvents:
    """Events (one per zero-up-crossing wave), ``n_waves``, mean period and ``p_exp``.

    Parameters
    ----------
    series : array_like, pandas.Series, list or dict of them
        One LF record or several: a 1-D array of samples at step ``dt``
        (time 0 at the first sample), a :class:`pandas.Series` indexed by
        time (s, or a datetime/timedelta index), a list of records (named
        0, 1, ...) or a dict ``{record name: record}`` (e.g. by seed).
    dt : float, optional
        Time step of the array records, s.
    threshold : float, optional
        LF level: only events with a higher peak go into the table (the
        rest cannot give a load, e.g. a relative elevation below the
        freeboard); ``n_waves`` still counts every wave.
    exposure : float, optional
        Exposure duration, s (3 h: ``3 * 3600``), for ``p_exp``.

    Returns
    -------
    LFEvents

    Examples
    --------
    >>> t = np.arange(0, 100, 0.1)                 # up-crossings at 2.5, 12.5, ... 92.5 s
    >>> ev = lf_events(-np.cos(2 * np.pi * t / 10), dt=0.1, exposure=3600)
    >>> ev.n_waves, round(ev.mean_period, 6), round(ev.p_exp, 6)
    (9, 10.0, 0.002778)
    """
    threshold = None if threshold is None else check_finite(threshold, "threshold")
    exposure = None if exposure is None else check_positive(exposure, "exposure")
    records = _records(series)
    if any(not isinstance(s, pd.Series) for _, s in records):
        if dt is None:
            raise ValueError("dt is missing: give the time step (s) of the array records, "
                             "or pass pandas Series indexed by time")
        dt = check_positive(dt, "dt")
    parts, rows = [], []
    for name, rec in records:
        label = f"series[{name!r}]" if len(records) > 1 else "series"
        t, x = _time_and_signal(label, rec, dt)
        peaks, t_start, t_end, t_peak = wave_events(t, x)
        if peaks.size == 0:
            raise ValueError(f"{label}: no complete zero-up-crossing wave in "
                             f"{t[-1] - t[0]:g} s; give a longer record or one about zero mean")
        wave = np.arange(peaks.size)
        width = len(str(peaks.size - 1))
        ids = [f"{name}-w{k:0{width}d}" for k in wave]
        parts.append(pd.DataFrame({"id": ids, "lf": peaks, "record": [name] * peaks.size,
                                   "wave": wave, "t_start": t_start, "t_peak": t_peak,
                                   "t_end": t_end}))
        rows.append({"record": name, "duration": float(t[-1] - t[0] + (t[-1] - t[-2])),
                     "n_waves": int(peaks.size), "mean_period": float(np.mean(t_end - t_start))})
    table = pd.concat(parts, ignore_index=True)
    n_waves = len(table)
    mean_period = float(np.mean(table["t_end"] - table["t_start"]))
    if threshold is not None:
        table = table[table["lf"] > threshold].reset_index(drop=True)
    p_exp = None if exposure is None else p_exp_from_duration(exposure, mean_period)
    per_record = pd.DataFrame(rows)
    return LFEvents(table=table, n_waves=n_waves, mean_period=mean_period,
                    duration=float(per_record["duration"].sum()), records=per_record,
                    threshold=threshold, exposure=exposure, p_exp=p_exp)


def _records(series):
    """``[(name, record)]`` of the ``series`` argument."""
    if isinstance(series, dict):
        if not series:
            raise ValueError("series is an empty dict; give at least one record")
        return list(series.items())
    if isinstance(series, list | tuple) and series and not np.isscalar(series[0]):
        return list(enumerate(series))
    return [(0, series)]


def _time_and_signal(label, rec, dt):
    """Time (s) and samples of one record, checked."""
    if isinstance(rec, pd.Series):
        index = rec.index
        if isinstance(index, pd.DatetimeIndex | pd.TimedeltaIndex):
            t = np.asarray((index - index[0]) / pd.Timedelta(seconds=1), dtype=float)
        elif pd.api.types.is_numeric_dtype(index) and not isinstance(index, pd.RangeIndex):
            t = index.to_numpy(dtype=float)
        else:
            raise ValueError(f"{label}: a Series needs a time index (s, datetime or "
                             "timedelta); for samples at a fixed step pass .to_numpy() and dt")
        x = _samples(rec.to_numpy(), label)
        if x.size != t.size or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise ValueError(f"{label}: its time index must be finite and strictly increasing; "
                             "sort it and drop repeated times")
        return t, x
    x = _samples(rec, label)
    return dt * np.arange(x.size), x


def _samples(values, label):
    try:
        x = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{label} must hold numbers (the LF signal's samples)") from None
    if x.ndim != 1:
        raise ValueError(f"{label} must be 1-D, got shape {x.shape}; pass several records "
                         "as a list or a dict of 1-D records")
    if x.size < 3:
        raise ValueError(f"{label} holds {x.size} sample(s); a record needs whole waves")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"{label} contains NaN or inf; clean or interpolate the record first")
    return x


def wave_events(t, x):
    """Crest, up-crossing time, next up-crossing time and crest time of every complete
    zero-up-crossing wave of ``x`` sampled at times ``t`` (one event per wave)."""
    up = zero_upcrossings(x)
    peaks, idx = wave_crests(x, up)
    if peaks.size == 0:
        return peaks, peaks, peaks, peaks
    crossing = upcrossing_times(t, x, up)
    return peaks, crossing[:-1], crossing[1:], t[idx]
