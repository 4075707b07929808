"""The CFD validation case: green water on a fixed bow, HF = OpenFOAM, truth by brute force.

One sea state (JONSWAP Hs 6 m, Tp 10 s, gamma 3.3, 40 m depth, long-crested,
no forward speed) and an LF record of twelve one-hour realisations (seeds
1-12, ``df = 1/3600`` Hz, components up to 1.6 rad/s, 2.5 times the peak
 frequency: a CFD wave maker cannot carry the short waves of the tail).  The LF indicator is the
linear crest at the bow of every zero-up-crossing wave.  The HF load is the
horizontal green-water force on the deckhouse wall of the example tank
(:class:`pas.cfd.GreenWaterTank`, 8 m freeboard, 0.5 m cells), as the peak
of its 0.25 s moving average in the event's own window (-1 to +3.5 s around
the linear crest's arrival at the bow), computed by OpenFOAM v1912 for each
event (:mod:`pas.cfd.event`).  The exposure is one hour: ``p_exp`` is the
record's mean zero-up-crossing period over 3600 s.

The CFD results are a table in the package (``data/cfd_green_water.csv``):
every event whose LF crest is above the cut, and a random sample below it.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

import numpy as np
import pandas as pd

from ..stats.exceedance import exceedance_probabilities, value_at_exceedance

__all__ = ["CFD_CASE", "CFDCase", "cfd_cut", "cfd_lf_record", "cfd_table", "cfd_truth"]


@dataclass(frozen=True)
class CFDCase:
    """Sea state, record and exposure of the CFD case."""

    hs: float = 6.0
    tp: float = 10.0
    gamma: float = 3.3
    depth: float = 40.0
    duration: float = 3600.0
    omega_max: float = 1.6
    seeds: tuple = tuple(range(1, 13))
    exposure: float = 3600.0
    dt: float = 0.05
    load: str = "wall_peak_filtered"
    unit: str = "N/m"

    def recipe(self) -> dict:
        """The sea's recipe for :mod:`pas.cfd.event` (``--sea``)."""
        return {"hs": self.hs, "tp": self.tp, "gamma": self.gamma, "depth": self.depth,
                "duration": self.duration, "omega_max": self.omega_max}


CFD_CASE = CFDCase()


def cfd_lf_record(case: CFDCase = CFD_CASE):
    """The LF events of the case: ``(events, n_waves, p_exp)``.

    ``events`` has one row per zero-up-crossing wave of every seed: ``id``
    (``s<seed>-<wave>``), ``lf`` (linear crest at the bow, m), ``seed``,
    ``t_start``, ``t_peak``, ``t_end`` (s of the seed's record).
    """
    from ..cfd.event import sea_from_recipe
    from ..stats.peaks import upcrossing_times, wave_crests, zero_upcrossings

    frames, periods = [], []
    for seed in case.seeds:
        t, x = sea_from_recipe(case.recipe(), seed).elevation(case.dt)
        up = zero_upcrossings(x)
        peaks, idx = wave_crests(x, up)
        cross = upcrossing_times(t, x, up)
        n = peaks.size
        frames.append(pd.DataFrame({
            "id": [f"s{seed:02d}-{k:04d}" for k in range(n)], "lf": peaks, "seed": seed,
            "t_start": cross[:n], "t_peak": t[idx], "t_end": cross[1:n + 1]}))
        periods.append(np.diff(cross))
    events = pd.concat(frames, ignore_index=True)
    tz = float(np.concatenate(periods).mean())
    return events, int(len(events)), tz / case.exposure


def cfd_table():
    """The CFD results of the case (one row per event run), as shipped with the package."""
    ref = resources.files("pas.validation") / "data" / "cfd_green_water.csv"
    with resources.as_file(ref) as path:
        return pd.read_csv(path)


def cfd_cut(events, table):
    """``(n_top, cut)``: how many of the largest LF events the table holds without a gap, and
    the LF threshold just below the last of them (every event above it was run in CFD)."""
    ranked = events.sort_values("lf", ascending=False)
    have = ranked["id"].isin(set(table["id"])).to_numpy()
    n_top = int(np.argmin(have)) if not have.all() else len(have)
    return n_top, float(ranked["lf"].iloc[n_top - 1]) - 1e-9


def cfd_truth(events, table, n_waves, p_exp, *, load=CFD_CASE.load):
    """Brute-force truth MPM of the load from the CFD table.

    Every event not in the table has a load of 0 (below the cut: the table's
    sample below it says whether that holds).  The MPM is the load whose
    exceedance per wave, ``rank / n_waves``, equals ``p_exp``, interpolated on
    ``ln`` of the exceedance (as the predictions are).
    """
    d, loads = exceedance_probabilities(table[load].to_numpy(float), n_waves)
    if p_exp < d[0] or p_exp > d[-1]:
        raise ValueError("p_exp lies outside the table's exceedance range")
    return float(value_at_exceedance(d, loads, p_exp))
