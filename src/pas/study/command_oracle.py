"""The command oracle: an external program per HF event, in a working directory of its own.

:class:`CommandOracle` fills the event's fields into an argument list, runs the
program in ``root/<event>`` (:mod:`pas.study.workdirs`), never via a shell, and
reads the HF peak it writes to ``{result}`` (:func:`parse_result`).  The folder
records the command (:func:`pas.study.workdirs.command_record`), so a result is
reused only for the same one.  The argument list itself — its placeholders, its
relative paths, the result file's text — is :mod:`pas.study.command_template`'s.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import time
import warnings

import numpy as np

from ._processes import OWN_SESSION, kill_group, try_lock
from .command_template import filled, missing_script, parse_result, resolve_paths, runs_script
from .hf_programs import (
    ENDED,
    LOCK,
    clear_holder,
    deadline,
    describe,
    end_group,
    holder,
    read_holder,
    write_holder,
)
from .oracles import OracleError
from .workdirs import command_record, event_dir, read_record, write_record

__all__ = ["CommandOracle", "parse_result", "resolve_paths"]


def _reusable(answer) -> bool:
    """True for a result left by an earlier run that may be taken instead of running again."""
    return isinstance(answer, dict) or (answer is not None and np.isfinite(answer) and answer >= 0)


class CommandOracle:
    """Run an external program per event (a CFD case, a post-processor), never via a shell.

    Parameters
    ----------
    args : sequence of str
        Argument-list template, e.g. ``["python", "cfd.py", "--event", "{id}",
        "--lf", "{lf}", "--out", "{result}"]``.  Placeholders: ``{id}``,
        ``{index}``, ``{lf}``, ``{d}``, ``{sea_state}`` (long-term analysis),
        ``{workdir}``, ``{result}``,
        ``{cwd}`` and every key of the event's ``meta`` (``{seed}``,
        ``{t_start}`` …).  For a design-wave
        :class:`~pas.waves.episode.Episode` (:func:`pas.run_rcw`) also
        ``{episode}`` and ``{components}``: CSV files of the episode's time
        series and wave components, written into the working directory, and
        its ``{level}``, ``{target}`` and ``{t0}``.
    root : str or os.PathLike
        Each event runs in its own working directory ``root/<event id>``
        (``root/<sea state>/<event id>`` in a long-term analysis), with
        ``stdout.log`` and ``stderr.log``; relative to ``cwd``.
    cwd : str or os.PathLike, optional
        The directory the campaign is started from (default: the current
        one when the oracle is made): relative paths in ``args`` and
        ``root`` mean paths there, not in the working directory
        (:func:`resolve_paths` says which arguments are taken as paths).
        It is stored in the oracle, so a Dask worker or a resumed run in
        another folder runs the same files; ``{cwd}`` gives it.
    timeout : float, optional
        Seconds before the program (and its process group) is killed.
    result_name : str, default "result.txt"
        File the program writes its HF peak to (plain number, JSON number or
        ``{"value": x}``, or a JSON object of named loads, :func:`parse_result`),
        relative to the working directory.
    env : dict, optional
        Extra environment variables.
    reuse : bool, default True
        Take a valid result file left by an earlier run of the same command
        (e.g. the driver was killed after the program finished) instead of
        running it again, with a warning that says so.  The argument list of
        every run (and a digest of an episode's input files) is recorded in
        its working directory (:mod:`pas.study.workdirs`): a result left by
        another command — a second study run into the same ``root``, or a
        command changed since — is an :class:`OracleError` naming the folder,
        never taken, whatever ``reuse`` says.
    on_interrupt : {"end", "leave"}, default "end"
        What Ctrl-C (or a termination signal turned into the same stop) does
        to a program waited for: ``"end"`` ends its process group
        (``SIGTERM``, then ``SIGKILL``; :mod:`pas.study.hf_programs`) and the
        event runs again on resume; ``"leave"`` leaves it running, and a
        resumed run waits for it and reuses its result.

    Notes
    -----
    A non-zero exit status, a time-out, a missing or unreadable result file
    raise :class:`OracleError` (recorded as a failed event, never as 0), and
    so does a relative script argument (``cfd.py``, ``../hf/run.sh``) missing
    from ``cwd``, naming the path it was looked for; the script of an
    interpreter (``python3 cfd.py``) and the placeholders are checked before
    any event runs (:meth:`check`).
    While the program runs it holds an ``flock`` on ``root/<id>/.lock``
    (inherited by the program), which records the program's PID, the ``pas``
    process, host, start and time-out (:mod:`pas.study.hf_programs`).  A
    resumed driver that finds the lock held waits for that program until its
    own time-out counted from its start (and reuses its result), then ends
    it and runs the event again; a lock no process holds is taken over.  The
    program runs in a session (POSIX) or process group (Windows) of its own,
    so the terminal's Ctrl-C reaches only the driver, which then decides
    (``on_interrupt``).  Where ``fcntl`` is missing (Windows) the lock is an
    ``msvcrt`` lock held by the driver only, so it does not cover an
    orphaned program.
    """

    def __init__(self, args, *, root, cwd=None, timeout: float | None = None,
                 result_name: str = "result.txt", env: dict | None = None, reuse: bool = True,
                 on_interrupt: str = "end"):
        if isinstance(args, (str, bytes)) or not all(isinstance(a, str) for a in args) or not args:
            raise ValueError("args must be a non-empty list of strings (an argument list, "
                             "not a shell command line)")
        if timeout is not None and not (isinstance(timeout, (int, float)) and timeout > 0):
            raise ValueError(f"timeout must be a positive number of seconds, got {timeout!r}")
        if not isinstance(result_name, str) or not result_name or os.path.isabs(result_name):
            raise ValueError(f"result_name must be a relative file name, got {result_name!r}")
        self.cwd = os.path.abspath(os.getcwd() if cwd is None else os.fspath(cwd))
        if not os.path.isdir(self.cwd):
            raise ValueError(f"cwd: {self.cwd} is not a directory (give the folder the "
                             "campaign's files are in)")
        self.template = list(args)
        self.args = resolve_paths(self.template, self.cwd)
        self.root = os.path.normpath(os.path.join(self.cwd, os.fspath(root)))
        self.timeout = None if timeout is None else float(timeout)
        self.result_name = result_name
        self.env = dict(env or {})
        self.reuse = bool(reuse)
        if on_interrupt not in ("end", "leave"):
            raise ValueError(f"on_interrupt must be 'end' or 'leave', got {on_interrupt!r}")
        self.on_interrupt = on_interrupt

    def __repr__(self) -> str:
        return f"CommandOracle({self.args!r}, root={self.root!r}, cwd={self.cwd!r})"

    def with_cwd(self, cwd) -> CommandOracle:
        """The same oracle with its relative paths resolved against ``cwd`` (``root`` kept)."""
        return CommandOracle(self.template, root=self.root, cwd=cwd, timeout=self.timeout,
                             result_name=self.result_name, env=self.env, reuse=self.reuse,
                             on_interrupt=self.on_interrupt)

    def command(self, event, workdir: str, files: dict | None = None) -> list[str]:
        """The argument list for ``event`` (``files``: extra placeholders, e.g. an episode's)."""
        return filled(self.args, event, files, workdir=workdir, cwd=self.cwd,
                       result=os.path.join(workdir, self.result_name))

    def check(self, event) -> None:
        """Refuse, before any event runs, a command that would fail every event: a
        placeholder ``event`` does not fill (``{idd}`` for ``{id}``), or the script of an
        interpreter (``python3 hff.py``, ``bash run.sh``) missing from :attr:`cwd`.

        ``event`` is one of the study's (its meta names the placeholders every event
        fills).  Raises a one-line :class:`ValueError` naming the placeholder and the
        known ones, or the path the script was looked for.
        """
        try:
            self.command(event, "{workdir}")
        except OracleError as exc:
            raise ValueError(str(exc)) from None
        program = os.path.basename(self.args[0]).removesuffix(".exe")
        if len(self.args) > 1 and runs_script(program):
            missing = missing_script(self.cwd, self.args[1])
            if missing:
                raise ValueError(missing)

    def recorded_command(self, event, files: dict | None = None) -> list[str]:
        """The command as an event's folder records it (:mod:`pas.study.workdirs`): the
        argument list as given, the event's fields filled in and the folders left as
        ``{workdir}``, ``{cwd}`` and ``{result}``, so that a campaign folder moved
        elsewhere still matches its records."""
        inside = {k: "{workdir}/" + os.path.basename(v) for k, v in (files or {}).items()}
        return filled(self.template, event, inside, workdir="{workdir}", cwd="{cwd}",
                       result="{result}")

    def __call__(self, event) -> float:
        self._check_scripts()
        workdir = os.path.join(self.root, event_dir(event))
        os.makedirs(workdir, exist_ok=True)
        result = os.path.join(workdir, self.result_name)
        lock = os.open(os.path.join(workdir, LOCK), os.O_RDWR | os.O_CREAT, 0o644)
        staging = None
        try:
            inherited = self._lock(lock, event, workdir)
            staging, staged, files = _staged_inputs(event, workdir)
            record = command_record(self.recorded_command(event, files), staged)
            kept = self._read(result, missing_ok=True)
            if _reusable(kept) and self._reuses(event, workdir, result, record):
                return kept
            if os.path.exists(result):
                os.remove(result)
            for name, path in (staged or {}).items():
                os.replace(path, files[name])
            write_record(workdir, record)
            try:
                self._run(self.command(event, workdir, files), workdir, lock, inherited,
                          event)
                return self._read(result)
            except OracleError:  # what a failed run wrote is no result to reuse
                write_record(workdir, {**record, "failed": True})
                raise
        finally:
            os.close(lock)
            if staging:
                shutil.rmtree(staging, ignore_errors=True)

    def _reuses(self, event, workdir, result, record) -> bool:
        """Whether to take the valid ``result`` an earlier run left in ``workdir``: only one
        of the same command that did not fail (:mod:`pas.study.workdirs`), only with
        ``reuse``; another command's result is an error."""
        recorded = read_record(workdir)
        if recorded is not None and recorded.pop("failed", False):
            return False
        if recorded is not None and recorded != record:
            raise OracleError(f"{workdir} holds the result of another command "
                              f"({_difference(recorded, record)}): give this study a root of "
                              "its own, or delete that folder to run the event again")
        if not self.reuse:
            return False
        how = "the same command" if recorded is not None else "a command it did not record"
        warnings.warn(f"event {event.id}: took {result}, left by an earlier run of {how} "
                      "(delete it to run the event again)", RuntimeWarning, stacklevel=3)
        return True

    def _check_scripts(self) -> None:
        """A relative script in the command that is not in :attr:`cwd` is an error naming
        the path it was looked for (else the program would be handed a path relative to
        the event's folder, and fail there)."""
        for a in self.args[1:]:
            missing = missing_script(self.cwd, a)
            if missing:
                raise OracleError(missing)

    def _lock(self, fd, event, workdir) -> bool:
        """Wait for the event's lock; True when the program can inherit it (``flock``).

        A program an earlier run left running holds it: wait until that program's own
        time-out counted from its start (this oracle's, counted from now, when the lock
        records none), then end it and run the event again
        (:mod:`pas.study.hf_programs`).
        """
        path = os.path.join(workdir, LOCK)
        since, said, ended = time.time(), False, None
        while (taken := try_lock(fd)) is False:
            now = time.time()
            record = read_holder(path)
            if ended is not None:
                if now > ended + 10:
                    raise OracleError(f"event {event.id}: {path} is still held {now - ended:.0f}"
                                      " s after its program was ended")
            elif not said and now > since + 1:
                due = deadline(record)
                warnings.warn(f"event {event.id}: waiting for its HF program an earlier run "
                              f"left running ({describe(record or {})}) "
                              + (f"until its time-out, {due - now:.0f} s from now"
                                 if due else "with no time-out")
                              + "; 'pas study hf-stop' ends it", RuntimeWarning, stacklevel=3)
                said = True
            due = deadline(record) or (None if self.timeout is None else since + self.timeout)
            if ended is None and due is not None and now > due:
                why = end_group(record) if record else "its lock names no program"
                if why is not None:
                    raise OracleError(f"event {event.id}: {path} is still held past its "
                                      f"time-out ({describe(record or {})}): {why}")
                warnings.warn(f"event {event.id}: ended its HF program that ran past its "
                              f"time-out ({describe(record)}); the event runs again",
                              RuntimeWarning, stacklevel=3)
                write_record(workdir, {**(read_record(workdir) or {}), "failed": True})
                ended = now
            time.sleep(0.05)
        return taken == "flock"

    def _run(self, cmd, workdir, lock, inherited, event) -> None:
        env = {**os.environ, **{str(k): str(v) for k, v in self.env.items()}}
        write_holder(lock, holder(None, event=event.id, timeout=self.timeout, program=cmd[0]))
        with open(os.path.join(workdir, "stdout.log"), "wb") as out, \
                open(os.path.join(workdir, "stderr.log"), "wb") as err:
            try:
                proc = subprocess.Popen(cmd, cwd=workdir, env=env, stdin=subprocess.DEVNULL,
                                        stdout=out, stderr=err,
                                        pass_fds=(lock,) if inherited else (), **OWN_SESSION)
            except OSError as exc:
                clear_holder(lock)
                raise OracleError(f"cannot start {cmd[0]!r}: {exc}") from None
            record = holder(proc.pid, event=event.id, timeout=self.timeout, program=cmd[0])
            write_holder(lock, record)
            try:
                code = proc.wait(timeout=self.timeout)
            except subprocess.TimeoutExpired:
                kill_group(proc)
                proc.wait()
                clear_holder(lock)
                raise OracleError(f"{cmd[0]} timed out after {self.timeout:g} s") from None
            except BaseException:  # Ctrl-C or a termination signal: end it, say so
                if self.on_interrupt == "end" and end_group(record) is None:
                    ENDED.append(record)
                    proc.wait()
                    write_record(workdir, {**(read_record(workdir) or {}), "failed": True})
                raise
            clear_holder(lock)
        if code != 0:
            tail = _last_line(os.path.join(workdir, "stderr.log"))
            raise OracleError(f"{os.path.basename(cmd[0])} exited with code {code}"
                              + (f": {tail}" if tail else ""))

    def _read(self, path, *, missing_ok=False):
        if not os.path.exists(path):
            if missing_ok:
                return None
            raise OracleError(f"the program wrote no result file {path}")
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        try:
            return parse_result(text)
        except OracleError as exc:
            if missing_ok:
                return None
            raise OracleError(f"{path}: {exc}") from None


def _difference(recorded: dict, record: dict) -> str:
    """The first argument (or input file) in which two records differ, for a message."""
    old, new = recorded.get("command", []), record["command"]
    for i, (a, b) in enumerate(zip(old, new)):
        if a != b:
            return f"argument {i + 1} was {a[:60]!r}, now {b[:60]!r}"
    if len(old) != len(new):
        return f"{len(old)} arguments then, {len(new)} now"
    return "its input files differ"


def _staged_inputs(event, workdir: str):
    """A design-wave episode's input files (:class:`pas.waves.episode.Episode`), written into
    a folder of their own in ``workdir`` until the program runs: ``(that folder, the staged
    paths, their paths in workdir)``, or ``(None, None, None)`` for an event without input
    files."""
    writer = getattr(event, "write_csv", None)
    if not callable(writer):
        return None, None, None
    folder = tempfile.mkdtemp(prefix=".inputs-", dir=workdir)
    try:
        staged = writer(folder)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    return folder, staged, {k: os.path.join(workdir, os.path.basename(v))
                            for k, v in staged.items()}


def _last_line(path: str) -> str:
    try:
        with open(path, "rb") as f:
            lines = f.read()[-2000:].decode(errors="replace").strip().splitlines()
    except OSError:
        return ""
    return lines[-1][:200] if lines else ""
