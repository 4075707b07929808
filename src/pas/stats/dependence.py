"""Rank dependence of LF–HF pairs: pseudo-observations, Kendall's τ, empirical tail dependence.

Plain functions over two samples; the copula models built on the
pseudo-observations are :mod:`pas.copulas`.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

__all__ = ["pseudo_observations", "weighted_ranks", "kendall_tau", "empirical_tail_dependence"]


def pseudo_observations(x, y):
    """Rank-based pseudo-observations ``u = rank(x)/(m+1)``, ``v = rank(y)/(m+1)`` (Eq. 5).

    Ties get their average rank.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"x and y must be 1-D of equal length, got {x.shape} and {y.shape}")
    m = x.size
    return stats.rankdata(x) / (m + 1.0), stats.rankdata(y) / (m + 1.0)


def weighted_ranks(x, w) -> np.ndarray:
    """Weighted mid-point plotting positions ``(W_{<i} + w_i/2) / W`` in (0, 1).

    The weighted empirical CDF halfway up each value's own step (Hazen's
    ``(i − ½)/m`` for equal weights); tied values share the mean of their
    positions.  PAS ranks the LF population with each peak weighted by its
    impact probability (:func:`pas.strategies.selection.population_lf_ranks`).

    Examples
    --------
    >>> weighted_ranks([3.0, 1.0, 2.0], [1.0, 1.0, 2.0]).tolist()
    [0.875, 0.125, 0.5]
    """
    x, w = np.asarray(x, float), np.asarray(w, float)
    order = np.argsort(x, kind="stable")
    cum = np.cumsum(w[order])
    mid = cum - w[order] / 2.0
    _, inv = np.unique(x[order], return_inverse=True)
    mid = (np.bincount(inv, mid * w[order]) / np.bincount(inv, w[order]))[inv]
    out = np.empty_like(mid)
    out[order] = mid / cum[-1]
    return out


def kendall_tau(x, y) -> float:
    """Kendall's τ-b of two samples (scipy)."""
    return float(stats.kendalltau(x, y).statistic)


def empirical_tail_dependence(x, y, *, q: float = 0.9):
    """Empirical upper and lower tail dependence at level ``q``.

    ``λ_U ≈ P(V > q | U > q)`` and ``λ_L ≈ P(V ≤ 1−q | U ≤ 1−q)`` on the
    pseudo-observations: a finite-sample indicator, not the limit.  With fewer
    than about ``1/(1−q)`` pairs they are NaN.
    """
    u, v = pseudo_observations(x, y)
    upper, lower = u > q, u <= 1 - q
    lam_u = float(np.mean(v[upper] > q)) if upper.any() else float("nan")
    lam_l = float(np.mean(v[lower] <= 1 - q)) if lower.any() else float("nan")
    return lam_u, lam_l
