"""Design waves: MLER and response-conditioned waves (FORM-RCW) on a wave surrogate.

A design wave replaces the irregular sea by one short episode whose response
reaches a target at a chosen time ``t0`` (Dermatis et al. 2025, §2.2.2).

The episode's sea and the surrogate response ``chi(t0 | u)`` it is conditioned
on are defined in :mod:`pas.waves.surrogate`.

MLER (Adegeest et al. 1998; Dietz 2004)
---------------------------------------
For a linear surrogate the most likely ``u`` with ``chi = R`` is the
conditional mean ``u* = R b / |b|^2``, i.e. ``A_n = R sigma_n^2 conj(T_n)
exp(-i w_n t0) / sum_k sigma_k^2 |T_k|^2`` (:func:`mler_amplitudes`).

FORM-RCW (Dermatis et al. 2025, §3.1.3, Eq. 6–7)
-----------------------------------------------
``min |u|`` subject to ``G(u) = R - chi(t0 | u) = 0``, started from MLER, by
the Hasofer–Lind–Rackwitz–Fiessler iteration with an Armijo step on the merit
function ``m(u) = |u|^2 / 2 + c |G(u)|`` (the improved HL-RF of Zhang &
Der Kiureghian 1995; the paper's MHLGA, Santos et al. 2012, is of this kind).

References
----------
Dermatis, A., Lasbleis, M., Kim, S., de Hauteclocque, G., Bouscasse, B.,
Ducrozet, G. (2025). A multi-fidelity approach for the evaluation of extreme
wave loads using nonlinear response-conditioned waves. Ocean Engineering 316,
119919. doi:10.1016/j.oceaneng.2024.119919 (CC BY 4.0)

Adegeest, L.J.M., Braathen, A., Løseth, R.M. (1998). Use of non-linear sea-loads
simulations in design of ships. PRADS'98.

Dietz, J.S. (2004). Application of conditional waves as critical wave episodes
for extreme loads on marine structures. PhD thesis, DTU.

Zhang, Y., Der Kiureghian, A. (1995). Two improved algorithms for reliability
analysis. Reliability and Optimization of Structural Systems, 297–304.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["mler_amplitudes", "mler", "FormResult", "form_rcw", "rayleigh_target"]


def mler_amplitudes(sigma, transfer, target, *, omega_e, t0=0.0):
    """MLER complex amplitudes in closed form (Adegeest et al. 1998; Dietz 2004).

    The conditional mean of a Gaussian sea given that its linear response
    ``Re sum T_n A_n exp(i w_n t)`` equals ``target`` at ``t0``:
    ``A_n = target sigma_n^2 conj(T_n) exp(-i w_n t0) / sum_k sigma_k^2 |T_k|^2``.

    Parameters
    ----------
    sigma : array_like, shape (N,)
        Standard deviation of each component's cosine (and sine) coefficient,
        ``sqrt(S(w_n) dw)``.
    transfer : array_like of complex, shape (N,)
        Response per unit complex wave amplitude.
    target : float
        Response at ``t0`` (any sign).
    omega_e : array_like, shape (N,)
        Frequencies of the time dependence (rad/s).
    t0 : float, default 0

    Returns
    -------
    ndarray of complex, shape (N,)
        ``A_n`` such that the wave is ``Re sum A_n exp(i w_n t)``.

    Examples
    --------
    >>> import numpy as np
    >>> a = mler_amplitudes([1.0, 2.0], [1.0, 0.5j], 3.0, omega_e=[1.0, 2.0])
    >>> float(np.real(np.sum(np.array([1.0, 0.5j]) * a)))   # the response hits the target
    3.0
    """
    s2 = np.asarray(sigma, dtype=float) ** 2
    t = np.asarray(transfer, dtype=complex)
    w = np.asarray(omega_e, dtype=float)
    if s2.shape != t.shape or w.shape != t.shape or s2.ndim != 1:
        raise ValueError("sigma, transfer and omega_e must be 1-D arrays of equal length")
    m0 = float(np.sum(s2 * np.abs(t) ** 2))
    if not m0 > 0:
        raise ValueError("the response has zero variance: transfer is zero where sigma is not")
    return float(target) * s2 * np.conj(t) * np.exp(-1j * w * t0) / m0


def mler(surrogate, target) -> np.ndarray:
    """MLER standard-normal coordinates ``u* = target b / |b|^2`` (linear part of ``chi``)."""
    bb = surrogate.b @ surrogate.b
    if not bb > 0:
        raise ValueError("the linear response has zero variance on this grid")
    return float(target) * surrogate.b / bb


@dataclass(frozen=True)
class FormResult:
    """Outcome of :func:`form_rcw`.

    ``u`` is the most probable point, ``beta = |u|`` its reliability index,
    ``residual = |chi(u) − target| / |target|`` and ``alignment`` the part of
    ``u`` orthogonal to the gradient over ``|u|`` (0 at a constrained
    minimum of ``|u|``).
    """

    u: np.ndarray
    beta: float
    value: float
    residual: float
    alignment: float
    iterations: int
    converged: bool


def _state(surrogate, u, target):
    chi, grad = surrogate.value_and_gradient(u)
    gg = float(grad @ grad)
    if not gg > 0:
        raise ValueError("the surrogate response has a zero gradient: no design wave reaches "
                         "the target from here")
    perp = u - (u @ grad) / gg * grad
    nu = float(np.linalg.norm(u))
    return chi - target, grad, gg, (float(np.linalg.norm(perp)) / nu if nu > 0 else 0.0)


def form_rcw(surrogate, target, *, start=None, tol=1e-6, max_iter=50) -> FormResult:
    """Most probable ``u`` with ``chi(t0 | u) = target`` (Eq. 6–7): improved HL-RF.

    Each iteration moves towards the HL-RF point
    ``u_HL = ((grad·u − G) / |grad|^2) grad`` (``G = chi − target``), halving
    the step until the merit ``|u|^2/2 + c |G|`` decreases by the Armijo
    fraction 1e-4 of its directional derivative (Zhang & Der Kiureghian 1995).

    Parameters
    ----------
    surrogate : ResponseSurrogate
    target : float
        Non-zero response at ``t0``.
    start : array_like, optional
        Starting point; default MLER (:func:`mler`).
    tol : float, default 1e-6
        Converged when ``|chi − target| <= tol |target|`` and the alignment
        (see :class:`FormResult`) is ``<= tol``.
    max_iter : int, default 50

    Returns
    -------
    FormResult
        ``converged`` is False when ``max_iter`` ran out; the last iterate is
        returned, never silently taken as the answer.
    """
    target = float(target)
    if not (np.isfinite(target) and target != 0.0):
        raise ValueError(f"target must be a non-zero finite response, got {target!r}")
    u = mler(surrogate, target) if start is None else surrogate._check(start).copy()
    g, grad, gg, align = _state(surrogate, u, target)
    it = 0
    while not (abs(g) <= tol * abs(target) and align <= tol) and it < max_iter:
        it += 1
        u_hl = ((grad @ u - g) / gg) * grad
        d = u_hl - u
        ud = float(u @ d)
        # Merit weight: c |grad| > |u| makes d a descent direction (Zhang & Der Kiureghian).
        c = 2.0 * max(float(np.linalg.norm(u)) / np.sqrt(gg), (ud / abs(g)) if g else 0.0, 1e-12)
        merit = 0.5 * float(u @ u) + c * abs(g)
        slope = ud - c * abs(g)  # directional derivative of the merit along d
        lam = 1.0
        while True:
            trial = u + lam * d
            g_t = surrogate.value(trial) - target
            if 0.5 * float(trial @ trial) + c * abs(g_t) <= merit + 1e-4 * lam * slope \
                    or lam < 1e-8:
                break
            lam *= 0.5
        u = trial
        g, grad, gg, align = _state(surrogate, u, target)
    return FormResult(u=u, beta=float(np.linalg.norm(u)), value=g + target,
                      residual=abs(g) / abs(target), alignment=align, iterations=it,
                      converged=bool(abs(g) <= tol * abs(target) and align <= tol))


def rayleigh_target(m0, p, *, peaks_per_wave=1.0):
    """Linear response exceeded with probability ``p`` per wave encounter (Rayleigh).

    ``r = sqrt(2 m0 ln(peaks_per_wave / p))``: each of ``peaks_per_wave``
    response peaks per encounter exceeds ``r`` with probability
    ``exp(-r^2 / (2 m0))`` (narrow band).

    Examples
    --------
    >>> round(float(rayleigh_target(1.0, 1e-3)), 4)
    3.7169
    """
    p = np.asarray(p, dtype=float)
    if not (np.isfinite(m0) and m0 > 0):
        raise ValueError(f"m0 must be a positive variance, got {m0!r}")
    if np.any(~(p > 0)) or np.any(p >= peaks_per_wave):
        raise ValueError("p must lie in (0, peaks_per_wave)")
    return np.sqrt(2.0 * m0 * np.log(peaks_per_wave / p))
