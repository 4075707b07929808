"""Laws of the second round of held-out known-truth types (``ho2-…``), never used for any choice.

The first round of held-out types (:mod:`harness.known_truth_held_out`)
informed the diagnosis of the band's misses (``docs/explanation/known-truth.md``), so a
mend chosen after it could have learned from them.  The second round adds
forms that neither the tuning types nor the first round have, written before
any mend was measured on them:

* :class:`StudentRegressionLaw` — ``h = HF_SCALE · l^a · exp(s T)``, ``T``
  Student-t with ν 3: multiplicative noise with a power-law tail, so that
  large loads also come from events of middling LF;
* :class:`HiddenExcessLaw` — a threshold on a hidden variable: the relative
  motion ``W = l · exp(s ε)`` must pass a freeboard ``c``, and the load is
  ``k (W − c)^γ``, else 0 — the misses and the small loads come from the same
  variable;
* :class:`SaturatingLaw` — a bounded HF marginal, ``h = H_max (1 − exp(−X /
  H_max))`` of a Weibull ``X``: a load that saturates (an HF law with an upper
  end, which no candidate marginal has);
* :class:`ScaledLaw` — a law's loads multiplied by a factor, the outliers of
  ``"gated"`` (:func:`harness.known_truth_held_out.outlier_share`): only
  events above the LF's 95 % level can carry them.

The dependence with a negative part (half Clayton rotated by 90°, τ −0.4;
half Gumbel, τ 0.75) is a copula mixture of the first round's kind, built
in :mod:`harness.known_truth_held_out`.  Every law gives ``draw`` and
the conditional survival function ``sf`` in closed form.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from .known_truth import HF_SCALE

GATED_U, GATED_P, GATED_FACTOR = 0.95, 0.05, 2.5


class StudentRegressionLaw:
    """``ln h = ln(HF_SCALE · l^power) + scale · T``, ``T`` Student-t with ``df`` degrees."""

    def __init__(self, power=1.5, scale=0.15, df=3.0):
        self.power, self.scale, self.df = power, scale, df

    def _log_median(self, lf):
        return np.log(HF_SCALE) + self.power * np.log(lf)

    def draw(self, lf, u, rng):
        return np.exp(self._log_median(lf) + self.scale * rng.standard_t(self.df, lf.size))

    def sf(self, h, lf, u):
        return stats.t.sf((np.log(h) - self._log_median(lf)) / self.scale, self.df)


class HiddenExcessLaw:
    """``W = l · exp(spread · ε)``; the load is ``factor · (W − freeboard)^power`` where
    ``W`` passes the freeboard, else 0 (a miss)."""

    def __init__(self, freeboard=3.0, spread=0.15, factor=2.0 * HF_SCALE, power=1.5):
        self.freeboard, self.spread, self.factor, self.power = freeboard, spread, factor, power

    def draw(self, lf, u, rng):
        w = lf * np.exp(self.spread * rng.standard_normal(lf.size))
        return self.factor * np.clip(w - self.freeboard, 0.0, None) ** self.power

    def sf(self, h, lf, u):
        w = self.freeboard + (np.asarray(h, float) / self.factor) ** (1.0 / self.power)
        return stats.norm.sf(np.log(w / lf) / self.spread)


class SaturatingLaw:
    """The HF marginal ``H_max (1 − exp(−X / H_max))`` of ``X`` Weibull(``shape``,
    HF_SCALE): a ``cdf``/``ppf`` pair with an upper end at ``H_max``."""

    def __init__(self, shape=1.2, h_max=3.0 * HF_SCALE):
        self.x, self.h_max = stats.weibull_min(shape, scale=HF_SCALE), h_max

    def cdf(self, h):
        h = np.clip(np.asarray(h, float), 0.0, self.h_max * (1.0 - 1e-15))
        return self.x.cdf(-self.h_max * np.log1p(-h / self.h_max))

    def ppf(self, q):
        return self.h_max * -np.expm1(-self.x.ppf(q) / self.h_max)


class ScaledLaw:
    """The loads of ``law`` multiplied by ``factor``."""

    def __init__(self, law, factor=GATED_FACTOR):
        self.law, self.factor = law, factor

    def draw(self, lf, u, rng):
        return self.factor * self.law.draw(lf, u, rng)

    def sf(self, h, lf, u):
        return self.law.sf(np.asarray(h, float) / self.factor, lf, u)
