"""The study loop: every campaign runs here, in this process or on any executor.

:func:`optimize` is the one loop behind :meth:`Study.optimize
<pas.study.study.Study.optimize>`, :func:`pas.run_pas`, ``pas run`` and
``pas study run``; like Optuna's ``_optimize_sequential`` it is a client of
:meth:`~pas.study.study.Study.ask` and :meth:`~pas.study.study.Study.tell`.
It asks the study for a batch of ``batch_size`` events (MD batch by
sequential fill) and hands them to the oracle — in this process one at a
time, in a local :class:`~concurrent.futures.ProcessPoolExecutor`
(``n_workers``) or on a cluster (a Dask ``distributed.Client(...).get_executor()``,
see ``docs/cluster.md``).  With a study store each result is written the
moment it arrives (``as_completed``).  The study is *told* the results in ask
order, each as soon as all earlier events of its batch are in, so the
decisions do not depend on which worker finished first and a resumed run
repeats them exactly.

``tell`` only records; the loop alone enforces ``max_failures``: after each
told result it raises :class:`~pas.study.oracles.OracleFailureLimit` once more
calls failed.  In this process no further oracle call is made; calls already
running on an executor are waited for and their results stored first.

Resume: events a killed run left pending are the first batch of the next
run.  Those whose result reached the store are told without calling the
oracle; the others are resubmitted (``pending="resubmit"``, the default) or
left for ``pas study tell`` / :meth:`Study.tell` (``pending="wait"``; their
results are picked up before each new ask).
"""

from __future__ import annotations

import pickle
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed

from .._validation import check_option, check_positive_int
from .oracles import OracleFailureLimit, call_oracle
from .state import EventState

__all__ = ["optimize", "PENDING_POLICIES"]

PENDING_POLICIES = ("resubmit", "wait")


def optimize(study, oracle, *, batch_size: int = 1, executor: Executor | None = None,
             n_workers: int | None = None, pending: str = "resubmit", callback=None):
    """Run ``study`` to the end with ``oracle``, storing every result as it arrives.

    Parameters
    ----------
    study : Study
        The study, with or without a store (:mod:`pas.study.store`).
    oracle : callable
        ``oracle(event) -> float``; must be picklable for a process pool
        (the oracles of :mod:`pas.study.oracles` are).
    batch_size : int, default 1
        Events per ask (``q``); all of a batch run concurrently.
    executor : concurrent.futures.Executor, optional
        Where oracle calls run; default: in this process, one at a time.
    n_workers : int, optional
        Without ``executor``: run in a local process pool of this size.
    pending : {"resubmit", "wait"}
        What to do with events a killed run left without a result.
    callback : callable, optional
        ``callback(study, row)`` after every told result.

    Returns
    -------
    ScreeningResult

    Raises
    ------
    OracleFailureLimit
        When more than ``study.max_failures`` oracle calls failed, with the
        result so far.
    """
    check_option(pending, "pending", PENDING_POLICIES)
    batch_size = check_positive_int(batch_size, "batch_size")
    if not callable(oracle):
        raise ValueError(f"oracle must be a callable oracle(event) -> float, got {oracle!r}")
    own = None
    if executor is None and n_workers is not None:
        own = executor = ProcessPoolExecutor(check_positive_int(n_workers, "n_workers"))
    try:
        if isinstance(executor, ProcessPoolExecutor):
            _check_picklable(oracle)
        result = _Loop(study, oracle, executor, callback).run(batch_size, pending)
    except BaseException:
        if own is not None:
            _abandon(own)
        raise
    if own is not None:
        own.shutdown()
    return result


def _abandon(pool: ProcessPoolExecutor) -> None:
    """Stop our own process pool without waiting for running oracle calls (Ctrl-C, errors).

    Their events stay pending in the store and are resubmitted on resume; a
    :class:`~pas.study.oracles.CommandOracle` program runs in its own session
    and survives its worker, and the resumed call waits for it and reuses
    its result.
    """
    workers = list((getattr(pool, "_processes", None) or {}).values())  # shutdown forgets them
    for proc in workers:
        proc.terminate()
    pool.shutdown(wait=False, cancel_futures=True)


def failure_limit(study) -> OracleFailureLimit | None:
    """The error to raise when ``study`` saw more failed oracle calls than it allows, else None."""
    if study.n_failed <= study.max_failures:
        return None
    last = next(r for r in reversed(study.rows) if r["status"] == EventState.FAILED)
    return OracleFailureLimit(
        f"the HF oracle failed {study.n_failed} times (max_failures={study.max_failures}); "
        f"last error on event {last['event_id']}: {last['error']}", result=study.result())


def _check_picklable(oracle) -> None:
    try:
        pickle.dumps(oracle)
    except Exception as exc:
        raise ValueError(f"oracle must be picklable to run in a process pool (use a module-level "
                         f"function or a pas.study.oracles oracle, not a lambda): {exc}") from None


class _Loop:
    def __init__(self, study, oracle, executor, callback):
        self.study, self.oracle, self.executor, self.callback = study, oracle, executor, callback
        self.store = study.store

    def run(self, batch_size: int, pending: str):
        study = self.study
        if (failure := failure_limit(study)) is not None:  # resumed past the limit
            raise failure
        batch = self._left_over(pending)
        while True:
            if not batch:
                self._absorb()
                batch = study.ask(batch_size)
                if not batch:
                    break
            self._run_batch(batch)
            batch = []
        return study.result()

    def _tell(self, event, value, error):
        """Tell one result; the failure limit's error when it is now exceeded."""
        row = self.study.tell(event, value, error=error)
        if self.callback is not None:
            self.callback(self.study, row)
        return failure_limit(self.study)

    def _left_over(self, pending):
        """Events asked but not told when the loop starts, in ask order."""
        if self.store is None:
            return self.study.pending
        rows = self.store.outstanding()
        if pending == "wait":
            rows = [r for r in rows if r[3]]
        return [self.study.lfset.event(self.study.lfset.position_of(r[0])) for r in rows]

    def _absorb(self):
        """Tell results that other processes stored for waiting events (arrival order)."""
        for idx, hf, err in self.store.unconsumed() if self.store is not None else ():
            if (failure := self._tell(int(idx), hf, err)) is not None:
                raise failure

    def _run_batch(self, batch):
        store = self.store
        results = {}
        if store is not None:
            results = {r[0]: (r[1], r[2]) for r in store.outstanding() if r[3]}
        told, failure = 0, None

        def tell_ready():
            nonlocal told, failure
            while failure is None and told < len(batch) and batch[told].index in results:
                ev = batch[told]
                told += 1
                failure = self._tell(ev, *results[ev.index])

        tell_ready()
        todo = [ev for ev in batch if ev.index not in results]
        if failure is None and todo:
            if store is not None:
                store.mark_submitted(todo)
            for ev, (value, error) in self._execute(todo):
                if store is not None:
                    store.record_result(ev, value, error)
                results[ev.index] = (value, error)
                tell_ready()
                if failure is not None and self.executor is None:
                    break  # in this process: no oracle call after the limit
        if failure is not None:
            raise failure

    def _execute(self, events):
        """Yield ``(event, (value, error))`` as the oracle calls finish."""
        if self.executor is None:
            for ev in events:
                yield ev, call_oracle(self.oracle, ev)
            return
        futures = {self.executor.submit(call_oracle, self.oracle, ev): ev for ev in events}
        for fut in as_completed(futures):
            try:
                out = fut.result()
            except Exception as exc:  # the worker died or the call could not be shipped
                out = (None, f"executor: {type(exc).__name__}: {exc}")
            yield futures[fut], out
