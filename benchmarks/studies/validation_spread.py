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

Run: python benchmarks/studies/validation_spread.py [N] [--cases 1a,3a] [--strategies pas,as,rcw]
[--out DIR] [--set band_marginals=alternate]
Writes runs.csv and summary.csv to DIR (default pas-output/spread).

``--write`` runs nothing: it re-reads ``DIR/runs.csv`` and writes the two
tables of ``docs/results/validation.md`` and its summary (from the same rows as
``summary.csv``) between that page's markers (with
``--known-truth DEFAULTS.csv PAPER.csv``, the ``runs.csv`` of
``known_truth.py`` and ``known_truth.py --preset paper``, also the summary
table of ``README.md``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

from pas.validation import CASE_IDS, generate_case
from pas.validation.reproduce import _strategies, parse_strategies, run_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth_runs import settings_from_args  # noqa: E402
from harness.result_tables import (  # noqa: E402
    readme_summary,
    rewrite_page,
    validation_summary,
    validation_tables,
)

PAGE, README = Path("docs/results/validation.md"), Path("README.md")
TAG = "validation_spread.py"


def summarise(runs: pd.DataFrame) -> pd.DataFrame:
    """Medians, ranges and shares per case and strategy (``summary.csv``)."""
    runs = runs.assign(absM2=runs["M2"].abs())
    return runs.groupby(["case", "strategy"]).agg(
        truth_median=("truth", "median"), n_hf_median=("n_hf", "median"),
        M1_median=("M1", "median"), M2_median=("M2", "median"),
        absM2_median=("absM2", "median"), absM2_max=("absM2", "max"),
        M2_min=("M2", "min"), M2_max=("M2", "max"), M3_median=("M3", "median"),
        converged=("converged", "mean"), covered=("covered", "mean"),
        n=("M2", "size")).reset_index()


def write_pages(runs: pd.DataFrame, known_truth, max_hf) -> None:
    """Rewrite the tables of the validation page and, given the known-truth runs, the README's."""
    rewrite_page(PAGE, {**validation_tables(runs), "summary": validation_summary(summarise(runs))},
                 TAG)
    if known_truth:
        defaults, paper = (pd.read_csv(p) for p in known_truth)
        rewrite_page(README, {"readme-summary": readme_summary(runs, defaults, paper, max_hf)},
                     TAG)
    else:
        print(f"{README} left as it is: --known-truth DEFAULTS.csv PAPER.csv writes its table")


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
    ap.add_argument("--write", action="store_true",
                    help=f"run nothing: write the tables of {PAGE} from DIR/runs.csv")
    ap.add_argument("--known-truth", nargs=2, metavar=("DEFAULTS.csv", "PAPER.csv"),
                    help="with --write: known-truth runs.csv files; also write README's table")
    args = ap.parse_args(argv)
    out = Path(args.out)
    if args.write:
        if not (out / "runs.csv").is_file():
            ap.error(f"--write: no {out / 'runs.csv'}; run the study first or give --out DIR")
        return write_pages(pd.read_csv(out / "runs.csv"), args.known_truth, args.max_hf)
    settings = settings_from_args(args.set)
    strategies = parse_strategies(args.strategies)
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
    summary = summarise(pd.DataFrame(rows))
    summary.to_csv(out / "summary.csv", index=False)
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(summary.round(4).to_string(index=False))


if __name__ == "__main__":
    main()
