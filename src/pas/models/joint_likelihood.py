"""The copula part of the joint likelihood of :mod:`pas.models.joint` and
:mod:`pas.models.joint_mixture`.

The optimiser's unconstrained values and the family's parameters, the
copula terms of ``ℓ = Σ [log c(u, F_H(h)) + log f_H(h)]`` (with the
left-censored loads as ``log P(H ≤ h_c | u)``), their gradient, and the
negative log-likelihood closure every HF marginal shares.
"""

from __future__ import annotations

import numpy as np

from .copula_densities import censored_terms, copula_loghfunc, copula_logpdf, scores

__all__ = ["copula_parameters", "parameter_slope", "loglik_and_copula_gradient",
           "negloglik_closure", "NU_STEP"]


_PAST_BOUNDS = 4.0
"""exp(4) = 54.6 lies past the Clayton and Gumbel bounds (28, 50): a larger optimiser value
gives the bound all the same, and exp() of it would overflow."""


def copula_parameters(base: str, c):
    """Unconstrained optimiser values → the family's parameter matrix (inside its bounds);
    with an array of values per parameter, shape ``(npar, 1, *values.shape)``."""
    if base == "gaussian":
        return np.array([[0.999 * np.tanh(c[0])]])
    if base == "student":
        with np.errstate(over="ignore"):  # exp(-c) = inf is ν = 2, its bound
            nu = 2.0 + 48.0 / (1.0 + np.exp(-c[1]))
        return np.array([[0.999 * np.tanh(c[0])], [nu]])
    if base == "clayton":
        return np.array([[np.clip(np.exp(np.minimum(c[0], _PAST_BOUNDS)), 1e-6, 28.0)]])
    if base == "gumbel":
        return np.array([[np.minimum(1.0 + np.exp(np.minimum(c[0], _PAST_BOUNDS)), 50.0)]])
    if base == "frank":
        return np.array([[35.0 * np.tanh(c[0] / 35.0)]])
    raise ValueError(f"no joint fit for the copula family {base!r}")


def parameter_slope(base: str, c) -> float:
    """``dθ/dc`` of :func:`copula_parameters` for the first parameter (Student-t: ρ);
    elementwise for an array of optimiser values per parameter."""
    if base in ("gaussian", "student"):
        return 0.999 * (1.0 - np.tanh(c[0]) ** 2)
    e = np.exp(np.minimum(c[0], _PAST_BOUNDS))
    if base == "clayton":
        return np.where((1e-6 < e) & (e < 28.0), e, 0.0)
    if base == "gumbel":
        return np.where(1.0 + e < 50.0, e, 0.0)
    return 1.0 - np.tanh(c[0] / 35.0) ** 2  # frank


def _copula_terms(base, rotation, p, u, v, log_f, density) -> float:
    """``Σ log f + log c`` over the loads with a density, ``Σ log P(H ≤ h_c | u)`` over the rest."""
    uu, vv = (1.0 - u, 1.0 - v) if rotation == 180 else (u, v)
    val = np.sum((log_f + copula_logpdf(base, p, uu, vv))[density])
    if not density.all():  # the censored loads: P(H ≤ h_c | u)
        lh = copula_loghfunc(base, p, uu[~density], vv[~density])
        val += np.sum(np.log(-np.expm1(lh)) if rotation == 180 else lh)
    return val


def _pair_terms(base, rotation, p, u, v, log_f, density) -> np.ndarray:
    """Each pair's term of :func:`_copula_terms`: ``log f + log c``, or ``log P(H ≤ h_c | u)``."""
    uu, vv = (1.0 - u, 1.0 - v) if rotation == 180 else (u, v)
    out = log_f + copula_logpdf(base, p, uu, vv)
    if not density.all():
        lh = copula_loghfunc(base, p, uu[~density], vv[~density])
        out[~density] = np.log(-np.expm1(lh)) if rotation == 180 else lh
    return out


NU_STEP = 1e-6
"""Step in Student-t's optimiser value of ν for its one forward difference."""


def fixed_pair_terms(base: str, u, density):
    """What every gradient evaluation reads of the fixed pairs: ``(censored indices,
    density as 0/1 floats, scores of u)`` (the Student-t scores depend on ν: None)."""
    u_scores = None if base == "student" else scores(base, None, u)
    return np.flatnonzero(~density), density.astype(float), u_scores


def loglik_and_copula_gradient(base, c, u, v, log_f, density, *, censored=None, u_scores=None):
    """The log-likelihood and the copula part of its gradient: ``(value, ∂/∂v per pair,
    gradient in the copula's optimiser values c)`` (no rotation; the marginal's chain
    rule is the caller's).

    ``censored``: the indices of the pairs not in ``density`` and ``u_scores`` the
    scores of ``u`` (:func:`~pas.models.copula_densities.censored_terms`), when the
    caller keeps them.  Student-t's ν enters through the t quantiles of ``u`` and ``v``,
    whose derivative in ν has no closed form: its component is a forward difference
    of the copula terms in ``c[1]`` (the marginal terms do not depend on it).
    """
    if censored is None:
        censored = np.flatnonzero(~density)
    p = copula_parameters(base, c).ravel()
    total, d_v, d_p = censored_terms(base, p, u, v, censored, u_scores=u_scores)
    g_c = [d_p.sum() * parameter_slope(base, c)]
    if base == "student":
        step = np.array([0.0, NU_STEP])
        moved = censored_terms(base, copula_parameters(base, c + step).ravel(), u, v, censored,
                               grad=False)[0]
        # the same sums as Σ log c over the densities and Σ log h over the censored
        moved_sum = moved[density].sum()
        if censored.size:
            moved_sum += moved[censored].sum()
        g_c.append((float(moved_sum) - float(total.sum())) / NU_STEP)
    return float(np.where(density, log_f + total, total).sum()), d_v, g_c


def negloglik_closure(base, rotation, u, density, marginal_terms, unpack, per_pair=False):
    """The negative log-likelihood of optimiser values ``x`` (+1e300 where not finite).

    ``marginal_terms(x)`` gives ``(log f_H(h), F_H(h), …)``; ``unpack(x)`` ends
    with the copula's optimiser values.  ``per_pair``: instead, each pair's
    log-likelihood term (their sum is the log-likelihood).
    """
    if per_pair:
        @np.errstate(all="ignore")
        def pair_logliks(x):
            log_f, v, _ = marginal_terms(x)
            p = copula_parameters(base, unpack(x)[-1]).ravel()
            return _pair_terms(base, rotation, p, u, v, log_f, density)

        return pair_logliks

    @np.errstate(all="ignore")  # the optimiser's trial steps may overflow: scored as +inf
    def negloglik(x):
        log_f, v, _ = marginal_terms(x)
        p = copula_parameters(base, unpack(x)[-1]).ravel()
        val = _copula_terms(base, rotation, p, u, v, log_f, density)
        return -float(val) if np.isfinite(val) else 1e300

    return negloglik
