"""Long-term validation analogues: the case-3 and case-2 ships over a North-Atlantic scatter.

The scatter diagram
-------------------
:func:`scatter_diagram` bins the joint Hs–Tz model of DNV-RP-C205 (DNV 2010,
§3.6.3, its North-Atlantic parameters: Hs a 3-parameter Weibull, ln Tz given
Hs normal; :func:`joint_model`, a virocon model) into Hs × Tz cells with
:meth:`pas.waves.ScatterDiagram.from_joint_model`; each cell is one JONSWAP sea state at its
centre, with ``Tp = Tz / r(γ)`` (``r(γ) = 0.6673 + 0.05037 γ − 0.006230 γ² +
0.0003341 γ³``, DNV-RP-C205 §3.5.5).  Cells steeper than the DNV limit
(``2π Hs / (g Tp²)`` ≤ 1/15 at Tp ≤ 8 s, ≤ 1/25 at Tp ≥ 15 s, linear between)
and cells with less than ``min_probability`` are dropped; their total
probability is returned.

The analogues
-------------
``"3"``: the 190 m ferry's green water on the accommodation (case 3,
:mod:`~pas.validation.case_impacts`: 150°, 2.4 m/s, γ 3.3) in every cell;
``"2"``: its hogging midship VBM (case 2a, :mod:`~pas.validation.case_vbm`:
head seas, 5.1 m/s, γ 3.0).  In each cell the case's own generator makes LF
indicator peaks and the HF value of every wave event for ``hours[s]`` one-hour
realisations; another data seed redraws the waves and the random parts of
the HF model in every cell (:func:`cell_seed` keeps cells independent).

The truth
---------
The long-term exceedance per wave encounter (class-rule long-term
statistics, e.g. IACS Rec. 34)::

    Q(x) = Σ_s p_s ν_s Q_s(x) / Σ_s p_s ν_s

with ``p_s`` the cell probability, ``ν_s = n_s / T_s`` its encounter rate and
``Q_s`` the empirical exceedance of all ``n_s`` HF values of the cell
(:func:`long_term_exceedance`, :func:`value_at_exceedance_long_term`); the
data set and its truth are :class:`~pas.validation.long_term_data.LongTermData`.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import replace

import numpy as np
import pandas as pd

from .._version import __version__
from ..waves import GRAVITY
from ..waves.scatter import ScatterDiagram, dnv_joint_model
from . import case_impacts, case_vbm
from ._common import SEED_LENGTH
from .generate import cache_dir
from .registry import Condition, get_case

__all__ = [
    "ANALOGUES",
    "NORTH_ATLANTIC",
    "cell_seed",
    "generate_cell",
    "joint_model",
    "long_term_exceedance",
    "scatter_diagram",
    "tz_over_tp",
    "value_at_exceedance_long_term",
]

NORTH_ATLANTIC = {
    "source": "DNV-RP-C205 (2010), §3.6.3, North Atlantic: Hs 3-p Weibull, ln Tz | Hs normal",
    "hs_scale": 3.041, "hs_shape": 1.484, "hs_location": 0.661,
    "mu": (0.70, 1.27, 0.131),          # mean of ln Tz: a0 + a1 Hs^a2
    "sigma": (0.1334, 0.0264, -0.1906),  # std of ln Tz: b0 + b1 exp(b2 Hs)
}
"""The joint Hs–Tz model binned by :func:`scatter_diagram` (DNV 2010)."""

ANALOGUES = {
    "3": {"case": "3a", "gamma": 3.3, "depth": 179.9, "heading": 150.0, "speed": 2.4,
          "unit": "kN", "load": "green-water force on the accommodation",
          "indicator": "linear bow RWE (m)"},
    "2": {"case": "2a", "gamma": 3.0, "depth": 1000.0, "heading": 180.0, "speed": 5.1,
          "unit": "N m", "load": "hogging midship VBM, non-linear",
          "indicator": "linear hogging VBM (N m)"},
}
"""The two long-term analogues: the case whose ship and HF model they use, its operating point."""


def tz_over_tp(gamma):
    """``Tz / Tp`` of a JONSWAP spectrum with peak enhancement ``gamma`` (DNV-RP-C205 §3.5.5)."""
    g = float(gamma)
    return 0.6673 + 0.05037 * g - 0.006230 * g**2 + 0.0003341 * g**3


def _steepness_limit(tp):
    """DNV's limiting steepness ``2π Hs / (g Tp²)``: 1/15 at Tp ≤ 8 s, 1/25 at Tp ≥ 15 s."""
    return np.interp(tp, [8.0, 15.0], [1.0 / 15.0, 1.0 / 25.0])


def joint_model(model=None):
    """The joint Hs–Tz model (:data:`NORTH_ATLANTIC` by default) as a virocon model."""
    m = NORTH_ATLANTIC if model is None else model
    return dnv_joint_model(hs_weibull=(m["hs_scale"], m["hs_shape"], m["hs_location"]),
                           mu=m["mu"], sigma=m["sigma"])


def scatter_diagram(*, hs_edges=None, tz_edges=None, gamma=3.3, model=None,
                    min_probability=1e-7):
    """Bin the joint Hs–Tz model into sea states (one row per kept cell).

    Parameters
    ----------
    hs_edges, tz_edges : array_like, optional
        Cell edges (m, s); default Hs 0–20 m in 2 m, Tz 3–17 s in 2 s.
    gamma : float, default 3.3
        JONSWAP peak enhancement for ``Tp = Tz / tz_over_tp(gamma)``.
    model : dict, optional
        Parameters as :data:`NORTH_ATLANTIC` (the default).
    min_probability : float, default 1e-7
        Cells with less probability are dropped.

    Returns
    -------
    cells : pandas.DataFrame
        ``name`` (``"hs05_tz09"``: centres in m and s), ``hs``, ``tz``,
        ``tp``, ``probability`` (of the whole model, not renormalised),
        ``steepness``.
    dropped : dict
        Probability of the steep cells, of the cells under
        ``min_probability`` and outside the edges.
    """
    he = np.arange(0.0, 20.01, 2.0) if hs_edges is None else hs_edges
    te = np.arange(3.0, 17.01, 2.0) if tz_edges is None else tz_edges
    try:
        sd = ScatterDiagram.from_joint_model(joint_model(model), he, te)
    except ValueError:
        raise ValueError("hs_edges and tz_edges must be increasing non-negative 1-D edges, "
                         "at least two each, around some of the model's probability") from None
    hs, tz = (a.ravel() for a in np.meshgrid(sd.hs, sd.period, indexing="ij"))
    p = sd.probability.ravel() * sd.coverage
    tp = tz / tz_over_tp(gamma)
    s = 2.0 * np.pi * hs / (GRAVITY * tp**2)
    steep = s > _steepness_limit(tp)
    small = ~steep & (p < min_probability)
    keep = ~steep & ~small
    names = [f"hs{h:04.1f}_tz{t:04.1f}".replace(".", "p") for h, t in zip(hs[keep], tz[keep])]
    cells = pd.DataFrame({"name": names, "hs": hs[keep], "tz": tz[keep], "tp": tp[keep],
                          "probability": p[keep], "steepness": s[keep]})
    return cells, {"steep": float(p[steep].sum()), "small": float(p[small].sum()),
                   "outside": 1.0 - sd.coverage}


def cell_seed(seed, cell_no):
    """Seed of cell ``cell_no`` in data set ``seed``: independent waves and HF draws per cell."""
    return 10_000 * (int(seed) + 1) + int(cell_no)


def _cell_spec(analogue, row):
    a = ANALOGUES[analogue]
    cond = Condition(str(row["name"]), float(row["hs"]), float(row["tp"]), a["gamma"],
                     a["depth"], a["heading"], a["speed"])
    return replace(get_case(a["case"]), condition=cond)


def _cell_key(analogue, row):
    mod = case_impacts if analogue == "3" else case_vbm
    blob = json.dumps([__version__, mod.VERSION, mod.COEFFICIENTS, ANALOGUES[analogue],
                       float(row["hs"]), float(row["tp"])], sort_keys=True, default=str)
    return hashlib.sha1(blob.encode()).hexdigest()[:10]


def generate_cell(analogue, row, seed, cell_no, hours, *, cache=True, path=None):
    """LF peaks and HF values of one scatter cell: ``hours`` one-hour realisations.

    Returns
    -------
    dict
        ``lf``, ``hf``, ``seed_no``, ``t_start``, ``t_end`` (one entry per
        wave event) and ``duration`` (s).  Cached as
        ``<cache>/lt<analogue>_<name>_seed<seed>_h<hours>_<key>.npz``, ``key`` a hash of
        the HF model and the cell's Hs and Tp.
    """
    if analogue not in ANALOGUES:
        raise ValueError(f"analogue must be one of {', '.join(ANALOGUES)}, got {analogue!r}")
    hours = int(hours)
    if hours < 1:
        raise ValueError(f"hours must be a whole number of one-hour realisations >= 1, "
                         f"got {hours!r}")
    file = cache_dir(path) / (f"lt{analogue}_{row['name']}_seed{int(seed)}_h{hours}_"
                              f"{_cell_key(analogue, row)}.npz")
    if cache and file.exists():
        try:
            with np.load(file) as z:
                return {k: z[k] for k in z.files} | {"duration": float(z["duration"])}
        except (OSError, ValueError, KeyError):
            pass  # unreadable cache entry: regenerate
    spec, s = _cell_spec(analogue, row), cell_seed(seed, cell_no)
    if analogue == "3":
        ev, _ = case_impacts.generate_green_water(spec, s, hours, SEED_LENGTH)
    else:
        ev, _ = case_vbm.generate_case2(spec, s, hours, SEED_LENGTH, mode="hog")
    out = dict(ev, duration=np.float64(hours * SEED_LENGTH))
    if cache:
        file.parent.mkdir(parents=True, exist_ok=True)
        tmp = file.with_suffix(".tmp.npz")
        np.savez(tmp, **out)
        os.replace(tmp, file)
    return out | {"duration": float(out["duration"])}


def long_term_exceedance(x, weights, hf_by_state):
    """``Q(x) = Σ_s w_s Q_s(x) / Σ_s w_s`` with ``Q_s`` the empirical exceedance of
    ``hf_by_state[s]``.

    Parameters
    ----------
    x : array_like
        Load levels.
    weights : mapping
        ``p_s ν_s`` per sea state (any common scale).
    hf_by_state : mapping
        HF value of every wave event of each sea state.

    Returns
    -------
    ndarray
        ``Q`` at each ``x`` (exceedance per wave encounter, ``>``).
    """
    x = np.atleast_1d(np.asarray(x, float))
    total = float(sum(weights[s] for s in hf_by_state))
    q = np.zeros(x.size)
    for s, hf in hf_by_state.items():
        h = np.sort(np.asarray(hf, float))
        q += weights[s] * (h.size - np.searchsorted(h, x, side="right")) / h.size
    return q / total


def value_at_exceedance_long_term(p, weights, hf_by_state):
    """The load whose long-term exceedance per encounter is ``p`` (log-linear between events).

    Every HF value of sea state ``s`` carries the probability ``w_s / (n_s Σ w)``;
    the values sorted descending give ``Q`` just below each of them, and the
    value at ``p`` is interpolated linearly in ``ln Q``.  NaN when ``p`` is
    beyond the largest value's exceedance.
    """
    total = float(sum(weights[s] for s in hf_by_state))
    vals = np.concatenate([np.asarray(h, float) for h in hf_by_state.values()])
    prob = np.concatenate([np.full(len(h), weights[s] / (len(h) * total))
                           for s, h in hf_by_state.items()])
    order = np.argsort(-vals, kind="stable")
    vals, cum = vals[order], np.cumsum(prob[order])
    if not 0.0 < p < 1.0:
        raise ValueError(f"p must be an exceedance probability in (0, 1), got {p!r}")
    if p < cum[0]:
        return float("nan")
    k = int(np.searchsorted(cum, p))
    if k == 0:
        return float(vals[0])
    if k >= vals.size:
        return float(vals[-1])
    if vals[k] <= 0.0 and vals[k - 1] > 0.0 and p > cum[k - 1]:
        return 0.0
    lo, hi = np.log(cum[k - 1]), np.log(cum[k])
    f = 0.0 if hi == lo else (np.log(p) - lo) / (hi - lo)
    return float(vals[k - 1] + f * (vals[k] - vals[k - 1]))

