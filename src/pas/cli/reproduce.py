"""``pas reproduce``: the paper's validation on the package's synthetic analogues.

::

    pas reproduce [CASE ...] [--all] [--strategies pas,as,rcw] [--replications N]
                  [--scale S] [--out DIR] [--properties]

Generates (and caches under ``$PAS_CACHE`` or ``./pas-cache``) the analogue of
each case — LF peaks and the full HF Monte-Carlo, built from seeded physics
models because the paper's HF data are not public — prints its data
properties (τ, λ_U/λ_L, misses, impact rate, truth against the paper), runs
PAS, AS and the design waves (RCW; MLER on request) on it with the paper's
settings, and prints a Table-4-style table: truth MPM of the analogue, the
paper's truth, predicted MPM, HF samples, M1, M2, M3.  With ``--out`` the
tables are written as ``properties.csv``, ``table.csv`` (and ``runs.csv``,
one row per run) with figures per case (``case_<id>.png``;
``design_<id>.png`` with the RCW points) and ``metrics.png``.
``--properties`` stops after the data properties.
"""

from __future__ import annotations

import json
import sys

from ._parsers import command_parser

__all__ = ["add_parser", "run"]

EPILOG = """\
examples:
  pas reproduce 1a --out pas-output          # case 1a, table + figures (< 1 min)
  pas reproduce --all --replications 10      # all twelve cases, 10 PAS/AS seeds each
  pas reproduce 2a 2b --strategies rcw,mler  # design waves only (one episode per level)
  pas reproduce 3a 4a --scale 0.2 --quiet    # quick, shorter Monte-Carlo
  pas reproduce --all --properties           # data properties of all twelve analogues
  pas reproduce long-term-3                  # long-term green water: PAS long-term, uniform,
                                             # contour and LF-only on one data set (minutes)
  pas reproduce cfd --replications 10        # OpenFOAM green water: PAS, paper preset, AS,
                                             # top-N, MLER against the brute-force CFD truth
cases: cfd (green water computed by OpenFOAM, from the package's CFD table);
  1a 1b (2nd-order crests), 2a 2b (hog/sag VBM), 3a 3b (green water), 4a 4b (slamming);
  3a-hard 3b-hard 4a-hard 4b-hard: the first impact analogues (upper-tail dependent, misses
  at the threshold), kept as a robustness test
"""


def add_parser(sub) -> None:
    """Register ``pas reproduce`` on the sub-command parser ``sub``."""
    p = command_parser(
        sub, "reproduce", "reproduce the paper's validation on synthetic analogues", __doc__, EPILOG
    )
    p.add_argument(
        "cases", nargs="*", metavar="CASE", help="case ids (1a ... 4b, 3a-hard ... 4b-hard)"
    )
    p.add_argument("--all", action="store_true",
                   help="all twelve cases (eight paper-like, four -hard)")
    p.add_argument("--replications", type=int, default=1, metavar="N",
                   help="PAS/AS seeds per case on the same data set (default 1)")
    p.add_argument("--scale", type=float, default=1.0, metavar="S",
                   help="fraction of the paper's Monte-Carlo duration (default 1.0)")
    p.add_argument("--seed", type=int, default=0, help="data-set seed (default 0)")
    p.add_argument("--strategies", default="pas,as,rcw", metavar="LIST",
                   help="comma-separated strategies from pas, as, rcw, mler (default pas,as,rcw)")
    p.add_argument("--out", metavar="DIR", help="write table.csv, runs.csv and figures here")
    p.add_argument("--no-figures", action="store_true", help="skip the figures")
    p.add_argument(
        "--no-cache", action="store_true", help="regenerate, do not read/write the cache"
    )
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.add_argument("--json", action="store_true", help="print the table as JSON records")
    p.add_argument("--properties", action="store_true",
                   help="only the data properties of the analogues; run no strategy")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..validation import CASE_IDS, get_case
    from ..validation.properties import format_properties
    from ..validation.reproduce import format_table, parse_strategies, reproduce

    long_term = [c for c in args.cases if c.strip().lower().startswith("long-term")]
    if long_term:
        return _run_long_term(args, long_term)
    if any(c.strip().lower() == "cfd" for c in args.cases):
        return _run_cfd(args)
    if args.all and args.cases:
        raise ValueError("give case ids or --all, not both")
    if not args.all and not args.cases:
        raise ValueError(f"name at least one case ({' '.join(CASE_IDS)}) or use --all")
    cases = list(CASE_IDS) if args.all else [get_case(c).id for c in args.cases]
    strategies = parse_strategies(args.strategies)
    progress = None if args.quiet else (lambda msg: print(msg, file=sys.stderr, flush=True))
    res = reproduce(cases, replications=args.replications, scale=args.scale, out=args.out,
                    seed=args.seed, strategies=strategies, figures=not args.no_figures,
                    cache=not args.no_cache, progress=progress,
                    properties_only=args.properties)
    table = res["properties"] if args.properties else res["table"]
    if args.json:
        print(json.dumps(json.loads(table.to_json(orient="records")), indent=1))
    else:
        print("Synthetic analogues of the paper's cases (not the paper's data).")
        print("Data properties (LF pool: over the threshold, or all peaks):")
        print(format_properties(res["properties"]))
        if not args.properties:
            print("\nResults; metrics vs the analogue's own HF Monte-Carlo truth:")
            print(format_table(table))
        if args.out:
            print(f"written: {', '.join(str(f) for f in res['files'])}")
    return 0


def _run_cfd(args) -> int:
    """``pas reproduce cfd``: the strategies against the brute-force OpenFOAM truth."""
    from ..validation.cfd_compare import compare_cfd, format_cfd, summarise_cfd

    if len(args.cases) != 1 or args.all:
        raise ValueError("give the cfd case on its own: pas reproduce cfd")
    names = [s for s in parse_strategy_names(args.strategies) if s in ("pas", "paper", "as")]
    runs, facts = compare_cfd(seeds=range(args.seed, args.seed + args.replications),
                              strategies=tuple(names) or ("pas", "paper", "as"))
    table = summarise_cfd(runs, facts)
    if args.json:
        print(json.dumps(json.loads(table.to_json(orient="records")), indent=1))
    else:
        print(format_cfd(table))
    if args.out:
        import os

        os.makedirs(args.out, exist_ok=True)
        runs.to_csv(os.path.join(args.out, "cfd_runs.csv"), index=False)
        table.to_csv(os.path.join(args.out, "cfd_table.csv"), index=False)
        print(f"written: {args.out}/cfd_runs.csv, {args.out}/cfd_table.csv")
    return 0


def parse_strategy_names(text):
    """``pas,as,paper`` as a list of names (``pas`` also brings the paper's preset)."""
    names = [s.strip().lower() for s in text.split(",") if s.strip()]
    return names + (["paper"] if "pas" in names and "paper" not in names else [])


def _run_long_term(args, cases) -> int:
    """``pas reproduce long-term-3 long-term-2``: the four long-term methods side by side."""
    from ..validation.long_term_compare import (
        LONG_TERM_IDS,
        format_long_term,
        reproduce_long_term,
    )

    if len(cases) != len(args.cases) or args.all:
        raise ValueError("give the long-term cases (long-term-3, long-term-2) on their own")
    progress = None if args.quiet else (lambda msg: print(msg, file=sys.stderr, flush=True))
    for case in cases:
        key = case.strip().lower()
        if key not in LONG_TERM_IDS:
            raise ValueError(f"unknown long-term case {case!r}; choose from "
                             f"{', '.join(LONG_TERM_IDS)}")
        res = reproduce_long_term(key, seed=args.seed + 1, scale=args.scale, out=args.out,
                                  cache=not args.no_cache, progress=progress)
        if args.json:
            print(json.dumps(json.loads(res["table"].to_json(orient="records")), indent=1))
            continue
        kept = res["plan"]
        print(f"{key}: synthetic long-term analogue, {int(kept['kept'].sum())} of {len(kept)} "
              f"scatter cells kept (estimated share of the dropped ones "
              f"{kept['share_rayleigh'][~kept['kept']].sum():.2%}); value at p_exceed "
              f"{res['table']['p_exceed'].iloc[0]:.3g} per encounter vs the brute-force truth:")
        print(format_long_term(res["table"]))
    return 0
