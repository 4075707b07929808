"""HF oracles: calling one safely, the built-in ones, and building one from a text spec.

An oracle is any callable ``oracle(event) -> float`` (0 = no impact, a false
positive), or ``-> {name: float}`` when one HF run gives several loads (panels,
pressure sensors, forces): the study screens on its ``target`` and the store
keeps them all (:func:`check_hf_answer`).  A failure is an exception with a
message; the study records it as a failed event and never takes it as 0
(:func:`call_oracle`).  The built-in
oracles, a results table and an external command per event, hold only plain
data, so they pickle for process pools and Dask workers.
:func:`pas.study.oracle_spec.oracle_from_spec` builds one from ``pas run
--oracle`` text or a ``pas study`` ``[oracle]`` table.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from ._processes import OWN_SESSION, kill_group, try_lock
from .answers import check_hf_answer, check_hf_value, check_target, lacks_target
from .inputs import read_table
from .workdirs import RECORD, command_record, event_dir, read_record, write_record

__all__ = ["OracleError", "OracleFailureLimit", "check_hf_value", "check_hf_answer",
           "lacks_target", "check_oracle", "call_oracle", "call_oracle_loads", "check_target",
           "TableOracle", "CommandOracle", "resolve_paths"]


class OracleError(RuntimeError):
    """An HF evaluation failed; the message is stored with the event."""


class OracleFailureLimit(RuntimeError):
    """Raised when the oracle failed more often than ``max_failures``.

    ``result`` holds the study's result so far (nothing evaluated is lost).
    """

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


def check_oracle(oracle) -> None:
    """Raise a one-line :class:`TypeError` naming ``oracle`` unless it can be called."""
    if not callable(oracle):
        raise TypeError(f"oracle must be a callable oracle(event) -> float (a function, "
                        f"pas.TableOracle or pas.CommandOracle), got {type(oracle).__name__} "
                        f"{oracle!r:.60}")


def call_oracle(oracle, event):
    """Call ``oracle(event)`` and validate the answer: ``(value, error)``."""
    return call_oracle_loads(oracle, event)[:2]


def call_oracle_loads(oracle, event, target=None):
    """Call ``oracle(event)``, its answer checked: ``(value, error, loads)``.

    :func:`~pas.study.answers.check_hf_answer` with ``target``.
    """
    try:
        raw = oracle(event)
    except Exception as exc:  # the oracle is user code: any failure is recorded
        return None, f"{type(exc).__name__}: {exc}", None
    return check_hf_answer(raw, target)


class TableOracle:
    """HF results looked up by event id: basin tests or a finished HF Monte-Carlo.

    Parameters
    ----------
    table : str, os.PathLike or pandas.DataFrame
        CSV or Parquet file, or a DataFrame.
    id_column : str, default "id"
        Column holding the event ids (matched to ``str(event.id)``).
    value_column : str or sequence of str, default "hf"
        Column holding the HF peak (0 = no impact).  Several columns (one per
        load: panels, sensors, forces) make the oracle answer ``{column:
        value}`` (a study then screens on its ``target``; ``pas run --oracle
        table:FILE:ID:COL1,COL2``).
    sea_state_column : str, default "sea_state"
        When the table has this column, rows are keyed by sea state and event
        id, and an event is looked up by ``(event.sea_state, event.id)`` (a
        long-term analysis, :func:`pas.run_long_term`, where ids may repeat
        across sea states); an event of no sea state by its id alone.

    Notes
    -----
    An event missing from the table, or with an empty value, is a failure,
    never 0 (with several columns: an empty one is a failure when it is the
    study's target, else that load is missing, :func:`check_hf_answer`).

    Examples
    --------
    >>> import pandas as pd
    >>> from pas.strategies.screening import Event
    >>> oracle = TableOracle(pd.DataFrame({"id": ["a", "b"], "hf": [1.5, 0.0]}))
    >>> oracle(Event(index=0, id="a", lf=1.0, d=0.1))
    1.5
    """

    def __init__(self, table, *, id_column: str = "id", value_column: str = "hf",
                 sea_state_column: str = "sea_state"):
        import pandas as pd

        if isinstance(table, pd.DataFrame):
            name, df = "the table", table
        else:
            name, df = Path(table).name, read_table(table)
        named = not isinstance(value_column, str)
        columns = list(value_column) if named else [value_column]
        if not columns or len(set(columns)) < len(columns):
            raise ValueError(f"value_column: give one column or several different ones, got "
                             f"{value_column!r}")
        for field, c in (("id_column", id_column), *(("value_column", c) for c in columns)):
            if c not in df.columns:
                raise ValueError(f"{field}: column {c!r} is missing from {name} "
                                 f"(columns: {', '.join(map(str, df.columns))})")
        keys = df[id_column].astype(str)
        self.by_sea_state = sea_state_column in df.columns and sea_state_column != id_column
        if self.by_sea_state:
            keys = df[sea_state_column].astype(str) + "\x1f" + keys
        dup = keys[keys.duplicated()]
        if len(dup):
            where = " (within its sea state)" if self.by_sea_state else ""
            raise ValueError(f"{id_column}: event id {dup.iloc[0].split(chr(31))[-1]!r} appears "
                             f"more than once{where} in {name}")
        values = [pd.to_numeric(df[c], errors="coerce").to_numpy(dtype=float).tolist()
                  for c in columns]
        self.name = name
        self.columns = columns if named else None
        self.values = dict(zip(keys, zip(*values)))
        if self.by_sea_state:  # a single-sea-state study looks up its ids alone, if unique
            plain = df[id_column].astype(str)
            once = set(plain[~plain.duplicated(keep=False)])
            self.values.update({k.split("\x1f", 1)[1]: v for k, v in self.values.items()
                                if k.split("\x1f", 1)[1] in once})

    def __call__(self, event):
        key = str(event.id)
        lookup = key
        sea_state = getattr(event, "sea_state", None)
        if self.by_sea_state and sea_state is not None:
            lookup = f"{sea_state}\x1f{key}"
            key = f"{key} of sea state {sea_state}"
        if lookup not in self.values:
            raise OracleError(f"event {key} is not in {self.name}")
        row = self.values[lookup]
        if self.columns is not None:
            return dict(zip(self.columns, row))
        if not math.isfinite(row[0]):
            raise OracleError(f"{self.name} has no valid value for event {key}")
        return row[0]


def parse_result(text: str):
    """An HF answer from a result file: a number, a JSON number or ``{"value": x}``,
    or several named loads as a JSON object ``{"deck_force": 812.0, "panel_p3": 41.2}``.

    A JSON object with the one key ``value`` is that number; any other object is
    a mapping of named loads, checked by :func:`check_hf_answer`.
    """
    text = text.strip()
    try:
        return float(text)
    except ValueError:
        pass
    try:
        obj = json.loads(text)
    except ValueError:
        obj = None
    if isinstance(obj, dict) and list(obj) == ["value"]:
        obj = obj["value"]
    if isinstance(obj, dict) and obj:
        return obj
    if isinstance(obj, (int, float)) and not isinstance(obj, bool):
        return float(obj)
    raise OracleError(f"result file holds {text[:60]!r}, not a number or a JSON object of "
                      "named loads")


def _reusable(answer) -> bool:
    """True for a result left by an earlier run that may be taken instead of running again."""
    return isinstance(answer, dict) or (answer is not None and np.isfinite(answer) and answer >= 0)


def resolve_paths(args, cwd: str) -> list[str]:
    """``args`` with the relative paths that name something in ``cwd`` made absolute.

    The rule of :class:`CommandOracle`: the program (``args[0]``) is resolved
    when it contains a directory separator (``./cfd.sh``, ``bin/cfd``) or
    names a file in ``cwd``; a bare name otherwise (``python``) is left to
    the ``PATH``.  A later argument is resolved when it names an existing
    file or directory relative to ``cwd`` (``cfd_event.py``, ``mesh/``).
    Absolute paths, ``.`` and ``..``, options (``-x``, ``--out=f``) and
    arguments with a placeholder are left as they are (write
    ``{cwd}/case.json`` to be explicit).

    Examples
    --------
    >>> resolve_paths(["python", "./missing.py", "--lf", "{lf}"], "/campaign")
    ['python', './missing.py', '--lf', '{lf}']
    """
    def rel(a: str) -> bool:
        return bool(a) and "{" not in a and not os.path.isabs(a) and not a.startswith("-") \
            and os.path.normpath(a) not in (".", "..")

    def here(a: str) -> str:
        return os.path.normpath(os.path.join(cwd, a))

    program, rest = args[0], list(args[1:])
    seps = tuple(s for s in (os.sep, os.altsep) if s)
    if rel(program) and (any(s in program for s in seps) or os.path.isfile(here(program))):
        program = here(program)
    return [program] + [here(a) if rel(a) and os.path.exists(here(a)) else a for a in rest]


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

    Notes
    -----
    A non-zero exit status, a time-out, a missing or unreadable result file
    raise :class:`OracleError` (recorded as a failed event, never as 0).
    While the program runs it holds an ``flock`` on ``root/<id>/.lock``
    (inherited by the program), so a resumed driver waits for a program
    orphaned by a killed driver and reuses its result instead of starting a
    second copy.  The program runs in a session (POSIX) or process group
    (Windows) of its own, so Ctrl-C in the driver does not stop it.  Where
    ``fcntl`` is missing (Windows) the lock is an ``msvcrt`` lock held by
    the driver only, so it does not cover an orphaned program.
    """

    def __init__(self, args, *, root, cwd=None, timeout: float | None = None,
                 result_name: str = "result.txt", env: dict | None = None, reuse: bool = True):
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

    def __repr__(self) -> str:
        return f"CommandOracle({self.args!r}, root={self.root!r}, cwd={self.cwd!r})"

    def with_cwd(self, cwd) -> CommandOracle:
        """The same oracle with its relative paths resolved against ``cwd`` (``root`` kept)."""
        return CommandOracle(self.template, root=self.root, cwd=cwd, timeout=self.timeout,
                             result_name=self.result_name, env=self.env, reuse=self.reuse)

    def command(self, event, workdir: str, files: dict | None = None) -> list[str]:
        """The argument list for ``event`` (``files``: extra placeholders, e.g. an episode's)."""
        fields = {str(k): v for k, v in event.meta.items()}
        fields.update(files or {})
        if getattr(event, "sea_state", None) is not None:  # else a meta key of that name
            fields["sea_state"] = event.sea_state
        fields.update(id=event.id, index=event.index, lf=repr(float(event.lf)),
                      d=repr(float(event.d)), workdir=workdir, cwd=self.cwd,
                      result=os.path.join(workdir, self.result_name))
        try:
            return [a.format_map(fields) for a in self.args]
        except (KeyError, IndexError) as exc:
            raise OracleError(f"args: placeholder {exc} is neither an event field nor in its "
                              "meta") from None

    def __call__(self, event) -> float:
        workdir = os.path.join(self.root, event_dir(event))
        os.makedirs(workdir, exist_ok=True)
        result = os.path.join(workdir, self.result_name)
        lock = os.open(os.path.join(workdir, ".lock"), os.O_RDWR | os.O_CREAT, 0o644)
        staged = None
        try:
            inherited = self._lock(lock, event)
            staged, files = _staged_inputs(event, workdir)
            cmd = self.command(event, workdir, files)
            record = command_record(cmd, staged)
            kept = self._read(result, missing_ok=True)
            if _reusable(kept) and self._reuses(event, workdir, result, record):
                return kept
            if os.path.exists(result):
                os.remove(result)
            for name, path in (staged or {}).items():
                os.replace(path, files[name])
            write_record(workdir, record)
            self._run(cmd, workdir, (lock,) if inherited else ())
            return self._read(result)
        finally:
            os.close(lock)
            if staged:
                shutil.rmtree(os.path.dirname(next(iter(staged.values()))), ignore_errors=True)

    def _reuses(self, event, workdir, result, record) -> bool:
        """Whether to take the valid ``result`` an earlier run left in ``workdir``: only one
        of the same command (:mod:`pas.study.workdirs`), and only with ``reuse``."""
        recorded = read_record(workdir)
        if recorded is not None and recorded != record:
            shown = " ".join(recorded.get("command", []))
            raise OracleError(f"{workdir} holds the result of another command ({shown[:120]}, "
                              f"recorded in its {RECORD}): give this study a root of its own, "
                              "or delete that folder to run the event again")
        if not self.reuse:
            return False
        how = "the same command" if recorded is not None else "a command it did not record"
        warnings.warn(f"event {event.id}: took {result}, left by an earlier run of {how} "
                      "(delete it to run the event again)", RuntimeWarning, stacklevel=3)
        return True

    def _lock(self, fd, event) -> bool:
        """Wait for the event's lock; True when the program can inherit it (``flock``)."""
        deadline = None if self.timeout is None else time.monotonic() + self.timeout
        while (taken := try_lock(fd)) is False:
            if deadline is not None and time.monotonic() > deadline:
                raise OracleError(f"event {event.id}: another run of it still holds "
                                  f"{self.root}/.../.lock after {self.timeout:g} s")
            time.sleep(0.05)
        return taken == "flock"

    def _run(self, cmd, workdir, pass_fds) -> None:
        env = {**os.environ, **{str(k): str(v) for k, v in self.env.items()}}
        with open(os.path.join(workdir, "stdout.log"), "wb") as out, \
                open(os.path.join(workdir, "stderr.log"), "wb") as err:
            try:
                proc = subprocess.Popen(cmd, cwd=workdir, env=env, stdin=subprocess.DEVNULL,
                                        stdout=out, stderr=err, pass_fds=pass_fds,
                                        **OWN_SESSION)
            except OSError as exc:
                raise OracleError(f"cannot start {cmd[0]!r}: {exc}") from None
            try:
                code = proc.wait(timeout=self.timeout)
            except subprocess.TimeoutExpired:
                kill_group(proc)
                proc.wait()
                raise OracleError(f"{cmd[0]} timed out after {self.timeout:g} s") from None
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


def _staged_inputs(event, workdir: str):
    """A design-wave episode's input files (:class:`pas.waves.episode.Episode`), written into
    a folder of their own in ``workdir`` until the program runs: ``(staged paths, their
    paths in workdir)``, or ``(None, None)`` for an event without input files."""
    writer = getattr(event, "write_csv", None)
    if not callable(writer):
        return None, None
    staged = writer(tempfile.mkdtemp(prefix=".inputs-", dir=workdir))
    return staged, {k: os.path.join(workdir, os.path.basename(v)) for k, v in staged.items()}


def _last_line(path: str) -> str:
    try:
        with open(path, "rb") as f:
            lines = f.read()[-2000:].decode(errors="replace").strip().splitlines()
    except OSError:
        return ""
    return lines[-1][:200] if lines else ""
