"""Who runs an HF program: the lock of an event's folder, and ending programs left running.

:class:`~pas.study.command_oracle.CommandOracle` runs each event's program in
``root/<event>`` under an ``flock`` on ``root/<event>/.lock``, which the program
inherits.  While it runs, the lock file names its *holder* (:func:`holder`):
the program's PID (also its process group: it runs in a session of its own),
the PID of the ``pas`` process that started it and of that one's parent (a
worker's driver), the host, the start time and the program's own time-out.
That is what a resumed run, ``pas study hf-programs`` and ``pas study
hf-stop`` read:

* a lock that can be taken is free, whatever it names (its program ended, or
  the run that started it was killed before clearing it): it is taken over;
* a held lock whose holder is on this host is a live program: it is waited
  for until its own time-out counted from its start, then ended (its process
  group: ``SIGTERM``, then ``SIGKILL`` after :data:`GRACE` seconds);
* a held lock of another host's program (a shared file system) cannot be
  checked or ended from here: the message says so and names the host.

An interrupted run (Ctrl-C, or a termination signal that the command line
turns into the same stop) ends the programs it started (:func:`end_programs`)
and says which: a CFD program that nobody waits for would hold its licence
and cores for up to its time-out.
"""

from __future__ import annotations

import json
import os
import socket
import time

from ._processes import try_lock

__all__ = ["LOCK", "GRACE", "holder", "write_holder", "clear_holder", "read_holder",
           "held_by", "running", "end_group", "end_programs", "describe", "ENDED"]

LOCK = ".lock"
"""The lock file of an event's working directory."""

GRACE = 5.0
"""Seconds an ended program's group is given after ``SIGTERM`` before ``SIGKILL``."""

ENDED: list[dict] = []
"""Holders of the programs this process ended on an interrupt, for the stop message."""


def holder(pid: int | None, *, event, timeout: float | None, program: str = "") -> dict:
    """The record of a program ``pid`` (None: not started yet) run for ``event`` now."""
    now = time.time()
    return {"pid": pid, "run_pid": os.getpid(), "parent_pid": os.getppid(),
            "host": socket.gethostname(), "started": now,
            "started_at": time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(now)),
            "timeout": timeout, "event": str(event), "program": program}


def write_holder(fd: int, record: dict) -> None:
    """Write ``record`` into the lock file ``fd`` (held by this process)."""
    data = json.dumps(record).encode()
    os.ftruncate(fd, 0)
    os.lseek(fd, 0, os.SEEK_SET)
    os.write(fd, data)


def clear_holder(fd: int) -> None:
    """Empty the lock file: its program ended and this run saw it end."""
    try:
        os.ftruncate(fd, 0)
    except OSError:
        pass


def read_holder(path: str) -> dict | None:
    """The holder recorded in the lock file ``path``; None when it is empty or unreadable."""
    try:
        with open(path, encoding="utf-8") as f:
            record = json.loads(f.read() or "null")
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) else None


def held_by(path: str):
    """``(held, holder)`` for the lock file ``path``: whether a process holds its lock now,
    and the holder it records (None when none)."""
    try:
        fd = os.open(path, os.O_RDWR)
    except OSError:
        return False, None
    try:
        record = read_holder(path)
        taken = try_lock(fd)
        return taken is False, record
    finally:
        os.close(fd)  # closing releases a lock taken just to look


def on_this_host(record: dict) -> bool:
    return record.get("host") == socket.gethostname()


def deadline(record: dict | None) -> float | None:
    """When the holder's program passes its own time-out (epoch seconds); None without one."""
    if not record or not record.get("timeout") or not record.get("started"):
        return None
    return float(record["started"]) + float(record["timeout"])


def running(root: str) -> list[dict]:
    """The programs running now in the event folders under ``root``: their holders, each
    with ``workdir``, the folder (``pid`` None while the program is being started)."""
    out = []
    for folder, dirs, files in os.walk(root):
        dirs.sort()
        if LOCK not in files:
            continue
        dirs[:] = []  # an event's folder: its program's case files hold no other lock
        held, record = held_by(os.path.join(folder, LOCK))
        if held:
            out.append({**(record or {}), "workdir": folder})
    return out


def end_group(record: dict, *, grace: float = GRACE) -> str | None:
    """End the holder's program and its children: ``SIGTERM`` to its process group, then
    ``SIGKILL`` if it is still there after ``grace`` seconds.  None when ended (or gone),
    else why it cannot be ended from here."""
    import signal

    pid = record.get("pid")
    if not pid:
        return "its program is still being started"
    if not on_this_host(record):
        return (f"it runs on host {record.get('host')}, which cannot be checked from here: "
                "stop it there")
    killpg = getattr(os, "killpg", None)
    if killpg is None:
        return "process groups cannot be signalled on this system: end it by hand"
    try:
        killpg(int(pid), signal.SIGTERM)
    except ProcessLookupError:
        return None
    except PermissionError:
        return f"process group {pid} belongs to another user"
    stop = time.monotonic() + grace
    while time.monotonic() < stop:
        if not _group_alive(int(pid)):
            return None
        time.sleep(0.05)
    try:
        killpg(int(pid), signal.SIGKILL)
    except ProcessLookupError:
        pass
    return None


def _group_alive(pgid: int) -> bool:
    """Whether a process of group ``pgid`` still runs: one that has exited but that its
    parent has not reaped yet (a zombie, holding no file and no licence) does not count."""
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    if not os.path.isdir("/proc/self"):
        return True
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if len(fields) > 2 and fields[2] == str(pgid) and fields[0] != "Z":
            return True
    return False


def end_programs(root: str | None, *, grace: float = GRACE) -> list[dict]:
    """End the programs under ``root`` that this process (or its workers) started and that
    still run; returns their holders with those :data:`ENDED` before, and empties that list."""
    mine = {os.getpid()}
    ended = list(ENDED)
    ENDED.clear()
    for record in running(root) if root and os.path.isdir(root) else []:
        if on_this_host(record) and mine & {record.get("run_pid"), record.get("parent_pid")}:
            if end_group(record, grace=grace) is None:
                ended.append(record)
    return ended


def describe(record: dict, *, now: float | None = None) -> str:
    """``event E: PID P, on host H, started T (S s ago), time-out X s, run by pas PID R``."""
    now = time.time() if now is None else now
    parts = [f"event {record.get('event', '?')}: "
             + (f"PID {record['pid']}" if record.get("pid") else "starting")]
    if record.get("host") and not on_this_host(record):
        parts.append(f"on host {record['host']}")
    if record.get("started"):
        parts.append(f"started {record.get('started_at')} ({now - record['started']:.0f} s ago)")
    timeout = record.get("timeout")
    parts.append(f"time-out {timeout:g} s" if timeout else "no time-out")
    if record.get("run_pid"):
        parts.append(f"run by pas PID {record['run_pid']}")
    return ", ".join(parts)
