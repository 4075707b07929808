"""SIGTERM stops a run like Ctrl-C: every result kept, the partial result written.

A batch scheduler (Slurm, PBS, LSF) sends SIGTERM at a job's time limit, and
``kill`` sends it by default.  Python's default is to die at once, without
the partial result or the line that says how to resume.  Within
:func:`terminate_as_interrupt` SIGTERM raises :class:`Terminated`, a
:class:`KeyboardInterrupt`, so everything that handles Ctrl-C handles it too.
"""

from __future__ import annotations

import os
import signal
import threading
from contextlib import contextmanager

__all__ = ["Terminated", "terminate_as_interrupt", "EXIT_TERMINATED"]

#: Exit code after SIGTERM (128 + 15), what a shell reports for a process that signal killed.
EXIT_TERMINATED = 128 + signal.SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived (a scheduler's time limit, ``kill``); handled like Ctrl-C."""


_OWNER = [None]
"""The process that installed the handler: a forked worker dies of SIGTERM as by default."""


def _raise(signum, frame):
    if os.getpid() != _OWNER[0]:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)
        return
    raise Terminated("SIGTERM")


@contextmanager
def terminate_as_interrupt():
    """Within the block SIGTERM raises :class:`Terminated`; the former handler is restored after.

    Does nothing outside the main thread (signals reach only it) or when the
    program set its own SIGTERM handler.
    """
    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGTERM) not in (signal.SIG_DFL, None):
        yield
        return
    _OWNER[0] = os.getpid()
    signal.signal(signal.SIGTERM, _raise)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
