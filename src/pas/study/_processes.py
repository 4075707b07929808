"""Process calls that exist on POSIX only, each with its fallback elsewhere (Windows).

:class:`~pas.study.command_oracle.CommandOracle` locks an event's folder, starts its
program where Ctrl-C does not reach it and kills it on a time-out.  ``fcntl``,
``os.setsid`` and ``os.killpg`` are looked up when used, so ``import pas`` and
every study run where they do not exist.
"""

from __future__ import annotations

import os
import subprocess

__all__ = ["OWN_SESSION", "try_lock", "kill_group"]

# POSIX: a session of its own; Windows: a process group of its own (Ctrl-C stays with us).
OWN_SESSION = ({"start_new_session": True} if hasattr(os, "setsid") else
               {"creationflags": getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0)})
"""Keyword arguments of :class:`subprocess.Popen` that keep the driver's Ctrl-C from the program."""


def try_lock(fd):
    """Lock ``fd`` without waiting: ``"flock"`` or ``"msvcrt"`` when taken, False when
    another process holds it, None where neither module exists (no lock)."""
    try:
        import fcntl
    except ImportError:
        pass
    else:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return False
        return "flock"
    try:
        import msvcrt
    except ImportError:
        return None
    try:
        msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
    except OSError:
        return False
    return "msvcrt"


def kill_group(proc) -> None:
    """Kill the program and, where process groups can be signalled (POSIX), its children."""
    import signal

    killpg = getattr(os, "killpg", None)
    if killpg is None or not hasattr(signal, "SIGKILL"):
        proc.kill()
        return
    try:
        killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass  # the group is gone: the program has already ended
