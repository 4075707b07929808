"""The tables of ``docs/known-truth.md`` from the ``runs.csv`` files of :mod:`known_truth`.

Run: python benchmarks/known_truth_table.py DEFAULTS.csv[,MORE.csv] PAPER.csv[,MORE.csv]
(comma-separated lists are concatenated: a run split over several processes).
"""

from __future__ import annotations

import sys

import pandas as pd


def _read(arg):
    return pd.concat([pd.read_csv(p) for p in arg.split(",")], ignore_index=True)


def _pct(x, signed=False):
    return f"{100 * x:+.1f} %" if signed else f"{100 * x:.1f} %"


def overall(runs, label):
    a = runs["error"].abs()
    return (f"| {label} | {_pct(a.median())} | {_pct(a.quantile(0.9))} | {_pct(a.max())} | "
            f"{100 * runs['covered'].mean():.0f} % | {runs['n_hf'].median():g} | "
            f"{100 * runs['converged'].mean():.0f} % |")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    default, paper = _read(argv[0]), _read(argv[1])
    print("| | median \\|error\\| | p90 | worst | U95 coverage | HF (median) | converged |")
    print("|---|---|---|---|---|---|---|")
    n = len(default)
    print(overall(default, f"defaults, all {n} runs"))
    print(overall(default[default["type_tau"] >= 0.6], "defaults, τ ≥ 0.6"))
    print(overall(default[default["type_tau"] < 0.5], "defaults, τ < 0.5"))
    print(overall(paper, f'`preset="paper"`, all {len(paper)} runs'))
    print()
    print("| problem type | median \\|error\\| | worst | median error | U95 coverage | HF | "
          "converged | paper preset: median \\|error\\| | coverage | HF |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, d in default.groupby("type", sort=False):
        p = paper[paper["type"] == name]
        a = d["error"].abs()
        print(f"| {name} | {_pct(a.median())} | {_pct(a.max())} | "
              f"{_pct(d['error'].median(), True)} | {100 * d['covered'].mean():.0f} % | "
              f"{d['n_hf'].median():g} | {100 * d['converged'].mean():.0f} % | "
              f"{_pct(p['error'].abs().median())} | {100 * p['covered'].mean():.0f} % | "
              f"{p['n_hf'].median():g} |")


if __name__ == "__main__":
    main()
