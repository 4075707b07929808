"""A data set of a long-term analogue, its generation and the choice of the contributing cells.

:class:`LongTermData` holds, per sea state of the scatter, the LF peaks and
the HF value of every wave event, and answers the brute-force truth
(:mod:`~pas.validation.long_term` gives the scatter, the generator and the
combination).  :func:`plan_cells` decides from a pilot run which cells can
contribute at a level; :func:`generate_long_term` makes the data set.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .long_term import (
    ANALOGUES,
    generate_cell,
    long_term_exceedance,
    scatter_diagram,
    value_at_exceedance_long_term,
)

__all__ = ["LongTermData", "generate_long_term", "plan_cells"]


@dataclass
class LongTermData:
    """One data set of a long-term analogue: per sea state LF peaks and the full HF.

    Attributes
    ----------
    analogue : str
        ``"3"`` or ``"2"``.
    sea_states : pandas.DataFrame
        ``name``, ``probability``, ``n_waves``, ``duration`` (s), ``hs``,
        ``tz``, ``tp``, ``heading``, ``speed`` — the table ``pas.run_long_term`` takes.
    lf, hf, ids : dict
        Per sea state name: LF indicator peaks, HF values, event ids.
    meta : dict
        Per sea state name: a DataFrame of ``seed_no``, ``t_start``, ``t_end``.
    seed : int
    unit : str
    info : dict
        Dropped probability of the scatter, generation wall time.
    """

    analogue: str
    sea_states: pd.DataFrame
    lf: dict
    hf: dict
    ids: dict
    meta: dict
    seed: int
    unit: str
    info: dict = field(default_factory=dict)

    @property
    def weights(self):
        """``p_s ν_s`` per sea state (1/s)."""
        t = self.sea_states
        return dict(zip(t["name"], t["probability"] * t["n_waves"] / t["duration"]))

    def exceedance(self, x):
        """The brute-force long-term exceedance per encounter ``Q(x)`` from every HF value."""
        return long_term_exceedance(x, self.weights, self.hf)

    def truth(self, p_exceed):
        """The brute-force long-term value at ``p_exceed`` (per encounter)."""
        return value_at_exceedance_long_term(p_exceed, self.weights, self.hf)

    def contributions(self, p_exceed):
        """Each sea state's share of ``Q`` at the truth value, with a 95 % upper bound.

        Returns a DataFrame with ``sea_state``, ``share`` (measured), ``share_u95``
        (the share with ``k`` exceedances replaced by the Poisson 95 % upper
        bound: 3.0 when none was seen), ``n_exceed``, ``n_waves``.
        """
        x = self.truth(p_exceed)
        w, tot = self.weights, float(sum(self.weights.values()))
        q = p_exceed * tot
        rows = []
        for s, hf in self.hf.items():
            k = int(np.sum(np.asarray(hf) > x))
            k_hi = 3.0 if k == 0 else k + 1.96 * np.sqrt(k) + 1.0
            rows.append({"sea_state": s, "share": w[s] * k / hf.size / q,
                         "share_u95": w[s] * k_hi / hf.size / q, "n_exceed": k,
                         "n_waves": int(hf.size)})
        return pd.DataFrame(rows)

    def oracle(self):
        """Table oracle: the HF value of ``event`` from ``event.sea_state`` and ``event.index``."""
        hf = self.hf

        def oracle(event):
            return float(hf[event.sea_state][event.index])

        return oracle

def generate_long_term(analogue, *, seed=0, hours=10, cells=None, cache=True, path=None,
                       progress=None):
    """A data set of the long-term analogue ``analogue`` (module docs).

    Parameters
    ----------
    analogue : {"3", "2"}
    seed : int, default 0
        Data-set seed: redraws the waves and the HF model's random parts in every cell.
    hours : int or mapping, default 10
        One-hour realisations per cell, or a mapping cell name → hours.
    cells : pandas.DataFrame, optional
        The scatter cells (default :func:`scatter_diagram` with the analogue's γ).
    cache, path : see :func:`generate_cell`.
    progress : callable, optional
        ``progress(str)`` after each cell.

    Returns
    -------
    LongTermData
    """
    a = ANALOGUES.get(str(analogue))
    if a is None:
        raise ValueError(f"analogue must be one of {', '.join(ANALOGUES)}, got {analogue!r}")
    dropped = {}
    if cells is None:
        cells, dropped = scatter_diagram(gamma=a["gamma"])
    t0 = time.perf_counter()
    rows, lf, hf, ids, meta = [], {}, {}, {}, {}
    for no, row in cells.reset_index(drop=True).iterrows():
        name = str(row["name"])
        h = hours.get(name, 0) if isinstance(hours, dict) else hours
        if not h:
            continue
        ev = generate_cell(str(analogue), row, seed, no, h, cache=cache, path=path)
        lf[name], hf[name] = ev["lf"], ev["hf"]
        ids[name] = np.array([f"{name}-s{s:03d}-e{i:06d}" for i, s in enumerate(ev["seed_no"])])
        meta[name] = pd.DataFrame({"seed_no": ev["seed_no"], "t_start": ev["t_start"],
                                   "t_end": ev["t_end"]})
        rows.append({"name": name, "probability": float(row["probability"]),
                     "n_waves": int(ev["lf"].size), "duration": ev["duration"],
                     "hs": float(row["hs"]), "tz": float(row["tz"]), "tp": float(row["tp"]),
                     "heading": a["heading"], "speed": a["speed"], "hours": int(h)})
        if progress:
            progress(f"cell {name}: {h} h, {ev['lf'].size} events")
    return LongTermData(str(analogue), pd.DataFrame(rows), lf, hf, ids, meta, int(seed),
                        a["unit"], {"dropped_probability": dropped,
                                    "seconds": time.perf_counter() - t0})


def plan_cells(analogue, p_exceed, *, pilot_hours=4, min_share=1e-3, cells=None, cache=True,
               path=None):
    """Which scatter cells can contribute to ``Q`` at ``p_exceed``: a pilot run decides.

    A pilot of ``pilot_hours`` per cell (data seed 0) gives the value ``x*``
    at ``p_exceed`` and the lowest LF peak ``l_min`` of the events whose HF
    exceeds the pilot's value at ``10 p_exceed`` (a larger load needs at least
    that LF, as the analogues' small LF give small loads), and the pooled
    share ``r`` of the events with LF over ``l_min`` whose HF exceeds ``x*``.
    A cell's share of ``Q(x*)`` is estimated as
    ``w_s · r · exp(−l_min² / 2σ_s²) / (p_exceed Σ w)`` (the Rayleigh
    exceedance of ``l_min`` by the cell's LF peaks, ``σ_s² = mean(lf²)/2``:
    an estimate, not a bound, assuming the milder cells turn a large LF into
    a large load no more often than the pooled pilot does) and measured as
    the pilot's share; a cell is *kept* when either reaches ``min_share``.

    Returns
    -------
    pandas.DataFrame
        The cells with ``share_rayleigh``, ``share_pilot`` and ``kept``.
    """
    a = ANALOGUES[str(analogue)]
    if cells is None:
        cells, _ = scatter_diagram(gamma=a["gamma"])
    pilot = generate_long_term(analogue, seed=0, hours=pilot_hours, cells=cells, cache=cache,
                               path=path)
    x_low = pilot.truth(10.0 * p_exceed)
    l_min = min(float(np.min(pilot.lf[s][pilot.hf[s] >= x_low]))
                for s in pilot.hf if np.any(pilot.hf[s] >= x_low))
    x_star = pilot.truth(p_exceed)
    over = np.concatenate([pilot.hf[s][pilot.lf[s] >= l_min] for s in pilot.hf])
    r = float(np.mean(over > x_star)) if over.size else 1.0
    w, tot = pilot.weights, float(sum(pilot.weights.values()))
    sigma2 = {s: float(np.mean(np.maximum(v, 0.0) ** 2)) / 2.0 for s, v in pilot.lf.items()}
    ray = {s: w[s] * r * np.exp(-l_min**2 / (2.0 * sigma2[s])) / (p_exceed * tot) for s in w}
    share = dict(zip(*pilot.contributions(p_exceed)[["sea_state", "share"]].to_numpy().T))
    out = cells.copy()
    out["share_rayleigh"] = out["name"].map(ray)
    out["share_pilot"] = out["name"].map(share).astype(float)
    out["kept"] = (out["share_rayleigh"] >= min_share) | (out["share_pilot"] >= min_share)
    out.attrs.update({"l_min": l_min, "x_pilot": x_star, "r_over_l_min": r, "x_low": x_low,
                      "pilot_hours": int(pilot_hours), "min_share": float(min_share)})
    return out
