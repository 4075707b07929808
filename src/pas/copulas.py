"""Copula candidates, maximum-likelihood fits, AIC selection and conditional draws.

Paper §2.2 and App. B: the LF–HF pairs become pseudo-observations (Eq. 5), five
one- or two-parameter families are fitted by maximum likelihood
(pyvinecopulib), the family with the lowest AIC (Eq. 13–14) is selected with a
ΔAIC ≥ 4 hysteresis, and HF ranks are drawn from the conditional inverse
``C⁻¹_{V|U}(r | u)`` (Eq. 7).

Conditional inverses are closed forms where they exist (Gaussian, Student-t,
Clayton, Frank, Gumbel, and their rotations) because pyvinecopulib inverts
several of them numerically, which costs 0.03–0.8 s per 150 000 draws; Joe,
BB1 and TLL use pyvinecopulib's ``hinv1``.  The closed forms are tested
against ``hinv1`` and against the ``copulas`` package.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pyvinecopulib as pv
from scipy import special

from .stats.dependence import kendall_tau, pseudo_observations  # Eq. 5: the input of every fit

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


def conditional_quantile(fit: CopulaFit | pv.Bicop, u, r) -> np.ndarray:
    """``v = C⁻¹_{V|U}(r | u)``, the conditional inverse of Eq. 7, vectorised.

    ``u`` and ``r`` broadcast against each other (pass ``u`` of shape
    ``(1, n0)`` and ``r`` of shape ``(z, n0)``: the ``u``-terms are then
    computed once per conditioning peak).  Closed forms for Gaussian,
    Student-t, Clayton, Frank and Gumbel (the latter through the Wright
    omega function) and their 180° rotations; pyvinecopulib's ``hinv1``
    otherwise.
    """
    bicop = fit.bicop if isinstance(fit, CopulaFit) else fit
    u, r = np.asarray(u, float), np.asarray(r, float)
    fam, rot = bicop.family, int(bicop.rotation)
    p = np.asarray(bicop.parameters, dtype=float).ravel()
    if rot == 180:
        # survival copula: C̄⁻¹(r | u) = 1 − C⁻¹(1 − r | 1 − u)
        base = pv.Bicop(family=fam, parameters=bicop.parameters, rotation=0)
        return 1.0 - _hinv1(fam, p, base, 1.0 - u, 1.0 - r)
    if rot != 0:
        raise ValueError(f"rotation {rot} is not supported for conditional draws")
    return _hinv1(fam, p, bicop, u, r)


def _hinv1(fam, p, bicop, u, r):
    if fam == pv.BicopFamily.gaussian:
        rho = p[0]
        return special.ndtr(rho * special.ndtri(u) + np.sqrt(1 - rho**2) * special.ndtri(r))
    if fam == pv.BicopFamily.student:
        rho, nu = p
        x1 = special.stdtrit(nu, u)
        scale = np.sqrt((nu + x1**2) * (1 - rho**2) / (nu + 1.0))
        return special.stdtr(nu, rho * x1 + scale * special.stdtrit(nu + 1.0, r))
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
        th = p[0]
        x = -np.log(u)
        s = (x + (th - 1) * np.log(x) - np.log(r)) / (th - 1) - np.log(th - 1)
        w = np.maximum((th - 1) * special.wrightomega(s).real, x)
        y = np.exp(np.log(np.maximum(w**th - x**th, 0.0)) / th)
        return np.exp(-y)
    if fam == pv.BicopFamily.indep or fam == pv.BicopFamily.gumbel:
        return np.broadcast_to(r, np.broadcast_shapes(u.shape, r.shape)).copy()
    u, r = np.broadcast_arrays(u, r)
    return bicop.hinv1(np.column_stack([u.ravel(), r.ravel()])).reshape(u.shape)
