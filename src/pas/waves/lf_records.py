"""LF records over a table of sea states: linear response time series and their indicator peaks.

Each sea state's LF record is the realisation standard of
:func:`pas.waves.realisation.linear_sea` (``df = 1 / duration``, random
phases from one seed, the encounter-frequency grid under way) multiplied by
the transfer function of the indicator response and synthesised by FFT. The
indicator peaks are the crests of the zero-up-crossing waves of that signal
(:func:`pas.waves.lf_events.wave_events`), one per wave event. Every event
carries what an HF run needs to start on the same waves: the sea state, the
seed and record duration of its realisation (the sea is redrawn exactly with
``linear_sea(spectrum, duration, seed=seed, speed=speed, heading=heading)``),
and the time window of the event (the wave's up-crossings ``t_start``,
``t_end``, its crest time ``t_peak``, and ``t_init = t_start - warm_up``,
when an HF run would start).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .lf_events import wave_events
from .linear_longterm import _check_table, sea_state_spectrum
from .realisation import linear_sea

__all__ = ["LFRecord", "lf_record", "lf_records", "sea_state_seed", "events_frame"]


def sea_state_seed(seed, index):
    """The seed of sea state number ``index`` drawn from the study seed (an int, recorded)."""
    return int(np.random.SeedSequence([int(seed), int(index)]).generate_state(1, np.uint32)[0])


@dataclass(frozen=True)
class LFRecord:
    """One sea state's LF record and its events.

    Attributes
    ----------
    t, signal : ndarray
        Time (s) and the indicator response.
    peaks : ndarray
        Crest of each zero-up-crossing wave (one per event).
    meta : list of dict
        Per event: ``sea_state``, ``seed``, ``duration``, ``t_init``,
        ``t_start``, ``t_peak``, ``t_end`` (s).
    """

    t: np.ndarray
    signal: np.ndarray
    peaks: np.ndarray
    meta: list

    @property
    def n_waves(self):
        """Number of wave events (peaks) in the record."""
        return int(self.peaks.size)


def lf_record(transfer, response, sea_state, duration, *, seed, dt=0.25, warm_up=60.0,
              omega_max=None):
    """LF record of ``response`` in one sea state.

    Parameters
    ----------
    transfer : TransferFunction
    response : str or tuple
        As :meth:`TransferFunction.response`.
    sea_state : mapping or pandas.Series
        ``name``, ``hs``, ``tp``, optionally ``gamma``, ``heading`` (180).
    duration : float
        Record length (s).
    seed : int
        Phase seed of this sea state (see :func:`sea_state_seed`).
    dt : float, default 0.25
        Time step (s).
    warm_up : float, default 60
        Lead time before an event at which an HF run would start (s).
    omega_max : float, optional
        Highest wave frequency kept; default the transfer function's highest.
    """
    heading = float(sea_state.get("heading", 180.0))
    w_max = float(transfer.omega[-1]) if omega_max is None else float(omega_max)
    sea = linear_sea(sea_state_spectrum(sea_state), duration, seed=seed, omega_max=w_max,
                     speed=transfer.speed, heading=heading)
    h = transfer.response(response, sea.omega, heading)
    t, x = sea.synthesise(h * sea.amplitude, dt)
    peaks, t_start, t_end, t_peak = wave_events(t, x)
    meta = [{"sea_state": str(sea_state["name"]), "seed": int(seed), "duration": float(duration),
             "t_init": float(max(t_start[k] - warm_up, 0.0)), "t_start": float(t_start[k]),
             "t_peak": float(t_peak[k]), "t_end": float(t_end[k])}
            for k in range(peaks.size)]
    return LFRecord(t=t, signal=x, peaks=peaks, meta=meta)


def lf_records(transfer, response, sea_states, duration, *, seed, dt=0.25, warm_up=60.0):
    """LF records of every sea state, in the shapes the long-term analysis takes.

    Parameters
    ----------
    transfer, response, dt, warm_up
        As :func:`lf_record`.
    sea_states : pandas.DataFrame
        E.g. :meth:`ScatterDiagram.sea_states`.
    duration : float or mapping
        Record length (s), one for all or ``{name: seconds}``.
    seed : int
        Study seed; sea state ``i`` gets ``sea_state_seed(seed, i)``.

    Returns
    -------
    table : pandas.DataFrame
        ``sea_states`` with ``n_waves``, ``duration`` and ``seed`` added.
    peaks : dict of str to ndarray
        LF indicator peaks per sea-state name.
    meta : dict of str to list of dict
        Event metadata per sea-state name (see :class:`LFRecord`).
    """
    _check_table(sea_states, transfer)
    table = sea_states.copy().reset_index(drop=True)
    peaks, meta, n_waves, durations, seeds = {}, {}, [], [], []
    for i, row in table.iterrows():
        d = float(duration[row["name"]]) if isinstance(duration, dict) else float(duration)
        s = sea_state_seed(seed, i)
        rec = lf_record(transfer, response, row, d, seed=s, dt=dt, warm_up=warm_up)
        if rec.n_waves < 1:
            raise ValueError(f"sea state {row['name']!r}: no complete wave in {d:g} s; "
                             "lengthen duration")
        peaks[row["name"]], meta[row["name"]] = rec.peaks, rec.meta
        n_waves.append(rec.n_waves)
        durations.append(d)
        seeds.append(s)
    table["n_waves"], table["duration"], table["seed"] = n_waves, durations, seeds
    return table, peaks, meta


def events_frame(meta):
    """Event metadata of :func:`lf_records` as one DataFrame (for a table oracle)."""
    return pd.DataFrame([m for name in meta for m in meta[name]])
