"""Rank dependence of LF–HF pairs: pseudo-observations, Kendall's τ, empirical tail dependence.

Plain functions over two samples; the copula models built on the
pseudo-observations are :mod:`pas.models.copulas`.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

__all__ = ["pseudo_observations", "weighted_ranks", "gpd_tail_ranks", "kendall_tau",
           "empirical_tail_dependence"]

GPD_TAIL_FRACTION, GPD_TAIL_MIN = 0.05, 50
"""The share of the largest values (and the fewest) :func:`gpd_tail_ranks` smooths."""


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


def weighted_ranks(x, w, rng: np.random.Generator | None = None) -> np.ndarray:
    """Weighted mid-point plotting positions ``(W_{<i} + w_i/2) / W`` in (0, 1).

    The weighted empirical CDF halfway up each value's own step (Hazen's
    ``(i − ½)/m`` for equal weights); tied values share the mean of their
    positions.  PAS ranks the LF population with each peak weighted by its
    impact probability (:func:`pas.strategies.selection.population_lf_ranks`).

    With ``rng``, each step ``w_i`` is replaced by a Gamma(``w_i``) draw: one
    draw of the population CDF at the values given their order (Rubin's
    Bayesian bootstrap, 1981; for equal weights the positions are then
    distributed as uniform order statistics), whose mean is about the
    positions without ``rng``.

    Examples
    --------
    >>> weighted_ranks([3.0, 1.0, 2.0], [1.0, 1.0, 2.0]).tolist()
    [0.875, 0.125, 0.5]
    """
    x, w = np.asarray(x, float), np.asarray(w, float)
    order = np.argsort(x, kind="stable")
    steps = w[order] if rng is None else rng.gamma(w[order])
    if not steps.sum() > 0:  # every Gamma draw of tiny weights underflowed
        steps = w[order]
    cum = np.cumsum(steps)
    mid = cum - steps / 2.0
    _, inv = np.unique(x[order], return_inverse=True)
    mid = (np.bincount(inv, mid * w[order]) / np.bincount(inv, w[order]))[inv]
    out = np.empty_like(mid)
    out[order] = mid / cum[-1]
    return out


def gpd_tail_ranks(x, u, *, rng: np.random.Generator | None = None, shape_scale=None):
    """Plotting positions ``u`` of ``x`` with their upper tail read from a fitted GPD.

    The ``k = max(50, 5 %)`` largest values get ``u = 1 − (1 − u_t) · S(x − x_t)``,
    ``S`` the survival function of a generalised Pareto distribution fitted by
    maximum likelihood to their excesses over the next value ``x_t``
    (location 0; peaks over threshold), ``u_t`` that value's own position.
    At the top of a sample the empirical positions scatter as order statistics
    do — the largest of 15 000 by a factor of about two — while the fitted
    tail pools the ``k`` largest.  Fewer than ``4 k`` values: ``u`` unchanged.

    ``rng``: the GPD is fitted to a bootstrap resample of the excesses (for a
    model band; a resample whose bounded tail ends below the largest excess
    is replaced by the point fit); ``shape_scale``: the point fit, already
    made to these excesses.
    Returns ``(positions, (shape, scale) or None)``.

    Examples
    --------
    >>> x = np.random.default_rng(0).rayleigh(1.0, 2000)
    >>> u = (np.argsort(np.argsort(x)) + 0.5) / x.size
    >>> v, fit = gpd_tail_ranks(x, u)
    >>> (bool(np.all(np.argsort(v) == np.argsort(x))),
    ...  bool(np.all(v[x < np.sort(x)[-100]] == u[x < np.sort(x)[-100]])))
    (True, True)
    """
    x, u = np.asarray(x, float), np.asarray(u, float)
    k = max(GPD_TAIL_MIN, int(GPD_TAIL_FRACTION * x.size))
    if x.size < 4 * k:
        return u, None
    order = np.argsort(x)[::-1]
    top, at = order[:k], order[k]
    excess = x[top] - x[at]
    if rng is not None:
        resampled = _gpd_fit(excess[rng.integers(0, k, k)])
        # a resample's bounded tail may end below the largest excess: that fit gives the
        # data zero likelihood, and the point fit stands in for it
        if resampled[0] >= 0 or -resampled[1] / resampled[0] > excess.max():
            shape_scale = resampled
    if shape_scale is None:
        shape_scale = _gpd_fit(excess)
    out = u.copy()
    out[top] = 1.0 - (1.0 - u[at]) * stats.genpareto.sf(excess, shape_scale[0], 0.0,
                                                         shape_scale[1])
    return out, shape_scale


def _gpd_fit(excess):
    """``(shape, scale)`` of the GPD by maximum likelihood, location 0, shape ≥ −0.5."""
    shape, _, scale = stats.genpareto.fit(excess, floc=0.0)
    if shape < -0.5:  # where the likelihood stops being regular (Smith, 1985)
        shape, _, scale = stats.genpareto.fit(excess, f0=-0.5, floc=0.0)
    return float(shape), float(scale)


_PAIRWISE_UP_TO = 200
"""Float samples up to this size count their pairs at once (O(n²)); larger ones, and
integers, by scipy's O(n log n) merge sort and its p-value: the pairs cost 0.05–0.08 of
its time at 10–40 values, 0.5 at 160, 0.8 at 200."""


def kendall_tau(x, y) -> float:
    """Kendall's τ-b of two samples, as :func:`scipy.stats.kendalltau` computes it (NaN for
    fewer than two pairs or a sample all alike)."""
    x, y = np.asarray(x).ravel(), np.asarray(y).ravel()
    if (x.size > _PAIRWISE_UP_TO or x.dtype.kind != "f" or y.dtype.kind != "f"
            or not (np.isfinite(x).all() and np.isfinite(y).all())):
        return float(stats.kendalltau(x, y).statistic)  # integers: no float cast
    sx, sy = np.sign(x[:, None] - x), np.sign(y[:, None] - y)  # every pair twice
    tot = x.size * (x.size - 1) // 2
    xtie = tot - int(np.count_nonzero(sx)) // 2
    ytie = tot - int(np.count_nonzero(sy)) // 2
    if tot == 0 or xtie == tot or ytie == tot:
        return float("nan")
    con_minus_dis = int(np.einsum("ij,ij->", sx, sy)) // 2
    tau = con_minus_dis / np.sqrt(tot - xtie) / np.sqrt(tot - ytie)  # scipy's arithmetic
    return float(min(1.0, max(-1.0, tau)))


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
