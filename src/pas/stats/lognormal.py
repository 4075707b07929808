"""The three-parameter log-normal distribution, a candidate HF marginal of the joint fit.

``F(x) = Φ((ln(x − θ) − μ) / σ)`` for ``x > θ``.  Its tail is heavier than
any Weibull's with β ≥ 1 and lighter than a power law; it is the law of a
multiplicative load model ``ln h = a + b ln l + σ ε``, which no Weibull
marginal follows into the tail.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from scipy import special, stats

__all__ = ["LogNormal3"]


@dataclass(frozen=True)
class LogNormal3:
    """A fitted three-parameter log-normal distribution (location θ, log-mean μ, log-sd σ)."""

    name: ClassVar[str] = "lognormal"

    theta: float
    mu: float
    sigma: float

    @property
    def frozen(self):
        """The equivalent ``scipy.stats.lognorm`` frozen distribution."""
        return stats.lognorm(self.sigma, loc=self.theta, scale=np.exp(self.mu))

    def _z(self, x):
        w = np.asarray(x, float) - self.theta
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(w > 0, (np.log(np.where(w > 0, w, 1.0)) - self.mu) / self.sigma,
                            -np.inf)

    def cdf(self, x):
        """``P(X ≤ x)``."""
        return special.ndtr(self._z(x))

    def sf(self, x):
        """``P(X > x)``, accurate in the far tail."""
        return special.ndtr(-self._z(x))

    def ppf(self, p):
        """Inverse of :meth:`cdf`."""
        return self.theta + np.exp(self.mu + self.sigma * special.ndtri(np.asarray(p, float)))

    def isf(self, q):
        """Inverse of :meth:`sf`: the value exceeded with probability ``q``."""
        return self.theta + np.exp(self.mu - self.sigma * special.ndtri(np.asarray(q, float)))
