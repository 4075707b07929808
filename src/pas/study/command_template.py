"""The HF command's argument list: placeholders, relative paths, scripts and the result file.

A :class:`~pas.study.command_oracle.CommandOracle` runs ``args`` with each
event's fields filled in (:func:`filled`: ``{id}``, ``{index}``, ``{lf}``,
``{d}``, the event's meta, the folders ``{workdir}``, ``{cwd}``,
``{result}``); relative paths are files of the folder the campaign is
started from (:func:`resolve_paths`), and a relative script that is not there
is named with the path it was looked for (:func:`missing_script`).  The
program writes its answer to ``{result}`` (:func:`parse_result`).
"""

from __future__ import annotations

import json
import os
import re

from .oracles import OracleError

__all__ = ["filled", "parse_result", "resolve_paths", "missing_script", "runs_script"]

_SCRIPT_SUFFIXES = (".py", ".sh", ".bash", ".jl", ".R", ".r", ".m", ".pl", ".rb", ".tcl", ".lua",
                    ".js")
_INTERPRETER = re.compile(r"(python|pypy)[0-9.]*|(ba|da|k|z)?sh")
"""Programs whose first argument, when it is a script, is the file they run."""


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


def filled(args, event, files, **folders) -> list[str]:
    """``args`` with ``event``'s fields, its meta, ``files`` and ``folders`` filled in."""
    fields = {str(k): v for k, v in event.meta.items()}
    fields.update(files or {})
    if getattr(event, "sea_state", None) is not None:  # else a meta key of that name
        fields["sea_state"] = event.sea_state
    fields.update(id=event.id, index=event.index, lf=repr(float(event.lf)),
                  d=repr(float(event.d)), **folders)
    try:
        return [a.format_map(fields) for a in args]
    except KeyError as exc:
        first = ["id", "index", "lf", "d", *folders]
        known = first + [k for k in fields if k not in first]
        raise OracleError(f"command: unknown placeholder {{{exc.args[0]}}} (known: "
                          + ", ".join(f"{{{k}}}" for k in known) + ")") from None
    except (IndexError, TypeError, AttributeError) as exc:  # {seed[0]}, {lf.real}
        raise OracleError(f"args: a placeholder indexes or reads an attribute of a field "
                          f"({exc}); the fields are filled in whole: write {{seed}}, not "
                          "{seed[0]}") from None
    except ValueError as exc:  # e.g. {lf:.3f}: the fields are text
        raise OracleError(f"args: {exc} (the fields are filled in as text: write {{lf}}, "
                          "not {lf:.3f})") from None


def runs_script(program: str) -> bool:
    """Whether ``program`` (a path's base name) is an interpreter whose first argument, when
    it is a script, is the file it runs (``python3``, ``bash``)."""
    return bool(_INTERPRETER.fullmatch(program))


def missing_script(cwd: str, a: str) -> str | None:
    """The message for ``a``, a relative script (``cfd.py``, ``../hf/run.sh``) that is
    not in ``cwd`` (:func:`resolve_paths` made those that are absolute), else None."""
    if ("{" not in a and not os.path.isabs(a) and not a.startswith("-")
            and not any(c.isspace() for c in a)
            and os.path.splitext(a)[1] in _SCRIPT_SUFFIXES):
        return (f"command: {a} not found: looked for "
                f"{os.path.normpath(os.path.join(cwd, a))} (relative paths resolve "
                f"against {cwd}, the folder the study was started from)")
    return None
