"""A two-component Weibull mixture: the body and the tail of bore + impulse loads.

``F(x) = 1 − p·exp(−(w/α₁)^β₁) − (1 − p)·exp(−(w/α₂)^β₂)``, ``w = x − θ > 0``.

Green-water and slamming loads are a quasi-static part (a bore: narrow, β of
2–5) and an impulsive part (wide, β near 1 or below); one Weibull fitted to
all of them bends its tail towards the body.  Beyond the paper, whose HF
marginal is one Weibull (van Essen & Seyffert 2026, Eq. 15).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

__all__ = ["WeibullMixture", "fit_weibull_mixture", "split_start"]

WEIGHT_LOW, WEIGHT_SPAN = 0.02, 0.96
"""The body's weight ``p`` is ``WEIGHT_LOW + WEIGHT_SPAN · sigmoid(x)``, in [0.02, 0.98]."""
LN_SHAPE_BOUNDS = (np.log(0.3), np.log(20.0))
"""Both components' ``ln β`` lie in [ln 0.3, ln 20]."""


def split_start(ln_alpha: float, ln_beta: float) -> list:
    """``[ln α₁, ln β₁, ln α₂, ln β₂]`` that split one Weibull (scale α, shape β) into a
    narrower, lower body and a wider, higher tail: the fits' starting point."""
    lo, hi = LN_SHAPE_BOUNDS
    return [np.log(0.8) + ln_alpha, min(ln_beta + np.log(2.0), hi - 0.1),
            np.log(1.6) + ln_alpha, max(ln_beta + np.log(0.7), lo + 0.1)]


@dataclass(frozen=True)
class WeibullMixture:
    """A fitted two-component Weibull mixture with a common location (module docs)."""

    name: ClassVar[str] = "weibull_mixture"
    theta: float
    p: float
    alpha1: float
    beta1: float
    alpha2: float
    beta2: float

    def _w(self, x):
        return np.maximum(np.asarray(x, float) - self.theta, 0.0)

    def sf(self, x):
        """``P(X > x)``."""
        w = self._w(x)
        return (self.p * np.exp(-(w / self.alpha1) ** self.beta1)
                + (1.0 - self.p) * np.exp(-(w / self.alpha2) ** self.beta2))

    def cdf(self, x):
        """``P(X ≤ x)``, accurate near the location too."""
        w = self._w(x)
        return (-self.p * np.expm1(-(w / self.alpha1) ** self.beta1)
                - (1.0 - self.p) * np.expm1(-(w / self.alpha2) ** self.beta2))

    def logpdf(self, x):
        """``ln f(x)``; −∞ at and below the location."""
        x = np.asarray(x, float)
        w = np.where(x > self.theta, x - self.theta, 1.0)
        parts = [np.log(weight * b / a) + (b - 1.0) * np.log(w / a) - (w / a) ** b
                 for weight, a, b in ((self.p, self.alpha1, self.beta1),
                                      (1.0 - self.p, self.alpha2, self.beta2))]
        return np.where(x > self.theta, np.logaddexp(*parts), -np.inf)

    def pdf(self, x):
        """``f(x)``."""
        return np.exp(self.logpdf(x))

    def _log_sf_and_slope(self, w):
        """``ln S(w)`` and ``d ln S / dw`` (``−f/S``)."""
        parts = []
        for a, b in ((self.alpha1, self.beta1), (self.alpha2, self.beta2)):
            z = (w / a) ** b
            s = np.exp(-z)
            parts.append((s, b * z / np.where(w > 0, w, 1.0) * s))
        (s1, f1), (s2, f2) = parts
        sf = self.p * s1 + (1.0 - self.p) * s2
        return np.log(sf), -(self.p * f1 + (1.0 - self.p) * f2) / sf

    def isf(self, q, *, newton_steps: int = 4):
        """The value exceeded with probability ``q``: a table, then Newton steps on ``ln S``
        in ``ln w``.  Accurate in the upper tail (relative error in ``x − θ`` below 1e-7
        for q ≤ 0.5, about 1e-14 for q ≤ 1e-6); for q near 1 only to within
        ``1e-12`` times the table's top.  ``isf(0)`` is ∞."""
        q_in = np.asarray(q, float)
        q = np.clip(np.nan_to_num(q_in, nan=1.0), 1e-300, 1.0)
        if q.size == 0:
            return q.copy()
        # sf ≤ the larger of the components' survival functions, so above both
        # components' own q-quantiles the mixture's sf is below q
        top = max(a * (-np.log(np.min(q))) ** (1.0 / b)
                  for a, b in ((self.alpha1, self.beta1), (self.alpha2, self.beta2)))
        if top <= 0:
            return np.where(np.isnan(q_in), np.nan, np.full_like(q, self.theta))
        grid = top * np.geomspace(1e-12, 1.0, 1024)
        log_sf, _ = self._log_sf_and_slope(grid)
        # −ln S rises with w: read ln w off the table at −ln q, in log–log space
        w = np.exp(np.interp(np.log(-np.log(q) + 1e-300), np.log(-log_sf + 1e-300),
                             np.log(grid)))
        for _ in range(newton_steps):  # in ln w, where both tails are close to straight
            log_s, slope = self._log_sf_and_slope(w)
            step = (log_s - np.log(q)) / np.minimum(slope * w, -1e-300)
            w = np.clip(w * np.exp(-np.clip(step, -2.0, 2.0)), 1e-300, top)
        x = self.theta + np.where(q >= 1.0, 0.0, w)
        return np.where(np.isnan(q_in), np.nan, np.where(q_in <= 0.0, np.inf, x))

    def ppf(self, p):
        """Inverse of :meth:`cdf`."""
        return self.isf(1.0 - np.asarray(p, float))


def fit_weibull_mixture(loads, *, loc=None) -> WeibullMixture:
    """Maximum-likelihood two-component Weibull mixture of peak loads.

    The weight ``p`` stays in [0.02, 0.98] and both shapes in [0.3, 20].  The
    start splits a three-parameter Weibull fit (``scipy.stats.weibull_min``)
    into a narrower, lower and a wider, higher component.  With a free
    location (``loc=None``) the smallest load, and every load tied with it,
    enters as ``P(X ≤ x_min)``: with a shape below 1 the density at the
    location is infinite, and the likelihood would otherwise grow without
    bound as the location reaches the smallest load (as in
    :func:`pas.models.joint.fit_joint`); the location stays at least 1e-9 load
    ranges below it, at most three below it, and at or above 0 when the
    loads are positive.  ``loc`` fixes it.
    Raises ValueError when no finite optimum is found.
    """
    from scipy import optimize, stats

    x = np.sort(np.asarray(loads, float))
    lo, span = x[0], float(np.ptp(x)) or float(x[0])
    n_low = int(np.sum(x == lo))  # ties at the smallest load are all censored
    if loc is None:
        c, theta0, scale = stats.weibull_min.fit(x)
        theta0 = min(max(theta0, 0.0), lo - 1e-6 * span)
        gap_max = np.log(min(3.0, lo / span)) if lo > 0 else np.log(3.0)
        bounds = [(min(np.log(1e-9), gap_max - 1.0), gap_max)]
        start = [np.log(max(lo - theta0, 1e-9 * span) / span)]
    else:
        if lo <= loc:
            raise ValueError(f"loads must lie above the fixed location {loc}")
        c, _, scale = stats.weibull_min.fit(x, floc=loc)
        bounds, start = [], []
    bounds += [(-8.0, 8.0), (None, None), LN_SHAPE_BOUNDS, (None, None), LN_SHAPE_BOUNDS]
    start += [0.4, *split_start(np.log(scale), np.log(c))]
    start = [float(np.clip(v, -np.inf if lo_b is None else lo_b, np.inf if hi_b is None else hi_b))
             for v, (lo_b, hi_b) in zip(start, bounds)]

    def mixture(v):
        theta = float(loc) if loc is not None else lo - np.exp(v[0]) * span
        k = 0 if loc is not None else 1
        p = WEIGHT_LOW + WEIGHT_SPAN / (1.0 + np.exp(-v[k]))
        a1, b1, a2, b2 = np.exp(v[k + 1:k + 5])
        return WeibullMixture(float(theta), float(p), float(a1), float(b1), float(a2), float(b2))

    @np.errstate(all="ignore")
    def negloglik(v):
        try:
            m = mixture(v)
            val = (np.sum(m.logpdf(x[n_low:])) + n_low * np.log(m.cdf(lo)) if loc is None
                   else np.sum(m.logpdf(x)))
        except (ZeroDivisionError, OverflowError):  # a trial step past float range
            return 1e300
        return -float(val) if np.isfinite(val) else 1e300

    res = optimize.minimize(negloglik, start, method="L-BFGS-B", bounds=bounds)
    if not np.isfinite(res.fun) or res.fun >= 1e299:
        raise ValueError(f"the Weibull mixture fit found no finite optimum: {res.message}")
    return mixture(res.x)
