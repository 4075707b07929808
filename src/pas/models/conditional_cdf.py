"""The conditional CDF ``C_{V|U}(v | u)`` of a fitted copula, the h-function of Eq. 7.

:func:`pas.models.copulas.conditional_quantile` inverts it; this module gives it
forward, for the long-record draws of :mod:`pas.strategies.tail_draws`: a draw
``v = C⁻¹(r | u)`` exceeds a level ``v_L`` exactly when ``r > C(v_L | u)``, so one
evaluation per conditioning peak tells which of its ``z`` uniforms can reach the
top of a realisation.  Closed forms for Gaussian, Student-t (through the fast
t quantile and CDF of :mod:`pas.models.copulas`), Clayton, Gumbel and Frank
(:mod:`pas.models.copula_densities`) and their 180° rotations, with the same
near-independence switches as the inverse; pyvinecopulib's ``hfunc1``
otherwise.
"""

from __future__ import annotations

import numpy as np
import pyvinecopulib as pv
from scipy import special

from .copula_densities import copula_loghfunc
from .copulas import CopulaFit, t_cdf, t_quantile

__all__ = ["conditional_cdf", "CLOSED_FORMS"]

CLOSED_FORMS = ("gaussian", "student", "clayton", "gumbel", "frank")
"""Families (and their 180° rotations) whose CDF here and inverse in
:func:`~pas.models.copulas.conditional_quantile` are both closed forms, agreeing to
~1e-11 relative in ``1 − r``; pyvinecopulib's numerical inverse of Joe is off by up
to 0.3 % there (tests/models/test_conditional_cdf.py)."""

_CLOSED = {pv.BicopFamily.clayton: "clayton", pv.BicopFamily.gumbel: "gumbel",
           pv.BicopFamily.frank: "frank"}


def conditional_cdf(fit: CopulaFit | pv.Bicop, v, u) -> np.ndarray:
    """``C_{V|U}(v | u) = ∂C(u, v)/∂u``, vectorised; ``v`` and ``u`` broadcast.

    Examples
    --------
    >>> import pyvinecopulib as pv
    >>> from pas.models.copulas import conditional_quantile
    >>> b = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[2.0]]))
    >>> u = np.array([0.1, 0.5, 0.99])
    >>> v = conditional_quantile(b, u, np.array([0.3, 0.9, 0.999]))
    >>> np.round(conditional_cdf(b, v, u), 12).tolist()
    [0.3, 0.9, 0.999]
    """
    bicop = fit.bicop if isinstance(fit, CopulaFit) else fit
    v, u = np.asarray(v, float), np.asarray(u, float)
    fam, rot = bicop.family, int(bicop.rotation)
    p = np.asarray(bicop.parameters, dtype=float).ravel()
    if rot == 180:  # survival copula: C̄(v | u) = 1 − C(1 − v | 1 − u)
        base = pv.Bicop(family=fam, parameters=bicop.parameters, rotation=0)
        return 1.0 - _hfunc1(fam, p, base, 1.0 - v, 1.0 - u)
    if rot != 0:
        raise ValueError(f"rotation {rot} is not supported for conditional draws")
    return _hfunc1(fam, p, bicop, v, u)


def _hfunc1(fam, p, bicop, v, u):
    shape = np.broadcast_shapes(v.shape, u.shape)
    if fam == pv.BicopFamily.gaussian:
        rho = p[0]
        return special.ndtr((special.ndtri(v) - rho * special.ndtri(u)) / np.sqrt(1 - rho**2))
    if fam == pv.BicopFamily.student:
        rho, nu = p
        x, y = t_quantile(nu, u), t_quantile(nu, v)
        scale = np.sqrt((nu + x**2) * (1 - rho**2) / (nu + 1.0))
        return t_cdf(nu + 1.0, (y - rho * x) / scale)
    name = _CLOSED.get(fam)
    # where conditional_quantile draws as from independence (v = r), so does this CDF
    if fam == pv.BicopFamily.indep or (name == "clayton" and p[0] < 1e-8) or (
            name == "frank" and abs(p[0]) < 1e-8) or (name == "gumbel" and p[0] <= 1 + 1e-6):
        return np.broadcast_to(v, shape).copy()
    if name is not None:
        return np.exp(copula_loghfunc(name, p, u, v))
    v, u = np.broadcast_arrays(v, u)
    return bicop.hfunc1(np.column_stack([u.ravel(), v.ravel()])).reshape(shape)
