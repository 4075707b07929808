"""The tables of ``docs/known-truth.md`` from the ``runs.csv`` files of :mod:`known_truth`.

Run: python benchmarks/studies/known_truth_table.py DEFAULTS.csv[,MORE.csv] PAPER.csv[,MORE.csv]
     [--write docs/known-truth.md]
(comma-separated lists are concatenated: a run split over several processes).
Prints the tables; ``--write PAGE`` also puts each between its markers in the
page (``<!-- BEGIN known_truth_table.py NAME -->`` … ``<!-- END … NAME -->``),
so the page's tables are the script's output, never edited by hand.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

from pas.validation.result_tables import write_between_markers


def _read(arg):
    return pd.concat([pd.read_csv(p) for p in arg.split(",")], ignore_index=True)


def _pct(x, signed=False):
    return f"{100 * x:+.1f} %" if signed else f"{100 * x:.1f} %"


def overall(runs, label):
    a = runs["error"].abs()
    return (f"| {label} | {_pct(a.median())} | {_pct(a.quantile(0.9))} | {_pct(a.max())} | "
            f"{100 * runs['covered'].mean():.0f} % | {runs['n_hf'].median():g} | "
            f"{100 * runs['converged'].mean():.0f} % |")


def tables(default, paper) -> dict[str, str]:
    """The page's two tables, by marker name: ``overall`` and ``per-type``."""
    rows = ["| | median \\|error\\| | p90 | worst | U95 coverage | HF (median) | converged |",
            "|---|---|---|---|---|---|---|",
            overall(default, f"defaults, all {len(default)} runs"),
            overall(default[default["type_tau"] >= 0.6], "defaults, τ ≥ 0.6"),
            overall(default[default["type_tau"] < 0.5], "defaults, τ < 0.5"),
            overall(paper, f'`preset="paper"`, all {len(paper)} runs')]
    per_type = ["| problem type | median \\|error\\| | worst | median error | U95 coverage | HF | "
                "converged | paper preset: median \\|error\\| | coverage | HF |",
                "|---|---|---|---|---|---|---|---|---|---|"]
    for name, d in default.groupby("type", sort=False):
        p = paper[paper["type"] == name]
        a = d["error"].abs()
        per_type.append(
            f"| {name} | {_pct(a.median())} | {_pct(a.max())} | "
            f"{_pct(d['error'].median(), True)} | {100 * d['covered'].mean():.0f} % | "
            f"{d['n_hf'].median():g} | {100 * d['converged'].mean():.0f} % | "
            f"{_pct(p['error'].abs().median())} | {100 * p['covered'].mean():.0f} % | "
            f"{p['n_hf'].median():g} |")
    return {"overall": "\n".join(rows), "per-type": "\n".join(per_type)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("defaults", help="runs.csv of the defaults (comma-separated list)")
    parser.add_argument("paper", help="runs.csv of --preset paper (comma-separated list)")
    parser.add_argument("--write", type=Path, help="page to write the tables into")
    args = parser.parse_args(argv)
    blocks = tables(_read(args.defaults), _read(args.paper))
    print(blocks["overall"], blocks["per-type"], sep="\n\n")
    if args.write:
        page = args.write.read_text(encoding="utf-8")
        args.write.write_text(write_between_markers(page, blocks, "known_truth_table.py"),
                              encoding="utf-8")


if __name__ == "__main__":
    main()
