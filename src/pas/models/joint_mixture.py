"""The joint conditional fit (:mod:`pas.models.joint`) with a two-component Weibull mixture HF
marginal.

Beyond the paper.  Impact loads are a narrow quasi-static body and a wide
impulsive tail (:mod:`pas.stats.weibull_mixture`); one Weibull fitted to all
of them bends its tail towards the body.  The likelihood is that of
:func:`pas.models.joint.fit_joint` — ``Σ log c(u, F_H(h)) + log f_H(h)``, the
smallest load left-censored — with ``F_H`` the mixture: a common location
``θ``, a weight ``p`` in [0.02, 0.98] and two scales and shapes (β in
[0.3, 20]).  The optimiser starts from the family's Weibull fit split into
a narrower, lower and a wider, higher component, and from an earlier mixture
fit when given.  Seven or eight parameters against the Weibull's four or
five, so callers compare by AIC (``pas.models.joint.best_per_family(..., by="aic")``).
"""

from __future__ import annotations

import numpy as np

from .._support.threads import one_blas_thread
from ..stats.weibull_mixture import (
    LN_SHAPE_BOUNDS,
    WEIGHT_LOW,
    WEIGHT_SPAN,
    WeibullMixture,
    split_start,
)
from .copula_densities import GRADIENT_FAMILIES
from .joint import (
    HF_MARGINALS,
    JointFit,
    _prepare,
    best_per_family,
    fit_joint_all,
    joint_fit_result,
    joint_objective,
    location_bounds,
    minimise_bounded,
    starts_cold,
)
from .joint_likelihood import (
    fixed_pair_terms,
    loglik_and_copula_gradient,
    negloglik_closure,
)

__all__ = [
    "HF_CHOICES",
    "MIXTURE",
    "fit_hf_candidates",
    "fit_joint_mixture",
    "fit_joint_mixture_all",
    "pair_logliks",
]

MIXTURE = "weibull_mixture"
HF_CHOICES = (*HF_MARGINALS, "both", MIXTURE)
"""What ``hf_marginal`` may ask for (:func:`fit_hf_candidates`)."""
_TINY = 1e-12


def _unpack(x, location, h_c, span):
    """Optimiser values → ``(θ, p, α1, β1, α2, β2, copula values)``."""
    k = 1 if location else 0
    theta = h_c - np.exp(x[0]) * span if location else 0.0
    sig = 1.0 / (1.0 + np.exp(-x[k]))
    a1, b1, a2, b2 = np.exp(x[k + 1:k + 5])
    return theta, WEIGHT_LOW + WEIGHT_SPAN * sig, a1, b1, a2, b2, x[k + 5:]


def mixture_objective(name: str, u, h, *, location: bool = True, censor: float = 0.0,
                      per_pair: bool = False):
    """``(negloglik, negloglik_grad or None, unpack)`` as :func:`pas.models.joint.joint_objective`
    (``per_pair`` as there)."""
    base, rotation, u, h, h_c, span, density = _prepare(name, u, h, location, censor)

    def unpack(x):
        return _unpack(x, location, h_c, span)

    def marginal_terms(x):
        theta, p, a1, b1, a2, b2, _ = unpack(x)
        w = h - theta
        parts = []
        for a, b in ((a1, b1), (a2, b2)):
            ln_r = np.log(w) - np.log(a)
            z = np.exp(b * ln_r)
            parts.append((a, b, ln_r, z, np.log(b / a) + (b - 1.0) * ln_r - z, np.exp(-z)))
        l1, l2 = np.log(p) + parts[0][4], np.log1p(-p) + parts[1][4]
        log_f = np.logaddexp(l1, l2)
        # F from each component's −expm1(−z), exact near θ where 1 − S loses digits
        cdf = -p * np.expm1(-parts[0][3]) - (1.0 - p) * np.expm1(-parts[1][3])
        return log_f, np.clip(cdf, _TINY, 1 - _TINY), (w, p, parts, l1 - log_f, l2 - log_f)

    negloglik = negloglik_closure(base, rotation, u, density, marginal_terms, unpack, per_pair)

    censored, dens, u_scores = fixed_pair_terms(base, u, density)

    @np.errstate(all="ignore")
    def negloglik_grad(x):
        """The same with its gradient (exact but in Student-t's ν; no rotation)."""
        c = unpack(x)[6]
        log_f, v, (w, p, parts, ln_r1, ln_r2) = marginal_terms(x)
        val, d_v, g_c = loglik_and_copula_gradient(base, c, u, v, log_f, density,
                                                   censored=censored, u_scores=u_scores)
        if not np.isfinite(val):
            return 1e300, np.zeros_like(x)
        weights = (p, 1.0 - p)
        resp = (np.exp(ln_r1), np.exp(ln_r2))  # each component's share of the density
        g_t = 0.0
        grad = []
        for (a, b, ln_r, z, _, s), wk, rk in zip(parts, weights, resp):
            # ∂ log f_k and ∂S_k by ln α, ln β, θ; F = 1 − Σ w_k S_k
            dl_a, ds_a = b * (z - 1.0), s * b * z
            dl_b, ds_b = 1.0 + b * ln_r * (1.0 - z), -s * z * b * ln_r
            dl_t, ds_t = (b * z - b + 1.0) / w, s * b * z / w
            grad += [np.sum(dens * rk * dl_a - d_v * wk * ds_a),
                     np.sum(dens * rk * dl_b - d_v * wk * ds_b)]
            g_t += np.sum(dens * rk * dl_t - d_v * wk * ds_t)
        s1, s2 = parts[0][5], parts[1][5]
        sig = (p - WEIGHT_LOW) / WEIGHT_SPAN
        dp_dx = WEIGHT_SPAN * sig * (1.0 - sig)
        g_p = np.sum(dens * (resp[0] / p - resp[1] / (1.0 - p)) - d_v * (s1 - s2)) * dp_dx
        grad = ([g_t * (-np.exp(x[0]) * span)] if location else []) + [g_p] + grad + g_c
        g = -np.asarray(grad, float)
        return (-val, g) if np.all(np.isfinite(g)) else (1e300, np.zeros_like(x))

    grad = negloglik_grad if base in GRADIENT_FAMILIES and rotation == 0 else None
    return negloglik, grad, unpack


def _split_start(weibull: JointFit, location: bool):
    """Optimiser values that split a Weibull joint fit into a body and a tail component."""
    x = np.asarray(weibull.x, float)
    n_marg = 3 if location else 2
    return np.r_[x[:1] if location else [], [0.4], split_start(x[n_marg - 2], x[n_marg - 1]),
                 x[n_marg:]]


def fit_joint_mixture(name: str, u, h, weibull: JointFit, *, start=None, location: bool = True,
                      censor: float = 0.0, cold: bool = True) -> JointFit:
    """Fit one copula family with the Weibull-mixture HF marginal (module docs).

    ``weibull`` is the same family's :func:`pas.models.joint.fit_joint` result, split
    into a body and a tail (the cold start); ``start`` an earlier mixture
    fit's optimiser values (the warm start; with ``cold=False`` the only one,
    unless it reaches no finite optimum: then the cold start is tried too, as
    in :func:`pas.models.joint.fit_joint`).  Raises ValueError when no start reaches a
    finite optimum.
    """
    negloglik, negloglik_grad, unpack = mixture_objective(name, u, h, location=location,
                                                          censor=censor)
    n_cop = 2 if name.partition("_")[0] == "student" else 1
    bounds = (
        location_bounds(h, censor, location)
        + [(-8.0, 8.0), (None, None), LN_SHAPE_BOUNDS, (None, None), LN_SHAPE_BOUNDS]
        + [(None, None)] * n_cop
    )
    def minimise(x0):
        return minimise_bounded(negloglik, negloglik_grad, x0, bounds)

    res = None
    if start is not None and len(start) == len(bounds):
        res = minimise(np.asarray(start, float))  # an earlier fit
    if cold or res is None or res.fun >= 1e299:  # as fit_joint: a failed warm start goes cold
        fresh = minimise(_split_start(weibull, location))
        res = fresh if res is None or fresh.fun < res.fun else res
    theta, p, a1, b1, a2, b2, c = unpack(res.x)
    hf = WeibullMixture(float(theta), float(p), float(a1), float(b1), float(a2), float(b2))
    return joint_fit_result(name, res, c, len(bounds) - n_cop, hf, MIXTURE)


def fit_joint_mixture_all(u, h, weibull_fits: dict, *, starts=None, location: bool = True,
                          censor: float = 0.0, cold=True,
                          only=None) -> dict[tuple[str, str], JointFit]:
    """:func:`fit_joint_mixture` for every family of ``weibull_fits`` (keys ``(family,
    "weibull")``).

    A family whose mixture fit fails keeps its Weibull (it gets no mixture
    entry); ``only``: the keys to fit (None: all).
    """
    starts = starts or {}
    out = {}
    with one_blas_thread():
        for (name, marginal), weibull in weibull_fits.items():
            if marginal != "weibull" or (only is not None and (name, MIXTURE) not in only):
                continue
            prev = starts.get((name, MIXTURE))
            try:
                out[name, MIXTURE] = fit_joint_mixture(
                    name, u, h, weibull, location=location, censor=censor,
                    cold=starts_cold(cold, name),
                    start=None if prev is None else prev.x)
            except ValueError:
                continue
    return out


def pair_logliks(fit: JointFit, u, h, *, location: bool = True,
                 censor: float = 0.0) -> np.ndarray:
    """Each pair's log-likelihood term at the optimum of ``fit`` (a joint fit to ``u``, ``h``
    of either marginal kind); their sum is ``fit.copula.loglik``."""
    kind = {} if fit.marginal == MIXTURE else {"marginal": fit.marginal}
    objective = mixture_objective if fit.marginal == MIXTURE else joint_objective
    return objective(fit.copula.name, u, h, location=location, censor=censor, per_pair=True,
                     **kind)[0](fit.x)


def fit_hf_candidates(u, h, families, choice: str, *, starts=None, location: bool = True,
                      censor: float = 0.0, cold=True, only=None):
    """The joint fits an ``hf_marginal`` choice asks for, and per family the one kept.

    ``choice``: one marginal of :data:`pas.models.joint.HF_MARGINALS`; ``"both"`` (the
    Weibull and the log-normal, the higher likelihood kept); :data:`MIXTURE`
    (the Weibull and the mixture); or ``"all"`` (the three).  With the mixture,
    which has three parameters more, the lower AIC is kept.
    ``censor`` and ``cold`` (a bool, or the families that also start cold) go
    to every fit (:func:`pas.models.joint.fit_joint`); ``only``: the
    ``(family, marginal)`` keys to fit (None: all; a mixture needs its Weibull).
    Returns ``(every fit by (family, marginal), the kept fit by family)``.
    """
    marginals = {"both": HF_MARGINALS, MIXTURE: ("weibull",),
                 "all": HF_MARGINALS}.get(choice, (choice,))
    every = fit_joint_all(u, h, families, marginals=marginals, starts=starts,
                          location=location, censor=censor, cold=cold, only=only)
    mixture = choice in (MIXTURE, "all")
    if mixture:
        every |= fit_joint_mixture_all(u, h, every, starts=starts, location=location,
                                       censor=censor, cold=cold, only=only)
    return every, best_per_family(every, by="aic" if mixture else "loglik")
