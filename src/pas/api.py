"""The entry points users call: :func:`run_pas`, :func:`run_as` and :func:`make_study`.

Settings are objects kept with what they configure: the strategy
(:class:`~pas.strategies.pas.PAS` with its estimator and
:class:`~pas.strategies.band.ModelBand`, or :class:`~pas.strategies.as_.AS`),
:class:`~pas.study.settings.Stopping` and :class:`~pas.study.settings.Budget`.
A keyword of pas 0.1 raises a ``TypeError`` naming its new place and the
docs page *Settings (old name → new place)*.
"""

from __future__ import annotations

import copy
import warnings

from ._support.moved import keywords_moved
from .strategies.as_ import AS
from .strategies.base import Strategy
from .strategies.pas import PAS
from .strategies.screening import check_n_waves
from .study.corrections import check_retry
from .study.factory import make_strategy
from .study.flat import MOVED, SETTINGS_PAGE
from .study.inputs import split_lf_table
from .study.oracles import check_oracle
from .study.result import ScreeningResult
from .study.settings import UNSET, given_names, keep_stored, lacks_a_limit, resolve
from .study.store import read_settings
from .study.study import Study

__all__ = ["run_pas", "run_as", "make_study"]

@keywords_moved(MOVED, SETTINGS_PAGE)
def make_study(strategy, lf_peaks, *, n_waves, p_exp, threshold=None, eps1=None, eps2=None,
               precision=None, seed=None, max_hf=UNSET, stopping=None, budget=None, store=None,
               n_waves_convention="count", target=None, stop_on_convergence=None,
               adaptive_threshold=None, threshold_step=None, fp_run=None,
               legacy_md=None) -> Study:
    """Validate the inputs and build a :class:`~pas.study.study.Study` for ``strategy``.

    Parameters
    ----------
    strategy : str, Strategy subclass or instance
        ``"pas"``, ``"as"``, ``"paper"`` (``PAS.paper()``), a strategy class
        (its defaults) or an instance such as ``PAS(z=20)``, of which the
        study takes a copy (so one instance may configure several studies).
    lf_peaks : array-like or pandas.DataFrame
        LF indicator peak of every wave event in the LF Monte-Carlo run; or a
        table, one row per event: the column ``lf`` (or its only column) the
        peaks, the column ``id`` (or else the index, unless it is the default
        ``0 … n-1``) the event ids, every other column the event's ``meta``
        (:func:`pas.study.inputs.split_lf_table`).
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration
        (counted: at least the LF peaks over the threshold; for ``n_w = T_MCS
        / T_p,e`` on purpose use ``n_waves_convention="spectral"``).
    p_exp : float
        Target exceedance probability (:func:`pas.p_exp_from_duration`).
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    eps1 : float, optional
        Stopping limit on the mean change of the predicted distribution, in
        load units (the paper: about 1–2 % of the expected maximum); fills
        :class:`~pas.study.settings.Stopping`.  None: no limit of this kind.
        Not together with ``stopping``.
    eps2 : float, optional
        Stopping limit on the COV of the last ``k2`` MPMs (with ``eps1``);
        None: :class:`~pas.study.settings.Stopping`'s 0.1.  Not together with
        ``stopping``.
    precision : float, optional
        A precision target (e.g. 0.10): stop once the U95 of the MPM lies
        within ``±precision × MPM`` and holds the last ``k2`` MPMs, and the
        fitted model passes its fit check (``Stopping.fit_check``).  With
        ``eps1`` both must hold.  The result's ``forecast_hf`` says how many
        more HF evaluations the target is expected to need.  Not together
        with ``stopping``.
    seed : int, optional
        Seed for reproducible draws (reported on the result when None).
    max_hf : int or None, default 160
        The study stops after this many HF evaluations, converged or not
        (fills :class:`~pas.study.settings.Budget`; 160 is the most the paper
        needed).  Not given with ``strategy="paper"``: no budget, as the
        paper ran.  None: no budget.  Not together with ``budget``.
    stopping : Stopping, optional
        The whole stopping rule (``k1``, ``k2``, ``measure`` too); default
        ``Stopping()``, ``Stopping.paper()`` with ``strategy="paper"``.
    budget : Budget, optional
        ``Budget(max_hf=160, max_failures=10)``: more than ``max_failures``
        failed oracle calls raise :class:`~pas.study.oracles.OracleFailureLimit`.
    store : str, os.PathLike or StudyStore, optional
        Makes the study crash-safe and resumable (:mod:`pas.study.store`);
        with ``seed=None`` an existing store's seed is used, and a stopping or
        budget setting this call does not name keeps its stored value
        (``pas study set`` changes them between runs).
    n_waves_convention : {"count", "spectral"}, default "count"
        How ``n_waves`` was obtained (:func:`pas.strategies.screening.check_n_waves`).
        ``"count"``: counted wave encounters; ``n_waves`` below the number of
        LF peaks over the threshold (exceedance probabilities above 1) is a
        ``ValueError``, below the number of all peaks a warning.
        ``"spectral"``: ``n_w = T_MCS / T_p,e`` on purpose, as in the paper's
        Table 2 and :mod:`pas.validation`; not checked.
    target : str, optional
        With an oracle answering several named loads ``{name: load}``: the one
        to screen on (the store keeps all; :func:`pas.refit` analyses another).
    stop_on_convergence : bool, optional
        None: True.  False keeps sampling until the budget is spent or the
        pool is empty.
    adaptive_threshold : bool, optional
        None: True.  Raise the acquisition threshold by ``threshold_step`` ×
        the largest LF peak after ``fp_run`` false positives in a row (§2.4).
    threshold_step : float, optional
        The step of ``adaptive_threshold``, a share of the largest LF peak;
        None: 0.02.
    fp_run : int, optional
        False positives in a row that raise the threshold; None: 5.
    legacy_md : bool, optional
        None: False.  True replays study stores written by pas 0.1 as they
        ran (MD gaps between true positives only).

    Returns
    -------
    Study
        Run it with :meth:`~pas.study.study.Study.optimize` (``n_workers``,
        ``pending``) or drive it with ask/tell.
    """
    return _make_study("make_study", **locals(), stacklevel=4)


def _make_study(where, strategy, lf_peaks, *, n_waves, p_exp, threshold, eps1, eps2, precision,
                seed, max_hf, stopping, budget, store, n_waves_convention, stacklevel,
                **options) -> Study:
    """:func:`make_study`, its errors naming ``where`` (the function the user called) and its
    warnings the user's line (``stacklevel`` frames up)."""
    lf, ids, meta = split_lf_table(lf_peaks)
    note = check_n_waves(lf, n_waves, threshold, convention=n_waves_convention,
                         names={"convention": "n_waves_convention='spectral'"})
    if note is not None:
        warnings.warn(note, stacklevel=stacklevel)
    if isinstance(strategy, str) and strategy == "paper":
        strategy = PAS.paper()
    elif isinstance(strategy, Strategy):  # its own copy: one object may serve many studies
        strategy = copy.deepcopy(strategy)
    given = given_names(stopping, budget, eps1=eps1, eps2=eps2, precision=precision,
                        max_hf=max_hf)
    stopping, budget = resolve(where, strategy, stopping, budget, eps1=eps1, eps2=eps2,
                               precision=precision, max_hf=max_hf)
    stored = {} if store is None else read_settings(store)  # read once: the seed too
    stopping, budget = keep_stored(stopping, budget, stored, given)
    seed = stored.get("seed") if seed is None else seed
    if (missing := lacks_a_limit(stopping.flat())) is not None:
        raise ValueError(f"{where}: {missing}")
    return Study.from_peaks(make_strategy(strategy), lf, n_waves=n_waves, p_exp=p_exp,
                            threshold=threshold, ids=ids, meta=meta, store=store, seed=seed,
                            stopping=stopping, budget=budget,
                            **{k: v for k, v in options.items() if v is not None})


@keywords_moved(MOVED, SETTINGS_PAGE)
def run_pas(lf_peaks, oracle, *, n_waves, p_exp, threshold=None, eps1=None, eps2=None,
            precision=None, seed=None, max_hf=UNSET, stopping=None, budget=None, strategy=None,
            study=None, batch_size=1, executor=None, callback=None, retry_failed=False,
            n_waves_convention="count") -> ScreeningResult:
    """Predict the MPM of an HF load with Probabilistic Adaptive Screening.

    Parameters
    ----------
    lf_peaks : array-like or pandas.DataFrame
        LF indicator peak of every wave event in the LF Monte-Carlo run; or a
        table, one row per event: the column ``lf`` (or its only column) the
        peaks, the column ``id`` (or else the index, unless it is the default
        ``0 … n-1``) the event ids, every other column the event's ``meta``
        (:func:`pas.study.inputs.split_lf_table`).
    oracle : callable
        ``oracle(event) -> float``: the HF peak of ``event`` (an
        :class:`~pas.strategies.screening.Event` with ``index``, ``id``, ``lf``, ``d``,
        ``meta``); 0.0 means no impact (a false positive).  An exception, NaN,
        inf or a negative value is recorded as a failure, never taken as 0.
        Or ``-> {name: float}``, several loads of one HF run
        (``pas.make_study(..., target=name)``).
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration
        (counted: at least the LF peaks over the threshold; for ``n_w = T_MCS
        / T_p,e`` on purpose use ``n_waves_convention="spectral"``).
    p_exp : float
        Target exceedance probability (:func:`pas.p_exp_from_duration`).
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    eps1 : float, optional
        Stopping limit on the mean change of the predicted distribution, in
        load units (the paper: about 1–2 % of the expected maximum); fills
        :class:`~pas.study.settings.Stopping`.  None: no limit of this kind.
        Not together with ``stopping``.
    eps2 : float, optional
        Stopping limit on the COV of the last ``k2`` MPMs (with ``eps1``);
        None: :class:`~pas.study.settings.Stopping`'s 0.1.  Not together with
        ``stopping``.
    precision : float, optional
        A precision target (e.g. 0.10): stop once the U95 of the MPM lies
        within ``±precision × MPM`` and holds the last ``k2`` MPMs, and the
        fitted model passes its fit check (``Stopping.fit_check``).  With
        ``eps1`` both must hold.  The result's ``forecast_hf`` says how many
        more HF evaluations the target is expected to need.  Not together
        with ``stopping``.
    seed : int, optional
        Seed for reproducible draws (reported on the result when None).
    max_hf : int or None, default 160
        The study stops after this many HF evaluations, converged or not
        (fills :class:`~pas.study.settings.Budget`; 160 is the most the paper
        needed).  Not given with ``strategy=PAS.paper()``: no budget, as the
        paper ran.  None: no budget.  Not together with ``budget``.
    stopping : Stopping, optional
        The whole stopping rule (``k1``, ``k2``, ``measure`` too); default
        ``Stopping()``, ``Stopping.paper()`` with ``strategy=PAS.paper()``.
    budget : Budget, optional
        ``Budget(max_hf=160, max_failures=10)``: more than ``max_failures``
        failed oracle calls raise :class:`~pas.study.oracles.OracleFailureLimit`.
    study : str or os.PathLike, optional
        SQLite study store (:mod:`pas.study.store`): created when missing,
        otherwise checked against this call and continued — no stored HF
        result is lost or re-run, and the run makes the decisions an
        uninterrupted one would have made (same ``batch_size``).  The
        stopping rule and the budget may change on a resumed study: no
        decision taken so far depends on them, so the continued run asks for
        the events an uninterrupted run with the new values would have asked
        for (a looser limit cannot undo evaluations already made).  Events a
        killed run left without a result run again
        (``pas.make_study(...).optimize(oracle, pending="wait")`` leaves them
        for ``pas study tell``).
    batch_size : int, default 1
        Events proposed per iteration.
    executor : concurrent.futures.Executor or int, optional
        Runs the oracle calls of a batch concurrently (e.g.
        ``distributed.Client(...).get_executor()``); results are stored as
        they arrive.  An int ``N``: a local pool of ``N`` processes (the oracle
        must be picklable).
    callback : callable, optional
        ``callback(study, row)`` after every HF result.
    retry_failed : bool, default False
        With ``study``: run the failed events of the stored study again (after
        fixing their cause), so it continues as if they had not failed
        (:meth:`Study.retry_failed <pas.study.study.Study.retry_failed>`).
    n_waves_convention : {"count", "spectral"}, default "count"
        How ``n_waves`` was obtained, as for :func:`make_study` (a validation
        case's ``run_kwargs()`` gives ``"spectral"``).
    strategy : PAS, optional
        The PAS settings (:class:`~pas.strategies.pas.PAS`): default
        ``PAS()``; ``PAS.paper()`` reproduces the paper's scripts (τ inversion
        for the Archimedean copulas, selected-sample space, redrawn uniforms,
        the sampling band, the step measure and no budget; the departures from
        the paper are listed on the docs page *Departures from the paper*).

    Returns
    -------
    ScreeningResult

    Raises
    ------
    OracleFailureLimit
        More than ``budget.max_failures`` oracle calls failed; ``.result``
        holds the result so far.
    TypeError
        A keyword of pas 0.1, naming its new place.

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
    return _run(PAS, locals())


@keywords_moved(MOVED, SETTINGS_PAGE)
def run_as(lf_peaks, oracle, *, n_waves, p_exp, threshold=None, eps1=None, eps2=None,
           precision=None, seed=None, max_hf=UNSET, stopping=None, budget=None, strategy=None,
           study=None, batch_size=1, executor=None, callback=None, retry_failed=False,
           n_waves_convention="count") -> ScreeningResult:
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
    lf_peaks : array-like or pandas.DataFrame
        LF indicator peak of every wave event in the LF Monte-Carlo run; or a
        table, one row per event: the column ``lf`` (or its only column) the
        peaks, the column ``id`` (or else the index, unless it is the default
        ``0 … n-1``) the event ids, every other column the event's ``meta``
        (:func:`pas.study.inputs.split_lf_table`).
    oracle : callable
        ``oracle(event) -> float``: the HF peak of ``event`` (an
        :class:`~pas.strategies.screening.Event` with ``index``, ``id``, ``lf``, ``d``,
        ``meta``); 0.0 means no impact (a false positive).  An exception, NaN,
        inf or a negative value is recorded as a failure, never taken as 0.
        Or ``-> {name: float}``, several loads of one HF run
        (``pas.make_study(..., target=name)``).
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration
        (counted: at least the LF peaks over the threshold; for ``n_w = T_MCS
        / T_p,e`` on purpose use ``n_waves_convention="spectral"``).
    p_exp : float
        Target exceedance probability (:func:`pas.p_exp_from_duration`).
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    eps1 : float, optional
        Stopping limit on the mean change of the predicted distribution, in
        load units (the paper: about 1–2 % of the expected maximum); fills
        :class:`~pas.study.settings.Stopping`.  None: no limit of this kind.
        Not together with ``stopping``.
    eps2 : float, optional
        Stopping limit on the COV of the last ``k2`` MPMs (with ``eps1``);
        None: :class:`~pas.study.settings.Stopping`'s 0.1.  Not together with
        ``stopping``.
    precision : float, optional
        A precision target (e.g. 0.10): stop once the U95 of the MPM lies
        within ``±precision × MPM`` and holds the last ``k2`` MPMs, and the
        fitted model passes its fit check (``Stopping.fit_check``).  With
        ``eps1`` both must hold.  The result's ``forecast_hf`` says how many
        more HF evaluations the target is expected to need.  Not together
        with ``stopping``.
    seed : int, optional
        Seed for reproducible draws (reported on the result when None).
    max_hf : int or None, default 160
        The study stops after this many HF evaluations, converged or not
        (fills :class:`~pas.study.settings.Budget`; 160 is the most the paper
        needed).  None: no budget.  Not together with ``budget``.
    stopping : Stopping, optional
        The whole stopping rule (``k1``, ``k2``, ``measure`` too); default
        ``Stopping()``.
    budget : Budget, optional
        ``Budget(max_hf=160, max_failures=10)``: more than ``max_failures``
        failed oracle calls raise :class:`~pas.study.oracles.OracleFailureLimit`.
    study : str or os.PathLike, optional
        SQLite study store (:mod:`pas.study.store`): created when missing,
        otherwise checked against this call and continued — no stored HF
        result is lost or re-run, and the run makes the decisions an
        uninterrupted one would have made (same ``batch_size``).  The
        stopping rule and the budget may change on a resumed study: no
        decision taken so far depends on them, so the continued run asks for
        the events an uninterrupted run with the new values would have asked
        for (a looser limit cannot undo evaluations already made).  Events a
        killed run left without a result run again
        (``pas.make_study(...).optimize(oracle, pending="wait")`` leaves them
        for ``pas study tell``).
    batch_size : int, default 1
        Events proposed per iteration.
    executor : concurrent.futures.Executor or int, optional
        Runs the oracle calls of a batch concurrently (e.g.
        ``distributed.Client(...).get_executor()``); results are stored as
        they arrive.  An int ``N``: a local pool of ``N`` processes (the oracle
        must be picklable).
    callback : callable, optional
        ``callback(study, row)`` after every HF result.
    retry_failed : bool, default False
        With ``study``: run the failed events of the stored study again (after
        fixing their cause), so it continues as if they had not failed
        (:meth:`Study.retry_failed <pas.study.study.Study.retry_failed>`).
    n_waves_convention : {"count", "spectral"}, default "count"
        How ``n_waves`` was obtained, as for :func:`make_study` (a validation
        case's ``run_kwargs()`` gives ``"spectral"``).
    strategy : AS, optional
        The AS settings (:class:`~pas.strategies.as_.AS`: ``fidelity``
        ``"multi"``/``"single"``, ``range_factor``, ``n_grid``, ``n_lf_bins``,
        ``n_restarts``); default ``AS()``.

    Returns
    -------
    ScreeningResult

    Raises
    ------
    OracleFailureLimit
        More than ``budget.max_failures`` oracle calls failed; ``.result``
        holds the result so far.
    TypeError
        A keyword of pas 0.1, naming its new place.

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
    return _run(AS, locals())


def _run(cls, given: dict) -> ScreeningResult:
    """:func:`run_pas` / :func:`run_as` with their arguments ``given``."""
    strategy = cls() if given["strategy"] is None else given["strategy"]
    if not isinstance(strategy, cls):
        raise TypeError(f"run_{cls.name}: strategy must be {cls.__name__}(...), "
                        f"got {strategy!r}")
    check_oracle(given["oracle"])  # before a study store is written
    check_retry(given["retry_failed"], given["study"])
    keys = ("n_waves", "p_exp", "threshold", "eps1", "eps2", "precision", "seed", "max_hf",
            "stopping", "budget", "n_waves_convention")
    built = _make_study(f"run_{cls.name}", strategy, given["lf_peaks"], store=given["study"],
                        stacklevel=5, **{k: given[k] for k in keys})
    if given["retry_failed"]:
        built.retry_failed()
    executor = given["executor"]
    n_workers = executor if isinstance(executor, int) and not isinstance(executor, bool) else None
    return built.optimize(given["oracle"], batch_size=given["batch_size"],
                          callback=given["callback"], n_workers=n_workers,
                          executor=None if n_workers is not None else executor)
