"""Several loads per HF event on the command line: ``pas study tell --load``, ``refit``.

::

    pas study tell STUDY.db EVENT --load deck_force=812 --load panel_p3=41.2
    pas study tell STUDY.db --csv basin.csv --value-column deck_force,panel_p3
    pas study refit STUDY.db --target panel_p3 [--out DIR] [--json]

``tell --load NAME=VALUE`` (repeated) records every load of one HF run, and
``tell --csv FILE --value-column A,B`` one per column for every row; the
study screens on its ``target``, which must be among them (an invalid other
load is kept as missing, as from an oracle; an ``error`` column fails the row).  ``refit``
analyses another stored load on the events the study chose
(:func:`pas.study.refit.refit`): the summary says the events were chosen for
the study's target, and ``--out`` receives the files ``pas run`` writes.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

__all__ = ["add_parsers", "tell_loads", "refit_command"]


def add_parsers(cmds, tell) -> None:
    """Add ``--load`` to the ``tell`` parser and the ``refit`` action to ``cmds``."""
    tell.add_argument("--load", action="append", metavar="NAME=VALUE",
                      help="one named load of the HF run (repeat for each; the study's target "
                           "among them), instead of VALUE")
    r = cmds.add_parser("refit", help="analyse another stored load on the same events, no HF run",
                        description="Analyse another load stored in STUDY.db on the events "
                                    "the study chose for its target, with no HF run.  The "
                                    "sample is not adapted to that load, and the summary says "
                                    "so; --out receives the files of 'pas run'.")
    r.add_argument("study", metavar="STUDY.db")
    r.add_argument("--target", required=True, metavar="NAME", help="the stored load to analyse")
    r.add_argument("--out", metavar="DIR", help="write the result files (as pas run) to DIR")
    r.add_argument("--unit", help="unit of the load, for the summary and figures")
    r.add_argument("--json", action="store_true", help="print the summary as JSON")


def _parse(items) -> dict:
    loads = {}
    for item in items:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ValueError(f"--load must be NAME=VALUE (e.g. --load deck_force=812), "
                             f"got {item!r}")
        if name in loads:
            raise ValueError(f"--load: load {name!r} is given twice")
        try:
            loads[name] = float(text)
        except ValueError:
            raise ValueError(f"--load {name}: the load must be a number, got {text!r}") from None
    return loads


def tell_loads(args) -> int:
    """``pas study tell`` with named loads: ``EVENT --load NAME=VALUE ...`` or ``--csv FILE
    --value-column A,B`` (one load per column, the study's target among them)."""
    from ..study.store import StudyStore

    if args.load and (args.event is None or args.value is not None or args.error is not None
                      or args.csv):
        raise ValueError("--load goes with EVENT alone: pas study tell STUDY.db EVENT "
                         "--load NAME=VALUE [--load NAME=VALUE ...]")
    with StudyStore(args.study, create=False) as store:
        target = store.settings().get("target")
        if args.load:
            told = [(args.event, _screened(_parse(args.load), target, "--load: ", args.study),
                     None)]
        else:
            told = _csv_told(args, target)
        new = 0
        with store.transaction():
            for key, (value, loads), error in told:
                new += bool(store.tell_by_key(key, value, error=error, loads=loads,
                                              source="cli", replace=args.replace))
    bad = sorted({n for _k, (_v, loads), _e in told for n, (_x, e) in (loads or {}).items()
                  if e})
    print(f"{'replaced' if args.replace else 'stored'} the loads of {new} event(s) in "
          f"{args.study}" + (f" ({len(told) - new} already stored)" if new < len(told) else "")
          + ("; the old values are listed by 'pas study status --events'" if args.replace
             and new else "")
          + (f"; invalid {', '.join(bad)} kept as missing" if bad else ""))
    return 0


def _screened(loads: dict, target, where: str, study) -> tuple:
    """``(screened value, checked loads)`` of one told event, or a one-line error."""
    from ..study.answers import check_hf_answer

    if target is None and len(loads) > 1:
        raise ValueError(f"{where}{study} has no target, so it takes one load per event, got "
                         f"{len(loads)} ({', '.join(loads)}); tell VALUE")
    if target is not None and target not in loads:
        raise ValueError(f"{where}{study} screens on {target!r}, which is not among the loads "
                         f"given ({', '.join(loads)})")
    value, error, checked = check_hf_answer(loads, target)
    if error is not None:
        name = target or next(iter(loads))
        raise ValueError(f"{where}the screened load {name} must be finite and >= 0 "
                         f"(0 = no impact), got {loads[name]!r}; record a failed evaluation "
                         "with --error MSG or an 'error' column")
    return value, checked


def _csv_told(args, target) -> list:
    """``(key, (value, loads), error)`` of every row of a results table with several columns."""
    from ..study.inputs import read_table

    if args.event is not None or args.error is not None:
        raise ValueError("give either EVENT VALUE / EVENT --error MSG or --csv FILE, not both")
    columns = args.value_column.split(",")
    if not all(columns) or len(set(columns)) < len(columns):
        raise ValueError(f"--value-column: give different column names separated by commas, "
                         f"got {args.value_column!r}")
    if target is not None and target not in columns:
        raise ValueError(f"--value-column: {args.study} screens on {target!r}; name its column "
                         f"among {args.value_column!r}")
    df = read_table(args.csv, columns=(args.id_column, *columns))
    name = Path(args.csv).name
    told = []
    for i, row in enumerate(df.to_dict("records")):
        key, error = row[args.id_column], row.get("error")
        if key is None or key != key:
            raise ValueError(f"{name}: column {args.id_column!r} is empty in data row {i + 1}")
        key = str(int(key)) if isinstance(key, float) and key.is_integer() else str(key)
        error = None if error is None or error != error else str(error)
        loads = {c: row[c] for c in columns}
        screened = ((None, None) if error else
                    _screened(loads, target, f"{name}, data row {i + 1}: ", args.study))
        told.append((key, screened, error))
    return told


def refit_command(args) -> int:
    """``pas study refit``: the result of another stored load on the same events."""
    import warnings

    from ..study.refit import refit_study

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        study, info = refit_study(args.study, args.target)
        result = study.result()
    result.refit = info
    for w in caught:
        print(f"pas study refit: warning: {w.message}", file=sys.stderr)
    inputs = {"study": str(args.study), "target": args.target, "unit": args.unit}
    if args.out:
        summary = result.save(Path(args.out), inputs=inputs, lfset=study.lfset)
    else:
        summary = {**result.to_dict(), "summary": result.summary(unit=args.unit), "inputs": inputs}
    if args.json:
        from .._support.strict_json import json_data

        print(json.dumps(json_data(summary), indent=2))
    else:
        print(result.summary(unit=args.unit))
        if args.out:
            print(f"results written to {args.out}/ (draw them with: pas plot {args.out} "
                  "--kind all)")
    return 0

