"""Accuracy of PAS, AS and design waves on the analogues over replications.

Default: all twelve ids (eight paper-like, four ``-hard``); ``--cases`` takes
any of them, e.g. ``--cases 3a,3a-hard``.

Each replication r = 0 … N−1 draws a *new* analogue data set (wave phases and
the random parts of the HF model seeded with r) and runs each strategy with
seed r, so the spread covers Monte-Carlo variability of the data as well as
PAS's own draws — not only the conditional-draw noise on one frozen data set
that ``pas reproduce --replications`` shows.  Every replication is scored
against its own data set's HF truth.  The design waves (``rcw``, ``mler``) are
deterministic given the data set: they vary between replications only through
the data (their LF Monte-Carlo targets; the truth they are scored against).

Run: python benchmarks/validation_spread.py [N] [--cases 1a,3a] [--strategies pas,as,rcw]
[--out DIR] [--set band_marginals=alternate]
Writes runs.csv and summary.csv to DIR (default pas-output/spread).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import pandas as pd

from pas.validation import CASE_IDS, generate_case
from pas.validation.known_truth_runs import settings_from_args
from pas.validation.reproduce import _strategies, parse_strategies, run_case


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10)
    ap.add_argument("--cases", default=",".join(CASE_IDS))
    ap.add_argument("--out", default="pas-output/spread")
    ap.add_argument("--max-hf", type=lambda v: None if v == "none" else int(v), default=160,
                    help="HF budget per run (default 160, as every study; 'none': none)")
    ap.add_argument("--strategies", default=",".join(_strategies()))
    ap.add_argument("--set", action="append", default=[],
                    help="extra screening setting NAME=VALUE (python literal), repeatable")
    args = ap.parse_args(argv)
    settings = settings_from_args(args.set)
    strategies = parse_strategies(args.strategies)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for case in args.cases.split(","):
        for r in range(args.n):
            t0 = time.perf_counter()
            data = generate_case(case, seed=r)
            gen = time.perf_counter() - t0
            for strategy in strategies:
                _, row = run_case(data, strategy=strategy, seed=r, max_hf=args.max_hf,
                                  settings=settings)
                row.update(replication=r, truth=data.truth_mpm, generate_s=gen)
                rows.append(row)
                print(f"{case} r{r} {strategy}: M2 {row['M2']:+.3f} HF {row['n_hf']} "
                      f"({row['seconds']:.1f} s)", flush=True)
            pd.DataFrame(rows).to_csv(out / "runs.csv", index=False)
    runs = pd.DataFrame(rows)
    runs["absM2"] = runs["M2"].abs()
    summary = runs.groupby(["case", "strategy"]).agg(
        truth_median=("truth", "median"), n_hf_median=("n_hf", "median"),
        M1_median=("M1", "median"), M2_median=("M2", "median"),
        absM2_median=("absM2", "median"), absM2_max=("absM2", "max"),
        M2_min=("M2", "min"), M2_max=("M2", "max"), M3_median=("M3", "median"),
        converged=("converged", "mean"), covered=("covered", "mean")).reset_index()
    summary.to_csv(out / "summary.csv", index=False)
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(summary.round(4).to_string(index=False))


if __name__ == "__main__":
    main()
