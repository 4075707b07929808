"""Many joint fits of one copula family and HF marginal at once: the model band's replicates.

The band (:mod:`pas.strategies.band`) fits each family and marginal to 50
bootstrap resamples of the same pairs: 50 problems of
:func:`pas.models.joint.fit_joint` that differ in their data only.  Here
each problem keeps its own L-BFGS-B — scipy's, stepped through its
reverse-communication routine with the tolerances of
:func:`scipy.optimize.minimize`, so every problem stops where it would on
its own — and the objectives all problems ask for at a step are evaluated
in one vectorised call (:func:`pas.models.lbfgsb.minimise_together`).  A resample's
likelihood is written as its distinct pairs weighted by how often they
were drawn (:func:`weighted_pairs`): fewer t quantiles for Student-t, whose
``special.stdtrit`` is most of a band's time.  The value and gradient are
those of :func:`pas.models.joint.joint_objective` (Weibull and log-normal
marginal, unrotated families with a gradient), summed in another order — but for
Student-t's derivative in ν, which here follows from the t quantiles'
(:func:`_student_parts`: two t quantiles and two t CDFs a pair) instead of a
forward difference of the whole likelihood (four t quantiles a pair).
"""

from __future__ import annotations

import numpy as np
from scipy import special

from .._support.threads import one_blas_thread
from ..stats.lognormal import LogNormal3
from ..stats.weibull import Weibull3
from .copula_densities import (
    GRADIENT_FAMILIES,
    _log_t_pdf,
    _student_logc,
    _student_logh,
    logc_grad,
    logh_grad,
)
from .copulas import kendall_tau
from .joint import _TINY, _prepare, joint_fit_result, location_bounds
from .joint_likelihood import copula_parameters, parameter_slope
from .joint_starts import _lognormal_start, _weibull_start, copula_start
from .lbfgsb import minimise_together

__all__ = ["batchable", "weighted_pairs", "minimise_together", "fit_joint_batch"]

_T_STEP = 1e-6
"""Step in ν of the forward difference of the t CDF ``∂T_ν(x)/∂ν`` (:func:`_student_parts`)."""


def batchable(name: str, marginal: str) -> bool:
    """Whether :func:`fit_joint_batch` fits this family and marginal (else :func:`fit_joint`)."""
    return name in GRADIENT_FAMILIES and marginal in ("weibull", "lognormal")


def weighted_pairs(name, samples, *, location=True, censor=0.0, width=None):
    """The problems' data as padded ``(R, width)`` arrays of distinct pairs and their counts.

    ``samples``: per problem ``(u, h)`` as :func:`pas.models.joint.fit_joint` takes
    them.  Returns a dict of ``u``, ``h`` (censored loads at their level), ``w``
    (counts; 0 in the padding), ``density`` and per problem ``h_c``, ``span``;
    ``width``: the padded width (None: the most distinct pairs of a problem).
    The checks and censoring are :func:`pas.models.joint._prepare`'s, on the
    resample with its repeats.
    """
    rows = []
    for u, h in samples:
        _, _, u, hc, h_c, span, density = _prepare(name, u, h, location, censor)
        order = np.lexsort((hc, u))  # sorted by u, then load: the distinct pairs in turn
        u, hc, density = u[order], hc[order], density[order]
        first = np.r_[True, (u[1:] != u[:-1]) | (hc[1:] != hc[:-1])]
        count = np.diff(np.r_[np.flatnonzero(first), u.size])
        rows.append((u[first], hc[first], count, density[first], h_c, span))
    width = max(r[0].size for r in rows) if width is None else width
    out = {k: np.empty((len(rows), width)) for k in ("u", "h", "w")}
    out["density"] = np.zeros((len(rows), width), dtype=bool)
    for j, (u, h, w, d, _, _) in enumerate(rows):
        pad = width - u.size  # a copy of the first pair, weighted 0
        out["u"][j], out["h"][j] = np.r_[u, [u[0]] * pad], np.r_[h, [h[0]] * pad]
        out["w"][j], out["density"][j] = np.r_[w, np.zeros(pad)], np.r_[d, [d[0]] * pad]
    out["h_c"] = np.array([r[4] for r in rows])
    out["span"] = np.array([r[5] for r in rows])
    return out


def _copula_parts(base, c, u, v, density):
    """Per pair ``(log c or log h, ∂/∂v, ∂/∂ first parameter)`` for rows of copula values ``c``."""
    p = [q[0] for q in copula_parameters(base, [ci[:, None] for ci in c])]
    total, d_v, d_p = logc_grad(base, p, u, v)
    censored = ~density
    if censored.any():
        pc = [np.broadcast_to(q, u.shape)[censored] for q in p]
        lh, dh_v, dh_p = logh_grad(base, pc, u[censored], v[censored])
        total, d_v, d_p = (np.where(density, a, 0.0) for a in (total, d_v, d_p))
        total[censored], d_v[censored], d_p[censored] = lh, dh_v, dh_p
    return total, d_v, d_p


def _on_pairs(f, nu, a, live):
    """``f(nu, a)`` (a scipy ufunc, rows of ``nu`` (k, 1)) evaluated only where ``live``;
    elsewhere — the padding of :func:`weighted_pairs`, a copy of its row's first pair —
    the value of the row's first pair.  None: everywhere."""
    if live is None or live.all():
        return f(nu, a)
    out = np.empty(a.shape)
    out[live] = f(np.broadcast_to(nu, a.shape)[live], a[live])
    return np.where(live, out, out[:, :1])


def _t_quantile_and_slope(nu, w, live=None):
    """The t quantile ``x = t_ν⁻¹(w)`` and its ``dx/dν`` at fixed ``w``.

    ``dx/dν = −(∂T_ν(x)/∂ν) / f_ν(x)`` (implicit function theorem), with
    ``∂T_ν/∂ν`` a forward difference of the CDF from ``T_ν(x) = w``.  Both in
    the lower tail, ``x = −t_ν⁻¹(1 − w)`` above the median: there ``1 − w`` is
    exact and the CDF's difference keeps its digits (``T_ν(x)`` near 1 leaves
    ``∂T_ν/∂ν`` none).  ``live``: the pairs of weight above 0 (:func:`_on_pairs`:
    the quantiles, most of the band's time, not computed for the padding; the
    same values).
    """
    upper = w > 0.5
    tail = np.where(upper, 1.0 - w, w)
    x = _on_pairs(special.stdtrit, nu, tail, live)
    t_moved = _on_pairs(special.stdtr, nu + _T_STEP, x, live)
    slope = -(t_moved - tail) / _T_STEP * np.exp(-_log_t_pdf(x, nu))
    sign = np.where(upper, -1.0, 1.0)
    return sign * x, sign * slope


def _student_parts(rho, nu, u, v, density, live=None):
    """Student-t per pair ``(log c or, censored, log h, ∂/∂v, ∂/∂ρ, d/dν)`` for rows of
    ``rho`` and ``nu`` (k, 1).

    ``d/dν`` is the total derivative, the t quantiles ``x = t_ν⁻¹(u)`` and
    ``y = t_ν⁻¹(v)`` moving with ν (:func:`_t_quantile_and_slope`; ``live``: the pairs
    of weight above 0, the others a copy of their row's first pair).
    """
    (x, dx), (y, dy) = _t_quantile_and_slope(nu, u, live), _t_quantile_and_slope(nu, v, live)
    total, d_v, d_rho = _student_logc((rho, nu), u, v, x, y, True)
    r2 = 1.0 - rho * rho
    q = x * x + y * y - 2 * rho * x * y
    den = nu * r2 + q
    explicit = (0.5 * (special.digamma((nu + 2) / 2) + special.digamma(nu / 2))
                - special.digamma((nu + 1) / 2) - 0.5 * np.log1p(q / (nu * r2))
                + (nu + 2) / 2 * q / (nu * den)
                + 0.5 * (np.log1p(x * x / nu) + np.log1p(y * y / nu))
                - (nu + 1) / 2 * (x * x / (nu * (nu + x * x)) + y * y / (nu * (nu + y * y))))
    d_x = -(nu + 2) * (x - rho * y) / den + (nu + 1) * x / (nu + x * x)
    d_y = -(nu + 2) * (y - rho * x) / den + (nu + 1) * y / (nu + y * y)
    d_nu = explicit + d_x * dx + d_y * dy
    cens = ~density
    if cens.any():  # log h = log T_{ν+1}(z), z = (y − ρx)/s, s² = (ν + x²)(1 − ρ²)/(ν + 1)
        n1 = np.broadcast_to(nu, u.shape)[cens] + 1.0
        rc = np.broadcast_to(rho, u.shape)[cens]
        xc, yc, dxc = x[cens], y[cens], dx[cens]
        lh, dh_v, dh_rho = _student_logh((rc, n1 - 1.0), u[cens], v[cens], xc, yc, True)
        s = np.sqrt((n1 - 1.0 + xc * xc) * (1.0 - rc * rc) / n1)
        z = (yc - rc * xc) / s
        h = np.exp(lh)
        ds = 0.5 * ((1.0 + 2.0 * xc * dxc) / (n1 - 1.0 + xc * xc) - 1.0 / n1)  # ds/dν / s
        dz = (dy[cens] - rc * dxc) / s - z * ds
        d_h = (special.stdtr(n1 + _T_STEP, z) - h) / _T_STEP + np.exp(_log_t_pdf(z, n1)) * dz
        total[cens], d_v[cens], d_rho[cens], d_nu[cens] = lh, dh_v, dh_rho, d_h / h
    return total, d_v, d_rho, d_nu


def batch_objective(name: str, data: dict, *, location: bool = True, marginal: str = "weibull"):
    """``objective(X, rows) -> (negloglik (k,), gradient (k, p))`` of the problems ``rows``
    of ``data`` (:func:`weighted_pairs`) at optimiser values ``X`` (k, p), as
    :func:`pas.models.joint.joint_objective`'s ``negloglik_grad``."""
    base = name.partition("_")[0]
    n_marg = 3 if location else 2
    lognormal = marginal == "lognormal"

    @np.errstate(all="ignore")
    def objective(X, rows):
        u, h, wt, dens = (data[k][rows] for k in ("u", "h", "w", "density"))
        gap = np.exp(X[:, :1]) * data["span"][rows, None] if location else 0.0
        theta = data["h_c"][rows, None] - gap if location else 0.0
        b = np.exp(X[:, n_marg - 1:n_marg])
        a = X[:, n_marg - 2:n_marg - 1] if lognormal else np.exp(X[:, n_marg - 2:n_marg - 1])
        c = [X[:, j] for j in range(n_marg, X.shape[1])]
        w = h - theta
        if lognormal:
            z = (np.log(w) - a) / b
            log_f = -np.log(w) - np.log(b) - 0.5 * np.log(2.0 * np.pi) - 0.5 * z * z
            v = np.clip(special.ndtr(z), _TINY, 1 - _TINY)
        else:
            ln_z = np.log(w) - np.log(a)
            zb = np.exp(b * ln_z)
            log_f = np.log(b / a) + (b - 1.0) * ln_z - zb
            v = np.clip(-np.expm1(-zb), _TINY, 1 - _TINY)
        student = base == "student"
        if student:
            rho, nu = (q[0] for q in copula_parameters(base, [ci[:, None] for ci in c]))
            total, d_v, d_p, d_nu = _student_parts(rho, nu, u, v, dens, wt > 0)
        else:
            total, d_v, d_p = _copula_parts(base, c, u, v, dens)
        val = np.sum(wt * np.where(dens, log_f + total, total), axis=1)
        dens_w, d_v = wt * dens, wt * d_v
        if lognormal:  # a = μ, b = σ; X holds μ and ln σ
            phi = np.exp(-0.5 * z * z) / np.sqrt(2.0 * np.pi)
            grads = [np.sum(dens_w * (1.0 + z / b) / w - d_v * phi / (b * w), axis=1),
                     np.sum(dens_w * z / b - d_v * phi / b, axis=1),
                     np.sum(dens_w * (z * z - 1.0) - d_v * phi * z, axis=1)]
        else:  # a = α, b = β; X holds ln α and ln β
            one_v = 1.0 - v
            grads = [np.sum(dens_w * (b * zb - b + 1.0) / w + d_v * one_v * (-b * zb / w), axis=1),
                     np.sum(dens_w * b * (zb - 1.0) + d_v * one_v * (-b * zb), axis=1),
                     np.sum(dens_w * (1.0 + b * ln_z * (1.0 - zb)) + d_v * one_v * b * zb * ln_z,
                            axis=1)]
        grads[0] = grads[0] * -gap[:, 0] if location else None
        grads.append(np.sum(wt * d_p, axis=1) * parameter_slope(base, c))
        if student:  # dν/dc of ν = 2 + 48 / (1 + e^−c)
            share = 1.0 / (1.0 + np.exp(-c[1]))
            grads.append(np.sum(wt * d_nu, axis=1) * 48.0 * share * (1.0 - share))
        g = -np.column_stack([x for x in grads if x is not None])
        bad = ~np.isfinite(val) | ~np.all(np.isfinite(g), axis=1)
        return np.where(bad, 1e300, -val), np.where(bad[:, None], 0.0, g)

    return objective


def fit_joint_batch(name: str, samples, starts, *, location: bool = True, censor: float = 0.0,
                    cold: bool = True, marginal: str = "weibull", width=None,
                    memos=None) -> list:
    """:func:`pas.models.joint.fit_joint` of one family and marginal on every sample at once.

    ``samples``: per problem ``(u, h)``; ``starts``: per problem the optimiser
    values of an earlier fit or None; ``cold``: also start from the data, the
    better optimum kept (as there; a problem without a start, or whose start
    fails, starts from the data anyway); ``width``: :func:`weighted_pairs`;
    ``memos``: per problem a dict keeping what its start from the data reads
    (Kendall's τ, the least-squares Weibull), for the next call on the same
    sample (the other marginal).  Returns per problem the
    :class:`~pas.models.joint.JointFit` or the ValueError its fit raised.
    """
    base = name.partition("_")[0]
    lognormal = marginal == "lognormal"
    n_marg = 3 if location else 2
    n_par = n_marg + (2 if base == "student" else 1)
    out = [None] * len(samples)
    for j, (u, h) in enumerate(samples):
        try:
            _prepare(name, u, h, location, censor)
        except ValueError as err:
            out[j] = err
    valid = [j for j in range(len(samples)) if out[j] is None]
    if not valid:
        return out
    samples, starts = [samples[j] for j in valid], [starts[j] for j in valid]
    memos = [{} for _ in valid] if memos is None else [memos[j] for j in valid]
    data = weighted_pairs(name, samples, location=location, censor=censor, width=width)
    shape = (np.log(0.02), np.log(10.0)) if lognormal else (np.log(0.05), np.log(50.0))
    bounds = [location_bounds(h, censor, location) + [(None, None), shape]
              + [(None, None)] * (n_par - n_marg) for _, h in samples]
    objective = batch_objective(name, data, location=location, marginal=marginal)

    def run(problems, x0s):
        if not problems:
            return []
        with one_blas_thread():  # an L-BFGS-B step in five parameters (pas._support.threads)
            return minimise_together(objective, x0s, [bounds[j] for j in problems],
                                     np.array(problems, int))

    def data_start(j):
        u, h = samples[j]
        memo = memos[j]
        if "tau" not in memo:
            u = np.clip(np.asarray(u, float), _TINY, 1 - _TINY)
            memo["tau"] = kendall_tau(u, np.asarray(h, float)) if u.size > 2 else 0.3
        h = np.asarray(h, float)
        if (location or not lognormal) and ("weibull", location) not in memo:
            memo["weibull", location] = _weibull_start(h, location)
        if lognormal:
            weibull = memo["weibull", location] if location else None
            start_marginal = _lognormal_start(h, location, weibull=weibull)
        else:
            start_marginal = memo["weibull", location]
        return np.r_[start_marginal, copula_start(base, memo["tau"])]

    warm = [j for j, s in enumerate(starts) if s is not None and len(s) == n_par]
    warm_x0 = [np.asarray(starts[j], float) for j in warm]
    if cold:  # every problem's warm and cold start stepped together: half the objective calls
        fresh = list(range(len(samples)))
        both = run(warm + fresh, warm_x0 + [data_start(j) for j in fresh])
        best, fresh_res = dict(zip(warm, both[:len(warm)])), both[len(warm):]
    else:
        best = dict(zip(warm, run(warm, warm_x0)))
        fresh = [j for j in range(len(samples)) if j not in best or best[j].fun >= 1e299]
        fresh_res = run(fresh, [data_start(j) for j in fresh])
    for j, res in zip(fresh, fresh_res):
        if j not in best or res.fun < best[j].fun:
            best[j] = res
    for j, i in enumerate(valid):
        res = best[j]
        x = res.x
        theta = data["h_c"][j] - np.exp(x[0]) * data["span"][j] if location else 0.0
        first = x[n_marg - 2] if lognormal else np.exp(x[n_marg - 2])
        hf = (LogNormal3 if lognormal else Weibull3)(float(theta), float(first),
                                                      float(np.exp(x[n_marg - 1])))
        try:
            out[i] = joint_fit_result(name, res, x[n_marg:], n_marg, hf, marginal)
        except ValueError as err:
            out[i] = err
    return out
