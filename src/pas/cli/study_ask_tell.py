"""``pas study ask`` and ``pas study tell``: events out, results in, in any process.

``ask`` replays the study, uses the results told since the last ask and
prints the next events (marked pending); ``tell`` only records results by
event id, so any number of processes may tell at once.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from .study_loads import tell_loads

__all__ = ["ask", "tell", "why_finished"]


def _event_row(ev) -> dict:
    row = {"id": ev.id, "index": ev.index, "lf": ev.lf, "d": ev.d}
    for k, v in ev.meta.items():
        row[k if k not in row else f"meta.{k}"] = v
    return row


def ask(args) -> int:
    """``pas study ask``: the next events, marked pending, as a table, CSV or JSON."""
    from ..study.resume import open_study
    from ..study.store import StudyStore

    if args.n < 1:
        raise ValueError(f"-n must be at least 1, got {args.n}")
    store = StudyStore(args.study, create=False)
    events, reused = [], []
    while len(events) < args.n:  # an event with a result a retry kept is told, not printed
        with store.transaction():
            study = open_study(store)
            initial = not study.state
            asked = study.ask(args.n - len(events))
            if initial and len(asked) < args.n - len(events):
                asked += study.ask(args.n - len(events) - len(asked))
            kept = {r.idx for r in store.outstanding() if r.has_result}  # results a retry kept
            fresh = [ev for ev in asked if ev.index not in kept]
            if fresh:
                store.mark_submitted(fresh)
        events += fresh
        again = [ev for ev in asked if ev.index in kept]
        if not again or {ev.index for ev in again} & {ev.index for ev in reused}:
            break  # nothing reused (the study asked what it could), or no progress
        reused += again
    store.close()
    if reused:
        print(f"{args.study}: {len(reused)} event(s) asked again after a retry took their kept "
              f"result ({', '.join(str(ev.id) for ev in reused)})", file=sys.stderr)
    if not events and not reused:
        print(f"{args.study}: nothing to ask ({why_finished(study)})", file=sys.stderr)
        return 0
    if len(events) > args.n:
        print(f"{args.study}: the study's first ask gives all {len(events)} events of its initial "
              f"design, more than -n {args.n}: the first model needs all of them; -n counts "
              "from the next ask on", file=sys.stderr)
    if events:
        _emit([_event_row(ev) for ev in events], args.format or _format_of(args.output),
              args.output)
    return 0


def _format_of(output) -> str:
    """The format an ``--output`` file's ending names (``.csv``, ``.json``), else a table."""
    suffix = Path(output).suffix.lower() if output else ""
    return {".csv": "csv", ".json": "json"}.get(suffix, "table")


def _emit(rows, fmt, output) -> None:
    import pandas as pd

    if fmt == "json":
        text = json.dumps(rows, indent=1, default=str) + "\n"
    elif fmt == "csv":
        text = pd.DataFrame(rows).to_csv(index=False)
    else:
        text = pd.DataFrame(rows).to_string(index=False) + "\n"
    if output:
        Path(output).write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)


def why_finished(study) -> str:
    """Why ``study`` asks for nothing more, in a few words."""
    if study.converged:
        return "converged"
    if study.max_hf is not None and study.n_hf + len(study.pending) >= study.max_hf:
        return f"max_hf={study.max_hf} reached, counting {len(study.pending)} pending"
    return "no LF peak left to sample"


def _check_value(text, field, where):
    try:
        v = float(text)
    except (TypeError, ValueError):
        raise ValueError(f"{where}{field} must be a number (the HF peak, 0 = no impact), "
                         f"got {text!r}") from None
    if not math.isfinite(v) or v < 0:
        raise ValueError(
            f"{where}{field} must be a finite load >= 0 (0 = no impact), got {text!r}; "
            "record a failed evaluation with --error/an 'error' column"
        )
    return v


def tell(args) -> int:
    """``pas study tell``: store results by event id (one, or a CSV of them)."""
    from ..study.inputs import read_table
    from ..study.store import StudyStore

    if args.load or "," in args.value_column:
        return tell_loads(args)
    if args.csv:
        if args.event is not None or args.error is not None:
            raise ValueError("give either EVENT VALUE / EVENT --error MSG or --csv FILE, not both")
        df = read_table(args.csv, columns=(args.id_column, args.value_column))
        name = Path(args.csv).name
        errors = df["error"] if "error" in df.columns else None
        told = []
        for i in range(len(df)):
            key = df[args.id_column].iloc[i]
            if key is None or (isinstance(key, float) and math.isnan(key)):
                raise ValueError(f"{name}: column {args.id_column!r} is empty in data row {i + 1}")
            err = None if errors is None or errors.isna().iloc[i] else str(errors.iloc[i])
            val = None if err else _check_value(df[args.value_column].iloc[i],
                                                f"column {args.value_column!r}",
                                                f"{name}, data row {i + 1}: ")
            told.append((key, val, err))
    else:
        if args.event is None:
            raise ValueError("EVENT is required (or --csv FILE)")
        if args.value is None and args.error is None:
            raise ValueError("VALUE is required (or --error MSG to record a failed evaluation)")
        if args.value is not None and args.error is not None:
            raise ValueError("give VALUE or --error MSG, not both")
        val = None if args.error else _check_value(args.value, "VALUE", "")
        told = [(args.event, val, args.error)]
    new = 0
    with StudyStore(args.study, create=False) as store:
        with store.transaction():
            for key, val, err in told:
                new += bool(store.tell_by_key(_key(key), val, error=err, source="cli",
                                              replace=args.replace))
    print(f"stored {new} result(s) in {args.study}"
          + (f" ({len(told) - new} already stored)" if new < len(told) else "")
          + ("; replaced results are listed by 'pas study status --events'" if args.replace
             else ""))
    return 0


def _key(x) -> str:
    if isinstance(x, float) and x.is_integer():
        return str(int(x))
    return str(x)
