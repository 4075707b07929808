"""Probabilistic Adaptive Screening: the copula model of paper §2.1 Steps 7–12.

Each step is one function; :class:`PAS` strings them together per iteration
and carries the one piece of state the method has, the selected copula family
(the ΔAIC hysteresis of §2.2 compares against it).

Stability remedy (beyond the paper)
-----------------------------------
A faithful implementation of the paper's selection, tried on a problem whose
true copula is Gumbel, saw its MPM double once ~80 HF samples were in: the
Student-t candidate won the AIC with ν at its lower bound (2), and its
strong symmetric tail dependence pushed conditional draws of the largest LF
peaks into the far extrapolation of the Weibull HF marginal.  An MLE on the
boundary of the parameter space is not a regular estimate — the
asymptotics behind AIC (Akaike 1974) assume an interior optimum — so the
default here is ``exclude_at_bound=True``: a candidate whose fitted parameter
sits on its bound (Student-t ν = 2 or 50, |ρ| = 1, an Archimedean parameter at
its upper limit) is not eligible for selection in that iteration; the next
best regular fit is used.  ``exclude_at_bound=False`` restores the paper's
exact selection.

Reading of Step 7
-----------------
The temporary outlier removal feeds the *copula* fit ("the remaining data
are then used for copula fitting", §2.1); the Weibull marginals of Step 9 are
fitted to all true-positive samples (``marginals_from="all"``).  Removing the
largest genuine loads from the HF marginal biases its tail low by
construction — on the slamming analogues (cases 4a/4b) the removal count grew
to 15 pairs and the MPM drifted 5–6 % lower than with all pairs.
``marginals_from="kept"`` fits the marginals to the cleaned pairs as well.

Impact model (optional, beyond the paper)
-----------------------------------------
With an LF threshold, every conditioning peak above ``l0`` gets a positive
HF draw, although the evaluated false positives show that some of them give
no impact.  ``impact_model=True`` estimates ``P(impact | LF)`` by logistic
regression on the evaluated events (true positives vs false positives) and
zeroes each draw with probability ``1 − P``.  Off by default.
"""

from __future__ import annotations

import numpy as np
from sklearn.linear_model import LogisticRegression

from .._validation import check_option
from ..copulas import (
    PAPER_FAMILIES,
    CopulaFit,
    _family_and_rotation,
    conditional_quantile,
    fit_candidates,
    fit_copula,
    select_family,
)
from ..marginals import fit_marginal
from ..screening import LFSet
from ..stats.dependence import empirical_tail_dependence, kendall_tau, pseudo_observations
from ..stats.exceedance import value_at_exceedance
from .acquisition import md_select
from .base import Pairs, Prediction, Strategy, band95

__all__ = [
    "PAS",
    "remove_outliers",
    "conditioning_set",
    "draw_conditional_hf",
    "impact_probability",
    "fit_marginals",
    "fit_model",
    "hf_distribution",
]

EPS = 1e-6


def remove_outliers(lf, hf, *, k: float = 3.0) -> np.ndarray:
    """Step 7: mask of pairs kept after temporary outlier removal.

    A quadratic ``h ≈ poly2(l)`` is fitted; pairs with ``|r| > k · RMS(r)`` are
    dropped for this iteration only.  Fewer than 4 pairs: all kept.
    """
    lf, hf = np.asarray(lf, float), np.asarray(hf, float)
    if lf.size < 4:
        return np.ones(lf.size, dtype=bool)
    scale = np.ptp(lf) or 1.0
    x = (lf - lf.mean()) / scale
    r = hf - np.polyval(np.polyfit(x, hf, 2), x)
    rms = np.sqrt(np.mean(r**2))
    if rms == 0:
        return np.ones(lf.size, dtype=bool)
    return np.abs(r) <= k * rms


def conditioning_set(lf_sorted, l0: float) -> np.ndarray:
    """Step 9: the LF peaks ``≥ l0 = min(l_sel)`` the copula is conditioned on."""
    return lf_sorted[lf_sorted >= l0]


def draw_conditional_hf(fit: CopulaFit, lf_marginal, hf_marginal, lf_cond, z: int,
                        rng: np.random.Generator, *, eps: float = EPS) -> np.ndarray:
    """Step 9: ``z`` realisations of HF values given each conditioning LF peak (Eq. 6–7).

    Returns an array of shape ``(z, n0)``.
    """
    u = np.clip(lf_marginal.cdf(lf_cond), eps, 1 - eps)
    r = rng.uniform(eps, 1 - eps, size=(z, u.size))
    v = np.clip(conditional_quantile(fit, u[None, :], r), eps, 1 - eps)
    # HF loads are non-negative by the oracle's contract; a Weibull location
    # below zero must not produce negative loads in the bulk
    return np.maximum(hf_marginal.ppf(v), 0.0)


def impact_probability(lf_true, lf_false):
    """P(impact | LF) from evaluated events: logistic regression of TP (1) vs FP (0) on LF.

    Returns a callable; ``None`` when no false positive has been seen.  An
    extension of the paper (module docs).
    """
    lf_false = np.asarray(lf_false, float)
    if lf_false.size == 0:
        return None
    x = np.r_[lf_true, lf_false]
    y = np.r_[np.ones(len(lf_true)), np.zeros(lf_false.size)]
    mu, sd = x.mean(), x.std() or 1.0
    model = LogisticRegression(C=1.0).fit(((x - mu) / sd)[:, None], y)
    return lambda l: model.predict_proba(((np.asarray(l, float) - mu) / sd)[:, None])[:, 1]


def fit_marginals(lf, hf, keep, *, upper_tail: bool, marginals_from: str = "all"):
    """Step 9's Weibull marginals: ``(F_l, F_h, lf_sample)``.

    Fitted to all pairs or to the ``keep`` mask of Step 7 (``marginals_from``,
    module docs); ``lf_sample`` is the LF sample they saw, whose minimum is the
    conditioning level ``l0``.
    """
    m_lf, m_hf = (lf, hf) if marginals_from == "all" else (lf[keep], hf[keep])
    return fit_marginal(m_lf, upper_tail=upper_tail), fit_marginal(m_hf, upper_tail=upper_tail), m_lf


def fit_model(lf, hf, family: str, *, outlier_k: float = 3.0, upper_tail: bool = True,
              marginals_from: str = "all"):
    """Steps 7–9 for one copula family: ``(copula fit, LF marginal, HF marginal)``.

    Outliers (Step 7) leave the copula fit; the marginals see all pairs or the
    kept ones (``marginals_from``, module docs).  Used to redraw a result's
    final model (:func:`pas.plotting.conditional_quantile_curves`).
    """
    lf, hf = np.asarray(lf, float), np.asarray(hf, float)
    keep = remove_outliers(lf, hf, k=outlier_k)
    fit = fit_copula(family, *pseudo_observations(lf[keep], hf[keep]))
    f_l, f_h, _ = fit_marginals(lf, hf, keep, upper_tail=upper_tail,
                                marginals_from=marginals_from)
    return fit, f_l, f_h


def hf_distribution(h_draws, n_waves: int):
    """Steps 10–11: exceedance probabilities and mean distribution with U95 (Eq. 8–10).

    Each realisation is sorted descending and gets ``d = k / n_w``; the mean
    distribution is the mean over realisations of each order statistic and
    the band ``h* ± 1.96 σ``.  Returns ``(d, h_mean, h_low, h_high)``.
    """
    h = -np.sort(-np.atleast_2d(h_draws), axis=1)
    d = np.arange(1, h.shape[1] + 1) / n_waves
    mean = h.mean(axis=0)
    sd = h.std(axis=0, ddof=1) if h.shape[0] > 1 else np.zeros_like(mean)
    return d, mean, *band95(mean, sd)


class PAS(Strategy):
    """The PAS copula model (Steps 7–12) with MD acquisition.

    Parameters
    ----------
    families : sequence of str
        Copula candidates; the paper's five by default
        (:data:`pas.copulas.PAPER_FAMILIES`), extras in
        :data:`pas.copulas.EXTRA_FAMILIES`.
    z : int, default 10
        Conditional realisations per iteration (Step 9).
    delta_aic : float, default 4.0
        AIC hysteresis (§2.2).
    exclude_at_bound : bool, default True
        Stability remedy (module docs); False is the paper's exact selection.
    upper_tail : bool or None
        Weibull upper-tail mode; None = on when no LF threshold is set (§2.3).
    outlier_k : float, default 3.0
        Step 7 residual limit in RMS units.
    n_bootstrap : int, default 50
        Bootstrap replicates for the model-uncertainty band (0 = off).
    skip_unsplittable : bool, default True
        MD ignores gaps no pool peak can split
        (:mod:`pas.strategies.acquisition`); False is Eq. 16–17 verbatim.
    marginals_from : {"all", "kept"}, default "all"
        Pairs the Weibull marginals are fitted to (module docs, Step 7).
    impact_model : bool, default False
        Zero draws by the estimated impact probability (module docs).
    """

    name = "pas"
    n_initial = 4
    min_pairs = 4

    def __init__(self, *, families=PAPER_FAMILIES, z: int = 10, delta_aic: float = 4.0,
                 exclude_at_bound: bool = True, upper_tail: bool | None = None,
                 outlier_k: float = 3.0, n_bootstrap: int = 50, skip_unsplittable: bool = True,
                 marginals_from: str = "all", impact_model: bool = False):
        for f in families:
            _family_and_rotation(f)
        if z < 2:
            raise ValueError(f"z must be at least 2 to estimate the band, got {z}")
        self.families = tuple(families)
        self.z = int(z)
        self.delta_aic = float(delta_aic)
        self.exclude_at_bound = bool(exclude_at_bound)
        self.upper_tail = upper_tail
        self.outlier_k = float(outlier_k)
        self.n_bootstrap = int(n_bootstrap)
        self.skip_unsplittable = bool(skip_unsplittable)
        self.marginals_from = check_option(marginals_from, "marginals_from", {"all", "kept"})
        self.impact_model = bool(impact_model)
        self.family_ = None

    def reset(self) -> None:
        self.family_ = None

    def propose(self, selected_d, lfset: LFSet, available: np.ndarray,
                last: Prediction | None, q: int = 1) -> list[int]:
        """Next ``q`` positions by MD (Eq. 16–17), with the ``skip_unsplittable`` setting."""
        return md_select(lfset.ln_d, available, np.log(selected_d), q,
                         skip_unsplittable=self.skip_unsplittable)

    def _upper_tail(self, lfset: LFSet) -> bool:
        return lfset.threshold is None if self.upper_tail is None else self.upper_tail

    def _marginals(self, lf, hf, keep, lfset):
        return fit_marginals(lf, hf, keep, upper_tail=self._upper_tail(lfset),
                             marginals_from=self.marginals_from)

    def _distribution(self, fit, marginals, lfset, rng, fp_lf=()):
        f_l, f_h, lf = marginals
        cond = conditioning_set(lfset.lf, lf.min())
        draws = draw_conditional_hf(fit, f_l, f_h, cond, self.z, rng)
        p_imp = impact_probability(lf, fp_lf) if self.impact_model else None
        if p_imp is not None:
            hit = rng.uniform(size=draws.shape) < p_imp(cond)[None, :]
            draws = np.where(hit, draws, 0.0)
        return hf_distribution(draws, lfset.n_waves)

    def predict(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator) -> Prediction:
        keep = remove_outliers(pairs.lf, pairs.hf, k=self.outlier_k)
        lf, hf = pairs.lf[keep], pairs.hf[keep]
        u, v = pseudo_observations(lf, hf)
        fits = fit_candidates(u, v, self.families)
        self.family_ = select_family(fits, self.family_, delta_aic=self.delta_aic,
                                     exclude_at_bound=self.exclude_at_bound)
        fit = fits[self.family_]
        marginals = self._marginals(pairs.lf, pairs.hf, keep, lfset)
        d, mean, low, high = self._distribution(fit, marginals, lfset, rng, pairs.fp_lf)
        lam_u, lam_l = empirical_tail_dependence(pairs.lf, pairs.hf)
        record = {
            "family": self.family_,
            **{f"aic_{k}": f.aic for k, f in fits.items()},
            # families select_family passed over for a fit on a parameter bound
            "ineligible": " ".join(k for k, f in fits.items() if f.at_bound)
            if self.exclude_at_bound and not all(f.at_bound for f in fits.values()) else "",
            "copula_params": " ".join(f"{x:.4g}" for x in fit.parameters),
            "n_outliers": int((~keep).sum()),
            "tau": kendall_tau(pairs.lf, pairs.hf),
            "lambda_u": lam_u,
            "lambda_l": lam_l,
        }
        return Prediction.read_at(lfset.p_exp, d, mean, low, high, record)

    def model_band(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator):
        """U95 of the MPM over a bootstrap of the LF–HF pairs (beyond the paper).

        Each replicate resamples the pairs with replacement, repeats outlier
        removal, refits the selected family and both marginals, and predicts
        with ``z`` realisations; the band is the 2.5–97.5 % range of the
        replicate MPMs.  Returns ``(low, high, mpms)`` or None when off.
        """
        if self.n_bootstrap <= 0 or self.family_ is None:
            return None
        mpms = []
        m = len(pairs)
        for _ in range(self.n_bootstrap):
            b = pairs.take(rng.integers(0, m, m))
            keep = remove_outliers(b.lf, b.hf, k=self.outlier_k)
            lf, hf = b.lf[keep], b.hf[keep]
            if np.ptp(lf) == 0 or np.ptp(hf) == 0 or lf.size < 3:
                continue
            try:
                fit = fit_copula(self.family_, *pseudo_observations(lf, hf))
                marginals = self._marginals(b.lf, b.hf, keep, lfset)
                d, mean, _, _ = self._distribution(fit, marginals, lfset, rng, b.fp_lf)
            except ValueError:
                continue
            mpms.append(float(value_at_exceedance(d, mean, lfset.p_exp)))
        if len(mpms) < 10:
            return None
        mpms = np.asarray(mpms)
        return float(np.percentile(mpms, 2.5)), float(np.percentile(mpms, 97.5)), mpms
