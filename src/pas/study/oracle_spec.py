"""An HF oracle from a text spec: ``pas run --oracle`` and the ``[oracle]`` table of a study file.

``table:FILE[:ID_COLUMN:VALUE_COLUMN]``, ``command:ARGS ...`` and
``python:FILE.py:FUNCTION`` (:func:`parse_oracle_spec`), or the same as a dict.
A command's relative paths mean paths in the directory the study was started
from (:func:`~pas.study.command_template.resolve_paths`): the spec's ``cwd``, which
``pas study create`` sets to the study file's folder, and which
:func:`keep_start_dir` records in a ``pas run`` study store, so a resumed
run in another folder runs the same files.
"""

from __future__ import annotations

import importlib
import importlib.util
import shlex
import sys
from pathlib import Path

from .command_oracle import CommandOracle
from .oracles import TableOracle

__all__ = ["oracle_from_spec", "parse_oracle_spec", "keep_start_dir", "started_oracle",
           "recorded_start_dir", "START_DIR_KEY",
           "COMMAND_KEY", "COMMAND_CHANGES_KEY", "ROOT_KEY"]

START_DIR_KEY = "oracle_cwd"
"""Meta key of a study store holding the directory its command oracle was first started from."""

COMMAND_KEY, COMMAND_CHANGES_KEY = "oracle_command", "oracle_command_changes"
"""Meta keys of a study store: the command oracle's argument list as last run, and the list
of its changes on resuming, ``{"old", "new", "at"}`` each."""

ROOT_KEY = "oracle_root"
"""Meta key of a study store: the folder of its command oracle's event folders."""


def parse_oracle_spec(spec: str) -> dict:
    """The ``[oracle]`` table equivalent to an oracle text spec (``pas run --oracle``).

    ``table:FILE[:ID_COLUMN:VALUE_COLUMN]`` gives ``{"table", "id_column",
    "value_column"}`` (``VALUE_COLUMN`` ``A,B``: a list, one named load per column);
    ``python:MODULE:FUNCTION`` gives ``{"python"}``;
    ``command:ARGS`` gives ``{"command": [...]}``, the arguments split like a
    shell would split them (never run through one).

    Examples
    --------
    >>> parse_oracle_spec("table:basin.csv:event:force")
    {'table': 'basin.csv', 'id_column': 'event', 'value_column': 'force'}
    >>> parse_oracle_spec("table:basin.csv:event:deck_force,panel_p3")["value_column"]
    ['deck_force', 'panel_p3']
    >>> parse_oracle_spec("command:python cfd.py --out {result}")
    {'command': ['python', 'cfd.py', '--out', '{result}']}
    """
    kind, sep, rest = spec.partition(":")
    if not sep or not rest:
        raise ValueError(f"{spec!r} is not table:FILE[:ID:VALUE], python:MODULE:FUNCTION or "
                         "command:ARGS")
    if kind == "table":
        parts = rest.split(":")
        if len(parts) == 1:
            return {"table": parts[0]}
        if len(parts) == 3 and all(parts):
            columns = parts[2].split(",")
            if len(columns) > 1 and not all(columns):
                raise ValueError(f"{spec!r}: empty name in the value columns {parts[2]!r}")
            return {"table": parts[0], "id_column": parts[1],
                    "value_column": columns if len(columns) > 1 else parts[2]}
        raise ValueError(f"{spec!r}: expected table:FILE or table:FILE:ID_COLUMN:VALUE_COLUMN")
    if kind == "python":
        target, sep, func = rest.rpartition(":")
        if not sep or not target or not func:
            raise ValueError(f"{spec!r}: expected python:MODULE:FUNCTION")
        return {"python": rest}
    if kind == "command":
        try:
            args = shlex.split(rest)
        except ValueError as exc:
            raise ValueError(f"cannot split the command {rest!r}: {exc}") from None
        if not args:
            raise ValueError("command: is empty")
        return {"command": args}
    raise ValueError(f"unknown kind {kind!r} (use table:, python: or command:)")


def oracle_from_spec(spec, *, root=None, timeout=None, cwd=None):
    """Build an HF oracle from a text spec or an ``[oracle]`` table.

    Parameters
    ----------
    spec : str or dict
        Text as for :func:`parse_oracle_spec`, or a table with exactly one of
        ``command`` (with ``root``, ``timeout``, ``result_name``, ``cwd``: see
        :class:`CommandOracle`), ``table`` (with ``id_column``,
        ``value_column``: see :class:`TableOracle`) or ``python``
        (``"MODULE:FUNCTION"``, ``MODULE`` an importable name or a ``.py`` file).
    root : path, optional
        Root of a command oracle's per-event working directories when ``spec``
        names none (default ``hf-runs``).
    timeout : float, optional
        Seconds per event of a command oracle when ``spec`` names none.
    cwd : path, optional
        Directory a command oracle's relative paths (and ``root``) resolve
        against when ``spec`` names none (default: the current directory).

    Returns
    -------
    callable
        ``oracle(event) -> float``.
    """
    o = parse_oracle_spec(spec) if isinstance(spec, str) else dict(spec)
    if "command" in o:
        return CommandOracle(o["command"], root=o.get("root", root or "hf-runs"),
                             cwd=o.get("cwd", cwd), timeout=o.get("timeout", timeout),
                             result_name=o.get("result_name", "result.txt"),
                             on_interrupt=o.get("on_interrupt", "end"))
    if "table" in o:
        return TableOracle(o["table"], id_column=o.get("id_column", "id"),
                           value_column=o.get("value_column", "hf"))
    if "python" in o:
        target, _, func = o["python"].rpartition(":")
        return _python_function(target, func)
    raise ValueError(f"an oracle needs one of command, table or python, got {sorted(o)}")


def started_oracle(oracle, recorded):
    """``oracle`` resolved against ``recorded``, the directory its study was started from
    (None for a new study), and the line saying so (None when nothing moved)."""
    if recorded is None or recorded == oracle.cwd:
        return oracle, None
    try:
        return oracle.with_cwd(recorded), (f"the command's relative paths resolve against "
                                           f"{recorded}, where the study was started")
    except ValueError:  # the first run's folder is gone: use this one, and say so
        return oracle, (f"the study was started in {recorded}, which no longer exists; the "
                        f"command's relative paths resolve against {oracle.cwd}")


def recorded_start_dir(path):
    """The directory the study in the store file ``path`` was started from (None: none yet)."""
    from .store import StudyStore

    if path is None or not Path(path).exists():
        return None
    with StudyStore(path, create=False) as store:
        return store.get(START_DIR_KEY)


def keep_start_dir(oracle, store):
    """``oracle`` resolved against the directory its study was first started from, recorded.

    A :class:`CommandOracle` bound to a new study store records its ``cwd``
    there (under :data:`START_DIR_KEY`); on a store holding another one it is
    rebuilt with that one (its ``root`` kept, :func:`started_oracle`), so
    relative script paths keep meaning the files of the first run.  Its
    argument list is recorded (:data:`COMMAND_KEY`): one that differs from the
    stored one is a change, appended to :data:`COMMAND_CHANGES_KEY` and said
    once.  Other oracles are returned as they are.  Check the command
    (:meth:`CommandOracle.check`) before: nothing of a command that cannot run
    should be recorded.

    Returns
    -------
    (oracle, note)
        ``note`` is None, or the lines (one per fact) saying which directory
        is used and how the command changed.
    """
    if not isinstance(oracle, CommandOracle) or store is None:
        return oracle, None
    recorded = store.get(START_DIR_KEY)
    oracle, moved = started_oracle(oracle, recorded)
    notes = [n for n in (moved, _command_change(oracle, store)) if n]
    store.put(ROOT_KEY, oracle.root)
    if recorded is None:
        store.put(START_DIR_KEY, oracle.cwd)
    return oracle, "\n".join(notes) if notes else None


def _command_change(oracle, store) -> str | None:
    """Record ``oracle``'s argument list in ``store``; the line saying how it changed."""
    from datetime import datetime, timezone

    old, new = store.get(COMMAND_KEY), list(oracle.template)
    if old == new:
        return None
    store.put(COMMAND_KEY, new)
    if old is None:
        return None
    at = datetime.now(timezone.utc).isoformat(timespec="seconds")
    store.put(COMMAND_CHANGES_KEY,
              store.get(COMMAND_CHANGES_KEY, []) + [{"old": old, "new": new, "at": at}])
    return (f"the HF command changed on resuming: it was {old}, now {new} (recorded in the "
            "study store; events already run keep their results)")


def _python_function(target: str, func: str):
    if target.endswith(".py"):
        file = Path(target)
        if not file.exists():
            raise FileNotFoundError(f"python file {file} does not exist")
        spec = importlib.util.spec_from_file_location(f"_pas_oracle_{file.stem}", file)
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # so a process pool can unpickle its functions
        try:
            spec.loader.exec_module(module)
        except Exception as exc:
            raise ValueError(f"importing {file} failed: {type(exc).__name__}: {exc}") from None
    else:
        try:
            module = importlib.import_module(target)
        except ImportError as exc:
            raise ValueError(f"cannot import module {target!r} ({exc})") from None
    fn = getattr(module, func, None)
    if not callable(fn):
        raise ValueError(f"{target} has no function {func!r}")
    return fn
