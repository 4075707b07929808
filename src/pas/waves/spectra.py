"""Wave spectra, spectral moments, periods and the linear dispersion relation.

All spectra are one-sided and defined on the angular frequency ``omega`` in
rad/s, in m^2 s/rad, so that ``m0 = integral S(omega) d omega`` and
``Hs = 4 sqrt(m0)``.

References
----------
Hasselmann, K. et al. (1973). Measurements of wind-wave growth and swell decay
during the Joint North Sea Wave Project (JONSWAP). Dtsch. Hydrogr. Z. A8(12).

DNV (2021). DNV-RP-C205 Environmental conditions and environmental loads,
Section 3.5.5 (JONSWAP, Pierson-Moskowitz, period relations).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy import integrate

__all__ = [
    "GRAVITY",
    "jonswap",
    "pierson_moskowitz",
    "spectral_moments",
    "mean_period_t1",
    "zero_crossing_period_tz",
    "wave_number",
]

GRAVITY = 9.81
"""Gravitational acceleration used throughout :mod:`pas.waves` (m/s^2)."""


def _check_sea_state(hs, tp):
    if not (np.isfinite(hs) and hs > 0):
        raise ValueError(f"hs must be a positive finite number, got {hs!r}")
    if not (np.isfinite(tp) and tp > 0):
        raise ValueError(f"tp must be a positive finite number, got {tp!r}")


def _jonswap_shape(x, gamma, sigma_a, sigma_b):
    """Unnormalised JONSWAP shape on ``x = omega / omega_p``."""
    x = np.asarray(x, dtype=float)
    out = np.zeros_like(x)
    pos = x > 0
    xp = x[pos]
    sigma = np.where(xp <= 1.0, sigma_a, sigma_b)
    peak = np.exp(-((xp - 1.0) ** 2) / (2.0 * sigma**2))
    out[pos] = xp**-5 * np.exp(-1.25 * xp**-4) * gamma**peak
    return out


@lru_cache(maxsize=64)
def _jonswap_shape_integral(gamma, sigma_a, sigma_b):
    def f(x):
        return float(_jonswap_shape(np.array([x]), gamma, sigma_a, sigma_b)[0])

    # The peak sits at x = 1; the enhancement is confined to |x - 1| < ~0.5.
    lo, _ = integrate.quad(f, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)
    mid, _ = integrate.quad(f, 1.0, 3.0, epsabs=0.0, epsrel=1e-13, limit=200)
    hi, _ = integrate.quad(f, 3.0, np.inf, epsabs=0.0, epsrel=1e-13, limit=200)
    return lo + mid + hi


def jonswap(omega, hs, tp, gamma=3.3, sigma_a=0.07, sigma_b=0.09):
    """JONSWAP spectrum scaled so that ``4 sqrt(m0) = hs`` exactly.

    ``S(w) = C w^-5 exp(-5/4 (wp/w)^4) gamma^r``,
    ``r = exp(-(w - wp)^2 / (2 sigma^2 wp^2))``, ``sigma = sigma_a`` for
    ``w <= wp`` and ``sigma_b`` above (Hasselmann et al. 1973). The constant
    ``C`` is not the usual Goda/DNV approximation ``1 - 0.287 ln(gamma)`` but
    the numerical integral of the shape over ``(0, inf)``, so the zeroth moment
    is ``hs**2 / 16`` to quadrature precision (~1e-12) for any ``gamma``.

    Parameters
    ----------
    omega : array_like
        Angular wave frequency (rad/s). Values ``<= 0`` give 0.
    hs : float
        Significant wave height (m).
    tp : float
        Peak period (s).
    gamma : float, default 3.3
        Peak enhancement factor (``gamma = 1`` is Pierson-Moskowitz).
    sigma_a, sigma_b : float, default 0.07, 0.09
        Spectral width parameters below and above the peak.

    Returns
    -------
    ndarray
        Spectral density (m^2 s/rad), same shape as ``omega``.

    Examples
    --------
    >>> import numpy as np
    >>> w = np.linspace(0.01, 6.0, 20000)
    >>> s = jonswap(w, 10.0, 11.0)
    >>> round(float(4 * np.sqrt(np.trapezoid(s, w))), 3)
    10.0
    """
    _check_sea_state(hs, tp)
    if not gamma >= 1.0:
        raise ValueError(f"gamma must be >= 1, got {gamma!r}")
    if not (sigma_a > 0 and sigma_b > 0):
        raise ValueError("sigma_a and sigma_b must be positive")
    wp = 2.0 * np.pi / tp
    norm = _jonswap_shape_integral(float(gamma), float(sigma_a), float(sigma_b))
    x = np.asarray(omega, dtype=float) / wp
    return (hs**2 / 16.0) * _jonswap_shape(x, gamma, sigma_a, sigma_b) / (wp * norm)


def pierson_moskowitz(omega, hs, tp):
    """Pierson-Moskowitz (Bretschneider / ISSC) spectrum.

    ``S(w) = 5/16 hs^2 wp^4 w^-5 exp(-5/4 (wp/w)^4)`` (DNV-RP-C205 Eq. 3.5.5.1),
    whose zeroth moment is exactly ``hs**2 / 16``.

    Parameters
    ----------
    omega : array_like
        Angular wave frequency (rad/s). Values ``<= 0`` give 0.
    hs, tp : float
        Significant wave height (m) and peak period (s).

    Returns
    -------
    ndarray
        Spectral density (m^2 s/rad).
    """
    _check_sea_state(hs, tp)
    wp = 2.0 * np.pi / tp
    w = np.asarray(omega, dtype=float)
    out = np.zeros_like(w)
    pos = w > 0
    out[pos] = 5.0 / 16.0 * hs**2 * wp**4 * w[pos] ** -5 * np.exp(-1.25 * (wp / w[pos]) ** 4)
    return out


def spectral_moments(omega, spectrum, orders=(0, 1, 2)):
    """Spectral moments ``m_n = integral omega^n S(omega) d omega`` (trapezoid).

    Parameters
    ----------
    omega : array_like, shape (n,)
        Increasing angular frequencies (rad/s).
    spectrum : array_like, shape (n,)
        Spectral density on ``omega``.
    orders : sequence of int, default (0, 1, 2)
        Moment orders.

    Returns
    -------
    ndarray, shape (len(orders),)
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    if w.ndim != 1 or s.shape != w.shape or w.size < 2:
        raise ValueError("omega and spectrum must be 1-D arrays of equal length >= 2")
    if np.any(np.diff(w) <= 0):
        raise ValueError("omega must be strictly increasing")
    return np.array([np.trapezoid(w**n * s, w) for n in orders])


def mean_period_t1(omega, spectrum):
    """Mean wave period ``T1 = 2 pi m0 / m1`` (s)."""
    m0, m1 = spectral_moments(omega, spectrum, orders=(0, 1))
    return 2.0 * np.pi * m0 / m1


def zero_crossing_period_tz(omega, spectrum):
    """Mean zero-crossing period ``Tz = T2 = 2 pi sqrt(m0 / m2)`` (s)."""
    m0, m2 = spectral_moments(omega, spectrum, orders=(0, 2))
    return 2.0 * np.pi * np.sqrt(m0 / m2)


def wave_number(omega, depth=np.inf, *, g=GRAVITY):
    """Wave number from the linear dispersion relation ``w^2 = g k tanh(k h)``.

    Solved for ``x = k h`` from ``x tanh x = y`` with ``y = w^2 h / g``, starting
    from Eckart's (1952) approximation ``x = y / sqrt(tanh y)`` followed by
    Newton iterations until the relative change is below 1e-15 (quadratic
    convergence; typically 3-5 iterations). ``depth = inf`` gives ``w^2 / g``.

    Parameters
    ----------
    omega : array_like
        Angular frequency (rad/s), ``>= 0``.
    depth : float, default inf
        Water depth (m), ``> 0``.
    g : float, default 9.81

    Returns
    -------
    ndarray
        Wave number (rad/m), 0 where ``omega == 0``.
    """
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and non-negative")
    if not depth > 0:
        raise ValueError(f"depth must be positive, got {depth!r}")
    k_deep = w**2 / g
    if np.isinf(depth):
        return k_deep
    y = np.atleast_1d(k_deep * depth).ravel()
    x = y.copy()
    shallow = (y > 0) & (y <= 40.0)  # tanh(40) == 1 in double precision
    x[shallow] = y[shallow] / np.sqrt(np.tanh(y[shallow]))
    active = shallow.copy()
    for _ in range(50):
        if not np.any(active):
            break
        idx = np.flatnonzero(active)
        xa = x[idx]
        t = np.tanh(xa)
        step = (xa * t - y[idx]) / (t + xa * (1.0 - t**2))
        x[idx] = xa - step
        active[idx[np.abs(step) <= 1e-15 * xa]] = False
    return (x / depth).reshape(np.shape(w))
