"""The model band's bootstrap replicates (:meth:`pas.strategies.pas.PAS.model_band`), in parallel.

The replicates draw what they drew one after another in one process, so the
band is the same for any ``n_jobs``.  They start from the final model's joint
fits (a replicate is a resample of the same pairs, so its optimum is near;
Student-t also from the data, :data:`COLD_FAMILIES`), refit only the copula
families that can win them (:data:`PRUNE_AIC`) and, where every candidate has
a batched form, are fitted together (:mod:`pas.strategies.band_batch`,
:mod:`pas.models.joint_batch`).  Workers
are forked processes (POSIX); the default ``n_jobs=None`` is every core, but
one process when this process runs other threads or where fork is unsafe.
Why each choice, and what it was measured to change:
``docs/explanation/model-band.md``.
"""

from __future__ import annotations

import contextlib
import copy
import multiprocessing
import os
import sys
import threading
from dataclasses import dataclass

import numpy as np

from .._support.checks import check_int, check_option
from .._support.forked import forked_call, forked_pool
from ..models.joint import HF_MARGINALS
from ..models.joint_batch import batchable
from ..models.joint_mixture import MIXTURE, pair_logliks
from . import model_form as model_forms
from .band_batch import Replicate, batch_fits, replicate_model
from .steps import conditioning_set

__all__ = ["ModelBand", "COLD_FAMILIES", "PRUNE_AIC", "ReplicateStarts", "bootstrap_band",
           "default_jobs", "process_count", "replicate_plan", "replicate_mpms",
           "replicate_starts"]

COLD_FAMILIES = ("student",)
"""Families whose replicate fits also start from the data, beside the final fit: a warm
start alone leaves Student-t's replicate fits short of their optimum (its ν and location
are trapped at the edges of the final fit), ``docs/explanation/model-band.md``."""

@dataclass(frozen=True)
class ModelBand:
    """The model-uncertainty band of :meth:`pas.strategies.pas.PAS.model_band` (beyond the paper).

    Parameters
    ----------
    n_bootstrap : int, default 50
        Bootstrap replicates (0: no model band, the paper's sampling band only).
    marginals : {"fitted", "reselected", "alternate"}, default "reselected"
        Conditional estimator: every replicate fits the estimator's
        ``hf_marginal`` ("fitted"); or fits the Weibull and the log-normal and
        keeps the one of higher likelihood, as it re-selects the copula family
        ("reselected"; with ``hf_marginal="weibull_mixture"`` the mixture too,
        all compared by AIC); or the replicates take the Weibull and the
        log-normal in turn ("alternate", never the mixture).
    lf_ranks : {"fixed", "redrawn"}, default "redrawn"
        Conditional estimator: every replicate also draws the LF population
        CDF at the peaks given their order (a Bayesian bootstrap,
        :func:`pas.stats.dependence.weighted_ranks`) instead of keeping their
        mid-ranks ("fixed"), so the band holds what the empirical LF ranks
        cannot tell about the LF tail (``docs/departures.md``).
    model_form : {"none", "semi-empirical"}, default "none"
        With "semi-empirical" every replicate also reads the MPM of its
        model's semi-empirical distribution — the evaluated events at their
        observed HF values, the model drawing the rest — and the band spans
        both sets of replicate MPMs (:mod:`pas.strategies.model_form`); the
        MPM itself is unchanged.
    """

    n_bootstrap: int = 50
    marginals: str = "reselected"
    lf_ranks: str = "redrawn"
    model_form: str = "none"

    def __post_init__(self):
        object.__setattr__(self, "n_bootstrap", check_int(self.n_bootstrap, "n_bootstrap",
                                                          minimum=0))
        check_option(self.marginals, "marginals", {"fitted", "reselected", "alternate"})
        check_option(self.lf_ranks, "lf_ranks", {"fixed", "redrawn"})
        check_option(self.model_form, "model_form", set(model_forms.MODEL_FORMS))


PRUNE_AIC = 100.0
"""A replicate refits the families with a candidate within this AIC of its best eligible
one, judged at the final fits' parameters on its resampled pairs (module docs)."""



class ReplicateStarts(dict):
    """The joint fits a band replicate starts from, by ``(family, marginal)``: only these
    candidates are fitted (:meth:`pas.strategies.pas.PAS.fit`)."""


def default_jobs() -> int:
    """The cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


def process_count(n_jobs: int | None, n_tasks: int) -> int:
    """The processes ``n_tasks`` tasks run in for ``n_jobs`` (1: this one; -1: every core;
    None: every core on Linux unless this process runs other threads, module docs): at
    most one a task, and this process alone where fork is not available."""
    if n_jobs is not None and int(n_jobs) != -1 and int(n_jobs) < 1:
        raise ValueError(f"n_jobs must be at least 1, or -1 for every core, got {n_jobs}")
    if n_jobs is None:
        n_jobs = -1 if threading.active_count() == 1 and sys.platform.startswith("linux") else 1
    n_jobs = int(n_jobs)
    n_jobs = min(default_jobs() if n_jobs == -1 else n_jobs, max(n_tasks, 1))
    return n_jobs if "fork" in multiprocessing.get_all_start_methods() else 1


def replicate_plan(pairs, rng: np.random.Generator, n: int, marginals) -> list:
    """Each replicate's ``(true-positive indices, false-positive indices, HF marginal choice,
    uniform stream)``, the indices drawn from ``rng`` in replicate order."""
    draw_rngs = rng.spawn(n)  # read only when the uniforms are not common to the study
    m, n_fp = len(pairs), len(pairs.fp_position)
    plan = []
    for i in range(n):
        idx = rng.integers(0, m + n_fp, m + n_fp)
        plan.append((idx[idx < m], idx[idx >= m] - m, marginals[i % len(marginals)],
                     draw_rngs[i]))
    return plan


def _resampled(pairs, tp, fp):
    """The replicate's pairs, or None when too few or too alike to fit (the joint fit
    needs 3 different HF loads: :func:`pas.models.joint.fit_joint`)."""
    b = pairs.take(tp, fp)
    return None if tp.size < 4 or np.ptp(b.lf) == 0 or np.unique(b.hf).size < 3 else b


def _lf_rank_streams(strategy, pairs, lfset, plan, lf_rng) -> list:
    """Per replicate, ``lf_rng`` as that replicate finds it when they run one after another.

    Each replicate's draw of the LF ranks (:func:`population_lf_ranks`) is
    made here in turn — it depends on the replicate's conditioning set and
    impact model, so it reads a varying amount of the stream — and a copy of
    the stream taken before it.
    """
    streams = []
    for tp, fp, _, _ in plan:
        streams.append(copy.deepcopy(lf_rng))
        b = _resampled(pairs, tp, fp)
        if b is None or strategy.estimator.name != "conditional":
            continue
        try:
            impact = strategy.impact_of(b)
        except (ValueError, np.linalg.LinAlgError):
            continue  # the fit fails before it draws
        n0 = conditioning_set(lfset.lf, b.lf.min()).size
        strategy.population_ranks(lfset, n0, impact, lf_rng)
    return streams


def _choice_marginals(strategy, choice) -> set:
    """The HF marginals a replicate's ``hf_marginal`` choice fits (None: the study's)."""
    choice = choice or strategy.estimator.hf_marginal
    return set({"both": HF_MARGINALS, MIXTURE: ("weibull", MIXTURE),
                "all": (*HF_MARGINALS, MIXTURE)}.get(choice, (choice,)))


def replicate_starts(strategy, b, lfset, starts: dict, choice) -> ReplicateStarts:
    """The :class:`ReplicateStarts` of the families that can win the replicate of pairs
    ``b``, with the HF marginals of ``choice``: a family with a candidate within
    :data:`PRUNE_AIC` of the best one not on a parameter bound, by the AIC of the final
    fits ``starts`` on ``b`` (its own conditioning set and censoring, the mid-ranks of
    its LF; module docs)."""
    keys = [k for k in starts if k[1] in _choice_marginals(strategy, choice)]
    location = strategy.estimator.hf_location
    impact = strategy.impact_of(b)
    n0 = conditioning_set(lfset.lf, b.lf.min()).size
    u = strategy.population_ranks(lfset, n0, impact, None)[b.position]
    aic = {k: 2.0 * starts[k].copula.npars
           - 2.0 * float(np.sum(pair_logliks(starts[k], u, b.hf, location=location)))
           for k in keys}
    eligible = [aic[k] for k in keys if not starts[k].copula.at_bound] or list(aic.values())
    # whole families: a marginal's start can be far from its replicate optimum (module docs)
    kept = {f for f, _ in keys
            if min(a if np.isfinite(a) else -np.inf for (g, _), a in aic.items() if g == f)
            <= min(eligible) + PRUNE_AIC}
    return ReplicateStarts((k, starts[k]) for k in keys if k[0] in kept)


def _replicate_mpm(job: tuple, i: int) -> tuple | None:
    """The MPMs of replicate ``i`` of ``job`` ``(strategy, pairs, lfset, starts, plan,
    lf_rngs)`` (:func:`model_form.replicate_values
    <pas.strategies.model_form.replicate_values>`), None when it cannot be fitted."""
    strategy, pairs, lfset, starts, plan, lf_rngs = job
    tp, fp, marginal, draw_rng = plan[i]
    b = _resampled(pairs, tp, fp)
    if b is None:
        return None
    try:
        if starts is not None:
            starts = replicate_starts(strategy, b, lfset, starts, marginal)
        model = strategy.fit(b, lfset, update=False, hf_marginal=marginal,
                             lf_ranks_rng=lf_rngs[i], starts=starts)
        return strategy._replicate_mpm(model, lfset, draw_rng, _observed(strategy, pairs))
    except (ValueError, np.linalg.LinAlgError):
        return None


def _observed(strategy, pairs):
    """The study's pairs when the band also reads the semi-empirical MPM, else None."""
    return pairs if strategy.band.model_form == "semi-empirical" else None


def replicate_mpms(strategy, pairs, lfset, starts, plan, lf_rng=None,
                   n_jobs: int | None = None) -> list:
    """The MPMs of every replicate of ``plan`` (None where it failed), in plan order.

    ``starts``: the final joint fits, those that can win a replicate its
    starts (:func:`replicate_starts`; None: the strategy's own rule); ``lf_rng``: the stream of
    the LF-rank draws, read by the replicates in turn (None: mid-ranks);
    ``n_jobs``: processes (1: this process; -1: every core; None: every core
    on Linux unless this process runs other threads, module docs).
    """
    n_jobs = process_count(n_jobs, len(plan))
    if _can_batch(strategy, starts, plan):
        return _batched_mpms(strategy, pairs, lfset, starts, plan, lf_rng, n_jobs)
    if n_jobs == 1:
        lf_rngs = [lf_rng] * len(plan)
    elif lf_rng is None:
        lf_rngs = [None] * len(plan)
    else:
        lf_rngs = _lf_rank_streams(strategy, pairs, lfset, plan, lf_rng)
    job = (strategy, pairs, lfset, starts, plan, lf_rngs)
    if n_jobs == 1:
        return [_replicate_mpm(job, i) for i in range(len(plan))]
    with forked_pool(n_jobs, _replicate_mpm, job) as pool:
        return pool.map(forked_call, range(len(plan)), chunksize=1)


def _can_batch(strategy, starts, plan) -> bool:
    """Whether every joint fit of the replicates has a batched form (:func:`batchable`)."""
    return (starts is not None and strategy.estimator.name == "conditional"
            and all(batchable(f, m) for f, m in starts)
            and all(_choice_marginals(strategy, p[2]) <= set(HF_MARGINALS) for p in plan))


def _prepared(strategy, pairs, lfset, plan, lf_rng) -> list:
    """Per replicate its :class:`Replicate` without its starts (None when it cannot be
    fitted), made in plan order, so the LF-rank draws read ``lf_rng`` as one replicate
    after another would; the starts are chosen by the worker (:func:`_chunk_mpms`)."""
    out = []
    for tp, fp, _, _ in plan:
        b = _resampled(pairs, tp, fp)
        try:
            if b is None:
                raise ValueError("too few or all alike")
            impact = strategy.impact_of(b)
            n0 = conditioning_set(lfset.lf, b.lf.min()).size
            out.append(Replicate(b, impact, n0,
                                 strategy.population_ranks(lfset, n0, impact, lf_rng), None))
        except (ValueError, np.linalg.LinAlgError):
            out.append(None)
    return out


def _chunk_mpms(job: tuple, indices) -> list:
    """The MPMs of the replicates ``indices`` of the batched ``job`` ``(strategy, pairs,
    lfset, starts, plan, replicates, width)``, fitted together from the starts that can
    win each (:func:`replicate_starts`)."""
    strategy, pairs, lfset, starts, plan, replicates, width = job
    chunk = {}
    for i in indices:
        if replicates[i] is not None:
            with contextlib.suppress(ValueError, np.linalg.LinAlgError):
                chunk[i] = Replicate(*replicates[i][:4], replicate_starts(
                    strategy, replicates[i][0], lfset, starts, plan[i][2]))
    fits = batch_fits(strategy, chunk, COLD_FAMILIES, width)
    out = []
    for i in indices:
        try:
            if fits.get(i) is None:
                raise ValueError("no fit")
            out.append(strategy._replicate_mpm(
                replicate_model(strategy, lfset, chunk[i], fits[i]), lfset, plan[i][3],
                _observed(strategy, pairs)))
        except (ValueError, np.linalg.LinAlgError):
            out.append(None)
    return out


def _batched_mpms(strategy, pairs, lfset, starts, plan, lf_rng, n_jobs) -> list:
    """:func:`replicate_mpms` with the replicates fitted together, in ``n_jobs`` chunks:
    this process fits the first, forked workers the others meanwhile."""
    replicates = _prepared(strategy, pairs, lfset, plan, lf_rng)
    width = max([np.unique(r[0].position).size for r in replicates if r is not None] or [1])
    job = (strategy, pairs, lfset, starts, plan, replicates, width)
    chunks = [list(c) for c in np.array_split(np.arange(len(plan)), n_jobs) if c.size]
    if len(chunks) <= 1:
        return _chunk_mpms(job, chunks[0]) if chunks else []
    with forked_pool(len(chunks) - 1, _chunk_mpms, job) as pool:
        others = pool.map_async(forked_call, chunks[1:], chunksize=1)
        first = _chunk_mpms(job, chunks[0])
        return first + [x for part in others.get() for x in part]


def bootstrap_band(strategy, band: ModelBand, pairs, lfset, rng: np.random.Generator,
                   n_jobs: int | None = None):
    """:meth:`pas.strategies.pas.PAS.model_band` with the settings ``band``: ``(low, high,
    replicate MPMs)`` or None when fewer than 10 replicates could be fitted."""
    conditional = strategy.estimator.name == "conditional"
    reselected = "all" if conditional and strategy.estimator.hf_marginal == MIXTURE else "both"
    marginals = {"fitted": (None,), "reselected": (reselected,),
                 "alternate": HF_MARGINALS}[band.marginals]
    starts = strategy.final_joint_fits(pairs, lfset, reselected) if conditional else None
    # a stream of its own, so the resampled pairs are those of "fixed"
    lf_rng = rng.spawn(1)[0] if band.lf_ranks == "redrawn" else None
    plan = replicate_plan(pairs, rng, band.n_bootstrap, marginals)
    return model_forms.band_ends(replicate_mpms(strategy, pairs, lfset, starts, plan, lf_rng,
                                                n_jobs))
