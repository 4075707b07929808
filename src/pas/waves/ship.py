"""Closed-form linear heave, pitch, midship VBM and relative wave elevation.

Model
-----
The ship is the homogeneously loaded box of Jensen, Mansour & Olsen (2004):
length ``L``, effective breadth ``B = Cb * B0`` (their correction of the
breadth for the hull shape, so that the displacement is right), draught ``T``,
uniform mass ``rho B T`` per unit length, sectional added mass ``rho B T`` and
sectional damping ``c = rho g^2 A^2 / w_e^3`` with the radiated-wave ratio
``A = 2 sin(k B alpha^2 / 2) exp(-k T alpha^2)``, ``alpha = w_e / w =
1 - Fn sqrt(kL) cos(mu)``, deep-water ``k = w^2 / g``. The sectional balance

``rho g B [kappa f_c eta(x) - D w(x)] = 0`` (per unit length, integrated)

with ``kappa = exp(-kT)``,
``f_c = 1 - kT + i A^2 / (k B alpha^3)`` (Froude-Krylov + diffraction) and
``D = 1 - 2 k T alpha^2 + i A^2 / (k B alpha^2)`` (restoring, inertia, damping)
gives, for ``w(x) = z - x theta`` and ``eta(x) = a exp(i q x)``,
``q = -k cos(mu)``:

``H_z = kappa f_c sinc(qL/2) / D``

``H_theta = -i kappa f_c 24 [sin(qL/2) - (qL/2) cos(qL/2)] / ((qL)^2 L D)``

whose magnitudes are the heave ``eta F`` and pitch ``eta G`` of Jensen et al.
(2004, Eqs. for ``Phi_w``, ``Phi_theta``); here the phases are kept so that
responses and wave share the same event. Pitch ``theta`` is positive bow
down (``w = z - x theta``, ``x`` forward from midship).

The midship vertical bending moment is the moment about midship of the net
load on the forward half, positive in hogging,

``M = -rho g B integral_0^{L/2} x [kappa f_c eta(x) - D w(x)] dx``,

which for zero speed and no damping is the closed form of Jensen & Mansour
(2002), ``rho g B L^2 kappa (1 - kT) [1 - cos(u) - (kL/4) sin(u)] / (kL)^2``,
``u = kL/2``. Their empirical hull-shape and speed correction factors are not
applied (see :class:`Ship` ``vbm_factor``).

The relative wave elevation at ``x`` is ``R = eta(x) - (z - x theta)``
(no swell-up, no diffraction of the incident wave at the bow).

References
----------
Jensen, J.J., Mansour, A.E., Olsen, A.S. (2004). Estimation of ship motions
using closed-form expressions. Ocean Engineering 31(1), 61-85.
doi:10.1016/S0029-8018(03)00108-2

Jensen, J.J., Mansour, A.E. (2002). Estimation of ship long-term wave-induced
bending moment using closed-form expressions. Trans. RINA 144, 41-55.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .spectra import GRAVITY

__all__ = ["Ship", "FERRY_190M", "ShipRAO", "ship_rao", "relative_elevation_rao",
           "ship_responses"]

RHO_SEAWATER = 1025.0


@dataclass(frozen=True)
class Ship:
    """Main particulars of a monohull for the closed-form responses.

    Attributes
    ----------
    length, beam, draught : float
        ``L``, ``B0``, ``T`` (m).
    block_coefficient : float
        ``Cb``; the hydrodynamic breadth is ``Cb * B0``.
    bow_freeboard : float
        Freeboard at the bow (m), for green-water use.
    vbm_factor : float, default 1.0
        Constant scale on the VBM of the box model (e.g. Jensen & Mansour's
        hull-form/speed corrections, if the user wants them).
    """

    length: float
    beam: float
    draught: float
    block_coefficient: float = 0.6
    bow_freeboard: float = 10.5
    vbm_factor: float = 1.0

    def __post_init__(self):
        for name in ("length", "beam", "draught", "block_coefficient", "vbm_factor"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be positive, got {v!r}")
        if self.block_coefficient > 1:
            raise ValueError("block_coefficient must be <= 1")

    def station_x(self, station, n_stations=20):
        """Longitudinal position from midship (m, forward positive) of a station.

        Station 0 is the aft perpendicular, ``n_stations`` the forward one;
        station 19 is at ``19/20 L`` from the stern, i.e. ``0.45 L`` forward.
        """
        return (station / n_stations - 0.5) * self.length


FERRY_190M = Ship(length=190.0, beam=30.0, draught=9.0, block_coefficient=0.6,
                  bow_freeboard=10.5)
"""The 190 m ferry of the paper's cases 2-4 (Cb = 0.6 is our assumption)."""


@dataclass(frozen=True)
class ShipRAO:
    """Complex transfer functions per unit complex wave amplitude at midship.

    ``heave`` (m/m), ``pitch`` (rad/m, bow down positive), ``vbm`` (N m/m,
    hogging positive), all at the absolute wave frequencies ``omega``.
    """

    omega: np.ndarray
    heave: np.ndarray
    pitch: np.ndarray
    vbm: np.ndarray
    q: np.ndarray


def _sinc(u):
    return np.sinc(u / np.pi)


def _pitch_shape(u):
    """``3 [sin u - u cos u] / u^3`` -> 1 as ``u -> 0`` (series below 1e-3)."""
    small = np.abs(u) < 1e-3
    us = np.where(small, 1.0, u)
    full = 3.0 * (np.sin(us) - us * np.cos(us)) / us**3
    return np.where(small, 1.0 - u**2 / 10.0, full)


def _half_moment(q, half):
    """``integral_0^half x exp(i q x) dx`` with a series for small ``q half``."""
    qs = np.where(np.abs(q * half) < 1e-3, 1.0, q)
    e = np.exp(1j * qs * half)
    full = half * e / (1j * qs) + (e - 1.0) / qs**2
    series = half**2 / 2 + 1j * q * half**3 / 3 - q**2 * half**4 / 8 - 1j * q**3 * half**5 / 30
    return np.where(np.abs(q * half) < 1e-3, series, full)


def ship_rao(ship, omega, *, speed=0.0, heading=180.0, g=GRAVITY, rho=RHO_SEAWATER):
    """Heave, pitch and midship VBM transfer functions (module docstring model).

    Parameters
    ----------
    ship : Ship
    omega : array_like
        Absolute wave frequencies (rad/s); zero gives the static limit.
    speed : float, default 0
        Forward speed (m/s).
    heading : float, default 180
        Wave heading relative to the ship (deg, 180 = head seas).

    Returns
    -------
    ShipRAO
    """
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and non-negative")
    L, T = ship.length, ship.draught
    B = ship.block_coefficient * ship.beam
    cmu = np.cos(np.deg2rad(heading))
    k = np.maximum(w**2 / g, 1e-12)
    alpha = 1.0 - speed / np.sqrt(g * L) * np.sqrt(k * L) * cmu
    if np.any(alpha <= 0):
        raise ValueError("encounter frequency <= 0 (following seas faster than the waves)")
    A = 2.0 * np.sin(0.5 * k * B * alpha**2) * np.exp(-k * T * alpha**2)
    kappa = np.exp(-k * T)
    f_c = 1.0 - k * T + 1j * A**2 / (k * B * alpha**3)
    D = 1.0 - 2.0 * k * T * alpha**2 + 1j * A**2 / (k * B * alpha**2)
    q = -k * cmu
    u = 0.5 * q * L
    exc = kappa * f_c
    heave = exc * _sinc(u) / D
    pitch = -1j * exc * q * _pitch_shape(u) / D
    lever = (_half_moment(q, 0.5 * L) * exc
             - D * (heave * L**2 / 8.0 - pitch * L**3 / 24.0))
    vbm = -rho * g * B * lever * ship.vbm_factor
    return ShipRAO(omega=w, heave=heave, pitch=pitch, vbm=vbm, q=q)


def relative_elevation_rao(ship, omega, x, *, speed=0.0, heading=180.0, g=GRAVITY):
    """Relative wave elevation ``R = eta(x) - (z - x theta)`` per unit amplitude.

    Parameters
    ----------
    ship : Ship
    omega : array_like
        Absolute wave frequencies (rad/s).
    x : float
        Ship-fixed longitudinal position from midship (m), e.g.
        ``ship.station_x(19)``.

    Returns
    -------
    ndarray of complex
    """
    r = ship_rao(ship, omega, speed=speed, heading=heading, g=g)
    return np.exp(1j * r.q * x) - (r.heave - x * r.pitch)


def ship_responses(sea, ship, dt, *, stations=(19,), bow_x=None):
    """Linear response time series of a ship in a :class:`LinearSea`.

    The complex wave amplitudes of the sea are multiplied by the transfer
    functions and synthesised with the same FFT, so all signals share the
    wave events (and the ``sea``'s speed and heading).

    Parameters
    ----------
    sea : LinearSea
        Encounter-frequency sea (``speed``/``heading`` taken from it).
    ship : Ship
    dt : float
        Time step (s).
    stations : sequence of float, default (19,)
        Stations (of 20) for the relative wave elevation.
    bow_x : float, optional
        Bow position from midship; default ``L / 2``.

    Returns
    -------
    dict of ndarray
        ``t``, ``eta`` (at midship), ``heave``, ``pitch``, ``vbm``,
        ``rwe_bow`` and ``rwe_<station>`` for each station.
    """
    r = ship_rao(ship, sea.omega, speed=sea.speed, heading=sea.heading)
    t, eta = sea.elevation(dt)
    out = {"t": t, "eta": eta}
    for name, h in (("heave", r.heave), ("pitch", r.pitch), ("vbm", r.vbm)):
        out[name] = sea.synthesise(h * sea.amplitude, dt)[1]
    xs = {"bow": 0.5 * ship.length if bow_x is None else bow_x}
    xs.update({f"{s:g}": ship.station_x(s) for s in stations})
    for name, x in xs.items():
        # Incident wave with the sea's own (finite-depth) wave numbers.
        amp = sea.amplitude_at(x) - (r.heave - x * r.pitch) * sea.amplitude
        out[f"rwe_{name}"] = sea.synthesise(amp, dt)[1]
    return out
