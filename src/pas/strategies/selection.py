"""The LF side of the selection-aware estimator: impacts and population ranks.

Beyond the paper.  MD (Eq. 16–17) spreads the HF samples uniformly over
``ln d``, so the selected pairs are tail-heavy: the ten largest of 15 000 LF
peaks are as likely to be sampled as the lowest 5 000.  Because MD chooses
events by their LF value alone, the law of HF *given* LF — and of an impact
given LF — is the same in the sample as in the population.  Two pieces of
PAS's default estimator (:mod:`pas.models.joint` has the third) use that:

* :func:`impact_probability` — ``P(impact | LF)`` from the true and false
  positives, so a conditional draw can be "no impact" (the paper draws a
  positive load for every conditioning peak although the false positives
  show that some give none);
* :func:`population_lf_ranks` — the LF pseudo-observations from the known
  LF population itself (every conditioning peak, counted with its impact
  probability), used for the pairs and for the draws of Eq. 6 alike, so no LF
  marginal is fitted.
"""

from __future__ import annotations

import numpy as np

__all__ = ["impact_probability", "falls_significantly", "FALLING_P", "population_lf_ranks"]


def impact_probability(lf_true, lf_false, *, falling_p: float | None = None):
    """``P(impact | LF)``: logistic regression of true (1) vs false (0) positives on LF.

    Returns a vectorised callable, or ``None`` when no false positive has been
    seen.  MD selects events by LF alone, so the regression needs no weights.
    The indicator is chosen because large LF peaks make impacts, so a fitted
    slope below zero (misses as common among the largest peaks, as spread
    misses make by chance) gives the constant impact share of the evaluated
    events instead — unless ``falling_p`` is given and a one-sided
    likelihood-ratio test rejects a flat probability at that level
    (:func:`falls_significantly`): then the evaluated events show misses
    concentrated at high LF, and the falling fit is kept.

    Examples
    --------
    >>> p = impact_probability([5.0, 6.0, 7.0], [5.5, 7.5])  # a miss high up
    >>> bool(p([5.0])[0] <= p([8.0])[0])
    True
    >>> hits, misses = [1.0, 1.5, 2.0, 2.5, 3.0, 3.5] * 3, [5.0, 5.5, 6.0, 6.5] * 3
    >>> p = impact_probability(hits, misses, falling_p=FALLING_P)
    >>> bool(p([1.0])[0] > 0.9 > 0.1 > p([6.5])[0])
    True
    """
    lf_false = np.asarray(lf_false, float)
    if lf_false.size == 0:
        return None
    from sklearn.linear_model import LogisticRegression

    x = np.r_[np.asarray(lf_true, float), lf_false]
    y = np.r_[np.ones(len(lf_true)), np.zeros(lf_false.size)]
    mu, sd = x.mean(), x.std() or 1.0
    z = ((x - mu) / sd)[:, None]
    model = LogisticRegression(C=1.0).fit(z, y)
    if model.coef_[0, 0] < 0 and (falling_p is None
                                  or not falls_significantly(model, z, y, falling_p)):
        share = y.mean()
        return lambda lf: np.full(np.shape(np.atleast_1d(lf)), share)
    return lambda lf: model.predict_proba(((np.asarray(lf, float) - mu) / sd)[:, None])[:, 1]


FALLING_P = 0.05
"""Level of the test that keeps a falling ``P(impact | LF)`` (``PAS(impact_trend="tested")``)."""


def falls_significantly(model, z, y, level: float) -> bool:
    """One-sided likelihood-ratio test of the fitted logistic ``model`` against a flat one.

    ``2 (ℓ₁ − ℓ₀)`` against χ²(1), halved for the one side (the slope is below
    zero when this is asked): True when that p-value is below ``level``.
    """
    from scipy import stats

    p1 = np.clip(model.predict_proba(z)[:, 1], 1e-12, 1 - 1e-12)
    p0 = np.clip(y.mean(), 1e-12, 1 - 1e-12)
    ll1 = np.sum(y * np.log(p1) + (1 - y) * np.log1p(-p1))
    ll0 = np.sum(y * np.log(p0) + (1 - y) * np.log1p(-p0))
    return 0.5 * stats.chi2.sf(max(2.0 * (ll1 - ll0), 0.0), 1) < level


def population_lf_ranks(lf_pool, impact=None, rng=None, *, gpd_tail: bool = False,
                        tail_fits: dict | None = None) -> np.ndarray:
    """LF pseudo-observations of every pool peak in the population of impacts.

    ``u_j`` is the weighted mid-rank of ``lf_pool[j]`` with weights
    ``P(impact | l_j)`` (all 1 without an impact model): the LF marginal of the
    population the copula describes, known without fitting.  With ``rng``: one
    Bayesian-bootstrap draw of that CDF at the pool's peaks
    (:func:`pas.stats.dependence.weighted_ranks`), for the model band.  With
    ``gpd_tail``: the largest peaks read from a fitted GPD tail
    (:func:`pas.stats.dependence.gpd_tail_ranks`); ``tail_fits`` keeps its
    point fit per pool.
    """
    from ..stats.dependence import gpd_tail_ranks, weighted_ranks

    lf_pool = np.asarray(lf_pool, float)
    w = np.ones(lf_pool.size) if impact is None else np.maximum(impact(lf_pool), 1e-6)
    u = weighted_ranks(lf_pool, w, rng)
    if not gpd_tail:
        return u
    key = (lf_pool.size, float(lf_pool.max()), float(lf_pool.min()))
    known = None if tail_fits is None else tail_fits.get(key)
    u, fit = gpd_tail_ranks(lf_pool, u, rng=rng, shape_scale=known)
    if fit is not None and rng is None and tail_fits is not None:
        tail_fits[key] = fit
    return u
