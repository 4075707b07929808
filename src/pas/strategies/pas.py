"""Probabilistic Adaptive Screening: the copula model of paper §2.1 Steps 7–12.

Each step is one function; :class:`PAS` strings them together per iteration
and carries the state the method has: the selected copula family (the ΔAIC
hysteresis of §2.2 compares against it), the previous joint fits (warm
starts) and the study's common random numbers.  ``PAS.paper()`` runs the
paper's method as written; the defaults depart from it where a measurement
said so — every departure, its reason and its measured effect are listed in
``docs/explanation/departures.md``.  In short:

Estimator (``estimator``, :mod:`pas.strategies.estimators`)
    :class:`~pas.strategies.estimators.ConditionalLikelihood` (default): the
    copula and a three-parameter HF marginal fitted together by the
    likelihood of HF given the LF population ranks, which selection by LF
    (MD) leaves valid; :class:`~pas.strategies.estimators.SelectedSample`:
    the paper's fit in selected-sample space (Eq. 5, 15; §5.4).
Impact model (``impact_model``, ``impact_trend``)
    Once false positives have been seen, ``P(impact | LF)`` (logistic
    regression on true vs false positives) zeroes draws, instead of a
    positive draw for every conditioning peak (:mod:`pas.strategies.selection`);
    it falls with LF only where a test says the evaluated events show it.
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
Model band (``band``, :class:`~pas.strategies.band.ModelBand`)
    A bootstrap of the evaluated events around the final model (beyond the paper).
"""

from __future__ import annotations

import numpy as np

from .._support.checks import check_finite, check_int, check_option
from ..models.copulas import PAPER_FAMILIES, _family_and_rotation, select_family
from ..stats.dependence import empirical_tail_dependence, kendall_tau
from . import band, model_form, tail_draws
from .acquisition import md_select
from .band import ModelBand
from .base import Pairs, Prediction, Strategy, read_only
from .estimators import (
    ESTIMATORS,
    CandidateFits,
    ConditionalLikelihood,
    FitRequest,
    SelectedSample,
    WarmStarts,
)
from .flat import moved_setting, pas_kwargs, pas_to_flat
from .random_numbers import PeakUniforms
from .screening import LFSet
from .selection import FALLING_P, impact_probability, population_lf_ranks
from .steps import (
    FittedModel,
    SharedOnCopy,
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


class PAS(Strategy):
    """The PAS copula model (Steps 7–12) with MD acquisition.

    Defaults are the package's (module docs; each departure from the paper is
    listed in ``docs/explanation/departures.md``); :meth:`paper` gives the paper's
    scripts.  An option of one estimator lives on that estimator's object
    (:mod:`pas.strategies.estimators`), the band's on
    :class:`~pas.strategies.band.ModelBand`; ``docs/reference/settings.md``
    maps the flat names of pas 0.1 to these places.

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
    skip_unsplittable : bool, default True
        MD ignores gaps no pool peak can split
        (:mod:`pas.strategies.acquisition`); False is Eq. 16–17 verbatim.
    impact_model : bool, default True
        Zero draws by the estimated impact probability once false positives
        have been seen (:mod:`pas.strategies.selection`); False is the paper.
    impact_trend : {"tested", "rising"}, default "tested"
        Whether that probability may fall with LF: ``"tested"`` where a
        one-sided likelihood-ratio test rejects a flat one at 5 %
        (:func:`~pas.strategies.selection.falls_significantly`), ``"rising"``
        never (a falling fit gives the constant impact share, as before 0.2).
    common_random_numbers : bool, default True
        Each LF peak keeps its own ``z`` uniforms for the whole study, so the
        stopping measures see model change, not redrawn noise (module docs);
        False redraws them every iteration, as the paper.
    estimator : ConditionalLikelihood or SelectedSample
        How the copula and the marginals are fitted; default
        ``ConditionalLikelihood()``.
    band : ModelBand
        The model-uncertainty band (:meth:`model_band`); default
        ``ModelBand()`` (50 replicates), ``ModelBand(n_bootstrap=0)`` is off.

    Examples
    --------
    >>> from pas.strategies.estimators import SelectedSample
    >>> PAS(z=20, band=ModelBand(n_bootstrap=0)).band.n_bootstrap
    0
    >>> PAS.paper().estimator == SelectedSample(copula_fit="itau", marginals_from="kept")
    True
    """

    name = "pas"
    n_initial = 4
    min_pairs = 4

    def __init__(self, *, families=PAPER_FAMILIES, z: int = 10, delta_aic: float = 4.0,
                 exclude_at_bound: bool = True, skip_unsplittable: bool = True,
                 impact_model: bool = True, impact_trend: str = "tested",
                 common_random_numbers: bool = True,
                 estimator: ConditionalLikelihood | SelectedSample = ConditionalLikelihood(),
                 band: ModelBand = ModelBand(), **moved):
        if moved:
            raise TypeError(moved_setting("PAS", next(iter(moved))))
        for f in families:
            _family_and_rotation(f)
        self.z = check_int(z, "z", minimum=2)  # 2 draws at least, for the band
        self.families = tuple(families)
        self.delta_aic = check_finite(delta_aic, "delta_aic")
        self.exclude_at_bound = bool(exclude_at_bound)
        self.skip_unsplittable = bool(skip_unsplittable)
        self.impact_model = bool(impact_model)
        self.impact_trend = check_option(impact_trend, "impact_trend", ("tested", "rising"))
        self.common_random_numbers = bool(common_random_numbers)
        if not isinstance(estimator, tuple(ESTIMATORS.values())):
            raise TypeError(f"estimator must be ConditionalLikelihood(...) or SelectedSample(...)"
                            f", got {estimator!r}")
        if not isinstance(band, ModelBand):
            raise TypeError(f"band must be ModelBand(...), got {band!r}")
        estimator.check_families(self.families)
        self.estimator = estimator
        self.band = band
        self.paper_study = False  # PAS.paper(): the study's defaults are the paper's too
        self.reset()

    @classmethod
    def paper(cls) -> PAS:
        """The paper's method as van Essen & Seyffert (2026) ran it (docs: *Departures*).

        τ inversion for the Archimedean copulas and the selected-sample space
        (:meth:`SelectedSample.paper <pas.strategies.estimators.SelectedSample.paper>`),
        AIC with hysteresis over all five families (§2.2), MD as Eq. 16–17,
        new uniforms every iteration (Eq. 7), a positive draw for every
        conditioning peak (Step 6) and the sampling band only (Eq. 10).
        :func:`pas.run_pas` given this strategy also takes the paper's stopping
        rule and no budget (:meth:`pas.study.settings.Stopping.paper`,
        :meth:`pas.study.settings.Budget.paper`) unless told otherwise.
        """
        strategy = cls(exclude_at_bound=False, skip_unsplittable=False,
                       common_random_numbers=False, z=10, impact_model=False, impact_trend="rising",
                       estimator=SelectedSample.paper(),
                       band=ModelBand(n_bootstrap=0, marginals="fitted", lf_ranks="fixed"))
        strategy.paper_study = True
        return strategy

    @classmethod
    def from_flat(cls, settings: dict, *, strict: bool = True) -> PAS:
        """A PAS from flat settings (:func:`pas.strategies.flat.pas_kwargs`)."""
        return cls(**pas_kwargs(settings, strict=strict))

    def settings(self) -> dict:
        """The settings as flat names (the study file's and the store's, pas 0.1's), from
        the objects' fields (:func:`pas.strategies.flat.pas_to_flat`)."""
        return pas_to_flat(self)

    def reset(self, seed: int | None = None) -> None:
        self.family_ = None
        self._uniforms = PeakUniforms(self.z, seed, self.common_random_numbers)
        self.warm = WarmStarts()
        self._lf_tail_fits = {}
        self._ranks = None

    def propose(self, selected_d, lfset: LFSet, available: np.ndarray,
                last: Prediction | None, q: int = 1) -> list[int]:
        """Next ``q`` positions by MD (Eq. 16–17), with the ``skip_unsplittable`` setting."""
        return md_select(lfset.ln_d, available, np.log(selected_d), q,
                         skip_unsplittable=self.skip_unsplittable)

    def impact_of(self, pairs: Pairs):
        """Step 6's impact model: ``P(impact | LF)`` of ``pairs``
        (:func:`~pas.strategies.selection.impact_probability`), None without the impact
        model or before a false positive."""
        if not self.impact_model:
            return None
        return impact_probability(pairs.lf, pairs.fp_lf,
                                  falling_p=FALLING_P if self.impact_trend == "tested" else None)

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
        ``hf_marginal``, ``lf_ranks_rng`` and ``starts`` apply to the
        conditional estimator (:class:`~pas.strategies.estimators.FitRequest`;
        :meth:`model_band`).
        """
        impact = self.impact_of(pairs)
        request = FitRequest(self.families if family is None else (family,), impact,
                             one_family=family is not None, update=update,
                             hf_marginal=hf_marginal, lf_ranks_rng=lf_ranks_rng, starts=starts,
                             warm=self.warm)
        return self.model_of(self.estimator.fit(self, pairs, lfset, request), lfset, impact,
                             family, update=update)

    def model_of(self, fitted: CandidateFits, lfset: LFSet, impact, family: str | None = None,
                 *, update: bool = False) -> FittedModel:
        """The model of :meth:`fit` from an estimator's ``fitted`` candidates: ``family``, or
        the selection (§2.2, with hysteresis and :attr:`family_` updated when ``update``)."""
        if family is None:
            family = select_family(fitted.copulas, self.family_ if update else None,
                                   delta_aic=self.delta_aic,
                                   exclude_at_bound=self.exclude_at_bound)
            if update:
                self.family_ = family
        cond = lfset.lf[:fitted.n0]
        return FittedModel(fitted.copulas[family], fitted.hf_marginals[family], fitted.lf_to_u,
                           np.asarray(fitted.lf_to_u(cond), float),
                           None if impact is None else impact(cond), fitted.copulas,
                           int((~fitted.keep).sum()))

    def population_ranks(self, lfset: LFSet, n0: int, impact, rng):
        """:func:`population_lf_ranks` of the top ``n0`` LF peaks; without an impact model or
        a draw the same every iteration, so kept for the latest ``n0`` of this ``lfset``."""
        fixed = impact is None and rng is None
        cached = self._ranks
        if fixed and cached is not None and cached[0] is lfset.lf and cached[1] == n0:
            return cached[2]
        u = population_lf_ranks(lfset.lf[:n0], impact, rng,
                                gpd_tail=getattr(self.estimator, "lf_tail", "ranks") == "gpd",
                                tail_fits=self._lf_tail_fits)
        if fixed:
            self._ranks = SharedOnCopy((lfset.lf, n0, u))
        return u

    def _random_numbers(self, n0: int, rng: np.random.Generator | None):
        """Step 9's uniforms ``r`` and ``q``, shape ``(z, n0)`` each (:class:`PeakUniforms`)."""
        return self._uniforms.draw(n0, rng)

    def _replicate_mpm(self, model: FittedModel, lfset: LFSet, rng, observed=None) -> tuple:
        """A band replicate's MPMs: ``(model,)`` from the top of each realisation
        (:mod:`pas.strategies.tail_draws`); with the study's pairs ``observed``
        (``ModelBand(model_form="semi-empirical")``) ``(model, semi-empirical)`` from
        the whole draws (:func:`pas.strategies.model_form.replicate_values`)."""
        if observed is None:
            return (tail_draws.mpm_from_top(model, self._uniforms, lfset, rng),)
        return model_form.replicate_values(tail_draws.whole_draws(model, self._uniforms, rng),
                                           observed, lfset, "semi-empirical")

    def predict(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator) -> Prediction:
        model = self.fit(pairs, lfset)
        self.model_ = model
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
        columns = {"lf": read_only(lfset.lf[:model.n0])}  # the result's table shares them
        if model.impact is not None:
            columns["p_impact"] = read_only(model.impact)
        # Steps 9-12: only the top of each realisation is drawn now, the rest when read
        return tail_draws.predict_from_top(model, self._uniforms, lfset, rng, record, columns)

    def model_band(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator, *,
                   n_jobs: int | None = None):
        """U95 of the MPM over a bootstrap of the evaluated events (beyond the paper).

        Each replicate resamples the true and false positives with
        replacement, repeats outlier removal, refits every candidate family,
        the marginals and the impact model, selects the family again (lowest
        eligible AIC, so the choice of family is part of the uncertainty), and
        predicts with the same random numbers; the band is the 2.5–97.5 %
        range of the replicate MPMs.  With the conditional estimator,
        ``band.marginals`` lets the replicates choose the HF marginal family
        too ("reselected") or take the families in turn ("alternate"), so
        that the band holds what the pairs cannot tell apart in the tail;
        and ``band.lf_ranks="redrawn"`` gives each replicate its own draw of
        the LF population CDF at the peaks: the copula is fitted on the LF
        ranks, and at the top of the record the ranks tell the population
        CDF only to within the spread of the largest order statistics.
        The conditional estimator's replicates start their joint fits from the
        final model's (:mod:`pas.strategies.band`); ``n_jobs`` processes fit
        them (1: this one; -1: every core; None: every core on Linux unless this process
        runs other threads), with the same band for any ``n_jobs``.
        Returns ``(low, high, mpms)`` or None when off.
        """
        if self.band.n_bootstrap <= 0 or self.family_ is None:
            return None
        return band.bootstrap_band(self, self.band, pairs, lfset, rng, n_jobs)

    def final_joint_fits(self, pairs: Pairs, lfset: LFSet, hf_marginal: str) -> dict:
        """Joint fits of every family and the marginals of ``hf_marginal`` to ``pairs``
        (conditional estimator; the band's starts): from the study's last fits, which are
        of these pairs, as a replicate starts; a marginal the study did not fit, from the data."""
        impact = self.impact_of(pairs)
        self.estimator.fit(self, pairs, lfset, FitRequest(self.families, impact, update=False,
                                                          hf_marginal=hf_marginal,
                                                          starts=self.warm.joint,
                                                          warm=self.warm))
        return self.warm.last
