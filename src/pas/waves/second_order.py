"""Second-order (sum and difference frequency) surface elevation, finite depth.

Theory
------
For long-crested linear components ``A_n = a_n exp(i phi_n)`` the second-order
elevation of Sharma & Dean (1979, 1981) is the double sum over all ordered
pairs

``eta2(t) = Re sum_n sum_m [ A_n A_m L+_nm exp(i (w_n + w_m) t)
                            + A_n conj(A_m) L-_nm exp(i (w_n - w_m) t) ]``

with ``R = w^2 / g = k tanh(kh)``, ``k+- = k_n +- k_m`` (long-crested) and

``D+ = [(sRn + sRm)(sRm (kn^2 - Rn^2) + sRn (km^2 - Rm^2))
        + 2 (sRn + sRm)^2 (kn km - Rn Rm)] / [(sRn + sRm)^2 - k+ tanh(k+ h)]``

``D- = [(sRn - sRm)(sRm (kn^2 - Rn^2) - sRn (km^2 - Rm^2))
        + 2 (sRn - sRm)^2 (kn km + Rn Rm)] / [(sRn - sRm)^2 - |k-| tanh(|k-| h)]``

``L+ = [(D+ - (kn km - Rn Rm)) / sqrt(Rn Rm) + Rn + Rm] / 4``

``L- = [(D- - (kn km + Rn Rm)) / sqrt(Rn Rm) + Rn + Rm] / 4``

(``sR = sqrt(R)``). These are the kernels of Sharma & Dean as implemented in
OpenFAST HydroDyn/SeaState (``Waves2.f90``: ``TransFuncD_plus``,
``TransFuncD_minus`` and the elevation transfer functions ``L+-`` of the
HydroDyn theory manual), specialised to a single direction. They reduce to the
deep-water forms ``L+ = (kn + km)/4`` and ``L- = -|kn - km|/4`` of
Longuet-Higgins (1963), to finite-depth Stokes second order for ``n = m``, and
to the Longuet-Higgins & Stewart (1964) set-down under a narrow group; the
tests check all three closed forms.

The diagonal difference terms (``n = m``) only produce a constant: the mean
water level is fixed at zero, so the zero-frequency term is dropped.

Algorithm
---------
On the equidistant grid ``f_j = j df`` the sum and difference frequencies of
two components fall on the grid, so the pair products are accumulated per
output frequency -- anti-diagonal sums (``n + m``) and diagonal sums
(``m - n``) of ``A_n A_m K_nm``, read through strided views of zero-padded
row blocks -- and synthesised with a single inverse FFT: O(N^2) once per seed,
never per time step. The kernels depend on the grid only and are computed once
(:func:`second_order_kernel`) and reused across seeds.

References
----------
Sharma, J.N., Dean, R.G. (1979). Development and evaluation of a procedure for
simulating a random directional second order sea surface and associated wave
forces. Ocean Engineering Report 20, University of Delaware.

Sharma, J.N., Dean, R.G. (1981). Second-order directional seas and associated
wave forces. Soc. Pet. Eng. J. 21(1), 129-140.

Jonkman, J.M. et al. HydroDyn User's Guide and Theory Manual; OpenFAST
``modules/seastate/src/Waves2.f90`` (Apache-2.0).

Longuet-Higgins, M.S., Stewart, R.W. (1964). Radiation stresses in water waves;
a physical discussion, with applications. Deep-Sea Res. 11, 529-562.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import as_strided

from .realisation import LinearSea, synthesise
from .spectra import GRAVITY, wave_number

__all__ = [
    "sharma_dean_kernels",
    "SecondOrderKernel",
    "second_order_kernel",
    "second_order_coefficients",
    "second_order_elevation",
    "direct_second_order",
]


def sharma_dean_kernels(omega_n, omega_m, depth=np.inf, *, g=GRAVITY):
    """Sharma-Dean elevation kernels ``L+`` and ``L-`` for long-crested pairs.

    Parameters
    ----------
    omega_n, omega_m : array_like
        Absolute angular frequencies (rad/s), broadcastable, ``> 0``.
    depth : float, default inf
        Water depth (m).
    g : float, default 9.81

    Returns
    -------
    l_plus, l_minus : ndarray
        Kernels (1/m). ``l_minus`` is set to 0 where ``omega_n == omega_m``
        (zero-frequency term, see module notes).

    Examples
    --------
    Deep water reduces to ``(kn + km)/4`` and ``-|kn - km|/4``:

    >>> lp, lm = sharma_dean_kernels(0.5, 0.8)
    >>> round(float(lp), 6), round(float(lm), 6)
    (0.022681, -0.009939)
    """
    wn = np.asarray(omega_n, dtype=float)
    wm = np.asarray(omega_m, dtype=float)
    if np.any(wn <= 0) or np.any(wm <= 0):
        raise ValueError("kernel frequencies must be positive")
    return _kernels(wn, wm, wave_number(wn, depth, g=g), wave_number(wm, depth, g=g), depth, g)


def _kernels(wn, wm, kn, km, depth, g):
    """Kernels from broadcastable frequencies and their wave numbers."""
    wn, wm, kn, km = np.broadcast_arrays(wn, wm, kn, km)
    rn = wn**2 / g
    rm = wm**2 / g
    srn = np.sqrt(rn)
    srm = np.sqrt(rm)
    sq = np.sqrt(rn * rm)

    def th(k):
        return np.ones_like(k) if np.isinf(depth) else np.tanh(k * depth)

    kp = kn + km
    sp = srn + srm
    d_plus = (sp * (srm * (kn**2 - rn**2) + srn * (km**2 - rm**2))
              + 2.0 * sp**2 * (kn * km - rn * rm)) / (sp**2 - kp * th(kp))
    l_plus = 0.25 * ((d_plus - (kn * km - rn * rm)) / sq + rn + rm)

    km_ = np.abs(kn - km)
    sm = srn - srm
    diag = wn == wm
    den = np.where(diag, 1.0, sm**2 - km_ * th(km_))
    d_minus = np.where(diag, 0.0,
                       (sm * (srm * (kn**2 - rn**2) - srn * (km**2 - rm**2))
                        + 2.0 * sm**2 * (kn * km + rn * rm)) / den)
    l_minus = np.where(diag, 0.0, 0.25 * ((d_minus - (kn * km + rn * rm)) / sq + rn + rm))
    return l_plus, l_minus


@dataclass(frozen=True)
class SecondOrderKernel:
    """Pair kernels on a contiguous block of grid indices ``j0 .. j0 + p - 1``.

    ``plus[n, m]`` holds ``L+`` (doubled off the diagonal, zero below it) and
    ``minus[n, m]`` holds ``2 L-`` above the diagonal (zero elsewhere), so each
    unordered pair is visited once.
    """

    j0: int
    plus: np.ndarray
    minus: np.ndarray
    df: float
    depth: float

    @property
    def size(self):
        return self.plus.shape[0]


_KERNEL_CACHE: dict = {}


def second_order_kernel(sea, *, omega_min=0.0, omega_max=5.0):
    """Kernels for all pairs of components of ``sea`` with ``omega_min <= w <= omega_max``.

    The result depends on the grid (``df``, frequencies, depth, speed,
    heading), not on the seed; the last few kernels are cached.

    Parameters
    ----------
    sea : LinearSea
    omega_min, omega_max : float, default 0, 5
        Band of absolute wave frequency (rad/s) taking part in interactions
        (the paper uses 0-5 rad/s).

    Returns
    -------
    SecondOrderKernel
    """
    if not isinstance(sea, LinearSea):
        raise TypeError("sea must be a LinearSea (equidistant grid)")
    w = sea.omega
    sel = np.flatnonzero((w > 0) & (w >= omega_min) & (w <= omega_max))
    if sel.size == 0:
        raise ValueError("no components inside the interaction band")
    j0, j1 = int(sel[0]), int(sel[-1]) + 1
    key = (sea.df, j0, j1, float(w[j0]), float(w[j1 - 1]), sea.depth)
    if key in _KERNEL_CACHE:
        return _KERNEL_CACHE[key]
    ws = w[j0:j1]
    ks = sea.wave_number[j0:j1]
    p = ws.size
    plus = np.zeros((p, p))
    minus = np.zeros((p, p))
    for r0 in range(0, p, 256):
        r1 = min(r0 + 256, p)
        lp, lm = _kernels(ws[r0:r1, None], ws[None, r0:], ks[r0:r1, None], ks[None, r0:],
                          sea.depth, GRAVITY)
        # Upper triangle only: each unordered pair once, off-diagonal doubled.
        offset = np.arange(r0, p)[None, :] - np.arange(r0, r1)[:, None]
        plus[r0:r1, r0:] = np.where(offset > 0, 2.0 * lp, np.where(offset == 0, lp, 0.0))
        minus[r0:r1, r0:] = np.where(offset > 0, 2.0 * lm, 0.0)
    kern = SecondOrderKernel(j0=j0, plus=plus, minus=minus, df=sea.df, depth=sea.depth)
    if len(_KERNEL_CACHE) >= 2:
        _KERNEL_CACHE.pop(next(iter(_KERNEL_CACHE)))
    _KERNEL_CACHE[key] = kern
    return kern


def second_order_coefficients(sea, kernel=None, *, x=0.0, chunk=128):
    """Complex second-order amplitudes on the grid ``f_q = q df``.

    Parameters
    ----------
    sea : LinearSea
    kernel : SecondOrderKernel, optional
        From :func:`second_order_kernel`; built (and cached) with the default
        0-5 rad/s band when omitted.
    x : float, default 0
        Ship-fixed longitudinal position (m) at which the surface is wanted.
    chunk : int, default 128
        Rows per block; bounds the memory to ``chunk * 2 p`` complex numbers.

    Returns
    -------
    ndarray of complex, shape (2 (j0 + p) - 1,)
        ``c_q`` such that ``eta2(t) = Re sum_q c_q exp(i 2 pi q df t)``;
        ``c_0 = 0``.
    """
    if kernel is None:
        kernel = second_order_kernel(sea)
    if kernel.df != sea.df or kernel.depth != sea.depth:
        raise ValueError("kernel was built for a different grid; rebuild it for this sea")
    p, j0 = kernel.size, kernel.j0
    a = sea.amplitude_at(x)[j0:j0 + p]
    out = np.zeros(2 * (j0 + p) - 1, dtype=complex)
    item = np.dtype(complex).itemsize
    for r0 in range(0, p, chunk):
        r1 = min(r0 + chunk, p)
        c, w = r1 - r0, p - r0
        ar = a[r0:r1, None]
        tail = a[None, r0:]
        buf = np.zeros((c, 2 * w), dtype=complex)
        # Sum frequencies: anti-diagonal u + i of block (i, u), u = m - r0.
        np.multiply(ar * tail, kernel.plus[r0:r1, r0:], out=buf[:, :w])
        anti = as_strided(buf, shape=(c, 2 * w - 1), strides=((2 * w - 1) * item, item))
        q0 = 2 * (j0 + r0)
        out[q0:q0 + 2 * w - 1] += anti.sum(axis=0)
        # Difference frequencies: diagonal u - i, i.e. m - n.
        np.multiply(np.conj(ar) * tail, kernel.minus[r0:r1, r0:], out=buf[:, :w])
        diag = as_strided(buf, shape=(c, w), strides=((2 * w + 1) * item, item))
        out[:w] += diag.sum(axis=0)
    out[0] = 0.0
    return out


def second_order_elevation(sea, dt, *, kernel=None, x=0.0):
    """Second-order elevation ``eta2`` of a :class:`LinearSea` by one inverse FFT.

    Parameters
    ----------
    sea : LinearSea
    dt : float
        Time step (s); must resolve twice the highest interacting frequency.
    kernel : SecondOrderKernel, optional
    x : float, default 0
        Ship-fixed longitudinal position (m).

    Returns
    -------
    t, eta2 : ndarray
        Add ``sea.elevation(dt, x=x)[1]`` for the total surface.
    """
    return synthesise(second_order_coefficients(sea, kernel, x=x), sea.df, dt)


def direct_second_order(omega, amplitude, t, *, depth=np.inf, omega_e=None, chunk=64):
    """Reference time-domain double summation of the Sharma-Dean elevation.

    Evaluates ``eta2(t)`` (module formula, zero-frequency term dropped) at
    each time by summing over all pairs of components: O(N^2) per time step.
    Meant for short slices, tests and the benchmark.

    Parameters
    ----------
    omega : array_like, shape (N,)
        Absolute wave frequencies (rad/s), ``> 0``.
    amplitude : array_like of complex, shape (N,)
        Complex amplitudes at the point of interest.
    t : array_like
        Times (s).
    depth : float, default inf
    omega_e : array_like, optional
        Frequencies of the phase rotation (encounter frequencies); default
        ``omega``.
    chunk : int, default 64
        Time steps per block.

    Returns
    -------
    ndarray
        ``eta2`` at ``t``.
    """
    w = np.asarray(omega, dtype=float)
    amp = np.asarray(amplitude, dtype=complex)
    we = w if omega_e is None else np.asarray(omega_e, dtype=float)
    k = wave_number(w, depth)
    lp, lm = _kernels(w[:, None], w[None, :], k[:, None], k[None, :], depth, GRAVITY)
    t = np.asarray(t, dtype=float)
    flat = t.ravel()
    out = np.empty(flat.size)
    for s in range(0, flat.size, chunk):
        e = amp[None, :] * np.exp(1j * np.outer(flat[s:s + chunk], we))
        out[s:s + chunk] = (np.einsum("tn,nm,tm->t", e, lp, e, optimize=True)
                            + np.einsum("tn,nm,tm->t", e, lm, np.conj(e), optimize=True)).real
    return out.reshape(t.shape)
