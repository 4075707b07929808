"""Data properties of the validation analogues over several data seeds (no strategy runs).

For each case and data seed 0 … N−1: generate the full-scale analogue (cache
``$PAS_CACHE`` or ``./pas-cache``) and compute its properties
(:func:`pas.validation.properties.data_properties`: τ, λ_U, λ_L, miss shares,
impact rate, truth β, truth against the paper, AIC family).  Prints the table
of seed 0 and, per case, the median and range over the seeds of the key
properties; writes every row to ``DIR/properties.csv``.

Run: python benchmarks/case_properties.py [N] [--cases 3a,3a-hard] [--out DIR]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import pandas as pd

from pas.validation import CASE_IDS, generate_case
from pas.validation.properties import data_properties, format_properties

KEY = ["lambda_u", "lambda_l", "miss_all", "miss_lnu50", "impact_rate", "truth_vs_paper", "tau"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10)
    ap.add_argument("--cases", default=",".join(CASE_IDS))
    ap.add_argument("--out", default="pas-output/properties")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows, t_gen = [], {}
    for case in args.cases.split(","):
        for seed in range(args.n):
            t0 = time.perf_counter()
            data = generate_case(case, seed=seed)
            t_gen[case] = t_gen.get(case, 0.0) + time.perf_counter() - t0
            rows.append(dict(data_properties(data), seed=seed))
        pd.DataFrame(rows).to_csv(out / "properties.csv", index=False)
    table = pd.DataFrame(rows)
    print("data seed 0:")
    print(format_properties(table[table.seed == 0]))
    spread = table.groupby("case", sort=False)[KEY].agg(["median", "min", "max"])
    flat = pd.DataFrame({k: [f"{m:.2f} [{lo:.2f}, {hi:.2f}]" for m, lo, hi in
                             zip(spread[k]["median"], spread[k]["min"], spread[k]["max"])]
                         for k in KEY}, index=spread.index)
    flat["λ_L ≥ λ_U"] = (table.assign(ok=table.lambda_l >= table.lambda_u)
                         .groupby("case", sort=False)["ok"].sum().astype(int).astype(str)
                         + f"/{args.n}")
    with pd.option_context("display.width", 250, "display.max_columns", 20):
        print(f"\nmedian [min, max] over data seeds 0-{args.n - 1}:")
        print(flat.to_string())
    print("\ngeneration time per case (s, sum over seeds): "
          + ", ".join(f"{c} {t:.0f}" for c, t in t_gen.items()))


if __name__ == "__main__":
    main()
