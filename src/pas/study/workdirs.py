"""Working directories of HF events: one folder per event, and the command that ran there.

:class:`~pas.study.command_oracle.CommandOracle` runs each event in ``root/<name>``
and reuses a result file it finds there, so two events must never share a
name: an id that is not a safe file name gets its index appended, and an
event of a long-term analysis (:mod:`pas.longterm`, where ids repeat across
sea states) lives under its sea state's folder.  Before the program starts,
the argument list it is given (and a digest of the input files written for
it) is recorded in the folder (:data:`RECORD`), so that a result is reused
only for the same command: a second study run into the same ``root``, or a
command changed since, finds a record that differs.
"""

from __future__ import annotations

import hashlib
import json
import os
import re

__all__ = ["RECORD", "event_dir", "command_record", "read_record", "write_record"]

_SAFE = re.compile(r"[^A-Za-z0-9._-]")

RECORD = ".pas-command.json"
"""The file, in an event's working directory, recording the command run there."""


def _safe(text: str, suffix) -> str:
    name = _SAFE.sub("_", text)
    return name if name == text and name not in (".", "..") else f"{name}-{suffix}"


def event_dir(event) -> str:
    """``<id>``, or ``<sea state>/<id>`` for an event of a long-term analysis."""
    name = _safe(str(event.id), event.index)
    sea_state = getattr(event, "sea_state", None)
    if sea_state is None:
        return name
    digest = hashlib.sha256(str(sea_state).encode()).hexdigest()[:8]
    return os.path.join(_safe(str(sea_state), digest), name)


def command_record(command, files=None) -> dict:
    """What a run is: its argument list and the SHA-256 of each input file written for it
    (``files``: placeholder → path, e.g. a design-wave episode's CSV files)."""
    digests = {}
    for name, path in sorted((files or {}).items()):
        with open(path, "rb") as f:
            digests[name] = hashlib.sha256(f.read()).hexdigest()
    return {"command": [str(a) for a in command], "files": digests}


def read_record(workdir: str):
    """The record of the command last started in ``workdir``; None when there is none (or
    it cannot be read: a folder of an earlier ``pas``, or one the program made itself)."""
    try:
        with open(os.path.join(workdir, RECORD), encoding="utf-8") as f:
            record = json.load(f)
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) else None


def write_record(workdir: str, record: dict) -> None:
    """Record ``record`` in ``workdir`` (written to a temporary file, then renamed)."""
    path = os.path.join(workdir, RECORD)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(record, f, indent=1)
    os.replace(path + ".tmp", path)
