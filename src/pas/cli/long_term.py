"""``pas long-term``: the long-term design value over a scatter diagram, one HF budget shared.

::

    pas long-term SEA_STATES.csv --lf DIR_OR_PATTERN --oracle KIND:ARGS
                  (--p-exceed P | --return-period YEARS) [--precision 10%] [options]

``SEA_STATES.csv`` has one row per sea state: ``name``, ``probability`` (share
of time), ``n_waves`` (wave encounters of its LF run), ``duration`` (s, of
its LF run) and any descriptive columns (``hs``, ``tp``, ...).  ``--lf``
finds each sea state's LF peaks: a folder holding ``<name>.csv``,
``<name>.parquet`` or ``<name>.npy``, or a pattern with ``{name}``
(``lf/{name}_peaks.csv``); the files are read as by ``pas run``
(``--lf-column``, ``--id-column``, ``--meta-columns``).  The oracle is given
as for ``pas run`` (``table:``, ``python:``, ``command:``); the event it gets
carries ``event.sea_state``.  :func:`pas.run_long_term` runs the analysis
(crash-safe in ``--study``, default ``OUT/long-term.sqlite``: the same
command again resumes it); the result goes to stdout and to ``--out``
(``summary.json``, ``contributions.csv``, ``distribution.csv``, ``history.csv``;
with ``--figures`` the three long-term figures in ``OUT/figures/``).
``--precision`` stops once the U95 of the value is within that share of it
(:mod:`pas.longterm.target`).  Exit codes as
``pas run``: 0 done, 2 bad input, 130 interrupted.
"""

from __future__ import annotations

import math
from pathlib import Path

from ._parsers import command_parser
from ._stopping_options import precision_option
from .run import _positive_int  # the same rule as pas run's options

__all__ = ["add_parser", "lf_files", "run"]

EPILOG = """\
examples:
  # per-sea-state LF peak files lf/<name>.csv, HF results keyed by sea state and event id
  pas long-term sea_states.csv --lf lf/ --oracle table:hf.csv --p-exceed 2e-6 --out lt1

  # the 20-year value, a Python oracle, 300 HF events in all
  pas long-term sea_states.csv --lf 'runs/{name}/peaks.npy' \\
      --oracle python:my_oracles.py:green_water --return-period 20 --max-hf 300

  # stop once the U95 of the value is within ±10 % of it; draw the figures
  pas long-term sea_states.csv --lf lf/ --oracle table:hf.csv --p-exceed 2e-6 \\
      --precision 10% --figures --out lt2

exit codes: 0 done; 2 bad input; 130 interrupted (see 'pas --help')
"""
_LF_SUFFIXES = (".csv", ".parquet", ".npy", ".txt")


def add_parser(sub) -> None:
    """Register ``pas long-term`` on the sub-command parser ``sub``."""
    p = command_parser(
        sub,
        "long-term",
        "long-term design value over a scatter diagram (one HF budget)",
        __doc__,
        EPILOG,
    )
    p.add_argument("sea_states", metavar="SEA_STATES", help="sea-state table (.csv or .parquet)")
    p.add_argument("--lf", required=True, metavar="DIR_OR_PATTERN",
                   help="folder of <name>.csv/.parquet/.npy files, or a pattern with {name}")
    p.add_argument("--lf-column", metavar="COL", help="column of the LF peaks (default 'lf')")
    p.add_argument("--id-column", metavar="COL", help="column of event ids (default 'id')")
    p.add_argument("--meta-columns", metavar="A,B", type=lambda s: [c for c in s.split(",") if c],
                   default=[], help="columns handed to the oracle as event.meta")
    p.add_argument("--oracle", required=True, metavar="KIND:ARGS",
                   help="table:FILE[:ID_COL:VALUE_COL] | python:MODULE:FUNCTION | command:ARGS")
    level = p.add_mutually_exclusive_group(required=True)
    level.add_argument("--p-exceed", type=float, metavar="P",
                       help="long-term exceedance probability per wave encounter")
    level.add_argument("--return-period", type=float, metavar="YEARS",
                       help="return period in years (with --hours-per-year)")
    p.add_argument("--hours-per-year", type=float, default=8766.0, metavar="H",
                   help="hours at sea per year (default 8766)")
    p.add_argument("--max-hf", type=_positive_int, default=400, metavar="N",
                   help="HF evaluations of all sea states together (default 400)")
    p.add_argument("--eps1", type=float, metavar="E",
                   help="stopping limit of each sea state's study (load units)")
    p.add_argument("--precision", type=precision_option, metavar="P",
                   help="stop once the U95 of the long-term value is within ±P of it "
                        "(10%% or 0.1); may change when a stored analysis is continued")
    p.add_argument("--figures", action="store_true",
                   help="draw the long-term figures into OUT/figures/ (distribution, "
                        "allocation over the first two descriptive columns, convergence)")
    p.add_argument("--unit", help="unit of the HF load, for the summary and the figures "
                                  "(e.g. kN)")
    p.add_argument("--seed", type=int, help="random seed (default: drawn and reported)")
    p.add_argument("--study", metavar="FILE",
                   help="the analysis' store (default OUT/long-term.sqlite)")
    p.add_argument("--no-store", action="store_true", help="keep no store")
    p.add_argument("--timeout", type=float, metavar="S", help="seconds per event (command oracle)")
    p.add_argument("--out", default="pas-long-term", metavar="DIR",
                   help="output folder (default: pas-long-term)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.set_defaults(func=run)


def lf_files(spec, names):
    """The LF peak file of each sea state ``name`` from a folder or a ``{name}`` pattern.

    Raises
    ------
    ValueError
        Naming ``--lf`` and the sea states without a file.
    """
    spec = str(spec)
    found, missing = {}, []
    for name in names:
        if "{name}" in spec:
            cands = [Path(spec.replace("{name}", str(name)))]
        elif Path(spec).is_dir():
            cands = [Path(spec) / f"{name}{suf}" for suf in _LF_SUFFIXES]
        else:
            raise ValueError(f"--lf {spec}: give a folder of <name>.csv files or a pattern "
                             "containing {name}")
        hit = [c for c in cands if c.is_file()]
        if hit:
            found[name] = hit[0]
        else:
            missing.append(str(name))
    if missing:
        raise ValueError(f"--lf {spec}: no LF peak file for sea state(s) "
                         f"{', '.join(missing[:5])}{' ...' if len(missing) > 5 else ''}")
    return found


def _read_table(path):
    import pandas as pd

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"SEA_STATES {path}: no such file")
    table = pd.read_parquet(path) if path.suffix == ".parquet" else pd.read_csv(path)
    need = [c for c in ("name", "probability", "n_waves", "duration") if c not in table.columns]
    if need:
        raise ValueError(f"SEA_STATES {path}: missing column(s) {', '.join(need)} (one row per "
                         "sea state: name, probability, n_waves, duration)")
    table["name"] = table["name"].astype(str)
    return table


def _check_numbers(args):
    if args.p_exceed is not None and not 0.0 < args.p_exceed < 1.0:
        raise ValueError(f"--p-exceed must lie in (0, 1), got {args.p_exceed:g}")
    for opt, v in (("--return-period", args.return_period), ("--eps1", args.eps1),
                   ("--hours-per-year", args.hours_per_year), ("--timeout", args.timeout)):
        if v is not None and not (math.isfinite(v) and v > 0):
            raise ValueError(f"{opt} must be a positive number, got {v:g}")


def read_inputs(args):
    """The sea-state table and ``name -> DataFrame(lf, id, meta...)`` from the options."""
    import pandas as pd

    from ..study.inputs import read_lf_peaks

    _check_numbers(args)
    table = _read_table(args.sea_states)
    peaks = {}
    names = {"file": "--lf", "column": "--lf-column", "id_column": "--id-column",
             "meta_columns": "--meta-columns"}
    for name, file in lf_files(args.lf, table["name"]).items():
        lf, ids, meta = read_lf_peaks(file, column=args.lf_column, id_column=args.id_column,
                                      meta_columns=args.meta_columns, guess_columns=True,
                                      names=names)
        frame = pd.DataFrame({"lf": lf, "id": ids if ids is not None else range(len(lf))})
        if meta is not None:
            frame = frame.join(pd.DataFrame(meta))
        peaks[name] = frame
    return table, peaks


def run(args) -> int:
    """Execute ``pas long-term``; returns the exit code (:data:`pas.cli.EXIT_CODES`)."""
    from .._support.strict_json import dumps
    from .run import output_and_oracle

    table, peaks = read_inputs(args)
    out, oracle = output_and_oracle(args)
    from ..longterm import run_long_term
    from ..study.schema import StoreError

    study = None if args.no_store else Path(args.study or out / "long-term.sqlite")
    out.mkdir(parents=True, exist_ok=True)
    try:
        result = run_long_term(table, peaks, oracle, p_exceed=args.p_exceed,
                               return_period=args.return_period,
                               hours_per_year=args.hours_per_year, max_hf=args.max_hf,
                               seed=args.seed, study=study, eps1=args.eps1,
                               precision=args.precision)
    except StoreError as exc:
        other = "--study" if args.study else "--out"
        raise ValueError(f"{exc} (to start a new analysis use another {other} or "
                         "--no-store)") from None
    summary = {"value": float(result.value), "band": [float(b) for b in result.band],
               "p_exceed": float(result.p_exceed), "n_hf": int(result.n_hf),
               "precision": result.precision, "converged": result.converged,
               "forecast": result.forecast,
               "seed": result.seed, "sea_states": str(args.sea_states), "lf": str(args.lf),
               "oracle": args.oracle, "study": None if study is None else str(study)}
    text = dumps(summary, indent=2, sort_keys=False)  # no inf or NaN: null
    (out / "summary.json").write_text(text + "\n")
    result.contributions.to_csv(out / "contributions.csv", index=False)
    result.distribution.to_csv(out / "distribution.csv", index=False)
    result.history.to_csv(out / "history.csv", index=False)
    if args.figures:
        from ..plotting.long_term import save_long_term_figures

        save_long_term_figures(result, out / "figures", unit=args.unit)
    if args.json:
        print(text)
    else:
        print(result.summary(unit=args.unit))
        print(f"results written to {out}/")
    return 0
