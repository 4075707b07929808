"""A two-component Weibull mixture: the body and the tail of bore + impulse loads.

``F(x) = 1 − p·exp(−(w/α₁)^β₁) − (1 − p)·exp(−(w/α₂)^β₂)``, ``w = x − θ > 0``.

Green-water and slamming loads are a quasi-static part (a bore: narrow, β of
2–5) and an impulsive part (wide, β near 1 or below); one Weibull fitted to
all of them bends its tail towards the body.  Beyond the paper, whose HF
marginal is one Weibull (van Essen & Seyffert 2026, Eq. 15).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["WeibullMixture"]


@dataclass(frozen=True)
class WeibullMixture:
    """A fitted two-component Weibull mixture with a common location (module docs)."""

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
        """``P(X ≤ x)``."""
        return 1.0 - self.sf(x)

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
        """The value exceeded with probability ``q``: a table, then Newton steps on ``ln S`` in ``ln w``."""
        q = np.clip(np.asarray(q, float), 1e-300, 1.0)
        # sf ≤ the larger of the components' survival functions, so above both
        # components' own q-quantiles the mixture's sf is below q
        top = max(a * (-np.log(np.min(q))) ** (1.0 / b)
                  for a, b in ((self.alpha1, self.beta1), (self.alpha2, self.beta2)))
        if top <= 0:
            return np.full_like(q, self.theta)
        grid = top * np.geomspace(1e-12, 1.0, 1024)
        log_sf, _ = self._log_sf_and_slope(grid)
        # −ln S rises with w: read ln w off the table at −ln q, in log–log space
        w = np.exp(np.interp(np.log(-np.log(q) + 1e-300), np.log(-log_sf + 1e-300),
                             np.log(grid)))
        for _ in range(newton_steps):  # in ln w, where both tails are close to straight
            log_s, slope = self._log_sf_and_slope(w)
            step = (log_s - np.log(q)) / np.minimum(slope * w, -1e-300)
            w = np.clip(w * np.exp(-np.clip(step, -2.0, 2.0)), 1e-300, top)
        return self.theta + np.where(q >= 1.0, 0.0, w)

    def ppf(self, p):
        """Inverse of :meth:`cdf`."""
        return self.isf(1.0 - np.asarray(p, float))
