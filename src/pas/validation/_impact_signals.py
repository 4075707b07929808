"""Signals shared by the impact analogues (cases 3–4, paper-like and ``-hard``).

Relative wave elevation at a point ``(x, y)`` of the 190 m ferry (module docs
of :mod:`pas.validation.case_impacts`):

* LF ``R' = c_sw η1(ξ) − (z − x θ)``, linear;
* HF ``R'' = c_sw (η1 + η2)(ξ) − (z − x θ)``, with the Sharma–Dean
  second-order surface ``η2``;

``ξ = x + y tan μ`` (long-crested waves: the point sees the wave of that
centreline point).  Both are returned as FFT coefficients on the sea's grid,
so a record, its time derivative and any other linear functional come from one
inverse FFT each.
"""

from __future__ import annotations

import numpy as np

from ..stats.peaks import zero_upcrossings
from ..waves import FERRY_190M, second_order_coefficients, second_order_kernel, ship_rao
from ._common import DT, coefficients_on, condition_sea

__all__ = ["OMEGA_MAX", "OMEGA_MAX_2", "rwe_coefficients", "impact_sea", "relative_elevations",
           "crossing_values", "time_derivative"]

OMEGA_MAX = 3.0      # rad/s, linear components
OMEGA_MAX_2 = 2.2    # rad/s, second-order interactions (3.5 wp; bounds the O(N^2) kernel)


def rwe_coefficients(sea, kernel, x, y, c_sw):
    """FFT coefficients of ``R'`` and ``R''`` and of the wave slope along propagation at (x, y).

    Parameters
    ----------
    sea : LinearSea
        Encounter-frequency sea of the condition.
    kernel : SecondOrderKernel
        Sharma–Dean kernel of the same grid.
    x, y : float
        Ship-fixed position from midship (m; x forward, y to port).
    c_sw : float
        Linear swell-up factor on the incident surface.

    Returns
    -------
    lin, nonlin, slope : ndarray of complex
        ``R'`` and ``R''`` on one grid, and the linear slope ``-∂η1/∂ξ``.
    """
    r = ship_rao(FERRY_190M, sea.omega, speed=sea.speed, heading=sea.heading)
    xe = x + y * np.tan(np.deg2rad(sea.heading))
    a1 = sea.amplitude_at(xe)
    motion = (r.heave - x * r.pitch) * sea.amplitude
    lin = c_sw * a1 - motion
    a2 = c_sw * second_order_coefficients(sea, kernel, x=xe)
    n = max(lin.size, a2.size)
    slope = -1j * sea.wave_number * a1
    return coefficients_on(n, lin), coefficients_on(n, lin, a2), slope


def impact_sea(spec, seed, k, duration):
    """Sea of realisation ``k`` of an impact case."""
    return condition_sea(spec.condition, duration, seed, k, omega_max=OMEGA_MAX)


def relative_elevations(sea, c, *, bow):
    """``R'`` and ``R''`` at the bow or at station 19, weather side (coefficients ``c``).

    Returns ``nonlin, slope, t, r_lf, r_hf``: the FFT coefficients of ``R''`` and of
    the wave slope (:func:`rwe_coefficients`), the sample times and the records of
    ``R'`` and ``R''`` (without the steady bow wave).
    """
    kernel = second_order_kernel(sea, omega_max=OMEGA_MAX_2)  # built once per grid (cached)
    x, y = (FERRY_190M.length / 2.0, 0.0) if bow else (FERRY_190M.station_x(19), c["y_station19"])
    lin, nonlin, slope = rwe_coefficients(sea, kernel, x, y, c["c_sw"])
    t, r_lf = sea.synthesise(lin, DT)
    return nonlin, slope, t, r_lf, sea.synthesise(nonlin, DT)[1]


def time_derivative(sea, coefficients):
    """FFT coefficients of the time derivative of a record given by ``coefficients``."""
    omega_q = 2.0 * np.pi * sea.df * np.arange(coefficients.size)
    return 1j * omega_q * coefficients


def crossing_values(x, level, *series):
    """Index of each up-crossing of ``level`` and ``series`` interpolated at it."""
    i = zero_upcrossings(x, level=level)
    i = i[i >= 1]
    frac = (level - x[i - 1]) / (x[i] - x[i - 1])
    return i, [s[i - 1] + frac * (s[i] - s[i - 1]) for s in series]
