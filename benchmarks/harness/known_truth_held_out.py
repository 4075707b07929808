"""Held-out known-truth types: forms the tuning types lack, never used to choose settings.

The tuning types (:mod:`harness.known_truth`) draw HF loads from one of
the candidate copulas (or a log-normal regression), a Weibull, log-normal or
two-Weibull HF law, misses with a probability ``p(u)`` that falls smoothly
with the LF, and outliers that multiply a load by 3.  A setting chosen on
them may only interpolate between them.  The held-out types test whether it
generalises, with (:data:`HELD_OUT_TYPES`)

* **dependence** that none of the five candidates (Gaussian, Student, Clayton,
  Gumbel, Frank) contains: BB1, BB7 and an asymmetric Tawn copula, mixtures
  of two copulas (one of them independence: a share of loads unrelated to
  the LF), and a Gaussian dependence whose correlation grows with the LF
  level (then not a copula of the HF marginal at all);
* **HF laws**: gamma, log-logistic (a power-law tail) and a Weibull body
  spliced to a generalised Pareto tail at its 90 % quantile;
* **misses by other mechanisms**: ``"rank"`` — a hidden variable decides,
  the load's own rank given its LF ``t = P(H ≤ h | l)`` (low-for-their-LF
  loads are mostly missed, hit probability ``q(t) = 0.2 + 0.8 t^1.5``, 52 %
  on average); ``"high"`` — misses concentrated above an LF level (60 % of
  the events with ``u > 0.75`` miss, none below);
* **outliers by other mechanisms**: ``"contaminate"`` — 2 % of the events
  carry a load from a heavy-tailed law (Fréchet α 3) whatever the LF;
  ``"second"`` — a second population of loads (Clayton τ 0.3, Weibull β 1.1
  at 3 times the scale) whose share grows with the LF (5 % → 30 %);
* **regressions**: ``"hump"``, an HF load that rises with the LF and falls
  past ``l = 3.2`` (non-monotone), and ``"hetero"``, a power law whose
  scatter grows with the LF.

A second round (:data:`FRESH_TYPES`, ``ho2-…``; laws in
:mod:`harness.known_truth_fresh`) was written after the first round had
informed the diagnosis of the band, and is never used for any choice: Student-t
noise on a power law, a threshold on a hidden variable, a saturating load,
outliers only above the LF's 95 % level (``"gated"``), and a copula mixture
with a negatively dependent half.

Truth, exact given the LF peaks: as for the tuning types, the ``h`` with
``Σ_j P(H_j > h | l_j) = P_exp · n_w``, where

``P(H > h | l) = (1 − c(u)) M(h | l) + c(u) S_o(h | l)``,

``c`` the share of outliers and ``S_o`` their survival function, and ``M``
the main law with its misses: ``p(u) S(h | l)``, or for ``"rank"`` misses
``∫_{t_h}^1 q(t) dt`` with ``t_h = 1 − S(h | l)`` (closed form).  ``S`` is
``1 − C_{V|U}(F_H(h) | u)`` (h-functions of pyvinecopulib, or the Gaussian
one in closed form), a mixture of such terms for a mixture of copulas, or
a normal tail in ``ln h`` for the regressions.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pyvinecopulib as pv
from scipy import stats

from .known_truth import HF_SCALE, copula
from .known_truth_fresh import (
    GATED_P,
    GATED_U,
    HiddenExcessLaw,
    SaturatingLaw,
    ScaledLaw,
    StudentRegressionLaw,
)

RANK_MISS_FLOOR, RANK_MISS_POWER = 0.2, 1.5  # q(t) = 0.2 + 0.8 t^1.5
HIGH_MISS_U, HIGH_MISS_P = 0.75, 0.6
CONTAMINATION_P, CONTAMINATION = 0.02, stats.invweibull(3.0, scale=2.5 * HF_SCALE)
HUMP_PEAK = 3.2


@dataclass(frozen=True)
class HeldOutType:
    """One held-out problem type (module docs); the strings are keys of the laws below."""

    name: str
    dependence: str
    hf_law: str = "weibull1.2"
    misses: str = "none"  # or "rank", "high"
    outliers: str = "none"  # or "contaminate", "second"
    threshold: bool = False
    floor: float = 0.0
    held_out: bool = True

    @property
    def group(self) -> str:
        """``miss`` (threshold + misses), ``outlier``, ``mix`` or ``reg``."""
        return self.name.split("-")[1]

    def loads(self, lf, u, rng) -> np.ndarray:
        """HF loads (0 for a miss) of the pool peaks ``lf`` at LF CDF values ``u``."""
        law = main_law(self)
        h = law.draw(lf, u, rng)
        if self.misses == "rank":
            hit_p = rank_hit_probability(1.0 - law.sf(h, lf, u))
        else:
            hit_p = lf_hit_probability(u, self.misses)
        h = np.where(rng.uniform(size=lf.size) < hit_p, h, 0.0)
        share = outlier_share(u, self.outliers)
        if self.outliers != "none":
            h = np.where(rng.uniform(size=lf.size) < share,
                         outlier_law(self).draw(lf, u, rng), h)
        return h

    def exceedance_count(self, h, lf, u) -> float:
        """``Σ_j P(H_j > h | l_j)``: expected number of pool events above ``h``."""
        s = main_law(self).sf(h, lf, u)
        if self.misses == "rank":
            main = rank_hit_mass(1.0 - s)
        else:
            main = lf_hit_probability(u, self.misses) * s
        if self.outliers == "none":
            return float(np.sum(main))
        share = outlier_share(u, self.outliers)
        return float(np.sum((1.0 - share) * main + share * outlier_law(self).sf(h, lf, u)))


def rank_hit_probability(t):
    """``q(t)``: the chance that a load of conditional rank ``t`` given its LF is a hit."""
    return RANK_MISS_FLOOR + (1.0 - RANK_MISS_FLOOR) * np.asarray(t, float) ** RANK_MISS_POWER


def rank_hit_mass(t_h):
    """``∫_{t_h}^1 q(t) dt``: the chance of a hit whose load lies above rank ``t_h``."""
    t_h = np.asarray(t_h, float)
    g = RANK_MISS_POWER + 1.0
    return (RANK_MISS_FLOOR * (1.0 - t_h)
            + (1.0 - RANK_MISS_FLOOR) * (1.0 - t_h**g) / g)


def lf_hit_probability(u, misses: str):
    """``p(u)`` of the misses that depend on the LF only (``"none"``, ``"high"``)."""
    u = np.asarray(u, float)
    if misses == "none":
        return np.ones_like(u)
    if misses == "high":
        return np.where(u > HIGH_MISS_U, 1.0 - HIGH_MISS_P, 1.0)
    raise ValueError(f"unknown held-out miss mechanism {misses!r}; use 'none', 'high', 'rank'")


def outlier_share(u, outliers: str):
    """``c(u)``: the share of events whose load comes from the outlier law."""
    u = np.asarray(u, float)
    if outliers == "none":
        return np.zeros_like(u)
    if outliers == "contaminate":
        return np.full_like(u, CONTAMINATION_P)
    if outliers == "second":
        return 0.05 + 0.25 * u**6
    if outliers == "gated":
        return np.where(u > GATED_U, GATED_P, 0.0)
    raise ValueError(f"unknown outlier mechanism {outliers!r}; use 'none', 'contaminate', "
                     "'second', 'gated'")


class SplicedWeibullGPD:
    """A Weibull(1.5, HF_SCALE) body below its 90 % quantile and a generalised Pareto
    tail (ξ 0.25) above, its scale set so that the density is continuous."""

    def __init__(self, shape=1.5, q_body=0.9, xi=0.25):
        self.body = stats.weibull_min(shape, scale=HF_SCALE)
        self.q_body, self.h_body = q_body, float(self.body.ppf(q_body))
        self.tail = stats.genpareto(xi, loc=self.h_body,
                                    scale=(1.0 - q_body) / float(self.body.pdf(self.h_body)))

    def cdf(self, x):
        x = np.asarray(x, float)
        above = self.q_body + (1.0 - self.q_body) * self.tail.cdf(x)
        return np.where(x <= self.h_body, self.body.cdf(x), above)

    def ppf(self, q):
        q = np.asarray(q, float)
        tail_q = np.clip((q - self.q_body) / (1.0 - self.q_body), 0.0, 1.0)
        return np.where(q <= self.q_body, self.body.ppf(q), self.tail.ppf(tail_q))


HF_LAWS = {
    "weibull1.2": lambda: stats.weibull_min(1.2, scale=HF_SCALE),
    "gamma0.7": lambda: stats.gamma(0.7, scale=HF_SCALE / 0.7),
    "loglogistic3.5": lambda: stats.fisk(3.5, scale=HF_SCALE),
    "weibull-gpd": SplicedWeibullGPD,
    "saturating1.2": SaturatingLaw,
}
"""HF marginals by key: each a ``cdf``/``ppf`` pair."""


def _bicop(family, *parameters, rotation=0):
    return pv.Bicop(family=getattr(pv.BicopFamily, family), rotation=rotation,
                    parameters=np.array(parameters, float).reshape(-1, 1))


class CopulaMixtureLaw:
    """HF ``F_H⁻¹(V)``, ``V | U`` from a mixture of copulas ``Σ w_k C_k`` (itself a copula)."""

    def __init__(self, parts, marginal):
        self.parts, self.marginal = parts, marginal

    def _conditional_cdf(self, v, u):
        uv = np.column_stack([u, np.broadcast_to(v, u.shape)])
        return sum(w * c.hfunc1(uv) for w, c in self.parts)

    def draw(self, lf, u, rng):
        weights = np.array([w for w, _ in self.parts])
        part = rng.choice(len(self.parts), size=u.size, p=weights / weights.sum())
        r = rng.uniform(1e-9, 1 - 1e-9, u.size)
        v = np.empty(u.size)
        for k, (_, c) in enumerate(self.parts):
            pick = part == k
            v[pick] = c.hinv1(np.column_stack([u[pick], r[pick]]))
        return self.marginal.ppf(np.clip(v, 1e-12, 1 - 1e-12))

    def sf(self, h, lf, u):
        v = np.clip(self.marginal.cdf(h), 1e-12, 1 - 1e-12)
        return 1.0 - self._conditional_cdf(v, u)


class VaryingGaussianLaw:
    """``Φ⁻¹(V) = ρ(u) Φ⁻¹(u) + √(1 − ρ²) ε``, ``ρ(u) = 0.2 + 0.7 u²``: dependence that
    strengthens with the LF level; ``h = F_H⁻¹(V)``."""

    def __init__(self, marginal):
        self.marginal = marginal

    @staticmethod
    def _rho(u):
        return 0.2 + 0.7 * u**2

    def draw(self, lf, u, rng):
        rho = self._rho(u)
        z = rho * stats.norm.ppf(u) + np.sqrt(1 - rho**2) * rng.standard_normal(u.size)
        return self.marginal.ppf(np.clip(stats.norm.cdf(z), 1e-12, 1 - 1e-12))

    def sf(self, h, lf, u):
        rho = self._rho(u)
        v = np.clip(self.marginal.cdf(h), 1e-12, 1 - 1e-12)
        return stats.norm.sf((stats.norm.ppf(v) - rho * stats.norm.ppf(u)) / np.sqrt(1 - rho**2))


class LogNormalRegressionLaw:
    """``ln h = ln(HF_SCALE · median(l)) + σ(l) ε``, ε standard normal."""

    def __init__(self, median, sigma):
        self.median, self.sigma = median, sigma

    def draw(self, lf, u, rng):
        return HF_SCALE * self.median(lf) * np.exp(self.sigma(lf) * rng.standard_normal(lf.size))

    def sf(self, h, lf, u):
        return stats.norm.sf(np.log(h / (HF_SCALE * self.median(lf))) / self.sigma(lf))


def _hump(lf):
    x = (lf / HUMP_PEAK) ** 2
    return 3.0 * x * np.exp(1.0 - x)  # 3 at l = HUMP_PEAK, less on either side


DEPENDENCE = {
    "bb1": lambda m: CopulaMixtureLaw(((1.0, _bicop("bb1", 0.3, 2.2)),), m),       # τ 0.60
    "bb7": lambda m: CopulaMixtureLaw(((1.0, _bicop("bb7", 2.5, 0.5)),), m),       # τ 0.51
    "tawn": lambda m: CopulaMixtureLaw(((1.0, _bicop("tawn", 0.6, 1.0, 8.0)),), m),  # τ 0.55
    "gumbel+indep": lambda m: CopulaMixtureLaw(
        ((0.75, copula("gumbel", 0.75)), (0.25, _bicop("indep"))), m),
    "clayton+gumbel": lambda m: CopulaMixtureLaw(
        ((0.5, copula("clayton", 0.6)), (0.5, copula("gumbel", 0.6))), m),
    "varying-gaussian": VaryingGaussianLaw,
    "hump": lambda m: LogNormalRegressionLaw(_hump, lambda lf: np.full(lf.shape, 0.25)),
    "hetero": lambda m: LogNormalRegressionLaw(lambda lf: lf**1.2, lambda lf: 0.12 * lf),
    "gumbel0.6": lambda m: CopulaMixtureLaw(((1.0, copula("gumbel", 0.6)),), m),
    "gaussian0.6": lambda m: CopulaMixtureLaw(((1.0, copula("gaussian", 0.6)),), m),
    "student-power": lambda m: StudentRegressionLaw(),
    "hidden-excess": lambda m: HiddenExcessLaw(),
    "clayton90+gumbel": lambda m: CopulaMixtureLaw(
        ((0.5, _bicop("clayton", 4.0 / 3.0, rotation=90)), (0.5, copula("gumbel", 0.75))), m),
}
"""Conditional laws of the HF given the LF, by key, built on an HF marginal
(the regressions ignore it)."""


@functools.cache
def main_law(ptype: HeldOutType):
    """The conditional law of a type's loads before misses and outliers."""
    return DEPENDENCE[ptype.dependence](HF_LAWS[ptype.hf_law]())


@functools.cache
def outlier_law(ptype: HeldOutType):
    """The law of a type's outlier loads (module docs)."""
    if ptype.outliers == "contaminate":
        return _Independent(CONTAMINATION)
    if ptype.outliers == "gated":
        return ScaledLaw(main_law(ptype))
    return CopulaMixtureLaw(((1.0, copula("clayton", 0.3)),),
                            stats.weibull_min(1.1, scale=3.0 * HF_SCALE))


class _Independent:
    """A load law that ignores the LF."""

    def __init__(self, law):
        self.law = law

    def draw(self, lf, u, rng):
        return self.law.ppf(rng.uniform(1e-9, 1 - 1e-9, lf.size))

    def sf(self, h, lf, u):
        return np.full(lf.shape, float(self.law.sf(h)))


def _held_out_types():
    t = HeldOutType
    out = [
        # threshold + misses
        t("ho-miss-rank-bb1-gamma", "bb1", "gamma0.7", misses="rank", threshold=True),
        t("ho-miss-high-tawn-loglogistic", "tawn", "loglogistic3.5", misses="high",
          threshold=True),
        t("ho-miss-rank-varying-gpd", "varying-gaussian", "weibull-gpd", misses="rank",
          threshold=True),
        # outliers
        t("ho-outlier-contaminate-bb7", "bb7", "weibull1.2", outliers="contaminate"),
        t("ho-outlier-second-varying", "varying-gaussian", "gamma0.7", outliers="second"),
        t("ho-outlier-contaminate-miss-bb1", "bb1", "weibull-gpd", misses="high",
          outliers="contaminate", threshold=True),
        # mixtures
        t("ho-mix-gumbel-indep-gamma", "gumbel+indep", "gamma0.7"),
        t("ho-mix-clayton-gumbel-loglogistic", "clayton+gumbel", "loglogistic3.5"),
        t("ho-mix-tawn-gpd", "tawn", "weibull-gpd"),
        # regressions
        t("ho-reg-hump", "hump"),
        t("ho-reg-hetero", "hetero"),
        t("ho-reg-hump-rank-miss", "hump", misses="rank", threshold=True),
    ]
    return {x.name: x for x in out}


def _fresh_types():
    t = HeldOutType
    out = [
        t("ho2-reg-power-student", "student-power"),
        t("ho2-miss-hidden-excess", "hidden-excess", threshold=True),
        t("ho2-reg-saturating-gumbel", "gumbel0.6", "saturating1.2"),
        t("ho2-outlier-gated-gaussian", "gaussian0.6", outliers="gated"),
        t("ho2-mix-negative-body", "clayton90+gumbel"),
    ]
    return {x.name: x for x in out}


HELD_OUT_TYPES = _held_out_types()
"""The held-out types by name (``ho-GROUP-…``); never used to choose settings."""
HELD_OUT_GROUPS = ("miss", "outlier", "mix", "reg")
FRESH_TYPES = _fresh_types()
"""The second round of held-out types by name (``ho2-GROUP-…``, module docs): written
after the first had informed the band's diagnosis, never used for any choice."""
"""Their groups: threshold + misses, outliers, mixtures, regressions."""
