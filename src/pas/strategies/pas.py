"""Probabilistic Adaptive Screening: the copula model of paper §2.1 Steps 7–12.

Each step is one function; :class:`PAS` strings them together per iteration
and carries the state the method has: the selected copula family (the ΔAIC
hysteresis of §2.2 compares against it), the previous joint fits (warm
starts) and the study's common random numbers.  ``pas.run_pas(...,
preset="paper")`` runs the paper's method as written; the defaults depart
from it where a measurement said so — every departure, its reason and its
measured effect are listed in ``docs/departures.md``.  In short:

Estimator (``estimator``)
    ``"conditional"`` (default): the LF ranks are those of the LF
    *population* (every conditioning peak is known), and the copula and a
    three-parameter Weibull HF marginal are fitted together by the
    likelihood of HF given LF (:mod:`pas.models.joint`), which selection by LF
    (MD) leaves valid.  ``"selected"``: the paper's fit of rank
    pseudo-observations of the selected sample (Eq. 5) and least-squares
    Weibull marginals (Eq. 15) — consistent only as far as a one-parameter
    copula and a Weibull describe a tail-heavy, non-i.i.d. sample (§5.4).
Impact model (``impact_model``)
    Once false positives have been seen, ``P(impact | LF)`` (logistic
    regression on true vs false positives) zeroes draws, instead of a
    positive draw for every conditioning peak (:mod:`pas.strategies.selection`).
Common random numbers (``common_random_numbers``)
    Each LF peak keeps its ``z`` uniforms for the whole study, so the
    stopping rule measures model change, not redrawn noise.
Stability remedy (``exclude_at_bound``)
    A faithful implementation of the paper's selection, tried on a problem
    whose true copula is Gumbel, saw its MPM double once ~80 HF samples were
    in: the Student-t candidate won the AIC with ν at its lower bound (2).
    An MLE on the boundary of the parameter space is not a regular estimate
    (the asymptotics behind AIC, Akaike 1974, assume an interior optimum), so
    a candidate whose parameter sits on its bound is not eligible.
Reading of Step 7 (``marginals_from``, selected-space estimator)
    The temporary outlier removal feeds the *copula* fit ("the remaining
    data are then used for copula fitting", §2.1); the Weibull marginals are
    fitted to all true-positive samples by default (``"kept"``: the cleaned
    pairs, the paper preset).
"""

from __future__ import annotations

import numpy as np

from .._support.checks import check_finite, check_int, check_option
from ..models.copulas import (
    PAPER_FAMILIES,
    _family_and_rotation,
    fit_candidates,
    select_family,
)
from ..models.joint import JOINT_FAMILIES
from ..models.joint_mixture import HF_CHOICES, fit_hf_candidates
from ..stats.dependence import (
    empirical_tail_dependence,
    kendall_tau,
    pseudo_observations,
)
from . import band
from .acquisition import md_select
from .base import Pairs, Prediction, Strategy
from .random_numbers import PeakUniforms
from .screening import LFSet
from .selection import impact_probability, population_lf_ranks
from .steps import (
    FittedModel,
    cold_turns,
    conditioning_set,
    draw_conditional_hf,
    fit_marginals,
    hf_distribution,
    remove_outliers,
)

__all__ = [
    "PAS",
    "FittedModel",
    "remove_outliers",
    "conditioning_set",
    "draw_conditional_hf",
    "impact_probability",
    "fit_marginals",
    "hf_distribution",
]

COLD_EVERY = 10


class PAS(Strategy):
    """The PAS copula model (Steps 7–12) with MD acquisition.

    Defaults are the package's (module docs; each departure from the paper is
    listed in ``docs/departures.md``); ``pas.run_pas(..., preset="paper")``
    reproduces the paper's scripts.

    Parameters
    ----------
    families : sequence of str
        Copula candidates; the paper's five by default
        (:data:`pas.models.copulas.PAPER_FAMILIES`), extras in
        :data:`pas.models.copulas.EXTRA_FAMILIES`.
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
    impact_model : bool, default True
        Zero draws by the estimated impact probability once false positives
        have been seen (:mod:`pas.strategies.selection`); False is the paper.
    estimator : {"conditional", "selected"}, default "conditional"
        Fit the copula and the HF marginal by the likelihood of HF given the
        LF population ranks (:mod:`pas.models.joint`), or to rank pseudo-observations
        of the selected sample with least-squares Weibull marginals (the
        paper, Eq. 5, 15; §5.4).
    copula_fit : {"mle", "itau"}, default "mle"
        Maximum likelihood for all families, or the paper's inversion of
        Kendall's τ for Clayton, Gumbel and Frank (§2.8).
    common_random_numbers : bool, default True
        Each LF peak keeps its own ``z`` uniforms for the whole study, so the
        stopping measures see model change, not redrawn noise (module docs);
        False redraws them every iteration, as the paper.
    hf_location : bool, default True
        Conditional estimator: a three-parameter HF marginal (location ≥ 0,
        below the smallest load) or the two-parameter one (location 0).
    hf_marginal : {"weibull", "lognormal", "both", "weibull_mixture"}, default "weibull"
        Conditional estimator: the HF marginal's family (the paper's Weibull
        by default), or ``"both"``: a Weibull and a log-normal fitted with
        each copula and the one of higher likelihood kept (:mod:`pas.models.joint`;
        measured trade-off in ``docs/departures.md``); or ``"weibull_mixture"``:
        per copula, a Weibull and a two-component Weibull mixture (a body and a
        tail, :mod:`pas.models.joint_mixture`), the one of lower AIC kept.  The
        selected-space estimator always fits the paper's Weibull (Eq. 15).
    band_marginals : {"fitted", "reselected", "alternate"}, default "reselected"
        Conditional estimator, model band (:meth:`model_band`): every
        bootstrap replicate fits the study's ``hf_marginal`` ("fitted");
        or fits the Weibull and the log-normal and keeps the one of higher
        likelihood, as it re-selects the copula family ("reselected"; with
        ``hf_marginal="weibull_mixture"`` the mixture too, all compared by
        AIC); or the replicates take the Weibull and the log-normal in turn,
        one each ("alternate", never the mixture).
    lf_tail : {"ranks", "gpd"}, default "ranks"
        Conditional estimator: the LF population CDF at the peaks is their
        mid-rank ("ranks"), or with "gpd" the largest 5 % (at least 50) take
        it from a generalised Pareto tail fitted to them
        (:func:`pas.stats.dependence.gpd_tail_ranks`): at strong dependence
        the scatter of the top ranks is most of the MPM's error.
    band_lf_ranks : {"fixed", "redrawn"}, default "redrawn"
        Conditional estimator, model band: every bootstrap replicate also
        draws the LF population CDF at the peaks given their order (a
        Bayesian bootstrap, :func:`pas.stats.dependence.weighted_ranks`)
        instead of keeping their mid-ranks ("fixed"), so the band holds
        what the empirical LF ranks cannot tell about the LF tail — at
        strong dependence the largest part of the error (``docs/departures.md``).
    """

    name = "pas"
    n_initial = 4
    min_pairs = 4

    def __init__(self, *, families=PAPER_FAMILIES, z: int = 10, delta_aic: float = 4.0,
                 exclude_at_bound: bool = True, upper_tail: bool | None = None,
                 outlier_k: float = 3.0, n_bootstrap: int = 50, skip_unsplittable: bool = True,
                 marginals_from: str = "all", impact_model: bool = True,
                 estimator: str = "conditional", copula_fit: str = "mle",
                 common_random_numbers: bool = True, hf_location: bool = True,
                 hf_marginal: str = "weibull", band_marginals: str = "reselected",
                 band_lf_ranks: str = "redrawn", lf_tail: str = "ranks"):
        for f in families:
            _family_and_rotation(f)
        self.z = check_int(z, "z", minimum=2)  # 2 draws at least, for the band
        self.families = tuple(families)
        self.delta_aic = check_finite(delta_aic, "delta_aic")
        self.exclude_at_bound = bool(exclude_at_bound)
        self.upper_tail = upper_tail
        self.outlier_k = None if outlier_k is None else float(outlier_k)
        self.n_bootstrap = int(n_bootstrap)
        self.skip_unsplittable = bool(skip_unsplittable)
        self.marginals_from = check_option(marginals_from, "marginals_from", {"all", "kept"})
        self.impact_model = bool(impact_model)
        self.estimator = check_option(estimator, "estimator",
                                      {"conditional", "selected"})
        unknown = [f for f in self.families if f not in JOINT_FAMILIES]
        if self.estimator == "conditional" and unknown:
            raise ValueError(f"families {', '.join(unknown)} have no joint fit; use "
                             f"estimator='selected' for them, or the families {JOINT_FAMILIES}")
        self.copula_fit = check_option(copula_fit, "copula_fit", {"mle", "itau"})
        self.common_random_numbers = bool(common_random_numbers)
        self.hf_location = bool(hf_location)
        self.hf_marginal = check_option(hf_marginal, "hf_marginal", set(HF_CHOICES))
        self.band_marginals = check_option(band_marginals, "band_marginals",
                                           {"fitted", "reselected", "alternate"})
        self.band_lf_ranks = check_option(band_lf_ranks, "band_lf_ranks", {"fixed", "redrawn"})
        self.lf_tail = check_option(lf_tail, "lf_tail", {"ranks", "gpd"})
        if self.lf_tail == "gpd" and self.estimator != "conditional":
            raise ValueError("lf_tail='gpd' reads the LF population ranks of the conditional "
                             "estimator; estimator='selected' fits an LF Weibull instead")
        self.reset()

    def reset(self, seed: int | None = None) -> None:
        self.family_ = None
        self._uniforms = PeakUniforms(self.z, seed, self.common_random_numbers)
        self._joint = {}
        self._n_fits = 0
        self._lf_tail_fits = {}
        self._last_joint = {}
        self._ranks = None

    def propose(self, selected_d, lfset: LFSet, available: np.ndarray,
                last: Prediction | None, q: int = 1) -> list[int]:
        """Next ``q`` positions by MD (Eq. 16–17), with the ``skip_unsplittable`` setting."""
        return md_select(lfset.ln_d, available, np.log(selected_d), q,
                         skip_unsplittable=self.skip_unsplittable)

    def _upper_tail(self, lfset: LFSet) -> bool:
        return lfset.threshold is None if self.upper_tail is None else self.upper_tail

    # -- Steps 7–9: the model ------------------------------------------------
    def fit(self, pairs: Pairs, lfset: LFSet, family: str | None = None, *,
            update: bool = True, hf_marginal: str | None = None,
            lf_ranks_rng: np.random.Generator | None = None,
            starts: dict | None = None) -> FittedModel:
        """Steps 7–9: fit the copula, the HF marginal and the impact model to ``pairs``.

        With ``family`` only that family is fitted; otherwise all candidates,
        and the selection with hysteresis (§2.2) updates :attr:`family_`.
        With ``update=False`` (bootstrap replicates) nothing the study carries
        changes: the family is the lowest eligible AIC of these pairs.
        ``hf_marginal`` overrides the setting of that name for this fit;
        ``lf_ranks_rng`` (conditional estimator) draws the LF population ranks
        instead of taking their mid-ranks (:meth:`model_band`); ``starts``
        (conditional estimator): joint fits by ``(family, marginal)`` to start
        from, and only from them but for the families of
        :data:`pas.strategies.band.COLD_FAMILIES` (:meth:`model_band`).
        """
        # Step 7 removes pairs by their HF value: a selection on the response, which
        # the conditional likelihood does not allow (it would drop the largest loads
        # from the tail it fits), so it belongs to the selected-space fit only
        keep = (np.ones(len(pairs), dtype=bool)
                if self.outlier_k is None or self.estimator == "conditional"
                else remove_outliers(pairs.lf, pairs.hf, k=self.outlier_k))
        families = self.families if family is None else (family,)
        impact = impact_probability(pairs.lf, pairs.fp_lf) if self.impact_model else None
        fit = self._fit_conditional if self.estimator == "conditional" else self._fit_selected
        fits, hf_marginals, lf_to_u, n0 = fit(pairs, lfset, keep, families, impact, family,
                                              update, hf_marginal or self.hf_marginal,
                                              lf_ranks_rng, starts)
        if family is None:
            family = select_family(fits, self.family_ if update else None,
                                   delta_aic=self.delta_aic,
                                   exclude_at_bound=self.exclude_at_bound)
            if update:
                self.family_ = family
        cond = lfset.lf[:n0]
        return FittedModel(fits[family], hf_marginals[family], lf_to_u,
                           np.asarray(lf_to_u(cond), float),
                           None if impact is None else impact(cond), fits, int((~keep).sum()))

    def _fit_selected(self, pairs, lfset, keep, families, impact, family, update, hf_marginal,
                      lf_ranks_rng, starts):
        """The paper's fit in selected-sample space (§2.2–2.3, Eq. 5, 15)."""
        lf, hf = pairs.lf[keep], pairs.hf[keep]
        fits = fit_candidates(*pseudo_observations(lf, hf), families, method=self.copula_fit)
        f_l, f_h, lf_sample = fit_marginals(pairs.lf, pairs.hf, keep,
                                            upper_tail=self._upper_tail(lfset),
                                            marginals_from=self.marginals_from)
        n0 = conditioning_set(lfset.lf, lf_sample.min()).size
        return fits, dict.fromkeys(fits, f_h), f_l.cdf, n0

    def _fit_conditional(self, pairs, lfset, keep, families, impact, family, update,
                         hf_marginal, lf_ranks_rng, starts):
        """Population LF ranks and the joint conditional likelihood (:mod:`pas.models.joint`)."""
        n0 = conditioning_set(lfset.lf, pairs.lf.min()).size
        cond_lf = lfset.lf[:n0]
        u_cond = self._population_ranks(lfset, n0, impact, lf_ranks_rng)
        # a band replicate fits only the candidates that can win it (band.ReplicateStarts)
        only = set(starts) if isinstance(starts, band.ReplicateStarts) else None
        if starts is not None:  # a band replicate from the final fits (model_band)
            cold = band.COLD_FAMILIES
        else:
            starts = self._joint if family is None else {
                k: v for k, v in self._joint.items() if k[0] == family}
            # a warm start from the previous iteration converges in a few steps; each
            # family's fit every COLD_EVERY-th iteration, the families in turn (steps.cold_turns),
            # and every other fit with update=False also starts from the data, so no fit
            # stays trapped in the basin of another sample
            cold = not update or (family is None and cold_turns(families, self._n_fits,
                                                                COLD_EVERY))
        every, joint = fit_hf_candidates(u_cond[pairs.position][keep], pairs.hf[keep], families,
                                         hf_marginal, starts=starts, location=self.hf_location,
                                         cold=cold or not starts, only=only)
        self._last_joint = every
        if update and family is None:
            self._joint = every
            self._n_fits += 1
        ascending = cond_lf[::-1], u_cond[::-1]
        return ({k: j.copula for k, j in joint.items()},
                {k: j.hf_marginal for k, j in joint.items()},
                lambda x: np.interp(x, *ascending), n0)

    def _population_ranks(self, lfset: LFSet, n0: int, impact, rng):
        """:func:`population_lf_ranks` of the top ``n0`` LF peaks; without an impact model or
        a draw the same every iteration, so kept for the latest ``n0`` of this ``lfset``."""
        fixed = impact is None and rng is None
        cached = self._ranks
        if fixed and cached is not None and cached[0] is lfset.lf and cached[1] == n0:
            return cached[2]
        u = population_lf_ranks(lfset.lf[:n0], impact, rng, gpd_tail=self.lf_tail == "gpd",
                                tail_fits=self._lf_tail_fits)
        if fixed:
            self._ranks = (lfset.lf, n0, u)
        return u

    def _random_numbers(self, n0: int, rng: np.random.Generator | None):
        """Step 9's uniforms ``r`` and ``q``, shape ``(z, n0)`` each (:class:`PeakUniforms`)."""
        return self._uniforms.draw(n0, rng)

    def _draws(self, model: FittedModel, rng) -> np.ndarray:
        """Step 9's HF draws, shape ``(z, n0)``; the Gaussian and Student-t draws read the
        normal scores of the common uniforms, kept from the first time."""
        r, q = self._random_numbers(model.n0, rng)
        scores = (self._uniforms.scores(model.n0)
                  if model.copula.name.partition("_")[0] in ("gaussian", "student") else None)
        return model.draws(r, q, scores)

    def _predict_model(self, model: FittedModel, lfset: LFSet, rng):
        return hf_distribution(self._draws(model, rng), lfset.n_waves)

    def predict(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator) -> Prediction:
        model = self.fit(pairs, lfset)
        self.model_ = model
        d, mean, low, high = self._predict_model(model, lfset, rng)
        lam_u, lam_l = empirical_tail_dependence(pairs.lf, pairs.hf)
        record = {
            "family": self.family_,
            **{f"aic_{k}": model.fits[k].aic if k in model.fits else np.nan
               for k in self.families},
            # families select_family passed over for a fit on a parameter bound
            "ineligible": " ".join(k for k, f in model.fits.items() if f.at_bound)
            if self.exclude_at_bound and not all(f.at_bound for f in model.fits.values()) else "",
            "copula_params": " ".join(f"{x:.4g}" for x in model.copula.parameters),
            "hf_marginal": model.hf_marginal.name,
            "n_outliers": model.n_outliers,
            "tau": kendall_tau(pairs.lf, pairs.hf),
            "lambda_u": lam_u,
            "lambda_l": lam_l,
            "p_impact": np.nan if model.impact is None else float(model.impact.mean()),
        }
        columns = {"lf": lfset.lf[:model.n0]}
        if model.impact is not None:
            columns["p_impact"] = model.impact
        return Prediction.read_at(lfset.p_exp, d, mean, low, high, record, columns)

    def model_band(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator, *,
                   n_jobs: int | None = None):
        """U95 of the MPM over a bootstrap of the evaluated events (beyond the paper).

        Each replicate resamples the true and false positives with
        replacement, repeats outlier removal, refits every candidate family,
        the marginals and the impact model, selects the family again (lowest
        eligible AIC, so the choice of family is part of the uncertainty), and
        predicts with the same random numbers; the band is the 2.5–97.5 %
        range of the replicate MPMs.  With the conditional estimator,
        ``band_marginals`` lets the replicates choose the HF marginal family
        too ("reselected") or take the families in turn ("alternate"), so
        that the band holds what the pairs cannot tell apart in the tail;
        and ``band_lf_ranks="redrawn"`` gives each replicate its own draw of
        the LF population CDF at the peaks: the copula is fitted on the LF
        ranks, and at the top of the record the ranks tell the population
        CDF only to within the spread of the largest order statistics.
        The conditional estimator's replicates start their joint fits from the
        final model's (:mod:`pas.strategies.band`); ``n_jobs`` processes fit
        them (1: this one; -1: every core; None: every core on Linux unless this process
        runs other threads), with the same band for any ``n_jobs``.
        Returns ``(low, high, mpms)`` or None when off.
        """
        if self.n_bootstrap <= 0 or self.family_ is None:
            return None
        return band.bootstrap_band(self, pairs, lfset, rng, n_jobs)

    def final_joint_fits(self, pairs: Pairs, lfset: LFSet, hf_marginal: str) -> dict:
        """Joint fits of every family and the marginals of ``hf_marginal`` to ``pairs``
        (conditional estimator; the band's starts): from the study's last fits, which are
        of these pairs, as a replicate starts; a marginal the study did not fit, from the data."""
        impact = impact_probability(pairs.lf, pairs.fp_lf) if self.impact_model else None
        self._fit_conditional(pairs, lfset, np.ones(len(pairs), bool), self.families, impact,
                              None, False, hf_marginal, None, self._joint)
        return self._last_joint
