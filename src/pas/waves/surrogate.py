"""The surrogate response of a design-wave episode (Dermatis et al. 2025, §3.1.2).

Parametrisation (Dermatis et al. 2025, Eq. 1–3)
-----------------------------------------------
The episode lives on the equidistant encounter grid ``f_n = n df`` of a
:class:`~pas.waves.realisation.LinearSea` (``df = 1 / duration``, periodic
record).  Component ``n`` has the complex amplitude, at the reference point,

``A_n = sigma_n (u_n + i ubar_n)``,   ``sigma_n^2 = S_e(w_e,n) dw_e``,

with ``u = (u_1 … u_N, ubar_1 … ubar_N)`` independent standard normal: every
``u`` is one realisation of the Gaussian sea, and ``|u|`` measures how likely
it is.

Surrogate response (Eq. 4–5)
----------------------------
``chi(t0 | u) = Re sum_q T(w_q) C_q(u) exp(i w_e,q t0)``: a linear transfer
function ``T`` (per unit wave amplitude at the structure point ``x``) applied,
as if every component were a free wave, to the Fourier coefficients ``C_q`` of
the surface at ``x`` -- linear only, or linear plus the Sharma–Dean
second-order surface of :mod:`pas.waves.second_order` (our stand-in for the
paper's HOS wave tank).  ``chi`` is then a quadratic form in ``u``,
``chi = b·u + u·Q u``, with exact gradient ``b + 2 Q u``; ``Q`` is assembled
once from the pair kernels of :func:`~pas.waves.second_order.second_order_kernel`.

References
----------
Dermatis, A., Lasbleis, M., Kim, S., de Hauteclocque, G., Bouscasse, B.,
Ducrozet, G. (2025). A multi-fidelity approach for the evaluation of extreme
wave loads using nonlinear response-conditioned waves. Ocean Engineering 316,
119919. doi:10.1016/j.oceaneng.2024.119919 (CC BY 4.0)
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .realisation import LinearSea, linear_sea, synthesise, wave_frequency_from_encounter
from .second_order import SecondOrderKernel, second_order_coefficients, second_order_kernel

__all__ = ["ResponseSurrogate", "response_surrogate", "synthesise_on"]


@dataclass(frozen=True)
class ResponseSurrogate:
    """Linear transfer function on a linear (+ second-order) surface; see module docs.

    Build with :func:`response_surrogate`.

    Attributes
    ----------
    template : LinearSea
        The episode grid; ``template.amplitude`` holds ``sigma_n`` (real).
    transfer : ndarray of complex, shape (n_out,)
        ``T`` on the output grid ``q df``, ``q = 0 … n_out − 1`` (``T_0 = 0``).
    x : float
        Ship-fixed position along the wave direction's x-projection (m) where
        the surface is taken.
    t0 : float
        Conditioning time (s), within ``[0, duration)``.
    kernel : SecondOrderKernel or None
        Pair kernels; ``None`` for a linear surrogate.
    b : ndarray, shape (2N,)
        Linear part of ``chi``.
    q : ndarray, shape (2N, 2N) or None
        Symmetric second-order part of ``chi``.
    """

    template: LinearSea
    transfer: np.ndarray
    x: float
    t0: float
    kernel: SecondOrderKernel | None
    b: np.ndarray = field(repr=False)
    q: np.ndarray | None = field(repr=False)

    @property
    def n(self) -> int:
        """Number of components ``N`` (``u`` has ``2 N`` entries)."""
        return self.template.amplitude.size

    @property
    def sigma(self) -> np.ndarray:
        return self.template.amplitude.real

    @property
    def second_order(self) -> bool:
        return self.kernel is not None

    @property
    def m0(self) -> float:
        """Variance of the linear response, ``sum sigma_n^2 |T_n|^2``."""
        return float(self.b @ self.b)

    @property
    def m2(self) -> float:
        """Second moment of the linear response spectrum, ``sum w_e^2 sigma^2 |T|^2``."""
        w = self.template.omega_e
        return float(np.sum((w * self.sigma) ** 2 * np.abs(self.transfer[:self.n]) ** 2))

    def value(self, u) -> float:
        """``chi(t0 | u)``."""
        u = self._check(u)
        v = float(self.b @ u)
        return v if self.q is None else v + float(u @ (self.q @ u))

    def value_and_gradient(self, u):
        """``chi(t0 | u)`` and its gradient with respect to ``u``."""
        u = self._check(u)
        if self.q is None:
            return float(self.b @ u), self.b.copy()
        qu = self.q @ u
        return float(self.b @ u + u @ qu), self.b + 2.0 * qu

    def sea(self, u) -> LinearSea:
        """The episode's linear components (complex amplitudes at the reference point)."""
        u = self._check(u)
        n = self.n
        return replace(self.template, amplitude=self.sigma * (u[:n] + 1j * u[n:]))

    def surface_coefficients(self, sea) -> np.ndarray:
        """Fourier coefficients of the (linear + second-order) surface at ``x``."""
        lin = sea.amplitude_at(self.x)
        if self.kernel is None:
            return lin
        c2 = second_order_coefficients(sea, self.kernel, x=self.x)
        out = np.zeros(max(lin.size, c2.size), dtype=complex)
        out[:lin.size] += lin
        out[:c2.size] += c2
        return out

    def response_coefficients(self, sea) -> np.ndarray:
        """Fourier coefficients of the surrogate response ``T C``."""
        c = self.surface_coefficients(sea)
        return self.transfer[:c.size] * c

    def _check(self, u):
        u = np.asarray(u, dtype=float)
        if u.shape != (2 * self.n,):
            raise ValueError(f"u must have shape ({2 * self.n},), got {u.shape}")
        return u


def response_surrogate(spectrum, transfer, *, duration=600.0, t0=None, omega_max=3.0,
                       depth=np.inf, speed=0.0, heading=180.0, x=0.0, second_order=True,
                       omega_max_2=None) -> ResponseSurrogate:
    """Build the surrogate response of an episode (module docs).

    Parameters
    ----------
    spectrum : callable
        ``spectrum(omega) -> S`` one-sided wave spectrum (m^2 s/rad) on the
        absolute frequency, e.g. ``lambda w: jonswap(w, 13.2, 10.0, 3.0)``.
    transfer : callable
        ``transfer(omega) -> T`` complex response per unit wave amplitude at
        ``x`` on the absolute frequency (rad/s); it is also applied to the
        second-order components, as if they were free waves (Eq. 5).
    duration : float, default 600
        Episode length (s); the grid step is ``1 / duration`` Hz and the
        record is periodic.
    t0 : float, optional
        Conditioning time (s); default the middle of the episode.
    omega_max : float, default 3.0
        Highest absolute wave frequency of the components (rad/s).
    depth, speed, heading : float
        Water depth (m), ship speed (m/s), wave heading (deg, 180 = head seas).
    x : float, default 0
        Ship-fixed longitudinal position (m) of the structure point.
    second_order : bool, default True
        Add the Sharma–Dean second-order surface; ``False`` gives the linear
        surrogate (whose FORM solution is MLER).
    omega_max_2 : float, optional
        Highest frequency taking part in second-order interactions (rad/s);
        default ``omega_max``.

    Returns
    -------
    ResponseSurrogate

    Examples
    --------
    >>> from pas.waves import jonswap
    >>> s = response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: 1.0 + 0 * w,
    ...                        depth=30.0, omega_max=2.0)
    >>> s.n, round(4 * s.m0 ** 0.5, 1)      # components and Hs of the grid
    (191, 10.0)
    """
    if not (np.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    t0 = 0.5 * duration if t0 is None else float(t0)
    if not 0.0 <= t0 < duration:
        raise ValueError(f"t0 must lie in [0, duration) = [0, {duration:g}), got {t0!r}")
    if not callable(spectrum) or not callable(transfer):
        raise ValueError("spectrum and transfer must be callables of the frequency (rad/s)")
    grid = linear_sea(spectrum, duration, seed=0, depth=depth, omega_max=omega_max,
                      speed=speed, heading=heading)
    template = replace(grid, amplitude=np.abs(grid.amplitude) / np.sqrt(2.0), seed=None)
    kernel = None
    n_out = template.amplitude.size
    if second_order:
        kernel = second_order_kernel(template, omega_max=omega_max if omega_max_2 is None
                                     else omega_max_2)
        n_out = max(n_out, 2 * (kernel.j0 + kernel.size) - 1)
    omega_e = 2.0 * np.pi * template.df * np.arange(n_out)
    omega = wave_frequency_from_encounter(omega_e, speed, heading)
    t = np.zeros(n_out, dtype=complex)
    t[1:] = np.broadcast_to(np.asarray(transfer(omega[1:]), dtype=complex), (n_out - 1,))
    if not np.all(np.isfinite(t)):
        raise ValueError("transfer(omega) must be finite on the grid frequencies")
    weight = t * np.exp(1j * omega_e * t0)
    b, q = _linear_part(template, weight, x), None
    if kernel is not None:
        q = _quadratic_part(template, kernel, weight, x)
    return ResponseSurrogate(template=template, transfer=t, x=float(x), t0=t0, kernel=kernel,
                             b=b, q=q)


def _linear_part(template, weight, x):
    """``b`` with ``chi_1 = b·u``: ``c_n = w_n sigma_n E_n``, ``b = (Re c, -Im c)``."""
    n = template.amplitude.size
    c = weight[:n] * template.amplitude_at(x)
    return np.concatenate([c.real, -c.imag])


def _quadratic_part(template, kernel, weight, x):
    """Symmetric ``Q`` with ``chi_2 = u·Q u`` (module docs).

    With ``a = d z``, ``z = x + i y``, ``d_n = sigma_n E_n`` and the kernels of
    :class:`SecondOrderKernel` (each unordered pair once), the second-order
    response at ``t0`` is ``Re(z^T P z + z^H M z)`` with
    ``P_nm = plus_nm w_{n+m} d_n d_m`` and ``M_nm = minus_nm w_{m-n} conj(d_n) d_m``.
    """
    n, p, j0 = template.amplitude.size, kernel.size, kernel.j0
    d = template.amplitude_at(x)[j0:j0 + p]
    idx = np.arange(p)
    w_sum = weight[2 * j0 + idx[:, None] + idx[None, :]]
    w_diff = weight[np.abs(idx[None, :] - idx[:, None])]
    pm = kernel.plus * w_sum * np.outer(d, d)
    mm = kernel.minus * w_diff * np.outer(np.conj(d), d)
    # Re(P z_i z_j) and Re(M conj(z_i) z_j) in the real variables (x, y).
    g = np.zeros((2 * n, 2 * n))
    xs, ys = slice(j0, j0 + p), slice(n + j0, n + j0 + p)
    g[xs, xs] = pm.real + mm.real
    g[ys, ys] = -pm.real + mm.real
    g[xs, ys] = -pm.imag - mm.imag
    g[ys, xs] = -pm.imag + mm.imag
    return 0.5 * (g + g.T)


def synthesise_on(surrogate, coefficients, dt):
    """Time series of coefficients on the surrogate's grid (helper for episodes)."""
    return synthesise(coefficients, surrogate.template.df, dt)
