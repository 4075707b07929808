"""The tables of ``docs/explanation/known-truth.md`` from the ``runs.csv`` of :mod:`known_truth`.

Run: python benchmarks/studies/known_truth_table.py DEFAULTS.csv[,MORE.csv] PAPER.csv[,MORE.csv]
     [--write docs/explanation/known-truth.md]
     python benchmarks/studies/known_truth_table.py --held-out HELD_OUT.csv[,MORE.csv] [--write …]
(comma-separated lists are concatenated: a run split over several processes).
The first form makes the tables of the tuning types (defaults beside the paper
preset), the second those of the held-out types (per group and per type).
Prints the tables; ``--write PAGE`` also puts each between its markers in the
page (``<!-- BEGIN known_truth_table.py NAME -->`` … ``<!-- END … NAME -->``),
so the page's tables are the script's output, never edited by hand.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import write_between_markers  # noqa: E402


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


HELD_OUT_GROUPS = {"miss": "threshold + misses", "outlier": "outliers", "mix": "mixtures",
                   "reg": "regressions"}


def _held_out_row(label, runs):
    a = runs["error"].abs()
    width = (runs["band_high"] - runs["band_low"]) / runs["truth"]
    return (
        f"| {label} | {len(runs)} | {100 * runs['covered'].mean():.0f} % | {_pct(a.median())} | "
        f"{_pct(a.quantile(0.9))} | {_pct(a.max())} | {_pct(runs['error'].median(), True)} | "
        f"{_pct(width.median())} | {runs['n_hf'].median():g} | "
        f"{100 * runs['converged'].mean():.0f} % |"
    )


def held_out_tables(runs) -> dict[str, str]:
    """The held-out types' tables, by marker name: ``held-out-groups`` (per group and
    overall) and ``held-out-types``."""
    head = [("| {} | runs | U95 coverage | median \\|error\\| | p90 | worst | median error | "
             "band width (median, of the truth) | HF (median) | converged |"),
            "|---|---|---|---|---|---|---|---|---|---|"]
    group = runs["type"].str.split("-").str[1]
    groups = [head[0].format("group"), head[1]]
    groups += [_held_out_row(label, runs[group == key])
               for key, label in HELD_OUT_GROUPS.items() if (group == key).any()]
    groups.append(_held_out_row("all held-out types", runs))
    types = [head[0].format("held-out type"), head[1]]
    types += [_held_out_row(name, d) for name, d in runs.groupby("type", sort=False)]
    return {"held-out-groups": "\n".join(groups), "held-out-types": "\n".join(types)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("defaults", nargs="?",
                        help="runs.csv of the defaults (comma-separated list)")
    parser.add_argument("paper", nargs="?",
                        help="runs.csv of --preset paper (comma-separated list)")
    parser.add_argument("--held-out", help="runs.csv of the held-out types (comma-separated "
                        "list; known_truth.py --held-out)")
    parser.add_argument("--write", type=Path, help="page to write the tables into")
    args = parser.parse_args(argv)
    if args.held_out:
        if args.defaults:
            parser.error("give either DEFAULTS PAPER or --held-out RUNS, not both")
        blocks = held_out_tables(_read(args.held_out))
    elif args.paper:
        blocks = tables(_read(args.defaults), _read(args.paper))
    else:
        parser.error("give DEFAULTS.csv PAPER.csv (tuning types) or --held-out RUNS.csv")
    print(*blocks.values(), sep="\n\n")
    if args.write:
        page = args.write.read_text(encoding="utf-8")
        args.write.write_text(write_between_markers(page, blocks, "known_truth_table.py"),
                              encoding="utf-8")


if __name__ == "__main__":
    main()
