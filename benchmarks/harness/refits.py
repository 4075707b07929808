"""PAS's estimator refitted to chosen events of an analogue data set.

The investigations of ``docs/results/investigations.md`` ask what PAS's MPM
would be on other samples of the same data set: its final sample without some
pairs, every event told, every event weighted as MD's design includes events.
:func:`error_at` answers for any set of pool positions;
:func:`md_design_positions` gives the weighting.  Used by
``benchmarks/investigations/final_sample_refits.py``, ``heavy_loads.py`` and
``md_weighting_control.py``.
"""

from __future__ import annotations

import numpy as np

import pas.strategies.pas as pas_module
from pas.strategies.base import Pairs
from pas.strategies.screening import LFSet


def pool_of(data):
    """The data set's LF pool and the HF load of each pool peak (0: no impact)."""
    lfset = LFSet(data.lf, n_waves=data.n_waves, p_exp=data.p_exp, threshold=data.threshold)
    return lfset, np.asarray(data.hf, float)[lfset.index]


def evaluated_positions(data, lfset, res):
    """Pool positions of the events a study evaluated."""
    position = np.full(len(data.lf), -1)
    position[lfset.index] = np.arange(lfset.n)
    return position[res.history["event_index"].dropna().to_numpy(int)]


def pairs_at(lfset, hf_pool, positions):
    """The true-positive pairs and false positives of pool ``positions``, in their order
    (the order decides which pairs a bootstrap replicate draws)."""
    idx = np.asarray(positions)
    tp, fp = idx[hf_pool[idx] > 0], idx[hf_pool[idx] == 0]
    return Pairs(tp, lfset.lf[tp], hf_pool[tp], lfset.d[tp], lfset.lf[fp], fp)


def error_at(data, lfset, hf_pool, positions, seed, settings=None):
    """Relative MPM error of PAS fitted to the events at pool ``positions`` (no band).

    Parameters
    ----------
    data : CaseData
        The data set; its ``truth_mpm`` scores the MPM.
    lfset, hf_pool
        From :func:`pool_of`.
    positions : array of int
        Pool positions of the events told (repeats count as repeated pairs).
    seed : int
        Seed of the strategy and of its draws.
    settings : dict, optional
        PAS settings; ``n_bootstrap`` > 0 reads the median of the bootstrap MPMs.

    Returns
    -------
    float
        ``MPM / truth − 1``.
    """
    settings = settings or {}
    pairs = pairs_at(lfset, hf_pool, positions)
    strategy = pas_module.PAS.from_flat({"n_bootstrap": 0, **settings})
    strategy.reset(seed)
    mpm = strategy.predict(pairs, lfset, np.random.default_rng(seed)).mpm
    if settings.get("n_bootstrap"):
        mpm = float(np.median(strategy.model_band(pairs, lfset,
                                                  np.random.default_rng(seed))[2]))
    return mpm / data.truth_mpm - 1


def md_design_positions(n, k=160, copies=10, seed=0):
    """Pool positions repeated as MD's design includes them: ``copies · min(1, c / rank)``
    times (stochastic rounding), with ``c`` such that ``k`` events are expected.

    MD spreads ``k`` events uniformly over ``ln d``, so the event of LF rank ``i``
    (its ln-d interval ``≈ 1/i`` wide) is included with probability ``≈ min(1, c/i)``.
    """
    rank = np.arange(1, n + 1)
    lo, hi = 1e-3, float(n)
    for _ in range(100):
        c = np.sqrt(lo * hi)
        lo, hi = (c, hi) if np.minimum(1.0, c / rank).sum() < k else (lo, c)
    weight = copies * np.minimum(1.0, c / rank)
    times = np.floor(weight + np.random.default_rng(seed).uniform(size=n)).astype(int)
    return np.repeat(np.arange(n), times)
