"""Two settings on the same known-truth data sets, run by run (``runs.csv`` of :mod:`known_truth`).

Pairs the runs of the same problem type and replication (the same data set)
and prints, per type, the median |error|, median error, U95 coverage, median
HF count and share converged of each setting, then the overall figures and
how many runs each setting got closer to the truth.

Run: python benchmarks/studies/known_truth_paired.py BASE.csv[,MORE.csv] OTHER.csv[,MORE.csv]
"""

from __future__ import annotations

import argparse

import pandas as pd


def _runs(arg):
    """The runs of a comma-separated list of files; a run that two files hold must agree."""
    runs = pd.concat([pd.read_csv(p) for p in arg.split(",")], ignore_index=True)
    key = ["type", "replication"]
    twice = runs[runs.duplicated(key, keep=False)]
    if not twice.drop(columns="seconds").drop_duplicates().duplicated(key).eq(False).all():
        raise ValueError(f"{arg}: a run held twice differs between the files")
    return runs.drop_duplicates(key, keep="last")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("base", help="runs.csv of setting a (comma-separated list)")
    ap.add_argument("other", help="runs.csv of setting b (comma-separated list)")
    args = ap.parse_args(argv)
    argv = [args.base, args.other]
    base, other = _runs(args.base), _runs(args.other)
    runs = base.merge(other, on=["type", "replication"], suffixes=("_a", "_b"))
    for s in "ab":
        runs[f"abs_{s}"] = runs[f"error_{s}"].abs()
    per_type = runs.groupby("type", sort=False).agg(
        **{
            f"{what}_{s}": (f"{col}_{s}", how)
            for s in "ab"
            for what, col, how in (
                ("median_abs", "abs", "median"),
                ("median_err", "error", "median"),
                ("coverage", "covered", "mean"),
                ("hf", "n_hf", "median"),
                ("converged", "converged", "mean"),
            )
        }
    )
    with pd.option_context("display.width", 250, "display.max_columns", 20):
        print(per_type.round(3).to_string())
    a, b = runs["abs_a"], runs["abs_b"]
    print(f"\n{len(runs)} paired runs (a = {argv[0]}, b = {argv[1]})")
    for label, fn in (("median |error|", "median"), ("mean |error|", "mean"),
                      ("worst |error|", "max")):
        print(f"{label}: {getattr(a, fn)():.3f} → {getattr(b, fn)():.3f}")
    print(f"U95 coverage: {runs['covered_a'].mean():.3f} → {runs['covered_b'].mean():.3f}")
    print(f"converged: {runs['converged_a'].mean():.3f} → {runs['converged_b'].mean():.3f}")
    print(f"b closer / farther / the same: {(b < a - 1e-9).sum()} / {(b > a + 1e-9).sum()} / "
          f"{((b - a).abs() <= 1e-9).sum()}")
    print(f"run time b / a (median of the pairs): "
          f"{(runs['seconds_b'] / runs['seconds_a']).median():.2f}")


if __name__ == "__main__":
    main()
