"""The entry points users call: :func:`run_pas`, :func:`run_as` and :func:`make_study`."""

from __future__ import annotations

import warnings

from .strategies.as_ import AS
from .strategies.pas import PAS
from .strategies.screening import check_n_waves
from .study.factory import DEFAULT_MAX_HF, apply_preset, split_settings
from .study.oracles import check_oracle
from .study.result import ScreeningResult
from .study.study import Study

__all__ = ["run_pas", "run_as", "make_study"]


def make_study(strategy, lf_peaks, *, n_waves, p_exp, eps1=None, eps2=0.1, threshold=None,
               seed=None, max_hf="default", ids=None, meta=None, store=None, preset=None,
               n_waves_convention="count", precision=None, **settings) -> Study:
    """Validate the inputs and build a :class:`~pas.study.study.Study` for ``strategy``.

    Parameters
    ----------
    strategy : str, Strategy subclass or instance
        ``"pas"``/``"as"`` or :class:`~pas.strategies.pas.PAS`/
        :class:`~pas.strategies.as_.AS` (built with the strategy settings
        found in ``settings``), or an instance (then ``settings`` holds study
        settings only).
    lf_peaks, n_waves, p_exp, eps1, eps2, precision, threshold, seed, max_hf, ids, meta
        As for :func:`run_pas`.
    store : str, os.PathLike or StudyStore, optional
        Makes the study crash-safe and resumable (:mod:`pas.study.store`);
        with ``seed=None`` an existing store's seed is used.  The stopping
        settings (``eps1``, ``precision``, ``eps2``, ``k1``, ``k2``) and budgets (``max_hf``,
        ``max_failures``) may differ from the stored ones: the new values
        are used from the first stored iteration on and recorded in the store.
    n_waves_convention : {"count", "spectral"}, default "count"
        As for :func:`run_pas`.
    preset : {None, "default", "paper"}, optional
        A named bundle of PAS settings (:data:`pas.study.factory.PRESETS`);
        settings given explicitly win.
    **settings
        Strategy settings (checked against the strategy's constructor;
        unknown names raise ``ValueError``) and study settings (``k1``,
        ``k2``, ``max_failures``, ``stop_on_convergence``,
        ``adaptive_threshold``, ``threshold_step``, ``fp_run``, ``target``: the load to
        screen on when the oracle answers several, see :func:`run_pas`).

    Returns
    -------
    Study
    """
    note = check_n_waves(lf_peaks, n_waves, threshold, convention=n_waves_convention,
                         names={"convention": "n_waves_convention='spectral'"})
    if note is not None:
        warnings.warn(note, stacklevel=3)
    settings = apply_preset(preset, strategy, settings)
    budget = settings.pop("max_hf", DEFAULT_MAX_HF)
    max_hf = budget if isinstance(max_hf, str) and max_hf == "default" else max_hf
    study_settings, strategy_settings = split_settings(settings)
    return Study.from_settings(
        {"strategy": strategy, "strategy_settings": strategy_settings, "n_waves": n_waves,
         "p_exp": p_exp, "threshold": threshold, "eps1": eps1, "eps2": eps2, "seed": seed,
         "precision": precision,
         "max_hf": max_hf, **study_settings},
        lf_peaks, ids=ids, meta=meta, store=store)


def run_pas(lf_peaks, oracle, *, n_waves, p_exp, eps1=None, eps2=0.1, threshold=None, seed=None,
            max_hf="default", ids=None, meta=None, batch_size=1, callback=None, study=None,
            pending="resubmit", executor=None, n_workers=None, n_waves_convention="count",
            preset=None, retry_failed=False, precision=None,
            **settings) -> ScreeningResult:
    """Predict the MPM of an HF load with Probabilistic Adaptive Screening.

    Parameters
    ----------
    lf_peaks : array-like, shape (n_events,)
        LF indicator peak of every wave event in the LF Monte-Carlo run.
    oracle : callable
        ``oracle(event) -> float``: the HF peak of ``event`` (an
        :class:`~pas.strategies.screening.Event` with ``index``, ``id``, ``lf``, ``d``,
        ``meta``); 0.0 means no impact (a false positive).  An exception, NaN,
        inf or a negative value is recorded as a failure, never taken as 0.
        Or ``-> {name: float}``, several loads of one HF run, with ``target``.
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration.
    p_exp : float
        Target exceedance probability (:func:`pas.p_exp_from_duration`).
    eps1 : float, optional
        Stopping limit on the mean change of the predicted distribution,
        in load units (paper: ≈ 1–2 % of the expected maximum).
    eps2 : float, default 0.1
        Stopping limit on the COV of the last K2 MPMs (with ``eps1``).
    precision : float, optional
        Stop once the U95 of the MPM (``result.mpm_band``) lies within
        ``±precision × MPM`` of it and the last K2 MPMs inside it, e.g. 0.10
        for ±10 % (scale-free; :mod:`pas.strategies.stopping`).  Give this or
        ``eps1``; with both, both rules must hold.  ``result.forecast_hf``
        says how many more HF evaluations the target is expected to take.
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    seed : int, optional
        Seed for reproducible draws (reported on the result when None).
    max_hf : int, None or "default"
        Budget of HF evaluations: the study stops there, converged or not.
        ``"default"``: 160 (:data:`pas.study.factory.DEFAULT_MAX_HF`, the
        most the paper needed), or none with ``preset="paper"``.  None: no
        budget.
    ids, meta : sequence, optional
        User ids / metadata per event, passed to the oracle on the event.
    batch_size : int, default 1
        Events proposed per iteration.
    callback : callable, optional
        ``callback(study, row)`` after every HF result.
    study : str or os.PathLike, optional
        SQLite study store (:mod:`pas.study.store`): created when missing,
        otherwise checked against this call and continued — no stored HF
        result is lost or re-run, and the run makes the decisions an
        uninterrupted one would have made (same ``batch_size``).  The
        stopping settings (``eps1``, ``eps2``, ``k1``, ``k2``) and budgets
        (``max_hf``, ``max_failures``) may change on a resumed study: no
        decision taken so far depends on them, so the continued run asks for
        the events an uninterrupted run with the new values would have asked
        for (a looser limit cannot undo evaluations already made).
    pending : {"resubmit", "wait"}, default "resubmit"
        Events a killed run left without a result: run them again, or leave
        them for ``pas study tell``.
    retry_failed : bool, default False
        With ``study``: run the failed events of the stored study again (after
        fixing their cause), so it continues as if they had not failed
        (:meth:`Study.retry_failed <pas.study.study.Study.retry_failed>`).
    executor : concurrent.futures.Executor, optional
        Runs the oracle calls of a batch concurrently (e.g.
        ``distributed.Client(...).get_executor()``); results are stored as
        they arrive.
    n_workers : int, optional
        Without ``executor``: a local process pool of this size (the oracle
        must be picklable).
    preset : {None, "default", "paper"}, optional
        ``"paper"`` reproduces the paper's scripts (τ inversion for the
        Archimedean copulas, selected-sample space, redrawn uniforms, the
        sampling band; :data:`pas.study.factory.PRESETS`,
        ``docs/departures.md``); settings given explicitly win.
    n_waves_convention : {"count", "spectral"}, default "count"
        How ``n_waves`` was obtained (:func:`pas.strategies.screening.check_n_waves`).
        ``"count"``: counted wave encounters; ``n_waves`` below the number of
        LF peaks over the threshold (exceedance probabilities above 1) is a
        ``ValueError``, below the number of all peaks a warning.
        ``"spectral"``: ``n_w = T_MCS / T_p,e`` on purpose, as in the paper's
        Table 2 and :mod:`pas.validation`; not checked.
    **settings
        Settings of :class:`~pas.strategies.pas.PAS` (``families``, ``z``,
        ``delta_aic``, ``exclude_at_bound``, ``upper_tail``, ``outlier_k``,
        ``n_bootstrap``, ``skip_unsplittable``, ``marginals_from``,
        ``impact_model``, ``estimator``, ``copula_fit``,
        ``common_random_numbers``, ``hf_location``, ``hf_marginal``, ``band_marginals``,
        ``band_lf_ranks``, ``lf_tail``)
        and study settings (``k1``, ``k2``,
        ``max_failures``, ``stop_on_convergence``, ``adaptive_threshold``,
        ``threshold_step``, ``fp_run``: :class:`~pas.study.study.Study`), and
        ``target``: with an oracle answering several named loads ``{name:
        load}``, the one to screen on (the store keeps all; :func:`pas.refit`
        analyses another on the same events).

    Returns
    -------
    ScreeningResult

    Raises
    ------
    OracleFailureLimit
        More than ``max_failures`` oracle calls failed; ``.result`` holds the
        result so far.

    Examples
    --------
    >>> import numpy as np, pas
    >>> rng = np.random.default_rng(0)
    >>> lf = rng.rayleigh(2.0, 3000)
    >>> res = pas.run_pas(lf, lambda ev: 1.2 * ev.lf ** 1.1, n_waves=3000, p_exp=1e-2,
    ...                   eps1=0.05, seed=1)
    >>> bool(res.converged), res.n_hf < 60
    (True, True)
    """
    check_oracle(oracle)  # before a study store is written
    built = make_study(PAS, lf_peaks, n_waves=n_waves, p_exp=p_exp, eps1=eps1, eps2=eps2,
                       precision=precision,
                       threshold=threshold, seed=seed, max_hf=max_hf, ids=ids, meta=meta,
                       store=_store_for_retry(study, retry_failed),
                       n_waves_convention=n_waves_convention, preset=preset, **settings)
    return _optimize(built, oracle, retry_failed, batch_size=batch_size, callback=callback,
                     executor=executor, n_workers=n_workers, pending=pending)


def run_as(lf_peaks, oracle, *, n_waves, p_exp, eps1=None, eps2=0.1, threshold=None, seed=None,
           max_hf="default", ids=None, meta=None, batch_size=1, callback=None, study=None,
           pending="resubmit", executor=None, n_workers=None, n_waves_convention="count",
           retry_failed=False, precision=None, **settings) -> ScreeningResult:
    """Predict the MPM of an HF load with Adaptive Screening (paper App. A), the GPR reference.

    Runs :class:`~pas.strategies.as_.AS` in the same study loop as
    :func:`run_pas`: same screening (steps 1–4), oracle, false positives and
    stopping rule (App. C); 2 initial samples, the order-statistics
    assumption (each HF sample gets its event's LF exceedance probability),
    a single- or multi-fidelity GPR surrogate of ``h`` over ``ln d`` and MVPD
    acquisition (Eq. 20).  AS is biased non-conservative when the indicator
    does not rank events like the HF load does.

    Parameters
    ----------
    lf_peaks : array-like, shape (n_events,)
        LF indicator peak of every wave event in the LF Monte-Carlo run.
    oracle : callable
        ``oracle(event) -> float``: the HF peak of ``event`` (an
        :class:`~pas.strategies.screening.Event` with ``index``, ``id``, ``lf``, ``d``,
        ``meta``); 0.0 means no impact (a false positive).  An exception, NaN,
        inf or a negative value is recorded as a failure, never taken as 0.
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration.
    p_exp : float
        Target exceedance probability (:func:`pas.p_exp_from_duration`).
    eps1 : float, optional
        Stopping limit on the mean change of the predicted distribution,
        in load units (paper: ≈ 1–2 % of the expected maximum).
    eps2 : float, default 0.1
        Stopping limit on the COV of the last K2 MPMs (with ``eps1``).
    precision : float, optional
        Stop once the U95 of the MPM (``result.mpm_band``) lies within
        ``±precision × MPM`` of it and the last K2 MPMs inside it, e.g. 0.10
        for ±10 % (scale-free; :mod:`pas.strategies.stopping`).  Give this or
        ``eps1``; with both, both rules must hold.  ``result.forecast_hf``
        says how many more HF evaluations the target is expected to take.
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    seed : int, optional
        Seed for reproducible runs (reported on the result when None).
    max_hf : int, None or "default"
        Budget of HF evaluations (at least 2; ``"default"``: 160; None: no
        budget).
    ids, meta : sequence, optional
        User ids / metadata per event, passed to the oracle on the event.
    batch_size : int, default 1
        Events proposed per iteration (the next-best MVPD targets).
    callback : callable, optional
        ``callback(study, row)`` after every HF result.
    study : str or os.PathLike, optional
        SQLite study store (:mod:`pas.study.store`): created when missing,
        otherwise checked against this call and continued — no stored HF
        result is lost or re-run, and the run makes the decisions an
        uninterrupted one would have made (same ``batch_size``).  The
        stopping settings (``eps1``, ``eps2``, ``k1``, ``k2``) and budgets
        (``max_hf``, ``max_failures``) may change on a resumed study: no
        decision taken so far depends on them, so the continued run asks for
        the events an uninterrupted run with the new values would have asked
        for (a looser limit cannot undo evaluations already made).
    pending : {"resubmit", "wait"}, default "resubmit"
        Events a killed run left without a result: run them again, or leave
        them for ``pas study tell``.
    retry_failed : bool, default False
        With ``study``: run the failed events of the stored study again (after
        fixing their cause), so it continues as if they had not failed
        (:meth:`Study.retry_failed <pas.study.study.Study.retry_failed>`).
    executor : concurrent.futures.Executor, optional
        Runs the oracle calls of a batch concurrently (e.g.
        ``distributed.Client(...).get_executor()``); results are stored as
        they arrive.
    n_workers : int, optional
        Without ``executor``: a local process pool of this size (the oracle
        must be picklable).
    n_waves_convention : {"count", "spectral"}, default "count"
        How ``n_waves`` was obtained (:func:`pas.strategies.screening.check_n_waves`).
        ``"count"``: counted wave encounters; ``n_waves`` below the number of
        LF peaks over the threshold (exceedance probabilities above 1) is a
        ``ValueError``, below the number of all peaks a warning.
        ``"spectral"``: ``n_w = T_MCS / T_p,e`` on purpose, as in the paper's
        Table 2 and :mod:`pas.validation`; not checked.
    **settings
        Settings of :class:`~pas.strategies.as_.AS` (``fidelity``
        ``"multi"``/``"single"``, ``range_factor``, ``n_grid``,
        ``n_lf_bins``, ``n_restarts``) and study settings (``k1``, ``k2``,
        ``max_failures``, ``stop_on_convergence``, ``adaptive_threshold``,
        ``threshold_step``, ``fp_run``: :class:`~pas.study.study.Study`).

    Returns
    -------
    ScreeningResult

    Raises
    ------
    OracleFailureLimit
        More than ``max_failures`` oracle calls failed; ``.result`` holds the
        result so far.

    Examples
    --------
    >>> import numpy as np, pas
    >>> rng = np.random.default_rng(0)
    >>> lf = rng.rayleigh(2.0, 3000)
    >>> res = pas.run_as(lf, lambda ev: 1.2 * ev.lf ** 1.1, n_waves=3000, p_exp=1e-2,
    ...                  eps1=0.05, seed=1)
    >>> res.strategy, bool(res.converged)
    ('as', True)
    """
    check_oracle(oracle)  # before a study store is written
    built = make_study(AS, lf_peaks, n_waves=n_waves, p_exp=p_exp, eps1=eps1, eps2=eps2,
                       precision=precision,
                       threshold=threshold, seed=seed, max_hf=max_hf, ids=ids, meta=meta,
                       store=_store_for_retry(study, retry_failed),
                       n_waves_convention=n_waves_convention, **settings)
    return _optimize(built, oracle, retry_failed, batch_size=batch_size, callback=callback,
                     executor=executor, n_workers=n_workers, pending=pending)


def _store_for_retry(study, retry_failed):
    """``study`` (the store), checked to be there when ``retry_failed`` asks for one."""
    if retry_failed and study is None:
        raise ValueError("retry_failed=True needs study=... (the study store of the run whose "
                         "failed events should run again)")
    return study


def _optimize(built, oracle, retry_failed, **loop_kw) -> ScreeningResult:
    if retry_failed:
        built.retry_failed()
    return built.optimize(oracle, **loop_kw)
