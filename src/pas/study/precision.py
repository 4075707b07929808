"""The precision target of a study: when to compute the model band, the stop, the forecast.

:meth:`Study._iterate <pas.study.study.Study>` calls :func:`judge` after each
fit of a study with ``precision``; the rule and its schedule of model bands are
:class:`~pas.strategies.stopping.StoppingRule`'s, the forecast
:mod:`pas.strategies.forecast`'s.  :func:`model_band` is the one place the
strategy's model band is computed for a study, in the loop and for the
result (:meth:`ScreeningResult.from_study
<pas.study.result.ScreeningResult.from_study>`): it draws from
``default_rng([seed, n_told, 1])`` and keeps the last band, so the result of
a study that stopped on its band reports that band without refitting it.
"""

from __future__ import annotations

import inspect
import time
from concurrent.futures.process import BrokenProcessPool

import numpy as np

from .._support.forked import forked_call, forked_executor
from ..strategies.forecast import relative_half_width

__all__ = ["model_band", "model_bands", "judge", "forecast_row", "union"]


def _has_model_band(strategy) -> bool:
    """Whether the strategy computes a model band: its own ``model_band``, and for a
    bootstrap band (PAS's :class:`~pas.strategies.band.ModelBand`) one replicate or more."""
    from ..strategies.base import Strategy

    return (type(strategy).model_band is not Strategy.model_band
            and getattr(getattr(strategy, "band", strategy), "n_bootstrap", 1) > 0)


def _band_key(study, pairs) -> tuple:
    """What a study's model band depends on: its told results, fits and ``pairs``."""
    return (study.n_told, len(study.rows), tuple(pairs.position), tuple(pairs.hf),
            tuple(pairs.fp_position))


def _kept(study, key) -> bool:
    """Whether ``study`` keeps the model band of ``key`` (:func:`_band_key`)."""
    return study.kept_band is not None and study.kept_band[0] == key


def model_band(study, pairs, row: dict | None = None, n_jobs: int | None = None) -> tuple | None:
    """``(low, high)`` of the strategy's model band for ``study`` as it stands, or None.

    ``row``: the history row of the fit; replaying a store, the band that row
    recorded is taken instead of refitted (:func:`pas.study.replay.attach`): the
    same pairs and draws give the same band.  ``n_jobs``: the processes the band
    may use (:meth:`pas.strategies.pas.PAS.model_band`; the same band for any).
    """
    key = _band_key(study, pairs)
    if _kept(study, key):
        return study.kept_band[1]
    stored = study.stored_bands.get(row["row"]) if row is not None else None
    if (study.replaying and stored is not None and stored.get("event_index") == row["event_index"]
            and stored.get("hf") == row["hf"]):
        band = (float(stored["model_low"]), float(stored["model_high"]))
    else:
        rng = np.random.default_rng([study.seed, study.n_told, 1])
        kw = {} if n_jobs is None else {"n_jobs": n_jobs}  # an own model_band may not take it
        mb = study.strategy.model_band(pairs, study.lfset, rng, **kw)
        band = None if mb is None else (float(mb[0]), float(mb[1]))
    study.kept_band = (key, band)
    return band


_FAILED = "failed"  # a worker's answer for a band that raised: the caller computes it again


def _band_in_worker(studies, i: int) -> tuple:
    """``(band, wall s)`` of study ``i`` of ``studies``, in a worker of :func:`model_bands`;
    :data:`_FAILED` for a band that raised (its error may not survive pickling)."""
    t0 = time.perf_counter()
    study = studies[i]
    try:
        band = model_band(study, study.pairs(), n_jobs=1)
    except Exception:  # noqa: BLE001 - computed again by the caller, which raises it as it is
        band = _FAILED
    return band, time.perf_counter() - t0


def _takes_n_jobs(strategy) -> bool:
    """Whether the strategy's ``model_band`` takes ``n_jobs`` (a strategy's own may not)."""
    return "n_jobs" in inspect.signature(strategy.model_band).parameters


def model_bands(studies, n_jobs: int | None = None) -> dict:
    """:func:`model_band` of every study of ``studies`` that has a fit and a model band not
    yet computed (a long-term analysis's sea states), each study's band in a process of
    its own, as many at once as ``n_jobs`` allows (:func:`pas.strategies.band.process_count`;
    the studies with the most pairs first); each study keeps its band as :func:`model_band`
    keeps it.  The bands are those one study after another gives (the same band for any
    number of processes), in less time than each band split over the cores.  A band that
    raised in a worker, or whose worker died, is computed again here (and raises here).
    Returns the wall seconds spent on each study's band, by position (computed at once,
    their share of the wall time the bands took together, in proportion to each band's
    own)."""
    from ..strategies.band import process_count

    keys = {i: _band_key(st, st.pairs()) for i, st in enumerate(studies)
            if st is not None and st.last is not None and _has_model_band(st.strategy)}
    todo = [i for i, key in keys.items() if not _kept(studies[i], key)]
    # a band whose model_band takes no n_jobs (a strategy's own) is computed here, as before
    apart = sorted((i for i in todo if _takes_n_jobs(studies[i].strategy)),
                   key=lambda i: -len(studies[i].pairs()))
    seconds = {}
    workers = process_count(n_jobs, len(apart))
    if workers > 1:
        t0 = time.perf_counter()
        try:
            with forked_executor(workers, _band_in_worker, studies) as pool:
                for i, (band, wall) in zip(apart, pool.map(forked_call, apart)):
                    if band != _FAILED:
                        studies[i].kept_band = (keys[i], band)
                        seconds[i] = wall
        except BrokenProcessPool:  # a worker died (out of memory, killed): the rest here
            pass
        # the wall time they took together, shared in proportion to each band's own
        scale = (time.perf_counter() - t0) / max(sum(seconds.values()), 1e-12)
        seconds = {i: wall * scale for i, wall in seconds.items()}
    for i in todo:
        if i not in seconds:
            t0 = time.perf_counter()
            jobs = n_jobs if _takes_n_jobs(studies[i].strategy) else None
            model_band(studies[i], studies[i].pairs(), n_jobs=jobs)
            seconds[i] = time.perf_counter() - t0
    return seconds


def union(sampling, model) -> tuple:
    """The U95: the sampling part, widened to hold the model part (when there is one)."""
    if model is None:
        return tuple(sampling)
    return min(sampling[0], model[0]), max(sampling[1], model[1])


def judge(study, pred, pairs, row: dict, paper_stop: bool) -> bool:
    """Whether the precision rule stops the study at this fit; writes its columns to ``row``.

    ``halfwidth_sampling`` every fit; where the model band was computed,
    ``model_low``/``model_high`` and ``halfwidth`` (the U95's relative
    half-width); and the forecast's further HF evaluations (:func:`forecast_row`).
    """
    rule = study.rule
    floor = relative_half_width(pred.mpm, pred.mpm_band)
    row["halfwidth_sampling"] = floor
    gate = paper_stop and rule.precision_gate(pred.mpm, pred.mpm_band)
    # a model that misfits the evaluated loads cannot stop the study: no band computed for it
    if gate and rule.fit_check is not None:
        gate = fits_evaluated(study, pairs, row, rule.fit_check)
    has_model = _has_model_band(study.strategy)
    if not has_model:  # the sampling part is the U95, and the part that narrows
        floor = 0.0
    met = False
    if not has_model or rule.band_due(len(pairs), gate, floor):
        model = model_band(study, pairs, row) if has_model else None
        band = union(pred.mpm_band, model)
        narrowing = (row["halfwidth_sampling"] if model is None
                     else relative_half_width(pred.mpm, model))
        rule.record_band(len(pairs), narrowing)
        row.update(halfwidth=relative_half_width(pred.mpm, band))
        if model is not None:
            row.update(model_low=model[0], model_high=model[1])
        met = gate and rule.precision_met(pred.mpm, band)
    forecast = rule.forecast(floor, n_now=len(pairs), may_stop_now=met)
    row.update(forecast_row(study, forecast, len(pairs)))
    return met


def fits_evaluated(study, pairs, row: dict, alpha: float) -> bool:
    """Whether the model of this fit passes the fit check on ``pairs`` at level ``alpha``
    (:class:`~pas.study.settings.Stopping` ``fit_check``); writes its p-value and, when it
    fails, the failing test to ``row`` (True for a strategy without a fitted model)."""
    from ..stats.fit_check import uniform_check

    model = getattr(study.strategy, "model_", None)
    if model is None or not hasattr(model, "transforms"):
        return True
    check = uniform_check(model.transforms(pairs))
    row["fit_check_p"] = check.p
    if check.rejects(alpha):
        row["fit_misfit"] = check.worst()
        return False
    return True


def forecast_row(study, forecast, n_pairs: int) -> dict:
    """The further HF evaluations a forecast expects, as history columns (NaN when none).

    Pairs are turned into evaluations at the study's ratio so far (false
    positives cost an evaluation and give no pair).
    """
    nan = float("nan")
    if forecast is None:
        return {"forecast_hf": nan, "forecast_hf_low": nan, "forecast_hf_high": nan}
    per_pair = study.n_hf / max(n_pairs, 1)
    expected, low, high = forecast.further(n_pairs, per_pair)
    return {"forecast_hf": expected, "forecast_hf_low": low, "forecast_hf_high": high}


def final_forecast(study, pairs, pred, model) -> dict | None:
    """The forecast of a result: the study's band widths and the final band's (``model``),
    with ``out_of_reach`` saying whether an infinite forecast was meant (JSON keeps no inf)."""
    rule = study.rule
    if rule.precision is None:
        return None
    sampling = relative_half_width(pred.mpm, pred.mpm_band)
    has_model = _has_model_band(study.strategy)
    extra = None
    if model is not None:
        extra = (len(pairs), relative_half_width(pred.mpm, model))
    elif not has_model:
        extra = (len(pairs), sampling)
    forecast = rule.forecast(sampling if has_model else 0.0, extra, n_now=len(pairs),
                             may_stop_now=bool(study.converged))
    row = forecast_row(study, forecast, len(pairs))
    return {**row, "out_of_reach": forecast is not None and not np.isfinite(forecast.n_pairs),
            "sampling_halfwidth": sampling if has_model else None}


def holds(study, mpm: float, band, model_band: bool) -> bool:
    """For the result of a study that stopped: whether its reported band still meets the
    precision target (True without one, or without the model band: the stop was judged on
    the U95).  Told results after the stop (the rest of a batch) can widen it."""
    rule = study.rule
    return rule.precision is None or not model_band or rule.precision_met(mpm, band)
