"""How :class:`~pas.strategies.pas.PAS` fits its model (Steps 7–9): an object per estimator.

Each estimator keeps the options that apply to it, and nothing else, and
fits with one method, :meth:`fit`, which returns :class:`CandidateFits`.

:class:`ConditionalLikelihood` (the default)
    The LF ranks are those of the LF *population* (every conditioning peak is
    known), and the copula and a three-parameter HF marginal are fitted
    together by the likelihood of HF given LF (:mod:`pas.models.joint`),
    which selection by LF (MD) leaves valid.
:class:`SelectedSample` (the paper's)
    Rank pseudo-observations of the selected sample (Eq. 5) and
    least-squares Weibull marginals (Eq. 15), after the outlier removal of
    Step 7 — consistent only as far as a one-parameter copula and a Weibull
    describe a tail-heavy, non-i.i.d. sample (van Essen & Seyffert 2026, §5.4).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, ClassVar

import numpy as np

from .._support.checks import check_option
from ..models.copulas import fit_candidates
from ..models.joint import JOINT_FAMILIES
from ..models.joint_mixture import HF_CHOICES, fit_hf_candidates
from ..stats.dependence import pseudo_observations
from . import band
from .steps import (
    CandidateFits,
    conditioning_set,
    fit_marginals,
    joint_candidates,
    remove_outliers,
)

__all__ = ["ConditionalLikelihood", "SelectedSample", "ESTIMATORS", "CandidateFits", "FitRequest"]

COLD_EVERY = 10
"""Every this many study fits, the conditional estimator also starts from the data."""


@dataclass
class WarmStarts:
    """The joint fits a study's next fit starts from (one per PAS, renewed by its ``reset``).

    ``joint``: the last study fit of every candidate; ``last``: the last fit
    of any kind (a band's final fits read it); ``n_fits``: study fits so far.
    """

    joint: dict = field(default_factory=dict)
    last: dict = field(default_factory=dict)
    n_fits: int = 0

    def of(self, family: str | None = None) -> dict:
        """The warm starts of every candidate, or of ``family``'s alone."""
        if family is None:
            return self.joint
        return {k: v for k, v in self.joint.items() if k[0] == family}

    def record(self, every: dict, *, study_fit: bool) -> None:
        """Keep the fits ``every`` made; a study fit of all candidates is the next start."""
        self.last = every
        if study_fit:
            self.joint = every
            self.n_fits += 1


@dataclass(frozen=True)
class FitRequest:
    """One fit's circumstances (:meth:`pas.strategies.pas.PAS.fit`).

    ``families``: the candidates; ``one_family``: only that one is fitted;
    ``update``: the fit is the study's (False for band replicates);
    ``hf_marginal``: overrides the estimator's for this fit; ``lf_ranks_rng``:
    draws the LF population ranks; ``starts``: joint fits to start from
    (band replicates); ``warm``: the study's warm starts, read and updated by
    the fit (a fresh one when not given).  The last four apply to
    :class:`ConditionalLikelihood`.
    """

    families: tuple
    impact: Callable | None
    one_family: bool = False
    update: bool = True
    hf_marginal: str | None = None
    lf_ranks_rng: np.random.Generator | None = None
    starts: dict | None = None
    warm: WarmStarts = field(default_factory=WarmStarts)


@dataclass(frozen=True)
class ConditionalLikelihood:
    """The joint conditional likelihood of HF given the LF population ranks (the default).

    Parameters
    ----------
    hf_marginal : {"weibull", "lognormal", "both", "weibull_mixture"}, default "weibull"
        The HF marginal's family (the paper's Weibull), or ``"both"``: a
        Weibull and a log-normal fitted with each copula and the one of higher
        likelihood kept (:mod:`pas.models.joint`); or ``"weibull_mixture"``:
        per copula, a Weibull and a two-component Weibull mixture (a body and
        a tail, :mod:`pas.models.joint_mixture`), the one of lower AIC kept.
    hf_location : bool, default True
        A three-parameter HF marginal (location >= 0, below the smallest
        load), or the two-parameter one (location 0).
    lf_tail : {"ranks", "gpd"}, default "ranks"
        The LF population CDF at the peaks is their mid-rank ("ranks"), or
        with "gpd" the largest 5 % (at least 50) take it from a generalised
        Pareto tail fitted to them (:func:`pas.stats.dependence.gpd_tail_ranks`).
    """

    hf_marginal: str = "weibull"
    hf_location: bool = True
    lf_tail: str = "ranks"
    name: ClassVar[str] = "conditional"

    def __post_init__(self):
        check_option(self.hf_marginal, "hf_marginal", set(HF_CHOICES))
        check_option(self.lf_tail, "lf_tail", {"ranks", "gpd"})
        object.__setattr__(self, "hf_location", bool(self.hf_location))

    def check_families(self, families) -> None:
        """Raise ``ValueError`` for a family this estimator has no joint fit for."""
        unknown = [f for f in families if f not in JOINT_FAMILIES]
        if unknown:
            raise ValueError(f"families {', '.join(unknown)} have no joint fit; use "
                             f"estimator=SelectedSample() for them, or the families "
                             f"{JOINT_FAMILIES}")

    def fit(self, pas, pairs, lfset, request: FitRequest) -> CandidateFits:
        """Population LF ranks and the joint conditional likelihood; reads and updates the
        request's warm starts (``request.warm``)."""
        # Step 7 removes pairs by their HF value: a selection on the response, which
        # the conditional likelihood does not allow (it would drop the largest loads
        # from the tail it fits), so every pair is kept
        keep = np.ones(len(pairs), dtype=bool)
        n0 = conditioning_set(lfset.lf, pairs.lf.min()).size
        cond_lf = lfset.lf[:n0]
        u_cond = pas.population_ranks(lfset, n0, request.impact, request.lf_ranks_rng)
        warm = request.warm
        starts, update = request.starts, request.update
        # a band replicate fits only the candidates that can win it (band.ReplicateStarts)
        only = set(starts) if isinstance(starts, band.ReplicateStarts) else None
        if starts is not None:  # a band replicate from the final fits (model_band)
            cold = band.COLD_FAMILIES
        else:
            family = request.families[0] if request.one_family else None
            starts = warm.of(family)
            # a warm start from the previous iteration converges in a few steps; every
            # COLD_EVERY-th fit, and every fit with update=False, also starts from the
            # data, so no fit stays trapped in the basin of another sample
            cold = not update or (family is None and warm.n_fits % COLD_EVERY == 0)
        choice = request.hf_marginal or self.hf_marginal
        u_pairs = u_cond[pairs.position]
        every, joint = fit_hf_candidates(u_pairs, pairs.hf, request.families, choice,
                                         starts=starts, location=self.hf_location,
                                         cold=cold or not starts, only=only)
        warm.record(every, study_fit=update and not request.one_family)
        return joint_candidates(joint, cond_lf, u_cond, keep)


@dataclass(frozen=True)
class SelectedSample:
    """The paper's fit in selected-sample space (§2.2–2.3, Eq. 5, 15; van Essen & Seyffert 2026).

    Parameters
    ----------
    copula_fit : {"mle", "itau"}, default "mle"
        Maximum likelihood for all families, or the paper's inversion of
        Kendall's τ for Clayton, Gumbel and Frank (§2.8).
    marginals_from : {"all", "kept"}, default "all"
        Pairs the Weibull marginals are fitted to: all true positives, or
        those Step 7's outlier removal kept (the paper; "the remaining data
        are then used for copula fitting", §2.1).
    outlier_k : float or None, default 3.0
        Step 7 residual limit in RMS units (None: no outlier removal).
    upper_tail : bool or None
        Weibull upper-tail mode; None = on when no LF threshold is set (§2.3).
    """

    copula_fit: str = "mle"
    marginals_from: str = "all"
    outlier_k: float | None = 3.0
    upper_tail: bool | None = None
    name: ClassVar[str] = "selected"

    def __post_init__(self):
        check_option(self.copula_fit, "copula_fit", {"mle", "itau"})
        check_option(self.marginals_from, "marginals_from", {"all", "kept"})
        if self.outlier_k is not None:
            object.__setattr__(self, "outlier_k", float(self.outlier_k))

    @classmethod
    def paper(cls) -> SelectedSample:
        """The paper's scripts: τ inversion (§2.8) and marginals of the kept pairs (Step 7)."""
        return cls(copula_fit="itau", marginals_from="kept")

    def check_families(self, families) -> None:
        """Every copula family has a fit in selected-sample space."""

    def fit(self, pas, pairs, lfset, request: FitRequest) -> CandidateFits:
        """Outlier removal (Step 7), the copula of the pseudo-observations, Weibull marginals."""
        keep = (np.ones(len(pairs), dtype=bool) if self.outlier_k is None
                else remove_outliers(pairs.lf, pairs.hf, k=self.outlier_k))
        fits = fit_candidates(*pseudo_observations(pairs.lf[keep], pairs.hf[keep]),
                              request.families, method=self.copula_fit)
        upper = lfset.threshold is None if self.upper_tail is None else self.upper_tail
        f_l, f_h, lf_sample = fit_marginals(pairs.lf, pairs.hf, keep, upper_tail=upper,
                                            marginals_from=self.marginals_from)
        n0 = conditioning_set(lfset.lf, lf_sample.min()).size
        return CandidateFits(fits, dict.fromkeys(fits, f_h), f_l.cdf, n0, keep)


ESTIMATORS = {e.name: e for e in (ConditionalLikelihood, SelectedSample)}
"""The estimator classes by the name a study stores (``estimator`` of the flat settings)."""
