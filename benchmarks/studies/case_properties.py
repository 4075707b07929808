"""Data properties of the validation analogues over several data seeds (no strategy runs).

For each case and data seed 0 … N−1: generate the full-scale analogue (cache
``$PAS_CACHE`` or ``./pas-cache``) and compute its properties
(:func:`pas.validation.properties.data_properties`: τ, λ_U, λ_L, miss shares,
impact rate, truth β, truth against the paper, AIC family).  Writes every row
to ``DIR/properties.csv`` and prints the two tables of
``docs/results/analogue-properties.md`` (seed 0; median and range over the
seeds); ``--write`` puts them between that page's markers.

Run: python benchmarks/studies/case_properties.py [N] [--cases 3a,3a-hard] [--out DIR]
     [--write] [--read DIR/properties.csv]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

from pas.validation import CASE_IDS, generate_case
from pas.validation.properties import data_properties

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import (  # noqa: E402
    properties_seed_table,
    properties_spread_table,
    write_between_markers,
)

PAGE = Path("docs/results/analogue-properties.md")


def measure(cases, n, out):
    """Generate each case at seeds 0 … n−1 and return its properties, one row per data set."""
    rows, t_gen = [], {}
    for case in cases:
        for seed in range(n):
            t0 = time.perf_counter()
            data = generate_case(case, seed=seed)
            t_gen[case] = t_gen.get(case, 0.0) + time.perf_counter() - t0
            rows.append(dict(data_properties(data), seed=seed))
        pd.DataFrame(rows).to_csv(out / "properties.csv", index=False)
    print("generation time per case (s, sum over seeds): "
          + ", ".join(f"{c} {t:.0f}" for c, t in t_gen.items()))
    return pd.DataFrame(rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10)
    ap.add_argument("--cases", default=",".join(CASE_IDS))
    ap.add_argument("--out", default="pas-output/properties")
    ap.add_argument("--read", type=Path, metavar="CSV",
                    help="take the rows from this properties.csv instead of measuring")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"write the tables between the markers of PAGE (default {PAGE})")
    args = ap.parse_args(argv)
    if args.read:
        table = pd.read_csv(args.read)
    else:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        table = measure(args.cases.split(","), args.n, out)
    blocks = {"seed-0": properties_seed_table(table[table.seed == 0]),
              "spread": properties_spread_table(table)}
    print(blocks["seed-0"], blocks["spread"], sep="\n\n")
    if args.write:
        page = args.write.read_text(encoding="utf-8")
        args.write.write_text(write_between_markers(page, blocks, "case_properties.py"),
                              encoding="utf-8")


if __name__ == "__main__":
    main()
