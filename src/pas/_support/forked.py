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
killed) is an error the caller can catch.
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor

__all__ = ["forked_pool", "forked_executor", "forked_call"]

_task = None  # (fn, job) in a worker of forked_pool / forked_executor; never set in the parent


def _install(fn, job) -> None:
    global _task
    _task = (fn, job)


def forked_call(item):
    """``fn(job, item)`` in a worker of :func:`forked_pool` or :func:`forked_executor`."""
    fn, job = _task
    return fn(job, item)


def forked_pool(processes: int, fn, job):
    """A :class:`multiprocessing.pool.Pool` of ``processes`` forked workers in which
    :func:`forked_call` runs ``fn(job, item)``."""
    return multiprocessing.get_context("fork").Pool(processes, initializer=_install,
                                                    initargs=(fn, job))


def forked_executor(processes: int, fn, job) -> ProcessPoolExecutor:
    """:func:`forked_pool` as a :class:`~concurrent.futures.ProcessPoolExecutor`."""
    return ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("fork"),
                               initializer=_install, initargs=(fn, job))
