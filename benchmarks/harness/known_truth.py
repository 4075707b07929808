"""Generated screening problems with exact truths: where PAS's defaults are chosen.

The validation analogues are measured once; method settings are chosen on
problems whose answer is known exactly (development rule of the project).

A problem is one LF Monte-Carlo "run" of ``n_w`` wave events with one LF
indicator peak each (Rayleigh, like linear crests), and for every event an HF
load drawn from a known model.  The *tuning* types (:data:`TUNING_TYPES`,
:class:`ProblemType`, the 50 types the defaults were chosen on) have

* **dependence**, either a copula — ``V | U ~ C_{V|U}(· | u)`` for a family
  and Kendall's τ, ``U = F_L(l)`` the LF population CDF over the pool (over
  the threshold when one is set), ``h = F_H⁻¹(V)`` with a Weibull HF marginal
  of shape ``hf_shape`` (smaller = heavier tail; ``hf_law="lognormal"``: a
  log-normal of log-sd ``hf_shape``, heavier than any Weibull with β ≥ 1)
  — or a regression that no candidate copula contains: ``"power"``,
  ``ln h = ln 1000 + 1.5 ln l + σ ε``, and ``"crest"``,
  ``h = 1000 (l + 0.15 l²) + 1000 σ ε`` (a second-order-crest-like HF, ε
  standard normal);
* **misses** (false positives, HF = 0): impact with probability ``p(u)`` —
  ``"none"``, ``"low"`` (clustered just above the threshold) or ``"spread"``
  (about 40 % everywhere, as the paper's green water);
* **outliers**: with probability ``outlier_p`` the load is ``outlier_k`` times
  larger, whatever the LF (timing-driven slams);
* **noise floor**: loads below ``floor`` are recorded as 0 (a sensor's noise
  threshold, as the basin's 100 kN): misses that cluster where loads are
  small.  It leaves the truth unchanged while the MPM is above the floor.

The *held-out* types (:mod:`harness.known_truth_held_out`) have forms
the tuning types lack and are never used to choose settings.

Truth, exact given the LF peaks of the data set: the MPM ``H`` solves
``Σ_j P(H_j > H | l_j) = P_exp · n_w`` (the mixture PAS estimates, Eq. 8–12
of van Essen & Seyffert 2026), with
``P(H_j > h | l_j) = p(u_j) [(1 − p_o) S(h | u_j) + p_o S(h / k | u_j)]`` and
``S(h | u) = 1 − C_{V|U}(F_H(h) | u)`` from pyvinecopulib's h-function.
Each replication redraws the LF peaks and the HF loads, and is scored
against its own truth.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyvinecopulib as pv
from scipy import stats

N_WAVES = 15_000
P_EXP = 2.0e-3
HF_SCALE = 1000.0  # kN, scale of the HF Weibull
THRESHOLD_EXCEEDANCE = 0.03  # LF threshold at the 3 % level of the Rayleigh peaks
THRESHOLD = float(np.sqrt(-2.0 * np.log(THRESHOLD_EXCEEDANCE)))
"""The LF threshold of the types that set one (Rayleigh σ = 1)."""


@dataclass(frozen=True)
class ProblemType:
    """One kind of generated tuning problem (module docs)."""

    name: str
    family: str = "gaussian"
    tau: float = 0.6
    hf_shape: float = 1.2
    hf_law: str = "weibull"  # or "lognormal" (hf_shape is then the log-sd), or "mixture"
    misses: str = "none"
    outlier_p: float = 0.0
    outlier_k: float = 3.0
    threshold: bool = False
    model: str = "copula"  # or "power", "crest" (module docs)
    sigma: float = 0.3
    floor: float = 0.0
    held_out: bool = False

    @property
    def group(self) -> str:
        """The group of the type: the first part of its name (``core``, ``miss``, …)."""
        return self.name.split("-", 1)[0]

    def loads(self, lf, u, rng) -> np.ndarray:
        """HF loads (0 for a miss) of the pool peaks ``lf`` at LF CDF values ``u``."""
        bicop = copula(self.family, self.tau)
        r = rng.uniform(1e-9, 1 - 1e-9, lf.size)
        if self.model == "power":
            h = HF_SCALE * lf**1.5 * np.exp(self.sigma * stats.norm.ppf(r))
        elif self.model == "crest":
            h = HF_SCALE * np.maximum(lf + 0.15 * lf**2 + self.sigma * stats.norm.ppf(r), 1e-3)
        else:
            h = copula_loads(self, bicop, u, r)
        if self.outlier_p > 0:
            h = np.where(rng.uniform(size=lf.size) < self.outlier_p, h * self.outlier_k, h)
        hit = rng.uniform(size=lf.size) < impact_probability(u, self.misses)
        return np.where(hit & (h >= self.floor), h, 0.0)

    def exceedance_count(self, h, lf, u) -> float:
        """``Σ_j P(H_j > h | l_j)``: expected number of pool events above ``h``."""
        bicop = copula(self.family, self.tau)
        s = conditional_sf(h, lf, u, self, bicop)
        if self.outlier_p > 0:
            s = ((1 - self.outlier_p) * s
                 + self.outlier_p * conditional_sf(h / self.outlier_k, lf, u, self, bicop))
        return float(np.sum(impact_probability(u, self.misses) * s))


def _tuning_types():
    out = []
    for fam in ("gaussian", "clayton", "gumbel", "frank"):
        # Frank's parameter bound in pyvinecopulib (35) is τ ≈ 0.89: 0.85 is its strongest
        for tau in (0.3, 0.45, 0.6, 0.75, 0.85 if fam == "frank" else 0.9):
            out.append(ProblemType(f"core-{fam}-t{tau:g}", fam, tau))
    for fam in ("gaussian", "gumbel"):
        for shape in (0.8, 3.0):
            out.append(ProblemType(f"tail-{fam}-b{shape:g}", fam, 0.6, shape))
    # the impact analogues' HF tails (truth Weibull β 0.3–0.6, cases/README.md)
    for fam in ("gaussian", "clayton"):
        out.append(ProblemType(f"tail-{fam}-b0.4", fam, 0.6, 0.4))
    # a quasi-static load with an impulsive part in some events (green water: bore + jet)
    for fam in ("gaussian", "clayton"):
        out.append(ProblemType(f"tail-{fam}-mix", fam, 0.6, hf_law="mixture"))
    for fam, sigma in (("gaussian", 0.6), ("gaussian", 1.0), ("gumbel", 1.0), ("clayton", 1.0)):
        out.append(ProblemType(f"tail-{fam}-ln{sigma:g}", fam, 0.6, sigma, hf_law="lognormal"))
    for fam in ("gaussian", "clayton"):
        for tau in (0.4, 0.7):
            for misses in ("low", "spread"):
                out.append(ProblemType(f"miss-{misses}-{fam}-t{tau:g}", fam, tau,
                                       misses=misses, threshold=True))
    for tau in (0.5, 0.8):
        out.append(ProblemType(f"outlier-gumbel-t{tau:g}", "gumbel", tau, outlier_p=0.02))
    out.append(ProblemType("outlier-miss-gaussian-t0.6", "gaussian", 0.6, misses="spread",
                           outlier_p=0.02, threshold=True))
    for fam, tau in (("gaussian", 0.6), ("clayton", 0.45)):
        out.append(ProblemType(f"floor-{fam}-t{tau:g}", fam, tau, threshold=True, floor=300.0))
    for sigma in (0.05, 0.3, 0.6):
        out.append(ProblemType(f"reg-power-s{sigma:g}", model="power", sigma=sigma))
    out.append(ProblemType("reg-crest-s0.1", model="crest", sigma=0.1))
    out.append(ProblemType("reg-power-miss-s0.3", model="power", sigma=0.3, misses="spread",
                           threshold=True))
    return {t.name: t for t in out}


TUNING_TYPES = _tuning_types()
"""The 50 types PAS's defaults were chosen on, by name."""
GROUPS = ("core", "tail", "miss", "outlier", "floor", "reg")
"""The groups of the tuning types (the first part of their names)."""


def impact_probability(u, misses: str):
    """``p(u)``: probability that an event over the pool gives an impact."""
    u = np.asarray(u, float)
    if misses == "none":
        return np.ones_like(u)
    if misses == "low":      # misses clustered just above the threshold: 60 % there, 0 at the top
        return 1.0 - 0.6 * (1.0 - u) ** 4
    if misses == "spread":   # misses everywhere: 45 % at the threshold, 30 % at the top
        return 0.55 + 0.15 * u
    raise ValueError(f"unknown miss pattern {misses!r}; use 'none', 'low' or 'spread'")


def copula(family: str, tau: float) -> pv.Bicop:
    """The pyvinecopulib copula of ``family`` at Kendall's ``tau``."""
    fam = getattr(pv.BicopFamily, family)
    b = pv.Bicop(family=fam)
    return pv.Bicop(family=fam, parameters=b.tau_to_parameters(tau))


@dataclass
class Problem:
    """One generated data set with its exact truth."""

    type: ProblemType
    replication: int
    lf: np.ndarray
    hf: np.ndarray
    n_waves: int
    p_exp: float
    threshold: float | None
    truth_mpm: float
    eps1: float

    def oracle(self):
        """The HF "simulation": the load of the event's index in the data set."""
        hf = self.hf
        return lambda event: float(hf[event.index])


def pool_cdf(lf, threshold):
    """LF population CDF over the pool (Rayleigh σ = 1, conditional on the threshold)."""
    sf = np.exp(-lf**2 / 2.0)
    if threshold is None:
        return 1.0 - sf
    sf0 = np.exp(-threshold**2 / 2.0)
    return 1.0 - sf / sf0


class WeibullMixture:
    """70 % Weibull(2, HF_SCALE) (quasi-static) and 30 % Weibull(0.7, 2.5 HF_SCALE)
    (impulsive): ``cdf`` exact, ``ppf`` by interpolation on ln h (relative error < 1e-6)."""

    parts = ((0.7, stats.weibull_min(2.0, scale=HF_SCALE)),
             (0.3, stats.weibull_min(0.7, scale=2.5 * HF_SCALE)))

    def __init__(self):
        self._ln_h = np.linspace(np.log(1e-6 * HF_SCALE), np.log(1e3 * HF_SCALE), 200_001)
        self._p = self.cdf(np.exp(self._ln_h))

    def cdf(self, x):
        return sum(w * d.cdf(x) for w, d in self.parts)

    def ppf(self, q):
        return np.exp(np.interp(q, self._p, self._ln_h))


def hf_law(ptype: ProblemType):
    """The HF marginal of a copula-type problem (frozen scipy distribution or a mixture)."""
    if ptype.hf_law == "lognormal":
        return stats.lognorm(ptype.hf_shape, scale=HF_SCALE)
    if ptype.hf_law == "mixture":
        return WeibullMixture()
    return stats.weibull_min(ptype.hf_shape, scale=HF_SCALE)


def copula_loads(ptype: ProblemType, bicop, u, r) -> np.ndarray:
    """HF loads of a copula-type problem at LF CDF values ``u`` from uniforms ``r``."""
    v = bicop.hinv1(np.column_stack([u, r]))
    return hf_law(ptype).ppf(np.clip(v, 1e-12, 1 - 1e-12))


def conditional_sf(x, lf, u, ptype: ProblemType, bicop) -> np.ndarray:
    """``P(H > x | l)`` given an impact, before outliers, for every pool peak."""
    if ptype.model == "power":
        return stats.norm.sf((np.log(x / HF_SCALE) - 1.5 * np.log(lf)) / ptype.sigma)
    if ptype.model == "crest":
        return stats.norm.sf((x / HF_SCALE - lf - 0.15 * lf**2) / ptype.sigma)
    v = np.clip(hf_law(ptype).cdf(x), 1e-12, 1 - 1e-12)
    return 1.0 - bicop.hfunc1(np.column_stack([u, np.full(u.size, v)]))


def truth_mpm(exceedance_count, n_waves, p_exp) -> float:
    """The ``h`` with ``exceedance_count(h) = P_exp · n_w`` (bisection on ``ln h``).

    ``exceedance_count`` is ``h ↦ Σ_j P(H_j > h | l_j)``, decreasing in ``h``.
    """
    target = p_exp * n_waves
    lo, hi = np.log(1e-3 * HF_SCALE), np.log(1e3 * HF_SCALE)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if exceedance_count(np.exp(mid)) > target:
            lo = mid
        else:
            hi = mid
    return float(np.exp(0.5 * (lo + hi)))


def type_seed(name: str, replication: int) -> list[int]:
    """The seed of data set ``replication`` of the type called ``name``."""
    return [int.from_bytes(name.encode()[:8].ljust(8, b"\0"), "little"), int(replication)]


def make_problem(ptype, replication: int, *, n_waves=N_WAVES, p_exp=P_EXP,
                 eps1_fraction=0.015) -> Problem:
    """Draw data set ``replication`` of ``ptype`` (seeded by its name and ``replication``).

    ``ptype`` is a tuning :class:`ProblemType` or a held-out type: anything with
    ``name``, ``threshold`` (bool), ``floor``, ``loads(lf, u, rng)`` and
    ``exceedance_count(h, lf, u)``.
    """
    rng = np.random.default_rng(type_seed(ptype.name, replication))
    lf_all = rng.rayleigh(1.0, n_waves)
    threshold = THRESHOLD if ptype.threshold else None
    lf = lf_all if threshold is None else lf_all[lf_all > threshold]
    u = pool_cdf(lf, threshold)
    h = ptype.loads(lf, u, rng)
    truth = truth_mpm(lambda x: ptype.exceedance_count(x, lf, u), n_waves, p_exp)
    if truth <= ptype.floor:
        raise ValueError(f"{ptype.name}: the MPM {truth:.4g} is below the noise floor")
    return Problem(ptype, replication, lf, h, n_waves, p_exp, threshold, truth,
                   eps1_fraction * truth)
