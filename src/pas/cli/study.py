"""``pas study``: ask/tell campaigns whose HF results arrive from another process, days later.

::

    pas study create STUDY.db --config study.toml
    pas study ask STUDY.db [-n N] [--format table|csv|json] [-o FILE]
    pas study tell STUDY.db EVENT VALUE | EVENT --error MSG | EVENT --load N=V ... | --csv FILE
        [--replace]
    pas study status STUDY [--json] [--events] [--refresh]
    pas study set STUDY.db [--precision P] [--eps1 E] [--eps2 C] [--k1 K] [--k2 K] [--max-hf N]
        [--max-failures N]
    pas study refit STUDY.db --target NAME [--out DIR]   (pas.cli.study_loads)
    pas study run STUDY.db [-q Q] [--workers N] [--pending resubmit|wait]
    pas study retry STUDY.db [EVENT ...]
    pas study hf-programs STUDY [--json]        (pas.cli.study_programs)
    pas study hf-stop STUDY [EVENT ...]
    pas study backup STUDY.db COPY.db

The study file is a :mod:`pas.study.store` (SQLite): ``tell`` only records the
result (any number of processes at once), ``ask`` replays the study, uses the
results told since the last ask and marks the next events pending.

The TOML file (paths relative to it; every key in ``docs/guide/study-file.md``)::

    n_waves = 16364          # required: wave encounters in the LF run
    p_exp = 2.55e-3          # required: target exceedance probability
    precision = "10%"        # stop once the U95 of the MPM is within ±10 % (or eps1 =
                             # a limit in load units, the paper's rule; one is required)
    [lf]
    file = "peaks.csv"       # .csv, .parquet or .npy
    column = "lf"            # required for .csv/.parquet
    [oracle]                 # optional, for 'pas study run': a command per event
    command = ["python", "cfd.py", "--event", "{id}", "--lf", "{lf}", "--out", "{result}"]

``pas study run`` drives the study with that oracle, storing each result as it
arrives; kill it at any time and run it again to continue (same ``-q``; the
batch size of the first run is the default).  ``pas study set`` changes the
stopping limits or the budget of a study, converged or not (recorded in the
store; no decision taken so far depends on them).  ``pas study retry`` runs
failed events again once their cause is fixed: the study continues as if they
had not failed (:mod:`pas.study.amend`; no told result is lost).  ``pas study
backup`` writes a consistent one-file copy of the study, also while it runs
(copying the file itself may miss the newest results, which SQLite keeps in
``STUDY.db-wal`` until the run ends).  ``tell
--replace`` corrects a told value, a failure or named loads (``--load
NAME=VALUE``); the old ones stay in the store's audit trail (``pas study
status --events``).
"""

from __future__ import annotations

import os
import sys

from ._parsers import command_parser
from ._stopping_options import precision_option
from .study_ask_tell import ask, tell, why_finished
from .study_config import check_oracle_command, load_config, load_peaks, study_objects
from .study_loads import add_parsers as add_load_parsers
from .study_loads import refit_command
from .study_programs import add_parsers as add_program_parsers
from .study_programs import list_programs, stop_programs

__all__ = ["add_parser", "run", "load_config", "load_peaks"]


EPILOG = """\
examples:
  pas study create campaign.db --config study.toml   # LF peaks, n_w, P_exp, eps1 from TOML
  pas study ask campaign.db -n 4 --format csv -o next.csv   # next 4 events for the basin/CFD
  pas study tell campaign.db 1532 812.5              # event id 1532 gave 812.5 kN
  pas study tell campaign.db 877 0                   # no impact: a false positive
  pas study tell campaign.db --csv results.csv       # columns id, hf (from any process)
  pas study status campaign.db                       # MPM so far, convergence, pending
  pas study set campaign.db --eps1 10 --max-hf 80    # tighter limit, bigger budget
  pas study run campaign.db -q 4 --workers 4         # drive it with the TOML's [oracle]
  pas study tell campaign.db 1532 120.5 --replace    # correct a typo (old value kept)
  pas study tell campaign.db 1532 --load panel_p3=40.1 --load deck=812.5 --replace
  pas study retry campaign.db                        # failed events run again
  pas study hf-programs run1                         # HF programs of 'pas run --out run1' running
  pas study hf-stop run1 w00382                      # end one (it runs again on resume)
  pas study backup campaign.db copy.db               # one-file copy, also while it runs
"""


def _action(cmds, name: str, help: str):
    """A ``pas study`` action whose ``--help`` starts with its one-line ``help``."""
    return cmds.add_parser(name, help=help, description=help[0].upper() + help[1:] + ".")


def add_parser(sub) -> None:
    p = command_parser(
        sub, "study", "ask/tell HF campaigns kept in a crash-safe study file", __doc__, EPILOG
    )
    cmds = p.add_subparsers(dest="study_command", metavar="<action>", required=True)
    c = _action(cmds, "create", "create STUDY.db from a TOML configuration")
    c.add_argument("study", metavar="STUDY.db")
    c.add_argument("--config", required=True, metavar="study.toml")
    a = _action(cmds, "ask", "print the next event(s) for the HF tool, marked pending")
    a.add_argument("study", metavar="STUDY.db")
    a.add_argument("-n", type=int, default=1, metavar="N", help="events wanted (default 1)")
    a.add_argument("--format", choices=("table", "csv", "json"), default=None,
                   help="default: csv or json for an --output FILE ending so, else table")
    a.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")
    t = _action(cmds, "tell", "record HF results (from any process)")
    t.add_argument("study", metavar="STUDY.db")
    t.add_argument("event", nargs="?", metavar="EVENT", help="event id as printed by ask")
    t.add_argument("value", nargs="?", metavar="VALUE", help="HF peak load (0 = no impact)")
    t.add_argument("--error", metavar="MSG", help="record a failed HF evaluation instead")
    t.add_argument("--csv", metavar="FILE", help="results table (CSV or Parquet)")
    t.add_argument("--id-column", default="id")
    t.add_argument("--value-column", default="hf",
                   help="column of the HF values (default hf, as the table oracle; A,B: one "
                        "named load per column)")
    t.add_argument("--replace", action="store_true",
                   help="replace a result told before (the old one is kept in the audit trail)")
    add_load_parsers(cmds, t)
    r = _action(cmds, "run", "drive the study with the [oracle] of its TOML file")
    r.add_argument("study", metavar="STUDY.db")
    r.add_argument("-q", "--batch-size", type=int, metavar="Q",
                   help="events per batch (default: the study's batch_size, else 1)")
    r.add_argument("--workers", type=int, metavar="N", help="run a batch in N local processes")
    r.add_argument("--pending", choices=("resubmit", "wait"), default="resubmit",
                   help="events a killed run left without a result (default resubmit)")
    r.add_argument("--quiet", action="store_true", help="no line per HF result")
    s = _action(
        cmds,
        "status",
        "print the MPM so far, whether it has converged, the counts and the pending events",
    )
    s.add_argument("study", metavar="STUDY",
                   help="study store, or the --out folder of pas run (its study.sqlite)")
    s.add_argument("--json", action="store_true")
    s.add_argument("--events", action="store_true",
                   help="also every event asked, replaced results and asks dropped by a retry")
    s.add_argument("--refresh", action="store_true",
                   help="replay the log and recompute the result (default: the stored one)")
    c = _action(cmds, "set", "change the stopping limits or the budget of a study")
    c.add_argument("study", metavar="STUDY.db")
    c.add_argument("--precision", type=precision_option, metavar="P",
                   help="precision target, e.g. 10%% or 0.1 (the U95 within +-P of the MPM)")
    c.add_argument("--eps1", type=float, metavar="E", help="limit on the distribution change")
    c.add_argument("--eps2", type=float, metavar="C", help="limit on the COV of the MPM")
    c.add_argument("--k1", type=int, metavar="K", help="window of the distribution change")
    c.add_argument("--k2", type=int, metavar="K", help="window of the MPM COV")
    c.add_argument("--max-hf", type=int, metavar="N", help="budget of HF evaluations")
    c.add_argument("--max-failures", type=int, metavar="N", help="failed calls tolerated")
    y = _action(cmds, "retry", "run failed events again (after fixing their cause)")
    y.add_argument("study", metavar="STUDY.db")
    y.add_argument(
        "events", nargs="*", metavar="EVENT", help="event ids (default: every failed one)"
    )
    add_program_parsers(cmds)
    b = _action(cmds, "backup", "write a consistent one-file copy of the study (also while it "
                "runs)")
    b.add_argument("study", metavar="STUDY.db")
    b.add_argument("copy", metavar="COPY.db", help="the new file")
    p.set_defaults(func=run)


def run(args) -> int:
    from .study_status import status

    return {"create": _create, "ask": ask, "tell": tell, "status": status, "run": _drive,
            "set": _set, "retry": _retry, "refit": refit_command, "hf-programs": list_programs,
            "hf-stop": stop_programs, "backup": _backup}[args.study_command](args)


# -- actions ----------------------------------------------------------------
def _create(args) -> int:
    from ..api import make_study
    from ..study.inputs import lf_table

    cfg = load_config(args.config)
    if os.path.exists(args.study):
        raise ValueError(f"{args.study} already exists (continue it with 'pas study ask')")
    lf, ids, meta = load_peaks(cfg["lf"])
    kw = {k: cfg[k] for k in ("threshold", "seed", "n_waves_convention") if k in cfg}
    objects = study_objects(cfg)
    try:
        study = make_study(objects.pop("strategy"), lf_table(lf, ids, meta, "lf.meta_columns"),
                           n_waves=cfg["n_waves"], p_exp=cfg["p_exp"], store=args.study,
                           **kw, **objects)
        if "oracle" in cfg:
            check_oracle_command(cfg["oracle"], study.lfset.event(0), args.config)
    except BaseException:
        for suffix in ("", "-wal", "-shm"):
            if os.path.exists(args.study + suffix):
                os.remove(args.study + suffix)
        raise
    study.store.put("batch_size", cfg.get("batch_size", 1))
    if "oracle" in cfg:
        study.store.put("oracle", cfg["oracle"])
    study.store.close()
    print(f"created {args.study}: {study.strategy.name.upper()} on {study.lfset.n} LF peaks "
          f"(seed {study.seed}); next: pas study ask {args.study}")
    return 0


def _drive(args) -> int:
    from ..study.oracle_spec import oracle_from_spec
    from ..study.oracles import OracleFailureLimit
    from ..study.resume import open_study
    from ..study.store import StudyStore
    from ._progress import Progress

    store = StudyStore(args.study, create=False)
    spec = store.get("oracle")
    if spec is None:
        raise ValueError(f"{args.study} has no oracle: add an [oracle] table to the TOML file "
                         "at create time, or use 'pas study ask/tell'")
    q = args.batch_size if args.batch_size is not None else store.get("batch_size", 1)
    if q < 1:
        raise ValueError(f"--batch-size must be at least 1, got {q}")
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be at least 1, got {args.workers}")
    study = open_study(store, consume=False)
    progress = Progress(sys.stdout, quiet=args.quiet, command="pas study run")
    oracle = oracle_from_spec(spec)
    try:
        res = study.optimize(oracle, batch_size=q, n_workers=args.workers,
                             pending=args.pending, callback=progress)
    except (KeyboardInterrupt, BrokenPipeError) as exc:
        from ._progress import stopped

        raise stopped("pas study run", exc, study, store=args.study,
                      resume=f"'pas study run {args.study}'", oracle=oracle) from None
    except OracleFailureLimit as exc:
        print(exc.result.summary())
        print(f"pas study run: error: {getattr(exc, 'reason', exc)}; fix the oracle, then "
              f"'pas study retry {args.study}' and run again, or raise the limit with "
              f"'pas study set {args.study} --max-failures N'", file=sys.stderr)
        return 1
    finally:
        store.close()
    print(res.summary())
    from . import EXIT_FAILED_LEFT_OUT
    return EXIT_FAILED_LEFT_OUT if res.n_failed else 0


def _backup(args) -> int:
    from ..study.store import StudyStore

    with StudyStore(args.study, create=False) as store:
        if store.is_new and not store.get("longterm"):
            raise ValueError(f"{args.study} holds no study (a copy of a study's file made while "
                             "its -wal file held the results?)")
        store.backup(args.copy)
    print(f"copied {args.study} to {args.copy} (one file, every result stored so far)")
    return 0


def _retry(args) -> int:
    from ..study.store import StudyStore

    with StudyStore(args.study, create=False) as store:
        if store.is_new:
            raise ValueError(f"{args.study} holds no study")
        report = store.retry_failed(args.events or None)
    if not report["retried"]:
        print(f"{args.study}: no failed event to retry")
        return 0
    print(f"{args.study}: {len(report['retried'])} failed event(s) will run again "
          f"({', '.join(report['retried'])}); {report['dropped']} later ask(s) taken out of the "
          f"log, {report['kept']} of their results kept and reused if asked again; "
          f"'pas study run {args.study}' runs them, or run them yourself and 'pas study tell' "
          "their results")
    return 0


def _set(args) -> int:
    from ..study.resume import open_study
    from ..study.store import StudyStore

    names = {
        "precision": "--precision",
        "eps1": "--eps1",
        "eps2": "--eps2",
        "k1": "--k1",
        "k2": "--k2",
        "max_hf": "--max-hf",
        "max_failures": "--max-failures",
    }
    changes = {k: getattr(args, k) for k in names if getattr(args, k) is not None}
    if not changes:
        raise ValueError(f"give at least one of {', '.join(names.values())}")
    with StudyStore(args.study, create=False) as store:
        old = store.settings()
        try:
            study = open_study(store, consume=False, changes=changes)
        except ValueError as exc:
            raise ValueError(_option_names(str(exc), names)) from None
    for key, value in changes.items():
        if old.get(key) != value:
            print(f"{args.study}: {key} {old.get(key)} -> {value}")
    print(f"recorded in {args.study}; the study is "
          + ("finished (" + why_finished(study) + ")" if study.finished else
             f"not finished: continue with 'pas study ask {args.study}'"))
    return 0


def _option_names(msg: str, names: dict) -> str:
    """An error of the study constructor with its argument names as the CLI options."""
    for key, opt in names.items():
        if msg.startswith(key + " "):
            return opt + msg[len(key):]
    return msg
