"""Forked worker processes that share one large job without pickling it.

A model band refits a study's model to many resampled pair sets; each
worker needs the strategy, the pairs and the LF pool (up to 10⁶ peaks).  A
forked worker starts with a copy of its parent's memory, so the job is
handed to it as an argument of the pool's initializer, which a fork does not
pickle, and every task calls ``fn(job, item)``.  Only the item and the
answer cross the pipe.

    with forked_pool(2, fit_one, job) as pool:
        answers = pool.map(forked_call, items)

:func:`forked_executor` is the same for a
:class:`concurrent.futures.ProcessPoolExecutor`, whose broken pool (a worker
killed) is an error the caller can catch.  Their workers, and those of any pool
started with :func:`end_with_parent` as initializer, end when the process that
started them is killed.
"""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

__all__ = ["forked_pool", "forked_executor", "forked_call", "end_with_parent"]

_task = None  # (fn, job) in a worker of forked_pool / forked_executor; never set in the parent


def _install(fn, job, parent: int) -> None:
    global _task
    _task = (fn, job)
    end_with_parent(parent)


def forked_call(item):
    """``fn(job, item)`` in a worker of :func:`forked_pool` or :func:`forked_executor`."""
    fn, job = _task
    return fn(job, item)


def forked_pool(processes: int, fn, job):
    """A :class:`multiprocessing.pool.Pool` of ``processes`` forked workers in which
    :func:`forked_call` runs ``fn(job, item)``."""
    return multiprocessing.get_context("fork").Pool(processes, initializer=_install,
                                                    initargs=(fn, job, os.getpid()))


def forked_executor(processes: int, fn, job) -> ProcessPoolExecutor:
    """:func:`forked_pool` as a :class:`~concurrent.futures.ProcessPoolExecutor`."""
    return ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("fork"),
                               initializer=_install, initargs=(fn, job, os.getpid()))


def end_with_parent(parent: int, every: float = 0.5) -> None:
    """In a worker process: exit once ``parent`` is no longer its parent.

    A pool's worker waits for work from the process that started it; when
    that process is killed (``kill -9``, an out-of-memory kill) the worker is
    handed to ``init`` and would wait for ever.  Run as the pool's
    initializer, a daemon thread checks the parent every ``every`` seconds and
    ends the worker then.  An HF program the worker started runs in its own
    session and goes on; a resumed run waits for it
    (:mod:`pas.study.hf_programs`).
    """
    import threading
    import time

    def watch():
        while os.getppid() == parent:
            time.sleep(every)
        os._exit(1)

    threading.Thread(target=watch, name="pas-end-with-parent", daemon=True).start()
