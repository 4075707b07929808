"""PAS per known-truth problem type: median and worst |error|, U95 coverage, HF count.

The problems, their exact truths and the split into tuning and held-out types
are :mod:`harness.known_truth` (docs/explanation/known-truth.md).

Run: ``python benchmarks/studies/known_truth.py [N] [--types core,miss] [--held-out]
[--preset paper]``
prints, per problem type, median |error|, worst |error|, U95 coverage,
median HF count and convergence, and writes ``runs.csv``.  ``N`` data sets
per type; ``--held-out`` runs the held-out types instead of the tuning ones.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import (  # noqa: E402
    TYPES,
    add_study_arguments,
    run_one,
    select_types,
    settings_from_args,
    summarise,
)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_study_arguments(ap, n=10)
    ap.add_argument("--preset", default=None, help="run_pas preset (e.g. paper)")
    ap.add_argument("--set", action="append", default=[],
                    help="extra run_pas setting NAME=VALUE (python literal), repeatable")
    ap.add_argument("--out", default="pas-output/known-truth")
    args = ap.parse_args(argv)
    try:
        settings = settings_from_args(args.set)
        names = select_types(args.types, held_out=args.held_out)
    except ValueError as exc:
        ap.error(str(exc))
    if args.preset:
        settings["preset"] = args.preset
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in names:
        for r in range(args.first, args.first + args.n):
            row = run_one(make_problem(TYPES[name], r), max_hf=args.max_hf, **settings)
            rows.append(row)
            print(f"{name} r{r}: err {row['error']:+.3f} HF {row['n_hf']} "
                  f"cov {row['covered']} ({row['seconds']:.1f} s)", flush=True)
        pd.DataFrame(rows).to_csv(out / "runs.csv", index=False)
    table = summarise(pd.DataFrame(rows))
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(table.round(3).to_string(index=False))
    return table


if __name__ == "__main__":
    main()
