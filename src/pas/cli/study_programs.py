"""``pas study hf-programs`` and ``pas study hf-stop``: a study's running HF programs.

::

    pas study hf-programs STUDY [--json]
    pas study hf-stop STUDY [EVENT ...]

``STUDY`` is a study store (``pas study create``), or the ``--out`` folder of
``pas run`` (its ``study.sqlite``).  The programs are those of the study's
command oracle whose event folders hold a lock now (:mod:`pas.study.hf_programs`):
one line each with the PID, host, start, time-out and the ``pas`` process that
started it, and whether that process still runs (if not, the program is an
orphan: a resumed run waits for it until its time-out, then ends it).
``hf-stop`` ends them (all, or those of the given events): ``SIGTERM`` to the
program's process group, ``SIGKILL`` a few seconds later; their events run again
on resume (a run still waiting for one records it as failed: ``--retry-failed``
or ``pas study retry``).  A program on another host is named, not stopped.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

__all__ = ["add_parsers", "list_programs", "stop_programs"]


def add_parsers(cmds) -> None:
    """Add the ``hf-programs`` and ``hf-stop`` actions to ``pas study``'s ``cmds``."""
    p = cmds.add_parser("hf-programs", help="list the study's HF programs running now",
                        description="List the HF programs of the study's command oracle that "
                                    "run now: PID, host, start, time-out and the pas process "
                                    "that started them.")
    p.add_argument("study", metavar="STUDY", help="study store, or the --out folder of pas run")
    p.add_argument("--json", action="store_true")
    s = cmds.add_parser("hf-stop", help="end the study's running HF programs",
                        description="End the HF programs of the study's command oracle that "
                                    "run now (their process groups: SIGTERM, then SIGKILL); "
                                    "their events run again on resume.")
    s.add_argument("study", metavar="STUDY", help="study store, or the --out folder of pas run")
    s.add_argument("events", nargs="*", metavar="EVENT",
                   help="event ids (default: every running program of the study)")


def store_path(study: str) -> str:
    """The study store ``STUDY`` names: the file itself, or the ``study.sqlite`` that
    ``pas run`` keeps in its ``--out`` folder when ``study`` is a folder."""
    path = Path(study)
    if not path.is_dir():
        return study
    if not (path / "study.sqlite").is_file():
        raise ValueError(f"STUDY: {study} is a folder with no study.sqlite in it (give a study "
                         "store, or the --out folder of pas run)")
    return str(path / "study.sqlite")


def _root(study: str) -> str:
    """The folder of the study's event folders, from its store."""
    from ..study.oracle_spec import ROOT_KEY
    from ..study.store import StudyStore

    path = Path(store_path(study))
    if not path.is_file():
        raise ValueError(f"STUDY: {study} is neither a study store nor a pas run --out folder "
                         "holding study.sqlite")
    store = StudyStore(path, create=False)
    try:
        root = store.get(ROOT_KEY) or (store.get("oracle") or {}).get("root")
    finally:
        store.close()
    if root is None:
        root = str(path.resolve().parent / "hf-runs")
    return root


def _alive(pid) -> bool:
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError, ValueError, TypeError):
        return True
    return True


def _line(record: dict) -> str:
    from ..study.hf_programs import describe, on_this_host

    line = describe(record)
    if on_this_host(record) and record.get("run_pid") and not _alive(record["run_pid"]):
        line += " (its pas process has ended: an orphan)"
    return f"{line}; {record['workdir']}"


def list_programs(args) -> int:
    """``pas study hf-programs``: one line per running program; exit 0."""
    from ..study.hf_programs import running

    root = _root(args.study)
    found = running(root)
    if args.json:
        print(json.dumps(found, indent=1))
        return 0
    if not found:
        print(f"no HF program of this study runs now (event folders in {root})")
    for record in found:
        print(_line(record))
    return 0


def stop_programs(args) -> int:
    """``pas study hf-stop``: end the running programs (of ``args.events``); exit 1 when one
    could not be ended from here."""
    from ..study.hf_programs import end_group, running
    from ..study.workdirs import read_record, write_record

    root = _root(args.study)
    found = running(root)
    if args.events:
        known = {r.get("event") for r in found}
        missing = [e for e in args.events if e not in known]
        if missing:
            raise ValueError(f"EVENT: no HF program runs now for {', '.join(missing)} "
                             f"(see 'pas study hf-programs {args.study}')")
        found = [r for r in found if r.get("event") in args.events]
    if not found:
        print(f"no HF program of this study runs now (event folders in {root})")
        return 0
    code = 0
    for record in found:
        why = end_group(record)
        if why is None:
            write_record(record["workdir"],
                         {**(read_record(record["workdir"]) or {}), "failed": True})
            print(f"ended {_line(record)}")
        else:
            print(f"pas study hf-stop: cannot end {_line(record)}: {why}", file=sys.stderr)
            code = 1
    return code
