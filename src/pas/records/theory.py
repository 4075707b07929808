"""Theoretical short-term crest distributions: Rayleigh and Forristall (2000).

Both are distributions of the crest ``c`` of a zero-up-crossing wave, per
wave, written as exceedance ``P(C > c)``; the most probable maximum (MPM) over
``n`` waves is the crest exceeded once in ``n`` waves, ``P(C > c) = 1/n``, and
the q-quantile of the maximum solves ``(1 − P(C > c))^n = q``.

* Rayleigh (linear, narrow-band Gaussian sea): ``P(C > c) = exp(−8 c²/Hs²)``,
  MPM ``c = sqrt(2 m0 ln n)`` with ``Hs = 4 sqrt(m0)``.
* Forristall (2000), "Wave crest distributions: observations and
  second-order theory", J. Phys. Oceanogr. 30(8), 1931–1943: a 2-parameter
  Weibull fitted to second-order (Sharma & Dean) simulations,
  ``P(C > c) = exp(−(c / (α Hs))^β)`` with steepness
  ``S1 = 2π Hs / (g T1²)`` and Ursell number ``Ur = Hs / (k1² d³)``, where
  ``T1 = 2π m0/m1`` is the mean period and ``k1`` the wave number of ``T1`` in
  depth ``d``. Coefficients (Forristall 2000, Eqs. 4–5 and 7–8; also
  reproduced in DNV-RP-C205 (2019) §3.5.9.3):

  ====================  =============================================
  long-crested (2D)     α = 0.3536 + 0.2892 S1 + 0.1060 Ur
                        β = 2 − 2.1597 S1 + 0.0968 Ur²
  short-crested (3D)    α = 0.3536 + 0.2568 S1 + 0.0800 Ur
                        β = 2 − 1.7912 S1 − 0.5302 Ur + 0.2824 Ur²
  ====================  =============================================

  With ``S1 = Ur = 0`` both reduce to Rayleigh (α = 1/√8, β = 2). The
  coefficients were fitted over the steepness and Ursell ranges of
  Forristall's simulations; outside them the formula is an extrapolation.
"""

from __future__ import annotations

import numpy as np

from .._support.checks import check_open_unit, check_positive
from ..waves.spectra import wave_number

__all__ = [
    "rayleigh_crest_exceedance",
    "rayleigh_crest_quantile",
    "rayleigh_crest_mpm",
    "forristall_parameters",
    "forristall_crest_exceedance",
    "forristall_crest_quantile",
    "forristall_crest_mpm",
]

G = 9.81

_FORRISTALL = {
    # kind: (alpha: a0, aS, aU), (beta: b0, bS, bU, bU2)
    "2d": ((0.3536, 0.2892, 0.1060), (2.0, -2.1597, 0.0, 0.0968)),
    "3d": ((0.3536, 0.2568, 0.0800), (2.0, -1.7912, -0.5302, 0.2824)),
}


def _n_waves(n):
    n = check_positive(n, "n_waves")
    if n <= 1:
        raise ValueError(f"n_waves must be > 1 for a maximum over several waves, got {n!r}")
    return n


def rayleigh_crest_exceedance(c, hs):
    """Rayleigh crest exceedance per wave, ``P(C > c) = exp(−8 c²/Hs²)``.

    Parameters
    ----------
    c : array_like
        Crest height above the mean level (m); negative crests give 1.
    hs : float
        Significant wave height ``4 sqrt(m0)`` (m).

    Examples
    --------
    >>> round(float(rayleigh_crest_exceedance(5.0, 10.0)), 6)   # exp(-2)
    0.135335
    """
    hs = check_positive(hs, "hs")
    c = np.asarray(c, dtype=float)
    return np.exp(-8.0 * (np.maximum(c, 0.0) / hs) ** 2)


def rayleigh_crest_quantile(hs, n_waves, q=np.exp(-1.0)):
    """q-quantile of the largest of ``n_waves`` Rayleigh crests.

    ``(1 − exp(−8c²/Hs²))^n = q`` gives ``c = Hs sqrt(−ln(1 − q^{1/n}) / 8)``.
    """
    hs = check_positive(hs, "hs")
    n = _n_waves(n_waves)
    q = check_open_unit(q, "q")
    p = -np.expm1(np.log(q) / n)
    return float(hs * np.sqrt(-np.log(p) / 8.0))


def rayleigh_crest_mpm(hs, n_waves):
    """Rayleigh crest MPM over ``n_waves`` waves, ``sqrt(2 m0 ln n) = Hs sqrt(ln n / 8)``.

    Examples
    --------
    >>> round(rayleigh_crest_mpm(10.0, 400), 4)
    8.6541
    """
    hs = check_positive(hs, "hs")
    return float(hs * np.sqrt(np.log(_n_waves(n_waves)) / 8.0))


def forristall_parameters(hs, t1, depth=np.inf, *, kind="2d", g=G):
    """Weibull scale ``α`` and shape ``β`` of Forristall's (2000) crest distribution.

    Parameters
    ----------
    hs : float
        Significant wave height (m).
    t1 : float
        Mean wave period ``T1 = 2π m0/m1`` (s). For JONSWAP γ = 3.3,
        ``T1 ≈ Tp / 1.198`` (:func:`pas.stats.mean_period_from_peak_period`).
    depth : float, default inf
        Water depth (m); ``inf`` gives ``Ur = 0``.
    kind : {"2d", "3d"}, default "2d"
        Long-crested ("2d") or short-crested ("3d") coefficients.
    g : float, default 9.81

    Returns
    -------
    alpha, beta : float
        ``P(C > c) = exp(−(c/(α Hs))^β)``.
    s1, ur : float
        Steepness ``2π Hs/(g T1²)`` and Ursell number ``Hs/(k1² d³)``.

    Examples
    --------
    >>> a, b, s1, ur = forristall_parameters(10.0, 9.0)
    >>> round(s1, 5), ur, round(a, 5), round(b, 5)
    (0.07907, 0.0, 0.37647, 1.82923)
    """
    if kind not in _FORRISTALL:
        raise ValueError(f"kind must be '2d' (long-crested) or '3d' (short-crested), got {kind!r}")
    hs = check_positive(hs, "hs")
    t1 = check_positive(t1, "t1")
    depth = float(depth)
    if not depth > 0:
        raise ValueError(f"depth must be > 0 (use inf for deep water), got {depth!r}")
    s1 = 2.0 * np.pi * hs / (g * t1**2)
    if np.isinf(depth):
        ur = 0.0
    else:
        k1 = float(wave_number(2.0 * np.pi / t1, depth, g=g))
        ur = hs / (k1**2 * depth**3)
    (a0, a_s, a_u), (b0, b_s, b_u, b_u2) = _FORRISTALL[kind]
    alpha = a0 + a_s * s1 + a_u * ur
    beta = b0 + b_s * s1 + b_u * ur + b_u2 * ur**2
    return float(alpha), float(beta), float(s1), float(ur)


def forristall_crest_exceedance(c, hs, t1, depth=np.inf, *, kind="2d"):
    """Forristall (2000) crest exceedance per wave, ``exp(−(c/(α Hs))^β)``.

    See :func:`forristall_parameters` for the arguments.
    """
    alpha, beta, _, _ = forristall_parameters(hs, t1, depth, kind=kind)
    c = np.asarray(c, dtype=float)
    return np.exp(-((np.maximum(c, 0.0) / (alpha * hs)) ** beta))


def forristall_crest_quantile(hs, t1, depth, n_waves, q=np.exp(-1.0), *, kind="2d"):
    """q-quantile of the largest of ``n_waves`` Forristall crests (m).

    ``c = α Hs (−ln(1 − q^{1/n}))^{1/β}``.
    """
    alpha, beta, _, _ = forristall_parameters(hs, t1, depth, kind=kind)
    n = _n_waves(n_waves)
    q = check_open_unit(q, "q")
    p = -np.expm1(np.log(q) / n)
    return float(alpha * hs * (-np.log(p)) ** (1.0 / beta))


def forristall_crest_mpm(hs, t1, depth, n_waves, *, kind="2d"):
    """Forristall (2000) crest MPM over ``n_waves`` waves, ``α Hs (ln n)^{1/β}`` (m).

    Examples
    --------
    >>> round(forristall_crest_mpm(10.0, 11.0 / 1.198, 30.0, 392), 2)
    10.31
    """
    alpha, beta, _, _ = forristall_parameters(hs, t1, depth, kind=kind)
    return float(alpha * hs * np.log(_n_waves(n_waves)) ** (1.0 / beta))
