"""Closed-form copula log-densities and h-functions, with their derivatives.

The joint fit of :mod:`pas.models.joint` evaluates these hundreds of times per PAS
iteration on ≤ 160 pairs, where building a pyvinecopulib object per call
costs more than the formulas; the derivatives give the optimiser exact
gradients.  Unrotated families of App. B.2: Gaussian (ρ), Student-t (ρ, ν),
Clayton, Gumbel and Frank (θ).  Tested against
``pyvinecopulib.Bicop.pdf``/``hfunc1`` and against finite differences.

``logc_grad(base, p, u, v)`` returns ``(log c, ∂/∂v, ∂/∂p)`` and
``logh_grad(base, p, u, v)`` the same for ``log C_{V|U}(v | u)``; the
derivative in ``p`` is for the first parameter of the family (Student-t: ρ;
its ν moves the t quantiles ``t_ν⁻¹(u)``, which have no closed-form
derivative in ν: :mod:`pas.models.joint` takes that one by a difference).

Both read each coordinate through its :func:`scores` (normal or t quantiles,
logarithms), which :func:`censored_terms` — the copula terms of the joint
likelihood at every pair — computes once for the densities and the censored
pairs alike, and which a caller may keep for the fixed ``u``.
"""

from __future__ import annotations

import numpy as np
from scipy import special

__all__ = ["copula_logpdf", "copula_loghfunc", "logc_grad", "logh_grad", "GRADIENT_FAMILIES",
           "scores", "censored_terms"]

GRADIENT_FAMILIES = ("gaussian", "student", "clayton", "gumbel", "frank")
"""Families with analytic derivatives in ``v`` and their first parameter."""


def copula_logpdf(base: str, p, u, v) -> np.ndarray:
    """``log c(u, v)`` of an unrotated family with parameters ``p``, vectorised."""
    return logc_grad(base, p, u, v, grad=False)[0]


def copula_loghfunc(base: str, p, u, v) -> np.ndarray:
    """``log C_{V|U}(v | u)`` (the h-function, ``∂C/∂u``) of an unrotated family, vectorised."""
    return logh_grad(base, p, u, v, grad=False)[0]


def scores(base: str, p, w):
    """What the formulas of family ``base`` read of one coordinate ``w``: normal (Gaussian)
    or t (Student-t, ν = ``p[1]``) quantiles, ``ln w`` (Clayton), ``(ln w, ln(−ln w))``
    (Gumbel), or None (Frank reads ``w`` itself)."""
    if base == "gaussian":
        return special.ndtri(w)
    if base == "student":
        return special.stdtrit(p[1], w)
    if base == "clayton":
        return np.log(w)
    if base == "gumbel":
        lw = np.log(w)
        return lw, np.log(-lw)
    return None


def _take(score, index):
    """The scores of the pairs at ``index``."""
    if score is None:
        return None
    return tuple(s[index] for s in score) if isinstance(score, tuple) else score[index]


def censored_terms(base: str, p, u, v, censored, *, u_scores=None, grad: bool = True):
    """``(term, ∂/∂v, ∂/∂p)`` per pair: ``log c`` of every pair, but ``log h`` at the
    indices ``censored`` (the left-censored loads' ``log P(V ≤ v | u)``).

    The scores of ``u`` and ``v`` (:func:`scores`) are computed once for both;
    ``u_scores``: those of ``u`` when the caller keeps them (not Student-t's, which move
    with ν).  The derivatives are None when ``grad`` is False.
    """
    logc, logh = _formula(_LOGC, base, "density"), _formula(_LOGH, base, "h-function")
    tu = scores(base, p, u) if u_scores is None else u_scores
    tv = scores(base, p, v)
    out = logc(p, u, v, tu, tv, grad)
    if censored.size:
        cens = logh(p, u[censored], v[censored], _take(tu, censored), _take(tv, censored),
                           grad)
        for full, part in zip(out, cens):
            if full is not None:
                full[censored] = part
    return out


def _log_t_pdf(y, nu):
    """``log f_ν(y)``, the Student-t density."""
    return (special.gammaln((nu + 1) / 2) - special.gammaln(nu / 2) - 0.5 * np.log(nu * np.pi)
            - (nu + 1) / 2 * np.log1p(y * y / nu))


def _student_logc(p, u, v, x, y, grad: bool):
    """Student-t ``(log c, ∂/∂v, ∂/∂ρ)`` with ``x = t_ν⁻¹(u)``, ``y = t_ν⁻¹(v)``."""
    rho, nu = p
    r2 = 1.0 - rho * rho
    q = x * x + y * y - 2 * rho * x * y
    const = (special.gammaln((nu + 2) / 2) + special.gammaln(nu / 2)
             - 2.0 * special.gammaln((nu + 1) / 2) - 0.5 * np.log(r2))
    val = (const - (nu + 2) / 2 * np.log1p(q / (nu * r2))
           + (nu + 1) / 2 * (np.log1p(x * x / nu) + np.log1p(y * y / nu)))
    if not grad:
        return val, None, None
    den = nu * r2 + q
    d_y = -(nu + 2) * (y - rho * x) / den + (nu + 1) * y / (nu + y * y)
    dv = d_y * np.exp(-_log_t_pdf(y, nu))  # dy/dv = 1 / f_ν(y)
    drho = rho / r2 + (nu + 2) * ((nu * rho + x * y) / den - rho / r2)
    return val, dv, drho


def _student_logh(p, u, v, x, y, grad: bool):
    """Student-t ``(log h, ∂/∂v, ∂/∂ρ)``: ``h = T_{ν+1}((y − ρx) / s)``,
    ``s² = (ν + x²)(1 − ρ²)/(ν + 1)``."""
    rho, nu = p
    r2 = 1.0 - rho * rho
    s = np.sqrt((nu + x * x) * r2 / (nu + 1.0))
    z = (y - rho * x) / s
    val = np.log(special.stdtr(nu + 1.0, z))
    if not grad:
        return val, None, None
    ratio = np.exp(_log_t_pdf(z, nu + 1.0) - val)  # f_{ν+1}(z) / T_{ν+1}(z)
    dv = ratio / s * np.exp(-_log_t_pdf(y, nu))
    drho = ratio * (-x / s + z * rho / r2)
    return val, dv, drho


def _frank_den(th, u, v):
    """``(1 − e^{−θ}) − (1 − e^{−θu})(1 − e^{−θv})`` without the cancellation of
    that form at large θ: ``e^{−θu} + e^{−θv} − e^{−θ(u+v)} − e^{−θ}``."""
    return np.exp(-th * u) + np.exp(-th * v) - np.exp(-th * (u + v)) - np.exp(-th)


def _clayton_sum(th, lu, lv):
    """``s = u^{−θ} + v^{−θ} − 1`` and ``ln s`` (Clayton)."""
    s = np.expm1(-th * lu) + np.expm1(-th * lv) + 1.0
    return s, np.log(s)


def _clayton_slope(th, lu, lv):
    """``v^{−θ}`` and ``∂s/∂θ`` (Clayton)."""
    vt = np.exp(-th * lv)
    return vt, -(np.exp(-th * lu) * lu + vt * lv)


def _gumbel_sum(th, la, lb):
    """``ln S`` with ``S = a^θ + b^θ`` (``a = −ln u``, ``b = −ln v``), and ``S^{1/θ}`` (Gumbel)."""
    ls = np.logaddexp(th * la, th * lb)
    return ls, np.exp(ls / th)


def _gumbel_slope(th, la, lb, ls, big):
    """``b^{θ−1}/S``, ``S'/S`` (θ-derivative) and ``∂S^{1/θ}/∂θ`` (Gumbel)."""
    r = np.exp((th - 1.0) * lb - ls)
    ds_s = (np.exp(th * la - ls) * la + np.exp(th * lb - ls) * lb)
    return r, ds_s, big * (-ls / th**2 + ds_s / th)


def _gaussian_logc(p, u, v, x, y, grad: bool):
    th = p[0]
    r2 = 1.0 - th * th
    q = th * th * (x * x + y * y) - 2.0 * th * x * y
    val = -0.5 * np.log(r2) - q / (2.0 * r2)
    if not grad:
        return val, None, None
    dv = -(th * th * y - th * x) / r2 * np.sqrt(2 * np.pi) * np.exp(0.5 * y * y)
    dth = th / r2 - ((th * (x * x + y * y) - x * y) * r2 + th * q) / (r2 * r2)
    return val, dv, dth


def _clayton_logc(p, u, v, lu, lv, grad: bool):
    th = p[0]
    s, ls = _clayton_sum(th, lu, lv)
    val = np.log1p(th) - (1.0 + th) * (lu + lv) - (2.0 + 1.0 / th) * ls
    if not grad:
        return val, None, None
    vt, ds = _clayton_slope(th, lu, lv)
    dv = -(1.0 + th) / v + (2.0 * th + 1.0) * vt / (v * s)
    dth = 1.0 / (1.0 + th) - (lu + lv) + ls / th**2 - (2.0 + 1.0 / th) * ds / s
    return val, dv, dth


def _gumbel_logc(p, u, v, tu, tv, grad: bool):
    th = p[0]
    (lu, la), (lv, lb) = tu, tv
    b = -lv
    ls, big = _gumbel_sum(th, la, lb)
    val = -big - lu - lv + (th - 1.0) * (la + lb) + (1.0 / th - 2.0) * ls + np.log(big + th - 1.0)
    if not grad:
        return val, None, None
    r, ds_s, dbig = _gumbel_slope(th, la, lb, ls, big)
    d_b = -big * r + (th - 1.0) / b + (1.0 - 2.0 * th) * r + big * r / (big + th - 1.0)
    dv = -d_b / v - 1.0 / v
    dth = -dbig + la + lb - ls / th**2 + (1.0 / th - 2.0) * ds_s + (dbig + 1.0) / (big + th - 1.0)
    return val, dv, dth


def _frank_logc(p, u, v, tu, tv, grad: bool):
    th = p[0]
    em = -np.expm1(-th)
    eu, ev = np.expm1(-th * u), np.expm1(-th * v)
    den = _frank_den(th, u, v)
    val = np.log(th * em) - th * (u + v) - 2.0 * np.log(np.abs(den))
    if not grad:
        return val, None, None
    fv = np.exp(-th * v)
    dv = -th - 2.0 * th * eu * fv / den
    dden = np.exp(-th) + u * np.exp(-th * u) * ev + v * fv * eu
    dth = 1.0 / th + np.exp(-th) / em - (u + v) - 2.0 * dden / den
    return val, dv, dth


def _gaussian_logh(p, u, v, x, y, grad: bool):
    th = p[0]
    sr = np.sqrt(1.0 - th * th)
    z = (y - th * x) / sr
    val = special.log_ndtr(z)
    if not grad:
        return val, None, None
    mills = np.exp(-0.5 * z * z - val) / np.sqrt(2 * np.pi)  # φ(z)/Φ(z)
    dv = mills / sr * np.sqrt(2 * np.pi) * np.exp(0.5 * y * y)
    dth = mills * (-x / sr + (y - th * x) * th / sr**3)
    return val, dv, dth


def _clayton_logh(p, u, v, lu, lv, grad: bool):
    th = p[0]
    s, ls = _clayton_sum(th, lu, lv)
    val = -(th + 1.0) * lu - (1.0 / th + 1.0) * ls
    if not grad:
        return val, None, None
    vt, ds = _clayton_slope(th, lu, lv)
    dv = (1.0 + th) * vt / (v * s)
    dth = -lu + ls / th**2 - (1.0 / th + 1.0) * ds / s
    return val, dv, dth


def _gumbel_logh(p, u, v, tu, tv, grad: bool):
    th = p[0]
    (lu, la), (_, lb) = tu, tv
    ls, big = _gumbel_sum(th, la, lb)
    val = -big - lu + (th - 1.0) * la + (1.0 / th - 1.0) * ls
    if not grad:
        return val, None, None
    r, ds_s, dbig = _gumbel_slope(th, la, lb, ls, big)
    d_b = -big * r + (1.0 - th) * r
    dv = -d_b / v
    dth = -dbig + la - ls / th**2 + (1.0 / th - 1.0) * ds_s
    return val, dv, dth


def _frank_logh(p, u, v, tu, tv, grad: bool):
    th = p[0]
    eu, ev = np.expm1(-th * u), np.expm1(-th * v)
    den = _frank_den(th, u, v)
    val = -th * u + np.log(np.abs(ev)) - np.log(np.abs(den))
    if not grad:
        return val, None, None
    fv = np.exp(-th * v)
    dv = -th * fv / ev - th * eu * fv / den
    dden = np.exp(-th) + u * np.exp(-th * u) * ev + v * fv * eu
    dth = -u - v * fv / ev - dden / den
    return val, dv, dth


_LOGC = {"gaussian": _gaussian_logc, "student": _student_logc, "clayton": _clayton_logc,
         "gumbel": _gumbel_logc, "frank": _frank_logc}
_LOGH = {"gaussian": _gaussian_logh, "student": _student_logh, "clayton": _clayton_logh,
         "gumbel": _gumbel_logh, "frank": _frank_logh}


def _formula(table, base, what):
    if base not in table:
        raise ValueError(f"no closed-form {what} for the copula family {base!r}")
    return table[base]


def logc_grad(base: str, p, u, v, *, grad: bool = True):
    """``(log c, ∂ log c/∂v, ∂ log c/∂θ)`` (derivatives None when ``grad`` is False)."""
    formula = _formula(_LOGC, base, "density")
    return formula(p, u, v, scores(base, p, u), scores(base, p, v), grad)


def logh_grad(base: str, p, u, v, *, grad: bool = True):
    """``(log h, ∂ log h/∂v, ∂ log h/∂θ)`` of ``h = C_{V|U}(v | u)``."""
    formula = _formula(_LOGH, base, "h-function")
    return formula(p, u, v, scores(base, p, u), scores(base, p, v), grad)
