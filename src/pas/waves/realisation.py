"""Random-phase realisations of long-crested linear seas.

Two discretisations:

* :func:`linear_sea` -- equidistant frequency grid with ``df = 1 / duration``
  (no repetition inside a seed), deterministic amplitudes, uniform random
  phases, synthesised with one inverse real FFT. With a forward speed the grid
  is built on the *encounter* frequency so the FFT gives the record in
  ship-fixed time.
* :func:`period_domain_sea` -- the period-domain standard of Razola et al.
  (``0.2 Tz <= T <= 2.5 Tz``, ``N = 100`` equal period bands, band energy
  integrated), for time-domain tools that limit the component count.

Conventions
-----------
A component ``j`` has complex amplitude ``A_j = a_j exp(i phi_j)`` and the
surface at a ship-fixed point ``(x, y)`` (``x`` forward along the ship, ``y``
to port, origin at the reference point, e.g. midship) is

``eta(t) = Re sum_j A_j exp(i (w_e,j t - k_j (x cos mu + y sin mu)))``

where ``mu`` is the wave heading relative to the ship (180 deg = head seas,
waves travelling towards -x) and ``w_e = w - k V cos mu`` with the
deep-water ``k = w^2 / g`` (paper Eq. 1). Without speed ``w_e = w``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .encounter import encounter_frequency, wave_frequency_from_encounter
from .spectra import GRAVITY, wave_number

__all__ = [
    "LinearSea",
    "ComponentSea",
    "linear_sea",
    "period_domain_sea",
    "synthesise",
]


def _time_grid(duration, dt):
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be positive, got {dt!r}")
    n_t = int(round(duration / dt))
    if n_t < 2:
        raise ValueError("dt must be smaller than half the record duration")
    return n_t


def synthesise(coefficients, df, dt):
    """Real time series ``x(t) = Re sum_j c_j exp(i 2 pi j df t)`` by inverse FFT.

    Parameters
    ----------
    coefficients : array_like of complex, shape (n,)
        Complex amplitudes on the grid ``f_j = j df``, ``j = 0 .. n-1``.
    df : float
        Frequency step (Hz); the record is periodic with ``duration = 1/df``.
    dt : float
        Requested time step (s). It is adjusted to ``duration / round(duration/dt)``
        so the record holds an integer number of samples.

    Returns
    -------
    t : ndarray, shape (n_t,)
    x : ndarray, shape (n_t,)

    Raises
    ------
    ValueError
        If a non-zero coefficient lies at or above the Nyquist frequency.
    """
    c = np.asarray(coefficients)
    if c.ndim != 1:
        raise ValueError("coefficients must be 1-D")
    duration = 1.0 / df
    n_t = _time_grid(duration, dt)
    n_half = n_t // 2
    nz = np.flatnonzero(c)
    if nz.size and nz[-1] >= n_half:
        raise ValueError(
            f"component at {nz[-1] * df:.4g} Hz is at or above the Nyquist frequency "
            f"{n_half * df:.4g} Hz; use dt < {1.0 / (2.0 * nz[-1] * df):.4g} s"
        )
    spec = np.zeros(n_half + 1, dtype=complex)
    m = min(c.size, n_half)
    spec[:m] = c[:m] * (n_t / 2.0)
    spec[0] = c[0].real * n_t if c.size else 0.0
    x = np.fft.irfft(spec, n=n_t)
    t = np.arange(n_t) * (duration / n_t)
    return t, x


@dataclass(frozen=True)
class LinearSea:
    """Linear long-crested sea on an equidistant (encounter) frequency grid.

    Component ``j`` sits at encounter frequency ``f_j = j df`` (Hz) in the
    ship-fixed frame (= wave frequency when ``speed == 0``) and has absolute
    wave frequency ``omega[j]``. Build with :func:`linear_sea`.

    Attributes
    ----------
    df : float
        Frequency step (Hz); ``duration = 1 / df``.
    amplitude : ndarray of complex, shape (n,)
        ``A_j = a_j exp(i phi_j)`` at the reference point; ``A_0 = 0``.
    omega : ndarray, shape (n,)
        Absolute wave frequency of each component (rad/s).
    depth : float
        Water depth (m), ``inf`` for deep water.
    speed, heading : float
        Ship speed (m/s) and wave heading (deg, 180 = head seas).
    seed : int or None
        Seed of the phases, for bookkeeping.
    """

    df: float
    amplitude: np.ndarray
    omega: np.ndarray
    depth: float = np.inf
    speed: float = 0.0
    heading: float = 180.0
    seed: int | None = None
    wave_number: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        amp = np.asarray(self.amplitude, dtype=complex)
        om = np.asarray(self.omega, dtype=float)
        if amp.ndim != 1 or om.shape != amp.shape:
            raise ValueError("amplitude and omega must be 1-D arrays of equal length")
        amp.setflags(write=False)
        om.setflags(write=False)
        k = wave_number(om, self.depth)
        k.setflags(write=False)
        object.__setattr__(self, "amplitude", amp)
        object.__setattr__(self, "omega", om)
        object.__setattr__(self, "wave_number", k)

    @property
    def duration(self):
        """Record length (s), ``1 / df``."""
        return 1.0 / self.df

    @property
    def freq(self):
        """Encounter frequency of each component (Hz)."""
        return np.arange(self.amplitude.size) * self.df

    @property
    def omega_e(self):
        """Encounter angular frequency of each component (rad/s)."""
        return 2.0 * np.pi * self.freq

    @property
    def m0(self):
        """Variance of the realised surface, ``sum |A_j|^2 / 2`` (m^2)."""
        return 0.5 * float(np.sum(np.abs(self.amplitude) ** 2))

    @property
    def hs(self):
        """Realised ``Hs = 4 sqrt(m0)`` (m)."""
        return 4.0 * np.sqrt(self.m0)

    def amplitude_at(self, x=0.0, y=0.0):
        """Complex amplitudes at the ship-fixed point ``(x, y)`` (m)."""
        mu = np.deg2rad(self.heading)
        return self.amplitude * np.exp(-1j * self.wave_number * (x * np.cos(mu) + y * np.sin(mu)))

    def synthesise(self, coefficients, dt):
        """Inverse-FFT synthesis of coefficients on this grid; see :func:`synthesise`."""
        return synthesise(coefficients, self.df, dt)

    def elevation(self, dt, *, x=0.0, y=0.0):
        """Linear surface elevation at a ship-fixed point.

        Returns
        -------
        t, eta : ndarray
            Time (s) and elevation (m) over one record of ``duration``.
        """
        return self.synthesise(self.amplitude_at(x, y), dt)

    def response(self, transfer, dt, *, x=0.0, y=0.0):
        """Linear response ``Re sum H(w_j) A_j exp(i w_e,j t)``.

        Parameters
        ----------
        transfer : array_like of complex, shape (n,), or callable
            Complex transfer function per component, or a callable taking
            this sea and returning it (e.g. from :mod:`pas.waves.ship`).
        dt : float
            Time step (s).
        x, y : float
            Point at which the wave amplitudes are referred (usually 0 when
            the transfer function already holds the phase of its position).
        """
        h = transfer(self) if callable(transfer) else np.asarray(transfer)
        if h.shape != self.amplitude.shape:
            raise ValueError("transfer function must have one value per component")
        return self.synthesise(h * self.amplitude_at(x, y), dt)


def _amplitudes_from_spectrum(spectrum, omega, d_omega, jacobian):
    s = np.asarray(spectrum(omega), dtype=float)
    if s.shape != omega.shape or np.any(~np.isfinite(s)) or np.any(s < 0):
        raise ValueError("spectrum(omega) must return finite non-negative values per frequency")
    return np.sqrt(2.0 * s / jacobian * d_omega)


def linear_sea(spectrum, duration, *, seed, depth=np.inf, omega_max=5.0,
               speed=0.0, heading=180.0, g=GRAVITY):
    """Random-phase linear sea with ``df = 1 / duration`` (FFT grid).

    Amplitudes are deterministic, ``a_j = sqrt(2 S_e(w_e,j) dw_e)``, phases are
    uniform on ``[0, 2 pi)`` from ``numpy.random.default_rng(seed)``. With
    speed the grid is equidistant in encounter frequency and the encounter
    spectrum is ``S_e(w_e) = S(w) / |dw_e/dw|``, ``dw_e/dw = 1 - 2 w V cos(mu)/g``.

    Parameters
    ----------
    spectrum : callable
        ``spectrum(omega) -> S`` one-sided wave spectrum (m^2 s/rad), e.g.
        ``lambda w: jonswap(w, 10.0, 11.0)``.
    duration : float
        Record length (s); also the period of the synthesised signal.
    seed : int
        Seed for the phases.
    depth : float, default inf
        Water depth (m).
    omega_max : float, default 5.0
        Highest absolute wave frequency kept (rad/s).
    speed, heading : float, default 0, 180
        Ship speed (m/s) and wave heading (deg, 180 = head seas).
    g : float, default 9.81

    Returns
    -------
    LinearSea
    """
    if not (np.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be positive, got {duration!r}")
    if not omega_max > 0:
        raise ValueError("omega_max must be positive")
    c = speed * np.cos(np.deg2rad(heading)) / g
    if c > 0 and omega_max >= 1.0 / (2.0 * c):
        raise ValueError(
            f"following seas: omega_max must stay below the turning point {1 / (2 * c):.4g} rad/s"
        )
    df = 1.0 / duration
    we_max = float(encounter_frequency(omega_max, speed, heading, g=g))
    n = int(np.floor(we_max / (2.0 * np.pi * df) + 1e-9)) + 1
    omega_e = 2.0 * np.pi * df * np.arange(n)
    omega = wave_frequency_from_encounter(omega_e, speed, heading, g=g)
    jac = np.abs(1.0 - 2.0 * c * omega)
    a = _amplitudes_from_spectrum(spectrum, omega, 2.0 * np.pi * df, jac)
    a[0] = 0.0
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, 2.0 * np.pi, n)
    return LinearSea(df=df, amplitude=a * np.exp(1j * phase), omega=omega, depth=depth,
                     speed=speed, heading=heading, seed=seed)


@dataclass(frozen=True)
class ComponentSea:
    """Linear sea from a short list of arbitrary components (direct summation).

    Attributes
    ----------
    omega : ndarray
        Absolute wave frequencies (rad/s).
    amplitude : ndarray of complex
        ``A_j = a_j exp(i phi_j)``.
    depth, speed, heading : float
        As in :class:`LinearSea`.
    """

    omega: np.ndarray
    amplitude: np.ndarray
    depth: float = np.inf
    speed: float = 0.0
    heading: float = 180.0

    @property
    def omega_e(self):
        return encounter_frequency(self.omega, self.speed, self.heading)

    @property
    def m0(self):
        return 0.5 * float(np.sum(np.abs(self.amplitude) ** 2))

    def elevation(self, t, *, x=0.0, chunk=4096):
        """Surface elevation at times ``t`` by direct summation (chunked in time)."""
        t = np.asarray(t, dtype=float)
        k = wave_number(self.omega, self.depth)
        amp = self.amplitude * np.exp(-1j * k * x * np.cos(np.deg2rad(self.heading)))
        we = self.omega_e
        out = np.empty(t.size)
        flat = t.ravel()
        for s in range(0, flat.size, chunk):
            out[s:s + chunk] = (np.exp(1j * np.outer(flat[s:s + chunk], we)) @ amp).real
        return out.reshape(t.shape)


def period_domain_sea(spectrum, tz, *, seed, n=100, period_range=(0.2, 2.5),
                      depth=np.inf, speed=0.0, heading=180.0, n_sub=64):
    """Period-domain discretisation of Razola et al.

    The period interval ``[0.2 Tz, 2.5 Tz]`` is cut into ``n`` equal bands
    ``dT``; each component sits at the band-centre period and carries the
    spectral energy integrated over its band,
    ``a_j = sqrt(2 integral_band S(w) dw)`` (trapezoid on ``n_sub`` points).
    Energy outside the interval is discarded.

    Parameters
    ----------
    spectrum : callable
        ``spectrum(omega) -> S`` (m^2 s/rad).
    tz : float
        Zero-crossing period (s), e.g. from :func:`zero_crossing_period_tz`.
    seed : int
        Seed for the phases.
    n : int, default 100
        Number of components.

    Returns
    -------
    ComponentSea
    """
    if not tz > 0 or n < 1:
        raise ValueError("tz must be positive and n >= 1")
    lo, hi = period_range
    edges = np.linspace(lo * tz, hi * tz, n + 1)
    centre = 0.5 * (edges[:-1] + edges[1:])
    w_hi = 2.0 * np.pi / edges[:-1]
    w_lo = 2.0 * np.pi / edges[1:]
    u = np.linspace(0.0, 1.0, n_sub)
    w = w_lo[:, None] + (w_hi - w_lo)[:, None] * u[None, :]
    s = np.asarray(spectrum(w.ravel()), dtype=float).reshape(w.shape)
    energy = np.trapezoid(s, w, axis=1)
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, 2.0 * np.pi, n)
    return ComponentSea(
        omega=2.0 * np.pi / centre,
        amplitude=np.sqrt(2.0 * energy) * np.exp(1j * phase),
        depth=depth,
        speed=speed,
        heading=heading,
    )
