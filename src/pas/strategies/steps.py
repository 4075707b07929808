"""The paper's PAS steps as plain functions (§2.1, Steps 7–11, Eq. 7–10).

:class:`pas.strategies.pas.PAS` strings them together with the model fits;
:class:`FittedModel` holds what one iteration fitted and draws from it (Steps 8–9).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np

from ..models.conditional_cdf import conditional_cdf
from ..models.copulas import CopulaFit, conditional_quantile
from ..models.marginals import fit_marginal
from .base import band95

__all__ = ["EPS", "FittedModel", "SharedOnCopy", "remove_outliers", "conditioning_set",
           "draw_conditional_hf", "fit_marginals", "hf_distribution"]

EPS = 1e-6


class CandidateFits(NamedTuple):
    """What an estimator fitted: per candidate ``copulas`` and ``hf_marginals`` (by family),
    ``lf_to_u`` (LF value -> LF rank), ``n0`` (conditioning peaks) and ``keep`` (pairs used)."""

    copulas: dict
    hf_marginals: dict
    lf_to_u: Callable
    n0: int
    keep: np.ndarray


def joint_candidates(joint: dict, cond_lf, u_cond, keep) -> CandidateFits:
    """:class:`CandidateFits` of the best joint fit per family, the LF ranks ``u_cond`` of
    the conditioning peaks ``cond_lf`` (descending) read by interpolation."""
    ascending = cond_lf[::-1], u_cond[::-1]
    return CandidateFits({k: j.copula for k, j in joint.items()},
                         {k: j.hf_marginal for k, j in joint.items()},
                         lambda x: np.interp(x, *ascending), len(cond_lf), keep)


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


def draw_conditional_hf(fit: CopulaFit, u_cond, hf_marginal, r, *, eps: float = EPS,
                        r_scores=None):
    """Step 9: HF values given each conditioning peak's LF rank ``u`` (Eq. 7).

    ``r`` holds the uniforms, shape ``(z, n0)`` (``r_scores``: their ``Φ⁻¹``,
    when kept); returns HF draws of that shape.
    """
    u = np.clip(np.asarray(u_cond, float), eps, 1 - eps)
    v = np.asarray(conditional_quantile(fit, u[None, :], r, r_scores=r_scores), float)
    v = np.clip(v, eps, 1 - eps, out=v if v.flags.writeable and v.shape == np.shape(r) else None)
    # HF loads are non-negative by the oracle's contract; a Weibull location
    # below zero must not produce negative loads in the bulk
    h = np.asarray(hf_marginal.ppf(v), float)
    del v
    return np.maximum(h, 0.0, out=h if h.flags.writeable and h.ndim == 2 else None)


def fit_marginals(lf, hf, keep, *, upper_tail: bool, marginals_from: str = "all"):
    """Step 9's Weibull marginals: ``(F_l, F_h, lf_sample)``.

    Fitted to all pairs or to the ``keep`` mask of Step 7 (``marginals_from``,
    module docs); ``lf_sample`` is the LF sample they saw, whose minimum is the
    conditioning level ``l0``.
    """
    m_lf, m_hf = (lf, hf) if marginals_from == "all" else (lf[keep], hf[keep])
    return (fit_marginal(m_lf, upper_tail=upper_tail), fit_marginal(m_hf, upper_tail=upper_tail),
            m_lf)


def hf_distribution(h_draws, n_waves: int):
    """Steps 10–11: exceedance probabilities and mean distribution with U95 (Eq. 8–10).

    Each realisation is sorted descending and gets ``d = k / n_w``; the mean
    distribution is the mean over realisations of each order statistic and
    the band ``h* ± 1.96 σ``.  Returns ``(d, h_mean, h_low, h_high)``.
    """
    h = np.sort(np.atleast_2d(h_draws), axis=1)[:, ::-1]
    d = np.arange(1, h.shape[1] + 1) / n_waves
    mean = h.mean(axis=0)
    sd = h.std(axis=0, ddof=1) if h.shape[0] > 1 else np.zeros_like(mean)
    return d, mean, *band95(mean, sd)


class SharedOnCopy(tuple):
    """A tuple of state never written in place, which a deep copy shares: the study copies
    the strategy before every fit (the kept LF ranks: 24 MB at 1.5 M peaks)."""

    def __deepcopy__(self, memo):
        return self


@dataclass
class FittedModel:
    """What one PAS iteration fitted (Steps 7–9), enough to draw from it again.

    ``u_cond`` are the LF ranks of the conditioning peaks (the top ``n0`` of the
    pool, LF descending), ``impact`` the probability of an impact at each of
    them (None: every draw is an impact, as in the paper).
    """

    copula: CopulaFit
    hf_marginal: object
    lf_to_u: object
    u_cond: np.ndarray
    impact: np.ndarray | None
    fits: dict
    n_outliers: int

    @property
    def n0(self) -> int:
        return int(self.u_cond.size)

    def __deepcopy__(self, memo):
        """Itself: nothing changes a fitted model once made, and the study copies the
        strategy before every fit (``u_cond`` and ``impact``: 24 MB at 1.5 M peaks)."""
        return self

    def draws(self, r, q=None, r_scores=None, peaks=slice(None)) -> np.ndarray:
        """HF draws for uniforms ``r`` (and impact uniforms ``q``; ``r_scores``: ``Φ⁻¹(r)``
        when kept), shape ``(z, n0)``; with ``peaks`` (a slice) those conditioning peaks'."""
        h = draw_conditional_hf(self.copula, self.u_cond[peaks], self.hf_marginal, r,
                                r_scores=r_scores)
        if self.impact is not None:
            h[~(q < self.impact[None, peaks])] = 0.0  # in place: no second array of draws
        return h

    def transforms(self, pairs) -> np.ndarray:
        """``F(h | l)`` of the evaluated ``pairs`` under this model's copula and HF marginal:
        uniform when the model is right (:func:`pas.stats.fit_check.uniform_check`)."""
        u = np.clip(self.u_cond[pairs.position], EPS, 1 - EPS)
        v = np.clip(self.hf_marginal.cdf(np.asarray(pairs.hf, float)), EPS, 1 - EPS)
        return np.asarray(conditional_cdf(self.copula, v, u), float)

    def conditional_quantiles(self, lf, q) -> np.ndarray:
        """HF quantile ``q`` given LF ``lf`` (given an impact), in real space."""
        u = np.clip(self.lf_to_u(np.asarray(lf, float)), EPS, 1 - EPS)
        v = np.clip(conditional_quantile(self.copula, u, np.full_like(u, q)), EPS, 1 - EPS)
        return self.hf_marginal.ppf(v)
