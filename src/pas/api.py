"""The two entry points users call: :func:`run_pas` and :func:`run_as`."""

from __future__ import annotations

import textwrap

from .screening import LFSet
from .strategies.as_ import AS
from .strategies.pas import PAS
from .study.result import ScreeningResult
from .study.study import Study

__all__ = ["run_pas", "run_as", "make_study"]

_STUDY_SETTINGS = ("k1", "k2", "max_failures", "stop_on_convergence", "adaptive_threshold",
                   "threshold_step", "fp_run")


def make_study(strategy, lf_peaks, *, n_waves, p_exp, eps1, eps2=0.1, threshold=None,
               seed=None, max_hf=None, ids=None, meta=None, store=None, **settings) -> Study:
    """Validate the inputs and build a :class:`~pas.study.study.Study` for ``strategy``.

    ``strategy`` is a class (built with the strategy settings found in
    ``settings``) or an instance.  Unknown settings raise ``ValueError``.
    ``store`` (a path or :class:`~pas.study.store.StudyStore`) makes the study
    crash-safe and resumable; with ``seed=None`` an existing store's seed is used.
    """
    if store is not None and seed is None:
        from .study.store import StudyStore, read_settings
        stored = store.settings() if isinstance(store, StudyStore) else read_settings(store)
        seed = stored.get("seed")
    study_kw = {k: settings.pop(k) for k in _STUDY_SETTINGS if k in settings}
    if isinstance(strategy, type):
        try:
            strategy = strategy(**settings)
        except TypeError as exc:
            raise ValueError(f"unknown setting for {strategy.__name__}: {exc}") from None
    elif settings:
        raise ValueError(f"unknown settings {sorted(settings)}")
    lfset = LFSet(lf_peaks, n_waves=n_waves, p_exp=p_exp, threshold=threshold, ids=ids,
                  meta=meta, min_peaks=max(4, strategy.n_initial))
    return Study(lfset, strategy, eps1=eps1, eps2=eps2, seed=seed, max_hf=max_hf, store=store,
                 **study_kw)


_PARAMETERS = """\
lf_peaks : array-like, shape (n_events,)
    LF indicator peak of every wave event in the LF Monte-Carlo run.
oracle : callable
    ``oracle(event) -> float``: the HF peak of ``event`` (an
    :class:`~pas.screening.Event` with ``index``, ``id``, ``lf``, ``d``,
    ``meta``); 0.0 means no impact (a false positive).  An exception, NaN,
    inf or a negative value is recorded as a failure, never taken as 0.
n_waves : int
    Number of wave encounters ``n_w`` in the LF Monte-Carlo duration.
p_exp : float
    Target exceedance probability (:func:`pas.p_exp_from_duration`).
eps1 : float
    Stopping limit on the mean change of the predicted distribution,
    in load units (paper: ≈ 1–2 % of the expected maximum).
eps2 : float, default 0.1
    Stopping limit on the COV of the last K2 MPMs.
threshold : float, optional
    LF threshold ``l0_input`` (Eq. 2).
seed : int, optional
    Seed for reproducible {seeded} (reported on the result when None).
max_hf : int, optional
    Budget of HF evaluations{max_hf}.
ids, meta : sequence, optional
    User ids / metadata per event, passed to the oracle on the event.
batch_size : int, default 1
    Events proposed per iteration{batch}.
callback : callable, optional
    ``callback(study, row)`` after every HF result.
study : str or os.PathLike, optional
    SQLite study store (:mod:`pas.study.store`): created when missing,
    otherwise checked against this call and continued — no stored HF
    result is lost or re-run, and the run makes the decisions an
    uninterrupted one would have made (same ``batch_size``).
pending : {{"resubmit", "wait"}}, default "resubmit"
    Events a killed run left without a result: run them again, or leave
    them for ``pas study tell``.
executor : concurrent.futures.Executor, optional
    Runs the oracle calls of a batch concurrently (e.g.
    ``distributed.Client(...).get_executor()``); results are stored as
    they arrive.
n_workers : int, optional
    Without ``executor``: a local process pool of this size (the oracle
    must be picklable).
**settings
    Strategy settings ({settings}) and study settings (``k1``, ``k2``,
    ``max_failures``, ``stop_on_convergence``, ``adaptive_threshold``,
    ``threshold_step``, ``fp_run``).
"""
"""The parameters :func:`run_pas` and :func:`run_as` share, written once; :func:`_documented`
fills in what differs."""


def _documented(**fields):
    """Put :data:`_PARAMETERS`, formatted with ``fields``, at ``{parameters}`` in the docstring.

    A field of several lines continues at the indentation of a description.
    """
    fields = {k: v.replace("\n", "\n    ") for k, v in fields.items()}
    text = textwrap.indent(_PARAMETERS.format(**fields), "    ")

    def decorate(fn):
        if fn.__doc__:  # None under python -OO
            fn.__doc__ = fn.__doc__.replace("    {parameters}\n", text)
        return fn
    return decorate


def _run(strategy, lf_peaks, oracle, *, study, batch_size, callback, pending, executor,
         n_workers, settings, **study_kw) -> ScreeningResult:
    """The body of :func:`run_pas` and :func:`run_as`: build the study, then optimise it."""
    built = make_study(strategy, lf_peaks, store=study, **study_kw, **settings)
    return built.optimize(oracle, batch_size=batch_size, callback=callback, executor=executor,
                          n_workers=n_workers, pending=pending)


@_documented(seeded="draws", max_hf="", batch="", settings="""\
:class:`~pas.strategies.pas.PAS`: ``families``,
``z``, ``delta_aic``, ``exclude_at_bound``, ``upper_tail``,
``outlier_k``, ``n_bootstrap``, ``skip_unsplittable``, ``marginals_from``,
``impact_model``""")
def run_pas(lf_peaks, oracle, *, n_waves, p_exp, eps1, eps2=0.1, threshold=None, seed=None,
            max_hf=None, ids=None, meta=None, batch_size=1, callback=None, study=None,
            pending="resubmit", executor=None, n_workers=None, **settings) -> ScreeningResult:
    """Predict the MPM of an HF load with Probabilistic Adaptive Screening.

    Parameters
    ----------
    {parameters}

    Returns
    -------
    ScreeningResult

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
    return _run(PAS, **locals())  # locals() is exactly the parameters here


@_documented(seeded="runs", max_hf=" (at least 2)", batch=" (the next-best MVPD targets)",
             settings="""\
:class:`~pas.strategies.as_.AS`: ``fidelity``
``"multi"``/``"single"``, ``range_factor``, ``n_grid``,
``n_lf_bins``, ``n_restarts``""")
def run_as(lf_peaks, oracle, *, n_waves, p_exp, eps1, eps2=0.1, threshold=None, seed=None,
           max_hf=None, ids=None, meta=None, batch_size=1, callback=None, study=None,
           pending="resubmit", executor=None, n_workers=None, **settings) -> ScreeningResult:
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
    {parameters}

    Returns
    -------
    ScreeningResult

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
    return _run(AS, **locals())  # locals() is exactly the parameters here
