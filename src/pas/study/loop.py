"""The study loop: every campaign runs here, in this process or on any executor.

:func:`optimize` is the one loop behind :meth:`Study.optimize
<pas.study.study.Study.optimize>`, :func:`pas.run_pas`, ``pas run`` and
``pas study run``; like Optuna's ``_optimize_sequential`` it is a client of
:meth:`~pas.study.study.Study.ask` and :meth:`~pas.study.study.Study.tell`.
It asks the study for a batch of ``batch_size`` events (MD batch by
sequential fill) and hands them to the oracle — in this process one at a
time, in a local :class:`~concurrent.futures.ProcessPoolExecutor`
(``n_workers``) or on a cluster (a Dask ``distributed.Client(...).get_executor()``,
see ``docs/guide/cluster.md``).  With a study store each result is written the
moment it arrives (``as_completed``).  The study is *told* the results in ask
order, each as soon as all earlier events of its batch are in, so the
decisions do not depend on which worker finished first and a resumed run
repeats them exactly.

``tell`` only records; the loop alone enforces ``max_failures``: after each
told result it raises :class:`~pas.study.oracles.OracleFailureLimit` once more
calls failed.  In this process no further oracle call is made; calls already
running on an executor are waited for and their results stored first.

SIGTERM (what a batch scheduler sends at a job's time limit) stops a run
in the main thread like Ctrl-C: :class:`~pas.study.signals.Terminated`, a
:class:`KeyboardInterrupt`, is raised with every result stored.  When the
loop ends, however it ends, the store is checkpointed so that its
``.sqlite`` file alone holds the study.

Resume: events a killed run left pending are the first batch of the next
run.  Those whose result reached the store are told without calling the
oracle; the others are resubmitted (``pending="resubmit"``, the default) or
left for ``pas study tell`` / :meth:`Study.tell` (``pending="wait"``; their
results are picked up before each new ask).
"""

from __future__ import annotations

import atexit
import gc
import os
import pickle
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed

from .._support.checks import check_option, check_positive_int
from .._support.forked import end_with_parent
from .answers import lacks_target
from .command_oracle import CommandOracle
from .loads import answers_from_loads, record_loads
from .oracles import OracleFailureLimit, call_oracle_loads, check_oracle
from .signals import terminate_as_interrupt
from .state import EventState

__all__ = ["optimize", "run_batch", "execute", "check_command", "failure_limit",
           "PENDING_POLICIES"]

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
        (the table and command oracles are).
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
    TypeError
        ``oracle`` is not callable (checked before any call).
    ValueError
        A :class:`~pas.study.command_oracle.CommandOracle` that cannot run the
        study's events (:meth:`~pas.study.command_oracle.CommandOracle.check`).
    OracleFailureLimit
        When more than ``study.max_failures`` oracle calls failed, with the
        result so far.
    """
    check_oracle(oracle)
    check_command(oracle, [study])
    check_option(pending, "pending", PENDING_POLICIES)
    batch_size = check_positive_int(batch_size, "batch_size")
    own = None
    if executor is None and n_workers is not None:
        own = executor = ProcessPoolExecutor(check_positive_int(n_workers, "n_workers"),
                                             initializer=end_with_parent,
                                             initargs=(os.getpid(),))
    try:
        with terminate_as_interrupt():
            if isinstance(executor, ProcessPoolExecutor):
                _check_picklable(oracle)
            result = _Loop(study, oracle, executor, callback).run(batch_size, pending)
    except BaseException as exc:
        if own is not None:
            _abandon(own)
        _checkpoint(study)
        if isinstance(exc, KeyboardInterrupt):
            _exit_quickly()
        raise
    if own is not None:
        own.shutdown()
    _checkpoint(study)
    return result


def _checkpoint(study) -> None:
    """Move the run's writes into the study's ``.sqlite`` file (:meth:`StudyStore.checkpoint
    <pas.study.store.StudyStore.checkpoint>`), so that file alone holds the study."""
    if getattr(study, "store", None) is None:
        return
    try:
        study.store.checkpoint()
    except Exception:  # a busy or closed store: the results are stored all the same
        pass


def _exit_quickly() -> None:
    """After Ctrl-C: let the interpreter exit without its collections over the whole heap.

    Every result is stored when the interrupt propagates; what remains is the
    exit, whose collections over the objects numpy, scipy and pandas made can
    take seconds on a loaded machine.  Freezing the heap at exit skips
    them (a session that goes on, e.g. Jupyter, is not affected until it ends).
    """
    atexit.register(gc.freeze)


def _abandon(pool: ProcessPoolExecutor) -> None:
    """Stop our own process pool without waiting for running oracle calls (Ctrl-C, errors).

    Their events stay pending in the store and are resubmitted on resume; a
    :class:`~pas.study.command_oracle.CommandOracle` program runs in its own session
    and survives its worker, and the resumed call waits for it and reuses
    its result.
    """
    workers = list((getattr(pool, "_processes", None) or {}).values())  # shutdown forgets them
    manager = getattr(pool, "_executor_manager_thread", None)
    for proc in workers:
        proc.terminate()
    pool.shutdown(wait=False, cancel_futures=True)
    # the pool's manager thread sees its workers gone and closes its pipes; let it finish
    # now, or its clean-up can race the interpreter's exit and print an OSError traceback
    if manager is not None:
        manager.join(timeout=5.0)


def failure_limit(study) -> OracleFailureLimit | None:
    """The error to raise when ``study`` saw more failed oracle calls than it allows, else None.

    Its message ends with how to continue from Python; ``reason`` holds the
    message without that, for the command-line tools to add their own.  Its
    ``result`` is the partial result without the model band, as after Ctrl-C:
    the study stopped on a broken oracle, and the band's refits (tens of
    seconds) would only delay the message that says how to mend it.
    """
    if study.n_failed <= study.max_failures:
        return None
    last = next(r for r in reversed(study.rows) if r["status"] == EventState.FAILED)
    reason = (f"the HF oracle failed {study.n_failed} times (max_failures={study.max_failures}); "
              f"last error on event {last['event_id']}: {last['error']}")
    error = OracleFailureLimit(
        f"{reason}; fix the cause and retry the failed events (study.retry_failed() or "
        "run_pas(..., retry_failed=True) on the same study store), or raise max_failures",
        result=study.result(model_band=False))
    error.reason = reason
    return error


def _check_picklable(oracle) -> None:
    try:
        pickle.dumps(oracle)
    except Exception as exc:
        raise ValueError(f"oracle must be picklable to run in a process pool (use a module-level "
                         f"function, pas.TableOracle or pas.CommandOracle, not a lambda): "
                         f"{exc}") from None


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

    def _left_over(self, pending):
        """Events asked but not told when the loop starts, in ask order."""
        if self.store is None:
            return self.study.pending
        rows = self.store.outstanding()
        if pending == "wait":
            rows = [r for r in rows if r.has_result]
        return [self.study.lfset.event(self.study.lfset.position_of(r.idx)) for r in rows]

    def _absorb(self):
        """Tell results and replacements other processes stored meanwhile (arrival order)."""
        for waiting in self.store.unconsumed() if self.store is not None else ():
            if (failure := self._tell(self.study, int(waiting.idx), waiting.hf, waiting.error,
                                      replace=True)) is not None:
                raise failure

    def _run_batch(self, batch):
        run_batch([(self.study, batch)], self.oracle, self.executor, self._tell)

    def _tell(self, study, event, value, error, replace=False):
        """Tell one result; the failure limit's error when it is now exceeded."""
        row = study.tell(event, value, error=error, replace=replace)
        if self.callback is not None:
            self.callback(study, row)
        return failure_limit(study)


def run_batch(asks, oracle, executor, tell) -> None:
    """Run the events of ``asks`` (``[(study, events)]``), storing each result as it arrives
    and telling each study its results in ask order.

    A result already stored (a killed run's, or loads stored for want of a
    target) is taken without calling the oracle.  ``tell(study, event, value,
    error)`` tells one result and returns the failure limit's error when it is
    now exceeded; the first such error, or an error raised while telling, is
    raised once the calls already running are stored (in this process no
    further call is made).  Ctrl-C is not held back: running calls go on in
    their own sessions and a resumed run takes their results.
    """
    results, told = [], [0] * len(asks)
    for study, events in asks:
        stored = {}
        if study.store is not None:
            stored = {r.idx: (r.hf, r.error) for r in study.store.outstanding() if r.has_result}
            stored.update(answers_from_loads(
                study.store, [ev.index for ev in events if ev.index not in stored],
                study.target))
        results.append(stored)
    failure = None

    def tell_ready(k):
        nonlocal failure
        study, events = asks[k]
        while failure is None and told[k] < len(events) and events[told[k]].index in results[k]:
            ev = events[told[k]]
            told[k] += 1
            failure = tell(study, ev, *results[k][ev.index])

    for k in range(len(asks)):
        tell_ready(k)
    todo = [(k, ev) for k, (_, events) in enumerate(asks) for ev in events
            if ev.index not in results[k]]
    if failure is None and todo:
        targets = {asks[k][0].target for k, _ in todo}
        if len(targets) > 1:  # before any event is marked as submitted
            raise ValueError(f"one batch of studies screening different loads {sorted(targets)}")
        for k in dict.fromkeys(k for k, _ in todo):
            if asks[k][0].store is not None:
                asks[k][0].store.mark_submitted([ev for j, ev in todo if j == k])
        where = {id(ev): k for k, ev in todo}
        error = None  # an error while telling: the results still arriving are stored first
        for ev, (value, error_text, loads) in execute(oracle, [ev for _, ev in todo],
                                                      targets.pop(), executor):
            k = where[id(ev)]
            study = asks[k][0]
            if lacks_target(loads, study.target):
                error = error or _loads_kept_for_target(study, ev, loads, error_text)
            else:
                if study.store is not None:
                    study.store.record_result(ev, value, error_text, loads=loads)
                results[k][ev.index] = (value, error_text)
                if error is None:
                    try:
                        tell_ready(k)
                    except Exception as exc:  # noqa: BLE001 - raised below, once stored
                        error = exc
            if (failure is not None or error is not None) and executor is None:
                break  # in this process: no oracle call after the limit or an error
        if error is not None:
            raise error
    if failure is not None:
        raise failure


def _loads_kept_for_target(study, event, loads, error) -> ValueError:
    """An answer of several loads and no target: keep its loads; the error that stops the run
    before the next call.

    The event stays pending; rerun with the target and its stored loads give its
    result (:func:`pas.study.loads.adopt_target`), no HF run is repeated.
    """
    where = ""
    if study.store is not None:
        record_loads(study.store, event, loads)
        where = f"; its loads are kept in {study.store.path}, rerun with the target to use them"
    return ValueError(f"event {event.id}: {error}{where}")


def check_command(oracle, studies) -> None:
    """Refuse a :class:`~pas.study.command_oracle.CommandOracle` that cannot run these studies'
    events (a typo'd placeholder, a missing script) before any event runs, unless none of
    them has anything left to run (a finished study reopened to read it)."""
    live = [st for st in studies if st is not None and (st.pending or not st.finished)]
    if live and isinstance(oracle, CommandOracle):
        oracle.check(live[0].lfset.event(0))


def execute(oracle, events, target=None, executor: Executor | None = None):
    """Yield ``(event, (value, error, loads))`` as the oracle calls of ``events`` finish.

    In this process one after another without ``executor``, else all
    submitted at once; a call the executor could not run is a failure.
    """
    if executor is None:
        for ev in events:
            yield ev, call_oracle_loads(oracle, ev, target)
        return
    futures = {executor.submit(call_oracle_loads, oracle, ev, target): ev for ev in events}
    for fut in as_completed(futures):
        try:
            out = fut.result()
        except Exception as exc:  # the worker died or the call could not be shipped
            out = (None, f"executor: {type(exc).__name__}: {exc}", None)
        yield futures[fut], out
