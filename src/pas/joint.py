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
* the copula parameters and a two-parameter Weibull HF marginal
  ``F_H(h) = 1 − exp(−(h/α)^β)`` are fitted together by maximising the
  conditional log-likelihood of the HF values given their LF ranks,
  ``ℓ = Σ_i [log c(u_i, F_H(h_i)) + log f_H(h_i)]``, which the selection by LF
  leaves valid (the likelihood of a regression does not depend on how its
  covariate was sampled);
* the location of the Weibull is 0 (loads are non-negative): a free location
  makes this likelihood unbounded as it approaches the smallest load with
  β < 1 (a known property of the three-parameter Weibull).

AIC (Eq. 13) counts the two marginal parameters with the copula's, so the
families are compared on the same likelihood.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyvinecopulib as pv
from scipy import optimize, special

from ._threads import one_blas_thread
from .copulas import CopulaFit, _at_bound, _family_and_rotation, kendall_tau
from .stats.weibull import Weibull3, fit_weibull3_ls

__all__ = ["JointFit", "copula_logpdf", "copula_loghfunc", "fit_joint", "fit_joint_candidates"]

_TINY = 1e-12


@dataclass(frozen=True)
class JointFit:
    """A copula and its HF Weibull marginal fitted together (module docs)."""

    copula: CopulaFit
    hf_marginal: Weibull3
    x: np.ndarray  # the optimiser's unconstrained parameters, for warm starts


def _copula_parameters(base: str, c):
    """Unconstrained optimiser values → the family's parameter matrix (inside its bounds)."""
    if base == "gaussian":
        return np.array([[0.999 * np.tanh(c[0])]])
    if base == "student":
        return np.array([[0.999 * np.tanh(c[0])], [2.0 + 48.0 / (1.0 + np.exp(-c[1]))]])
    if base == "clayton":
        return np.array([[np.clip(np.exp(c[0]), 1e-6, 28.0)]])
    if base == "gumbel":
        return np.array([[min(1.0 + np.exp(c[0]), 50.0)]])
    if base == "frank":
        return np.array([[35.0 * np.tanh(c[0] / 35.0)]])
    raise ValueError(f"no joint fit for the copula family {base!r}")


def copula_logpdf(base: str, p, u, v) -> np.ndarray:
    """``log c(u, v)`` of an unrotated family with parameters ``p`` (App. B.2), vectorised.

    Closed forms, so the joint fit's inner loop does not build a
    pyvinecopulib object per evaluation; tested against ``Bicop.pdf``.
    """
    if base == "gaussian":
        rho = p[0]
        x, y = special.ndtri(u), special.ndtri(v)
        r2 = 1.0 - rho * rho
        return -0.5 * np.log(r2) - (rho * rho * (x * x + y * y) - 2.0 * rho * x * y) / (2.0 * r2)
    if base == "student":
        rho, nu = p
        x, y = special.stdtrit(nu, u), special.stdtrit(nu, v)
        r2 = 1.0 - rho * rho
        const = (special.gammaln((nu + 2) / 2) + special.gammaln(nu / 2)
                 - 2.0 * special.gammaln((nu + 1) / 2) - 0.5 * np.log(r2))
        return (const - (nu + 2) / 2 * np.log1p((x * x + y * y - 2 * rho * x * y) / (nu * r2))
                + (nu + 1) / 2 * (np.log1p(x * x / nu) + np.log1p(y * y / nu)))
    lu, lv = np.log(u), np.log(v)
    if base == "clayton":
        th = p[0]
        return (np.log1p(th) - (1.0 + th) * (lu + lv)
                - (2.0 + 1.0 / th) * np.log(np.expm1(-th * lu) + np.expm1(-th * lv) + 1.0))
    if base == "gumbel":
        th = p[0]
        a, b = -lu, -lv
        ls = np.logaddexp(th * np.log(a), th * np.log(b))
        big_a = np.exp(ls / th)
        return (-big_a - lu - lv + (th - 1.0) * (np.log(a) + np.log(b)) + (1.0 / th - 2.0) * ls
                + np.log(big_a + th - 1.0))
    if base == "frank":
        th = p[0]
        em = -np.expm1(-th)  # 1 − e^{−θ}
        den = em - np.expm1(-th * u) * np.expm1(-th * v)
        return np.log(th * em) - th * (u + v) - 2.0 * np.log(np.abs(den))
    raise ValueError(f"no closed-form density for the copula family {base!r}")


def copula_loghfunc(base: str, p, u, v) -> np.ndarray:
    """``log C_{V|U}(v | u)`` (the h-function, ``∂C/∂u``) of an unrotated family, vectorised."""
    if base == "gaussian":
        rho = p[0]
        return special.log_ndtr((special.ndtri(v) - rho * special.ndtri(u))
                                / np.sqrt(1.0 - rho * rho))
    if base == "student":
        rho, nu = p
        x, y = special.stdtrit(nu, u), special.stdtrit(nu, v)
        z = (y - rho * x) / np.sqrt((nu + x * x) * (1.0 - rho * rho) / (nu + 1.0))
        return np.log(special.stdtr(nu + 1.0, z))
    lu, lv = np.log(u), np.log(v)
    if base == "clayton":
        th = p[0]
        return (-(th + 1.0) * lu
                - (1.0 / th + 1.0) * np.log(np.expm1(-th * lu) + np.expm1(-th * lv) + 1.0))
    if base == "gumbel":
        th = p[0]
        a, b = -lu, -lv
        ls = np.logaddexp(th * np.log(a), th * np.log(b))
        return -np.exp(ls / th) - lu + (th - 1.0) * np.log(a) + (1.0 / th - 1.0) * ls
    if base == "frank":
        th = p[0]
        num = -th * u + np.log(np.abs(np.expm1(-th * v)))
        den = np.log(np.abs(np.expm1(-th) + np.expm1(-th * u) * np.expm1(-th * v)))
        return num - den
    raise ValueError(f"no closed-form h-function for the copula family {base!r}")


def _copula_start(base: str, tau: float):
    tau = float(np.clip(tau, 0.05, 0.85))
    if base in ("gaussian", "student"):
        rho = np.sin(np.pi * tau / 2.0)
        return [np.arctanh(rho / 0.999)] + ([0.0] if base == "student" else [])
    if base == "clayton":
        return [np.log(2 * tau / (1 - tau))]
    if base == "gumbel":
        return [np.log(tau / (1 - tau))]  # θ − 1 = τ/(1−τ)
    p = pv.Bicop(family=pv.BicopFamily.frank).tau_to_parameters(tau).ravel()[0]
    return [35.0 * np.arctanh(min(p, 34.9) / 35.0)]


def _weibull_start(h, location: bool):
    """Least-squares Weibull on Weibull paper (ranks i/(n+1)) as optimiser values."""
    if location and h.size >= 3 and np.ptp(h) > 0:
        w = fit_weibull3_ls(h)
        h_min, span = h.min(), np.ptp(h)
        gap = max(h_min - w.theta, 1e-3 * span)
        return [np.log(gap / span), np.log(w.alpha), np.log(max(w.beta, 0.2))]
    x = np.log(np.sort(h))
    y = np.log(-np.log1p(-np.arange(1, h.size + 1) / (h.size + 1.0)))
    beta, c = np.polyfit(x, y, 1)
    beta = max(beta, 0.2)
    return [np.log(np.exp(-c / beta)), np.log(beta)]


def fit_joint(name: str, u, h, *, start=None, location: bool = True,
              cold: bool = True) -> JointFit:
    """Fit one copula family and the Weibull HF marginal by conditional likelihood.

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
    start : ndarray, optional
        Optimiser values of an earlier fit (``JointFit.x``): the optimiser
        starts there as well as from the least-squares Weibull and the
        copula with the pairs' Kendall τ, and keeps the better optimum (a
        warm start alone can stay in the basin of a fit to fewer pairs).
    cold : bool, default True
        With ``start``: also start from the data (slower, safer); False
        starts from ``start`` only.
    """
    family, rotation = _family_and_rotation(name)
    base = name.partition("_")[0]
    u = np.clip(np.asarray(u, float), _TINY, 1 - _TINY)
    h = np.asarray(h, float)
    if np.any(h <= 0):
        raise ValueError("the joint fit needs positive HF loads (false positives are not pairs)")
    i_min = int(np.argmin(h))
    h_min, span = float(h[i_min]), float(np.ptp(h)) or float(h[i_min])
    n_marg = 3 if location else 2

    def unpack(x):
        theta = h_min - np.exp(x[0]) * span if location else 0.0
        return theta, np.exp(x[n_marg - 2]), np.exp(x[n_marg - 1]), x[n_marg:]

    uu = 1.0 - u if rotation == 180 else u
    density = np.ones(h.size, dtype=bool)
    if location:
        density[i_min] = False

    @np.errstate(all="ignore")  # the optimiser's trial steps may overflow: scored as +inf
    def negloglik(x):
        theta, alpha, beta, c = unpack(x)
        ln_z = np.log(h - theta) - np.log(alpha)
        zb = np.exp(beta * ln_z)
        v = np.clip(-np.expm1(-zb), _TINY, 1 - _TINY)
        vv = 1.0 - v if rotation == 180 else v
        p = _copula_parameters(base, c).ravel()
        log_f = np.log(beta / alpha) + (beta - 1.0) * ln_z - zb
        val = np.sum((log_f + copula_logpdf(base, p, uu, vv))[density])
        if location:  # the smallest load, left-censored: P(H ≤ h_min | u)
            lh = copula_loghfunc(base, p, uu[~density], vv[~density])
            val += np.sum(np.log(-np.expm1(lh)) if rotation == 180 else lh)
        return -float(val) if np.isfinite(val) else 1e300

    n_par = n_marg + (2 if base == "student" else 1)
    starts = []
    if start is not None and len(start) == n_par:
        starts.append(np.asarray(start, float))  # an earlier fit
    if cold or not starts:
        tau = kendall_tau(u, h) if u.size > 2 else 0.3
        starts.append(np.r_[_weibull_start(h, location), _copula_start(base, tau)])
    res = min((optimize.minimize(negloglik, x0, method="L-BFGS-B") for x0 in starts),
              key=lambda r: r.fun)
    if not np.isfinite(res.fun) or res.fun >= 1e299:
        raise ValueError(f"joint fit of the {name} copula failed: {res.message}")
    theta, alpha, beta, c = unpack(res.x)
    cop = pv.Bicop(family=family, rotation=rotation, parameters=_copula_parameters(base, c))
    k = n_marg + float(cop.npars)
    loglik = -float(res.fun)
    fit = CopulaFit(name=name, bicop=cop, loglik=loglik, aic=2.0 * k - 2.0 * loglik,
                    npars=k, at_bound=_at_bound(cop, name))
    return JointFit(fit, Weibull3(float(theta), float(alpha), float(beta)), np.asarray(res.x))


def fit_joint_candidates(u, h, families, *, starts=None, location: bool = True,
                         cold: bool = True) -> dict[str, JointFit]:
    """:func:`fit_joint` for every family (``starts``: earlier fits by name, to warm-start)."""
    starts = starts or {}
    out = {}
    with one_blas_thread():
        for name in families:
            prev = starts.get(name)
            out[name] = fit_joint(name, u, h, start=None if prev is None else prev.x,
                                  location=location, cold=cold)
    return out
