"""Copula and HF marginal fitted together by the likelihood of HF given LF.

Beyond the paper (its §5.4 names the problem).  PAS's samples are chosen by
their LF value alone — MD spreads them uniformly over ``ln d``, so they are
tail-heavy and not i.i.d.  The law of HF *given* LF is the same in the sample
as in the population; the marginal laws are not.  Fitting rank
pseudo-observations of the sample (Eq. 5) therefore describes the sample, not
the population the predicted distribution (Eq. 8–12) is about.  Here:

* the LF ranks ``u`` are those of the LF *population* (every conditioning
  peak is known; :func:`pas.strategies.selection.population_lf_ranks`), so
  no LF marginal is fitted at all;
* the copula parameters and a three-parameter Weibull HF marginal
  ``F_H(h) = 1 − exp(−((h − θ)/α)^β)`` are fitted together by maximising the
  conditional log-likelihood of the HF values given their LF ranks,
  ``ℓ = Σ_i [log c(u_i, F_H(h_i)) + log f_H(h_i)]``, which a selection by LF
  leaves valid (the likelihood of a regression does not depend on how its
  covariate was sampled) — and which a selection by HF, such as the paper's
  Step 7 outlier removal, would not: every pair enters;
* the smallest load enters left-censored, as ``P(H ≤ h_min | u)``: with its
  density instead, the likelihood is unbounded as θ approaches it with β < 1
  (a known property of the three-parameter Weibull); θ stays in
  ``[max(0, h_min − 3·range), h_min)`` and β in [0.05, 50], so the Weibull can
  neither produce negative loads nor run off to its Gumbel limit;
* ``location=False`` gives the two-parameter Weibull (θ = 0);
* ``marginal="lognormal"`` replaces the Weibull by a three-parameter
  log-normal ``F_H(h) = Φ((ln(h − θ) − μ)/σ)`` (same location rules), whose
  tail is heavier than a Weibull's with β ≥ 1; :func:`best_per_family` keeps,
  per copula family, the marginal of higher likelihood (the same number of
  parameters, so also the lower AIC);
* a two-component Weibull mixture marginal is in :mod:`pas.models.joint_mixture`.

AIC (Eq. 13) counts the marginal's parameters with the copula's, so the
families are compared on the same likelihood.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyvinecopulib as pv
from scipy import optimize, special

from .._support.threads import one_blas_thread
from ..stats.lognormal import LogNormal3
from ..stats.weibull import Weibull3
from ..stats.weibull_mixture import WeibullMixture
from .copula_densities import GRADIENT_FAMILIES
from .copulas import CopulaFit, _at_bound, _family_and_rotation
from .joint_likelihood import (
    copula_parameters,
    fixed_pair_terms,
    loglik_and_copula_gradient,
    negloglik_closure,
)
from .joint_starts import DataStarts, copula_start
from .lbfgsb import minimise_one

__all__ = ["JOINT_FAMILIES", "HF_MARGINALS", "JointFit", "censoring_level", "fit_joint",
           "fit_joint_all", "best_per_family", "starts_cold", "location_bounds", "minimise_bounded",
           "joint_fit_result"]

HF_MARGINALS = ("weibull", "lognormal")
"""HF marginals the joint fit knows (module docs)."""

JOINT_FAMILIES = ("gaussian", "student", "clayton", "gumbel", "frank", "clayton_180", "gumbel_180")
"""Families the joint fit knows: the paper's five and the survival Clayton and Gumbel."""

_TINY = 1e-12


@dataclass(frozen=True)
class JointFit:
    """A copula and its HF marginal fitted together (module docs)."""

    copula: CopulaFit
    hf_marginal: Weibull3 | LogNormal3 | WeibullMixture
    x: np.ndarray  # the optimiser's unconstrained parameters, for warm starts
    marginal: str = "weibull"

    def __post_init__(self):
        x = np.array(self.x, dtype=float)
        x.flags.writeable = False
        object.__setattr__(self, "x", x)

    def __deepcopy__(self, memo):
        """A fit is a value (frozen, ``x`` read-only, the copula never refitted): a deep copy
        of a study's state (``tell(..., replace=True)``) shares it."""
        return self


def censoring_level(h, censor: float, location: bool) -> float:
    """The load at and below which loads enter the likelihood left-censored.

    The smallest ``censor`` fraction of the loads (with a location, at least
    the smallest one) count as "at most this load"; 0 when none.
    """
    h = np.sort(np.asarray(h, float))
    k = int(np.floor(censor * h.size))
    if location:
        k = max(k, 1)
    return float(h[min(k, h.size - 2) - 1]) if k > 0 else 0.0


def _prepare(name: str, u, h, location: bool, censor: float):
    """What both marginals' objectives share: checked data, censoring, the rotation."""
    family, rotation = _family_and_rotation(name)
    u = np.clip(np.asarray(u, float), _TINY, 1 - _TINY)
    h = np.asarray(h, float)
    if np.any(h <= 0):
        raise ValueError("the joint fit needs positive HF loads (false positives are not pairs)")
    if np.unique(h).size < 3:
        raise ValueError(f"the joint fit needs at least 3 different HF loads, got "
                         f"{np.unique(h).size} among {h.size} pairs")
    h_c = censoring_level(h, censor, location)
    span = float(np.ptp(h)) or float(h.min())
    density = h > h_c
    h = np.where(density, h, h_c)  # a censored load counts as "at most h_c"
    return name.partition("_")[0], rotation, u, h, h_c, span, density


def joint_objective(name: str, u, h, *, location: bool = True, censor: float = 0.0,
                    marginal: str = "weibull", per_pair: bool = False):
    """The negative log-likelihood of :func:`fit_joint` and how to read its parameters.

    Returns ``(negloglik, negloglik_grad, unpack)``: the objective of the
    optimiser values ``x``; the objective with its gradient (exact, but for
    Student-t's ν: a difference; None for rotated families); and ``x → (θ, α, β, copula values)``
    (log-normal: ``(θ, μ, σ, copula values)``).  ``per_pair``: the first is
    instead each pair's log-likelihood term (:func:`negloglik_closure`).
    """
    if marginal not in HF_MARGINALS:
        raise ValueError(f"marginal must be one of {HF_MARGINALS}, got {marginal!r}")
    base, rotation, u, h, h_c, span, density = _prepare(name, u, h, location, censor)
    n_marg = 3 if location else 2
    lognormal = marginal == "lognormal"

    def unpack(x):
        theta = h_c - np.exp(x[0]) * span if location else 0.0
        first = x[n_marg - 2] if lognormal else np.exp(x[n_marg - 2])
        return theta, first, np.exp(x[n_marg - 1]), x[n_marg:]

    def marginal_terms(x, unpacked=None):
        """``(log f_H(h), F_H(h), pieces the gradient needs)``; ``unpacked``: ``unpack(x)``."""
        theta, a, b, _ = unpack(x) if unpacked is None else unpacked
        w = h - theta
        if lognormal:
            z = (np.log(w) - a) / b
            log_f = -np.log(w) - np.log(b) - 0.5 * np.log(2.0 * np.pi) - 0.5 * z * z
            return log_f, np.clip(special.ndtr(z), _TINY, 1 - _TINY), (w, z)
        ln_z = np.log(w) - np.log(a)
        zb = np.exp(b * ln_z)
        log_f = np.log(b / a) + (b - 1.0) * ln_z - zb
        return log_f, np.clip(-np.expm1(-zb), _TINY, 1 - _TINY), (w, ln_z, zb)

    negloglik = negloglik_closure(base, rotation, u, density, marginal_terms, unpack, per_pair)

    censored, dens, u_scores = fixed_pair_terms(base, u, density)

    @np.errstate(all="ignore")
    def negloglik_grad(x):
        """The same with its gradient (exact but in Student-t's ν; no rotation)."""
        unpacked = unpack(x)
        b, c = unpacked[2], unpacked[3]
        log_f, v, parts = marginal_terms(x, unpacked)
        val, d_v, g_c = loglik_and_copula_gradient(base, c, u, v, log_f, density,
                                                   censored=censored, u_scores=u_scores)
        if not np.isfinite(val):
            return 1e300, np.zeros_like(x)
        if lognormal:  # a = μ, b = σ; x holds μ and ln σ
            w, z = parts
            phi = np.exp(-0.5 * z * z) / np.sqrt(2.0 * np.pi)  # dv/dz
            g_a = (dens * z / b - d_v * phi / b).sum()
            g_b = (dens * (z * z - 1.0) - d_v * phi * z).sum()
            g_t = (dens * (1.0 + z / b) / w - d_v * phi / (b * w)).sum()
        else:  # a = α, b = β; x holds ln α and ln β
            w, ln_z, zb = parts
            one_v = 1.0 - v  # dv/dzb
            g_a = (dens * b * (zb - 1.0) + d_v * one_v * (-b * zb)).sum()
            g_b = (dens * (1.0 + b * ln_z * (1.0 - zb)) + d_v * one_v * b * zb * ln_z).sum()
            g_t = (dens * (b * zb - b + 1.0) / w + d_v * one_v * (-b * zb / w)).sum()
        grad = [g_a, g_b, *g_c]
        if location:
            grad.insert(0, g_t * (-np.exp(x[0]) * span))
        g = -np.asarray(grad, float)
        return (-val, g) if np.isfinite(g).all() else (1e300, np.zeros_like(x))

    grad = negloglik_grad if base in GRADIENT_FAMILIES and rotation == 0 else None
    return negloglik, grad, unpack


def fit_joint(name: str, u, h, *, start=None, location: bool = True, censor: float = 0.0,
              cold: bool = True, marginal: str = "weibull",
              data_starts: DataStarts | None = None) -> JointFit:
    """Fit one copula family and the HF marginal by conditional likelihood.

    Parameters
    ----------
    name : str
        Copula family (``"gaussian"``, ``"student"``, ``"clayton"``,
        ``"gumbel"``, ``"frank"`` or their ``_180`` rotations).
    u : array-like, shape (m,)
        LF population ranks of the pairs, in (0, 1).
    h : array-like, shape (m,)
        Their HF loads, > 0.
    location : bool, default True
        A three-parameter Weibull marginal (location below the smallest
        load, which enters the likelihood left-censored — "a load of at most
        ``min(h)``" — so the likelihood stays bounded; module docs), or the
        two-parameter Weibull with location 0.
    censor : float, default 0
        Fraction of the smallest loads that enter left-censored, as "at most
        the largest of them" (:func:`censoring_level`): the marginal is then
        fitted to the shape of the upper loads — the tail the MPM is read
        from — while every pair still informs the copula through
        ``P(H ≤ h_c | u)``.  The likelihood analogue of the paper's
        upper-tail mode (§2.3).
    start : ndarray, optional
        Optimiser values of an earlier fit (``JointFit.x``): the optimiser
        starts there as well as from the least-squares Weibull and the
        copula with the pairs' Kendall τ, and keeps the better optimum (a
        warm start alone can stay in the basin of a fit to fewer pairs).
    cold : bool, default True
        With ``start``: also start from the data (slower, safer); False
        starts from ``start`` only.
    marginal : {"weibull", "lognormal"}, default "weibull"
        The HF marginal's family (module docs); the location rules are the
        same for both.
    data_starts : DataStarts, optional
        The cold start of these pairs, shared with the other families'
        fits (:func:`fit_joint_all`); None: computed here.
    """
    base = name.partition("_")[0]
    u = np.clip(np.asarray(u, float), _TINY, 1 - _TINY)
    h = np.asarray(h, float)
    negloglik, negloglik_grad, unpack = joint_objective(name, u, h, location=location,
                                                        censor=censor, marginal=marginal)
    lognormal = marginal == "lognormal"
    n_marg = 3 if location else 2
    n_par = n_marg + (2 if base == "student" else 1)
    # the location within three load ranges below the smallest load and at or above 0
    # (loads are non-negative, so no draw needs clipping; :func:`location_bounds`);
    # β in [0.05, 50], log-normal σ in [0.02, 10]
    shape = (np.log(0.02), np.log(10.0)) if lognormal else (np.log(0.05), np.log(50.0))
    bounds = location_bounds(h, censor, location) + [
        (None, None), shape] + [(None, None)] * (n_par - n_marg)

    def minimise(x0):
        return minimise_bounded(negloglik, negloglik_grad, x0, bounds)

    res = None
    if start is not None and len(start) == n_par:
        res = minimise(np.asarray(start, float))  # an earlier fit
    if cold or res is None or res.fun >= 1e299:
        data = DataStarts(u, h, location) if data_starts is None else data_starts
        fresh = minimise(np.r_[data.marginal(marginal), copula_start(base, data.tau())])
        res = fresh if res is None or fresh.fun < res.fun else res
    return _result(name, res, unpack, n_marg, marginal)


def _result(name: str, res, unpack, n_marg: int, marginal: str) -> JointFit:
    """The :class:`JointFit` of optimiser values ``res.x`` with value ``res.fun``."""
    theta, a, b, c = unpack(res.x)
    hf = (LogNormal3 if marginal == "lognormal" else Weibull3)(float(theta), float(a), float(b))
    return joint_fit_result(name, res, c, n_marg, hf, marginal)


def location_bounds(h, censor: float, location: bool) -> list:
    """The optimiser's bound on the location gap (empty without a location).

    The Weibull may not run off to its Gumbel limit (location → −∞, β → ∞):
    the location stays within three load ranges below the censoring level, as
    in :func:`pas.stats.weibull.fit_weibull3_ls`, and at or above 0.
    """
    if not location:
        return []
    h = np.asarray(h, float)
    h_c = censoring_level(h, censor, location)
    span = float(np.ptp(h)) or float(h.min())
    s_max = min(np.log(3.0), np.log(max(h_c, 1e-300) / span))
    return [(min(np.log(1e-9), s_max - 1.0), s_max)]


def minimise_bounded(negloglik, negloglik_grad, x0, bounds):
    """L-BFGS-B from ``x0`` clipped into ``bounds``, with the exact gradient when there is one."""
    x0 = np.array([np.clip(x, lo if lo is not None else -np.inf, hi if hi is not None else np.inf)
                   for x, (lo, hi) in zip(x0, bounds)])
    if negloglik_grad is not None:  # scipy.optimize.minimize's iterates (pas.models.lbfgsb)
        return minimise_one(negloglik_grad, x0, bounds)
    return optimize.minimize(negloglik, x0, method="L-BFGS-B", bounds=bounds)


def joint_fit_result(name: str, res, c, n_marg: int, hf, marginal: str) -> JointFit:
    """A :class:`JointFit` from an optimum: the copula, its likelihood and AIC (Eq. 13).

    ``n_marg`` marginal parameters count with the copula's; raises ValueError
    when the optimiser found no finite optimum.
    """
    if not np.isfinite(res.fun) or res.fun >= 1e299:
        raise ValueError(f"joint fit of the {name} copula failed: {res.message}")
    family, rotation = _family_and_rotation(name)
    cop = pv.Bicop(family=family, rotation=rotation,
                   parameters=copula_parameters(name.partition("_")[0], c))
    k = n_marg + float(cop.npars)
    loglik = -float(res.fun)
    fit = CopulaFit(name=name, bicop=cop, loglik=loglik, aic=2.0 * k - 2.0 * loglik,
                    npars=k, at_bound=_at_bound(cop, name))
    return JointFit(fit, hf, np.asarray(res.x), marginal)


def fit_joint_all(u, h, families, *, marginals=("weibull",), starts=None,
                  location: bool = True, censor: float = 0.0,
                  cold=True, only=None) -> dict[tuple[str, str], JointFit]:
    """:func:`fit_joint` for every copula family and HF marginal, by ``(family, marginal)``.

    ``starts``: earlier fits by the same keys, to warm-start; ``cold``: a bool
    for every family, or the families that also start cold; ``only``: the
    ``(family, marginal)`` keys to fit, the others skipped (None: all).
    """
    starts = starts or {}
    out = {}
    data = DataStarts(u, h, location)
    with one_blas_thread():
        for name in families:
            for marginal in marginals:
                if only is not None and (name, marginal) not in only:
                    continue
                prev = starts.get((name, marginal))
                out[name, marginal] = fit_joint(name, u, h, location=location, censor=censor,
                                                start=None if prev is None else prev.x,
                                                cold=starts_cold(cold, name), marginal=marginal,
                                                data_starts=data)
    return out


def starts_cold(cold, name: str) -> bool:
    """Whether family ``name`` also starts cold: ``cold`` is a bool or a collection of names."""
    return cold if isinstance(cold, bool) else name in cold


def best_per_family(fits: dict[tuple[str, str], JointFit], *,
                    by: str = "loglik") -> dict[str, JointFit]:
    """Per copula family, the HF marginal of highest likelihood (``by="aic"``: of lowest
    AIC, for marginals with different numbers of parameters); ties: the first listed."""
    score = ((lambda f: f.copula.loglik) if by == "loglik" else (lambda f: -f.copula.aic))
    out = {}
    for (name, _), fit in fits.items():
        if name not in out or score(fit) > score(out[name]):
            out[name] = fit
    return out
