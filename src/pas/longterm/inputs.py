"""The inputs of a long-term analysis: the sea-state table, the LF peaks per sea state, the level.

Every check raises a one-line ``ValueError`` naming the argument and the fix.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pandas as pd

from .._support.checks import check_finite, check_open_unit, check_peaks, check_positive

__all__ = ["SeaState", "PROBABILITY_TOLERANCE", "REQUIRED_COLUMNS", "read_sea_states",
           "encounter_weights", "encounters_per_year", "design_exceedance"]

REQUIRED_COLUMNS = ("name", "probability", "n_waves", "duration")
PROBABILITY_TOLERANCE = 1e-3
"""How far the sea states' probabilities may sum from 1 (rounding in a scatter table)."""


@dataclass(frozen=True)
class SeaState:
    """One row of the sea-state table with its LF peaks (ids and metadata as for ``run_pas``)."""

    name: str
    probability: float
    n_waves: int
    duration: float
    lf: np.ndarray
    ids: list | None = None
    meta: list | None = None
    threshold: float | None = None

    @property
    def rate(self) -> float:
        """Wave encounters per second, ``ν_s = n_waves / duration``."""
        return self.n_waves / self.duration

    @cached_property
    def sorted_lf(self) -> np.ndarray:
        """The LF peaks in ascending order (sorted once: every exceedance reads them)."""
        return np.sort(self.lf)

    def lf_exceedance(self, x) -> np.ndarray:
        """Empirical LF exceedance per encounter, ``#(lf > x) / n_waves``, at levels ``x``."""
        lf = self.sorted_lf
        return (lf.size - np.searchsorted(lf, np.atleast_1d(np.asarray(x, dtype=float)),
                                          side="right")) \
            / self.n_waves


def _peaks_of(name, given):
    """``(lf, ids, meta)`` from an array or a DataFrame with an ``lf`` column (``id``, others
    meta)."""
    label = f"lf_peaks[{name!r}]"
    if isinstance(given, pd.DataFrame):
        if "lf" not in given.columns:
            raise ValueError(f"{label}: a table needs an 'lf' column (columns: "
                             f"{', '.join(map(str, given.columns))})")
        ids = given["id"].tolist() if "id" in given.columns else None
        rest = [c for c in given.columns if c not in ("lf", "id")]
        meta = given[rest].to_dict("records") if rest else None
        return check_peaks(given["lf"].to_numpy(), label), ids, meta
    return check_peaks(given, label), None, None


def read_sea_states(sea_states, lf_peaks) -> list[SeaState]:
    """Check the sea-state table and the LF peaks and pair them, in table order.

    Parameters
    ----------
    sea_states : pandas.DataFrame
        One row per sea state: ``name``, ``probability`` (share of time),
        ``n_waves`` (wave encounters of its LF run), ``duration`` (s, of its
        LF run), optionally ``threshold`` (its LF threshold), and any
        descriptive columns.
    lf_peaks : mapping or pandas.DataFrame
        ``name -> array`` of LF peaks, or ``name -> DataFrame`` with ``lf``
        (and ``id``; the other columns become each event's ``meta``), or one
        DataFrame with a ``sea_state`` column besides those.
    """
    if isinstance(lf_peaks, pd.DataFrame) and "sea_state" in lf_peaks.columns:
        lf_peaks = {str(k): g.drop(columns="sea_state").reset_index(drop=True)
                    for k, g in lf_peaks.groupby(lf_peaks["sea_state"].astype(str), sort=False)}
    if not isinstance(sea_states, pd.DataFrame):
        raise ValueError(f"sea_states must be a pandas DataFrame with columns "
                         f"{', '.join(REQUIRED_COLUMNS)}, got {type(sea_states).__name__}")
    missing = [c for c in REQUIRED_COLUMNS if c not in sea_states.columns]
    if missing:
        raise ValueError(
            f"sea_states: column(s) {', '.join(missing)} missing (it needs "
            f"{', '.join(REQUIRED_COLUMNS)}; has {', '.join(map(str, sea_states.columns))})"
        )
    if len(sea_states) == 0:
        raise ValueError("sea_states is empty: give one row per sea state")
    names = [str(n) for n in sea_states["name"]]
    if any(not n.strip() for n in names):
        raise ValueError("sea_states: every name must be a non-empty text")
    dup = pd.Series(names)[pd.Series(names).duplicated()]
    if len(dup):
        raise ValueError(f"sea_states: name {dup.iloc[0]!r} appears more than once")
    if not hasattr(lf_peaks, "keys"):
        raise ValueError(f"lf_peaks must be a mapping sea-state name -> LF peaks (or a table "
                         f"with a sea_state column), got {type(lf_peaks).__name__}")
    unknown = [str(k) for k in lf_peaks if str(k) not in names]
    if unknown:
        raise ValueError(f"lf_peaks: sea state {unknown[0]!r} is not in sea_states (names: "
                         f"{', '.join(names[:8])}{' ...' if len(names) > 8 else ''})")
    given = {str(k): v for k, v in lf_peaks.items()}
    prob = _numbers(sea_states["probability"], "probability")
    if (prob < 0).any():
        raise ValueError(f"sea_states: probability of {names[int(np.argmax(prob < 0))]!r} is "
                         "negative")
    total = float(prob.sum())
    if abs(total - 1.0) > PROBABILITY_TOLERANCE:
        raise ValueError(f"sea_states: the probabilities sum to {total:.6g}, not 1 (within "
                         f"{PROBABILITY_TOLERANCE:g}): give every sea state's share of time, "
                         "the missing ones included, or normalise them")
    out = []
    thresholds = sea_states["threshold"] if "threshold" in sea_states.columns else None
    for i, row in enumerate(sea_states.itertuples(index=False)):
        name = names[i]
        if name not in given:
            raise ValueError(f"lf_peaks: no LF peaks for sea state {name!r} (every row of "
                             "sea_states needs its peaks; drop the row or give them)")
        n_waves = _positive_int(row.n_waves, f"n_waves of {name!r}")
        duration = check_positive(row.duration, f"sea_states: duration of {name!r}")
        lf, ids, meta = _peaks_of(name, given[name])
        if lf.size > n_waves:
            raise ValueError(f"sea_states: n_waves of {name!r} is {n_waves}, below its "
                             f"{lf.size} LF peaks (one peak per wave encounter at most): give "
                             "the wave encounters of its LF run")
        thr = None
        if thresholds is not None and not pd.isna(thresholds.iloc[i]):
            thr = check_finite(thresholds.iloc[i], f"sea_states: threshold of {name!r}")
        out.append(SeaState(name, float(prob[i]) / total, n_waves, duration, lf, ids, meta, thr))
    return out


def _numbers(column, what) -> np.ndarray:
    values = pd.to_numeric(column, errors="coerce").to_numpy(dtype=float)
    if not np.isfinite(values).all():
        raise ValueError(f"sea_states: column {what} holds a value that is not a finite "
                         f"number (row {int(np.argmax(~np.isfinite(values)))})")
    return values


def _positive_int(value, what) -> int:
    try:
        whole = float(value) == int(value) and int(value) >= 1
    except (TypeError, ValueError):
        whole = False
    if not whole:
        raise ValueError(f"sea_states: {what} must be a positive whole number, got {value!r}")
    return int(value)


def encounter_weights(states) -> np.ndarray:
    """``p_s ν_s / Σ p ν``: each sea state's share of the wave encounters."""
    w = np.array([s.probability * s.rate for s in states])
    return w / w.sum()


def encounters_per_year(states, hours_per_year: float) -> float:
    """Wave encounters per year, ``Σ p_s ν_s × hours_per_year × 3600``."""
    return float(sum(s.probability * s.rate for s in states) * hours_per_year * 3600.0)


def design_exceedance(states, p_exceed, return_period, hours_per_year) -> float:
    """The per-encounter exceedance probability of the design level, from either argument.

    ``return_period`` (years) gives ``1 / (return_period × encounters per
    year)``: the level exceeded once, on average, in that many years.
    """
    if (p_exceed is None) == (return_period is None):
        raise ValueError("give exactly one of p_exceed (per wave encounter) and return_period "
                         "(years)")
    if p_exceed is not None:
        return check_open_unit(p_exceed, "p_exceed")
    years = check_positive(return_period, "return_period")
    per_year = encounters_per_year(states, check_positive(hours_per_year, "hours_per_year"))
    return check_open_unit(1.0 / (years * per_year), "the p_exceed of return_period")
