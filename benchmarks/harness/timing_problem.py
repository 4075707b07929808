"""The problem the timing benchmarks share (``benchmarks/timing/study_parts.py``,
``benchmarks/studies/precision_stop.py --cost``): 15 000 Rayleigh LF peaks, ``n_w``
16 364, a Gumbel (θ = 3) copula to a Weibull HF load, the CPU clock they read, and a fixed
piece of work that tells how fast the machine runs at the time (:func:`reference_seconds`)."""

from __future__ import annotations

import resource

import numpy as np

__all__ = ["N", "N_W", "P_EXP", "scenario", "cpu_seconds", "reference_seconds",
           "REFERENCE_QUIET"]

N, N_W, P_EXP = 15000, 16364, 2.55e-3


def scenario(n=N, seed=1):
    """LF peaks and the oracle's HF value for each (a Gumbel copula, Weibull HF)."""
    import pyvinecopulib as pv
    from scipy import stats

    rng = np.random.default_rng(seed)
    lf = rng.rayleigh(2.5, n)
    u = stats.rankdata(lf) / (n + 1.0)
    cop = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[3.0]]))
    v = cop.hinv1(np.column_stack([u, rng.uniform(size=n)]))
    return lf, stats.weibull_min(1.5, scale=5.0).ppf(np.clip(v, 1e-12, 1 - 1e-12))


def cpu_seconds():
    """CPU seconds of this process and of its waited-for children (forked band workers)."""
    return sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
               for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


REFERENCE_QUIET = 0.62
"""CPU seconds of :func:`reference_seconds` on the project's 2-core machine when it was quiet
(2026-12-04: the least of several readings on the idle machine, which ranged 0.62-0.78 s
within minutes)."""


def reference_seconds(repeats: int = 3) -> float:
    """Least CPU seconds of ``repeats`` runs of a fixed piece of work — 200 t quantiles of
    10 000 values (``special.stdtrit``, most of a model band's time) — so that times measured
    on a shared machine can be read against how fast it ran then (:data:`REFERENCE_QUIET`)."""
    from scipy import special

    p = np.random.default_rng(0).uniform(0.001, 0.5, 10000)
    nu = np.full(p.size, 20.0)
    best = np.inf
    for _ in range(repeats):
        t = cpu_seconds()
        for _ in range(200):
            special.stdtrit(nu, p)
        best = min(best, cpu_seconds() - t)
    return float(best)
