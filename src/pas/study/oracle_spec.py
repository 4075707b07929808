"""An HF oracle from a text spec: ``pas run --oracle`` and the ``[oracle]`` table of a study file.

``table:FILE[:ID_COLUMN:VALUE_COLUMN]``, ``command:ARGS ...`` and
``python:FILE.py:FUNCTION`` (:func:`parse_oracle_spec`), or the same as a dict.
"""

from __future__ import annotations

import importlib
import importlib.util
import shlex
import sys
from pathlib import Path

from .oracles import CommandOracle, TableOracle

__all__ = ["oracle_from_spec", "parse_oracle_spec"]


def parse_oracle_spec(spec: str) -> dict:
    """The ``[oracle]`` table equivalent to an oracle text spec (``pas run --oracle``).

    ``table:FILE[:ID_COLUMN:VALUE_COLUMN]`` gives ``{"table", "id_column",
    "value_column"}`` (``VALUE_COLUMN`` ``A,B``: a list, one named load per column); ``python:MODULE:FUNCTION`` gives ``{"python"}``;
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


def oracle_from_spec(spec, *, root=None, timeout=None):
    """Build an HF oracle from a text spec or an ``[oracle]`` table.

    Parameters
    ----------
    spec : str or dict
        Text as for :func:`parse_oracle_spec`, or a table with exactly one of
        ``command`` (with ``root``, ``timeout``, ``result_name``: see
        :class:`CommandOracle`), ``table`` (with ``id_column``,
        ``value_column``: see :class:`TableOracle`) or ``python``
        (``"MODULE:FUNCTION"``, ``MODULE`` an importable name or a ``.py`` file).
    root : path, optional
        Root of a command oracle's per-event working directories when ``spec``
        names none (default ``hf-runs``).
    timeout : float, optional
        Seconds per event of a command oracle when ``spec`` names none.

    Returns
    -------
    callable
        ``oracle(event) -> float``.
    """
    o = parse_oracle_spec(spec) if isinstance(spec, str) else dict(spec)
    if "command" in o:
        return CommandOracle(o["command"], root=o.get("root", root or "hf-runs"),
                             timeout=o.get("timeout", timeout),
                             result_name=o.get("result_name", "result.txt"))
    if "table" in o:
        return TableOracle(o["table"], id_column=o.get("id_column", "id"),
                           value_column=o.get("value_column", "hf"))
    if "python" in o:
        target, _, func = o["python"].rpartition(":")
        return _python_function(target, func)
    raise ValueError(f"an oracle needs one of command, table or python, got {sorted(o)}")


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
