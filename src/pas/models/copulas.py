"""Copula candidates, maximum-likelihood fits, AIC selection and conditional draws.

Paper §2.2 and App. B: the LF–HF pairs become pseudo-observations (Eq. 5), five
one- or two-parameter families are fitted by maximum likelihood
(pyvinecopulib), the family with the lowest AIC (Eq. 13–14) is selected with a
ΔAIC ≥ 4 hysteresis, and HF ranks are drawn from the conditional inverse
``C⁻¹_{V|U}(r | u)`` (Eq. 7).

Conditional inverses are closed forms where they exist (Gaussian, Student-t,
Clayton, Frank, Gumbel, and their rotations) because pyvinecopulib inverts
several of them numerically, far slower for the draws of an iteration; Joe,
BB1 and TLL use pyvinecopulib's ``hinv1``.  The closed forms are tested
against ``hinv1`` and against the ``copulas`` package.  The Student-t one
needs the t quantile and CDF; :func:`t_quantile` and :func:`t_cdf` give them
from cubic Hermite interpolants cached per ν (~1e-9 relative to scipy,
several times faster).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np
import pyvinecopulib as pv
from scipy import special

from ..stats.dependence import (  # Eq. 5: the input of every fit
    kendall_tau,
    pseudo_observations,
)

__all__ = [
    "PAPER_FAMILIES",
    "EXTRA_FAMILIES",
    "CopulaFit",
    "pseudo_observations",
    "tau_inversion_parameter",
    "fit_copula",
    "fit_candidates",
    "select_family",
    "conditional_quantile",
]

PAPER_FAMILIES = ("gaussian", "student", "clayton", "gumbel", "frank")
"""The paper's five candidates (§2.2), the default candidate set."""

EXTRA_FAMILIES = ("clayton_180", "gumbel_180", "joe", "joe_180", "bb1", "bb1_180", "tll")
"""Optional extra candidates: survival (180°-rotated) versions, Joe, BB1, TLL."""

_FAMILY = {
    "gaussian": pv.BicopFamily.gaussian,
    "student": pv.BicopFamily.student,
    "clayton": pv.BicopFamily.clayton,
    "gumbel": pv.BicopFamily.gumbel,
    "frank": pv.BicopFamily.frank,
    "joe": pv.BicopFamily.joe,
    "bb1": pv.BicopFamily.bb1,
    "tll": pv.BicopFamily.tll,
}


def _family_and_rotation(name: str):
    base, _, rot = name.partition("_")
    if base not in _FAMILY or rot not in ("", "180"):
        raise ValueError(
            f"unknown copula family {name!r}; choose from {PAPER_FAMILIES + EXTRA_FAMILIES}"
        )
    return _FAMILY[base], int(rot or 0)


@dataclass(frozen=True)
class CopulaFit:
    """One fitted candidate: its name, the pyvinecopulib model and its scores.

    ``at_bound`` is true when a parameter sits on the edge of its admissible
    range (e.g. Student-t ν at 2): the MLE is then not an interior optimum and
    AIC's justification does not hold for it.
    """

    name: str
    bicop: pv.Bicop = field(repr=False)
    loglik: float
    aic: float
    npars: float
    at_bound: bool

    @property
    def parameters(self) -> np.ndarray:
        return np.asarray(self.bicop.parameters, dtype=float).ravel()

    @property
    def tau(self) -> float:
        return float(self.bicop.parameters_to_tau(self.bicop.parameters))


def _at_bound(bicop: pv.Bicop, name: str) -> bool:
    if name.startswith("tll"):
        return False
    p = np.asarray(bicop.parameters, dtype=float).ravel()
    lo = np.asarray(bicop.parameters_lower_bounds, dtype=float).ravel()
    hi = np.asarray(bicop.parameters_upper_bounds, dtype=float).ravel()
    tol = 1e-3 * np.maximum(1.0, np.abs(hi - lo))
    if name.startswith("gaussian") or name.startswith("student"):
        # |ρ| = 1 is degenerate; ν at either end is the boundary case of pas.strategies.pas.
        return bool(np.any(np.abs(p - lo) < tol) or np.any(np.abs(p - hi) < tol))
    # one-parameter families: the lower bound is independence (Clayton, Gumbel, Joe)
    # or strong negative dependence (Frank) — neither is the case of pas.strategies.pas
    return bool(np.any(np.abs(p - hi) < tol))


#: families whose paper fit is the inversion of Kendall's tau (§2.8, the ``copulas`` package)
ARCHIMEDEAN = ("clayton", "gumbel", "frank")


def tau_inversion_parameter(name: str, tau: float) -> float:
    """The parameter of a one-parameter family with Kendall's ``tau`` (App. B.2).

    Clayton ``θ = 2τ/(1−τ)``, Gumbel ``θ = 1/(1−τ)``, Frank by the Debye
    relation — the rank-based estimator of the ``copulas`` package the paper
    used for these families (§2.8).  Raises ``ValueError`` where the family
    cannot have that τ (Clayton and Gumbel need τ > 0), as that package does.
    """
    base = name.partition("_")[0]
    if not -1.0 < tau < 1.0:
        raise ValueError(f"Kendall's tau must be in (-1, 1) for a {name} fit, got {tau}")
    if base == "clayton":
        if tau <= 0:
            raise ValueError(f"a Clayton copula cannot have tau = {tau:.3f} <= 0")
        return 2.0 * tau / (1.0 - tau)
    if base == "gumbel":
        if tau < 0:
            raise ValueError(f"a Gumbel copula cannot have tau = {tau:.3f} < 0")
        return 1.0 / (1.0 - tau)
    if base == "frank":
        family, _ = _family_and_rotation(name)
        return float(pv.Bicop(family=family).tau_to_parameters(tau).ravel()[0])
    raise ValueError(f"tau inversion is defined here for {ARCHIMEDEAN}, not {name!r}")


def fit_copula(name: str, u, v, *, method: str = "mle") -> CopulaFit:
    """Fit one family to pseudo-observations ``(u, v)``.

    ``method="mle"``: maximum likelihood (pyvinecopulib).
    ``method="itau"``: the inversion of Kendall's τ for Clayton, Gumbel and
    Frank (:func:`tau_inversion_parameter`, the paper's estimator for these
    three); other families are fitted by maximum likelihood.
    """
    family, rotation = _family_and_rotation(name)
    data = np.column_stack([np.asarray(u, float), np.asarray(v, float)])
    if method not in ("mle", "itau"):
        raise ValueError(f"method must be 'mle' or 'itau', got {method!r}")
    if method == "itau" and name.partition("_")[0] in ARCHIMEDEAN:
        tau = kendall_tau(data[:, 0], data[:, 1])  # a 180° rotation keeps τ
        theta = tau_inversion_parameter(name, tau)
        bicop = pv.Bicop(family=family, rotation=rotation)
        lo = float(np.ravel(bicop.parameters_lower_bounds)[0])
        hi = float(np.ravel(bicop.parameters_upper_bounds)[0])
        bicop = pv.Bicop(family=family, rotation=rotation,
                         parameters=np.array([[min(max(theta, lo), hi)]]))
    else:
        bicop = pv.Bicop(family=family, rotation=rotation)
        controls = pv.FitControlsBicop(family_set=[family], parametric_method="mle")
        bicop.fit(data, controls=controls)
    loglik = float(bicop.loglik(data))
    npars = float(bicop.npars)
    return CopulaFit(name=name, bicop=bicop, loglik=loglik, aic=2.0 * npars - 2.0 * loglik,
                     npars=npars, at_bound=_at_bound(bicop, name))


def fit_candidates(u, v, families=PAPER_FAMILIES, *, method: str = "mle") -> dict[str, CopulaFit]:
    """Fit every candidate family; returns ``{name: CopulaFit}`` in the given order.

    A family that cannot be fitted to these data (a τ-inversion Clayton or
    Gumbel with τ ≤ 0) is left out, as the paper's stack fails on it.
    """
    fits = {}
    for name in families:
        try:
            fits[name] = fit_copula(name, u, v, method=method)
        except ValueError:
            if method != "itau":
                raise
    if not fits:
        raise ValueError("no copula family could be fitted to these pairs")
    return fits


def select_family(fits: dict[str, CopulaFit], current: str | None = None, *,
                  delta_aic: float = 4.0, exclude_at_bound: bool = False) -> str:
    """Pick the family by AIC with hysteresis (§2.2).

    The lowest-AIC candidate replaces ``current`` only if its AIC is at least
    ``delta_aic`` lower than ``current``'s on the same data.  With
    ``exclude_at_bound`` candidates whose MLE sits on a parameter bound are
    not eligible (a boundary MLE is not a regular fit; see
    :mod:`pas.strategies.pas` for why this is the default there).
    """
    eligible = {k: f for k, f in fits.items() if not (exclude_at_bound and f.at_bound)}
    if not eligible:
        eligible = fits
    best = min(eligible, key=lambda k: eligible[k].aic)
    if current is None or current not in eligible:
        return best
    if eligible[best].aic <= eligible[current].aic - delta_aic:
        return best
    return current


def conditional_quantile(fit: CopulaFit | pv.Bicop, u, r, *, r_scores=None) -> np.ndarray:
    """``v = C⁻¹_{V|U}(r | u)``, the conditional inverse of Eq. 7, vectorised.

    ``u`` and ``r`` broadcast against each other (pass ``u`` of shape
    ``(1, n0)`` and ``r`` of shape ``(z, n0)``: the ``u``-terms are then
    computed once per conditioning peak).  Closed forms for Gaussian,
    Student-t, Clayton, Frank and Gumbel (the latter through the Wright
    omega function) and their 180° rotations; pyvinecopulib's ``hinv1``
    otherwise.  ``r_scores``: ``Φ⁻¹(r)`` when the caller keeps it (common
    random numbers), read by the Gaussian and Student-t draws.
    """
    bicop = fit.bicop if isinstance(fit, CopulaFit) else fit
    u, r = np.asarray(u, float), np.asarray(r, float)
    fam, rot = bicop.family, int(bicop.rotation)
    p = np.asarray(bicop.parameters, dtype=float).ravel()
    if rot == 180:
        # survival copula: C̄⁻¹(r | u) = 1 − C⁻¹(1 − r | 1 − u); Φ⁻¹(1 − r) = −Φ⁻¹(r)
        base = pv.Bicop(family=fam, parameters=bicop.parameters, rotation=0)
        return 1.0 - _hinv1(fam, p, base, 1.0 - u, 1.0 - r,
                            None if r_scores is None else -r_scores)
    if rot != 0:
        raise ValueError(f"rotation {rot} is not supported for conditional draws")
    return _hinv1(fam, p, bicop, u, r, r_scores)


def _hinv1(fam, p, bicop, u, r, r_scores=None):
    if fam == pv.BicopFamily.gaussian:
        rho = p[0]
        scores = special.ndtri(r) if r_scores is None else r_scores
        z, x = np.sqrt(1 - rho**2) * np.asarray(scores, float), rho * special.ndtri(u)
        if np.ndim(z) and z.shape == np.broadcast_shapes(z.shape, np.shape(x)):
            z += x  # in place: one array of the draws' shape
            return special.ndtr(z, out=z)
        return special.ndtr(z + x)
    if fam == pv.BicopFamily.student:
        rho, nu = p
        x1 = t_quantile(nu, u)
        scale = np.sqrt((nu + x1**2) * (1 - rho**2) / (nu + 1.0))
        return t_cdf(nu, rho * x1 + scale * t_quantile(nu + 1.0, r, scores=r_scores))
    if fam == pv.BicopFamily.clayton:
        th = p[0]
        if th < 1e-8:
            return np.broadcast_to(r, np.broadcast_shapes(u.shape, r.shape)).copy()
        return np.exp(-np.log1p(np.expm1(-th / (1 + th) * np.log(r)) * u ** (-th)) / th)
    if fam == pv.BicopFamily.frank:
        th = p[0]
        if abs(th) < 1e-8:
            return np.broadcast_to(r, np.broadcast_shapes(u.shape, r.shape)).copy()
        # algebraically −ln(1 + r(e^{−θ}−1)/(r + (1−r)e^{−θu}))/θ, rearranged so that
        # nothing cancels for large θ and u near 1
        return (u - np.log((1 - r) + r * np.exp(-th * (1 - u))) / th
                + np.log(r + (1 - r) * np.exp(-th * u)) / th)
    if fam == pv.BicopFamily.gumbel and p[0] > 1 + 1e-6:
        # h(v|u) = r with x = −ln u, w = ((−ln u)^θ + (−ln v)^θ)^{1/θ} gives
        # w + (θ−1) ln w = x + (θ−1) ln x − ln r, solved by w = (θ−1) ω(s) with
        # the Wright omega function ω (ω + ln ω = s).
        # in place: two arrays of the draws' shape alive at a time, not five
        th = p[0]
        x = -np.log(u)
        s = np.subtract(x + (th - 1) * np.log(x), np.log(r))
        s /= th - 1
        s -= np.log(th - 1)
        w = special.wrightomega(s).real
        del s
        w *= th - 1
        np.maximum(w, x, out=w)
        np.power(w, th, out=w)
        w -= x**th
        np.maximum(w, 0.0, out=w)
        np.log(w, out=w)
        w /= th
        np.exp(w, out=w)
        np.negative(w, out=w)
        return np.exp(w, out=w)
    if fam == pv.BicopFamily.indep or fam == pv.BicopFamily.gumbel:
        return np.broadcast_to(r, np.broadcast_shapes(u.shape, r.shape)).copy()
    u, r = np.broadcast_arrays(u, r)
    return bicop.hinv1(np.column_stack([u.ravel(), r.ravel()])).reshape(u.shape)


# -- Student-t quantile and CDF for the conditional draws --------------------
# scipy's stdtrit/stdtr are the costly part of an iteration's Student-t draws.  Both
# are monotone maps that become smooth after a change of variable, so a cubic Hermite
# interpolant with exact derivatives on a fixed grid, built once per ν (cheap) and
# looked up by index arithmetic, reproduces them to
# ~1e-9 relative (tests/models/test_copulas.py); values beyond the grid go to scipy.
_T_Z = 5.4
"""Half-width of the normal-score grid: Φ(−5.4) ≈ 3e-8, below the ε = 1e-6 draws."""
_T_NODES = 1024
"""Grid intervals per half of each table."""


def _t_pdf(x, nu):
    c = special.gammaln((nu + 1) / 2) - special.gammaln(nu / 2) - 0.5 * np.log(nu * np.pi)
    return np.exp(c - (nu + 1) / 2 * np.log1p(x * x / nu))


def _phi(z):
    return np.exp(-0.5 * z * z) / np.sqrt(2 * np.pi)


def _hermite_coefficients(y, dy, h):
    """Per-interval cubic coefficients, rows ``(c0, c1, c2, c3)``, of the Hermite interpolant
    through ``y`` with slopes ``dy`` on a grid of step ``h`` (local variable in [0, 1])."""
    y0, y1, m0, m1 = y[:-1], y[1:], dy[:-1] * h, dy[1:] * h
    return np.vstack([y0, m0, 3 * (y1 - y0) - 2 * m0 - m1, 2 * (y0 - y1) + m0 + m1])


def _hermite(x, x0, h, coef):
    """The interpolant of :func:`_hermite_coefficients` on the grid ``x0 + k h`` at ``x``.

    NaN where ``x`` is NaN; the caller replaces values outside the grid.  Each
    coefficient is gathered from its own contiguous row and Horner's rule runs in
    place (twice as fast as gathering the four together).
    """
    s = (x - x0) * (1.0 / h)
    i = np.fmin(np.fmax(s, 0.0), coef.shape[1] - 1).astype(np.intp)  # NaN -> 0
    with np.errstate(invalid="ignore", over="ignore"):  # ±inf outside the grid
        t = s - i
        out = np.take(coef[3], i)
        for row in coef[2::-1]:
            out *= t
            out += np.take(row, i)
    return out


@functools.lru_cache(maxsize=128)
def _t_quantile_table(nu: float):
    """Grid start, step and Hermite coefficients of ``t_ν⁻¹(Φ(z))`` on ``z ∈ [−Z, Z]``."""
    z = np.linspace(-_T_Z, _T_Z, 2 * _T_NODES + 1)
    low = special.stdtrit(nu, special.ndtr(z[:_T_NODES]))  # lower half: no cancellation
    q = np.concatenate([low, [0.0], -low[::-1]])
    h = z[1] - z[0]
    return z[0], h, _hermite_coefficients(q, _phi(z) / _t_pdf(q, nu), h)


@functools.lru_cache(maxsize=128)
def _t_cdf_table(nu: float):
    """Grid start, step and Hermite coefficients of ``Φ⁻¹(F_ν(sinh a))`` (a = asinh x)."""
    a_max = float(np.arcsinh(-special.stdtrit(nu, special.ndtr(-_T_Z))))
    a = np.linspace(-a_max, a_max, 2 * _T_NODES + 1)
    low = special.ndtri(special.stdtr(nu, np.sinh(a[:_T_NODES])))
    z = np.concatenate([low, [0.0], -low[::-1]])
    h = a[1] - a[0]
    return a[0], h, _hermite_coefficients(z, _t_pdf(np.sinh(a), nu) * np.cosh(a) / _phi(z), h)


def t_quantile(nu, p, *, scores=None) -> np.ndarray:
    """Student-t quantile ``t_ν⁻¹(p)``, elementwise; scipy's ``stdtrit`` to ~1e-9, faster.

    ``scores``: ``Φ⁻¹(p)`` when the caller has it.

    Examples
    --------
    >>> from scipy import special
    >>> p = np.array([1e-6, 0.025, 0.5, 0.9, 1 - 1e-6])
    >>> bool(np.allclose(t_quantile(3.5, p), special.stdtrit(3.5, p), rtol=1e-8))
    True
    """
    x = special.ndtri(np.asarray(p, dtype=float)) if scores is None else scores
    out = np.asarray(_hermite(x, *_t_quantile_table(float(nu))))
    outside = np.abs(x) > _T_Z
    if outside.any():
        out[outside] = special.stdtrit(nu, np.asarray(p, dtype=float)[outside])
    return out


def t_cdf(nu, x) -> np.ndarray:
    """Student-t CDF ``F_ν(x)``, elementwise; scipy's ``stdtr`` to ~1e-9 relative, faster.

    Examples
    --------
    >>> from scipy import special
    >>> x = np.array([-300.0, -2.0, 0.0, 1.5, 40.0])
    >>> bool(np.allclose(t_cdf(3.5, x), special.stdtr(3.5, x), rtol=1e-8, atol=0))
    True
    """
    a0, h, coef = _t_cdf_table(float(nu))
    x = np.asarray(x, dtype=float)
    w = np.arcsinh(x)
    out = np.asarray(special.ndtr(_hermite(w, a0, h, coef)))
    outside = np.abs(w) > -a0
    if outside.any():
        out[outside] = special.stdtr(nu, x[outside])
    return out
