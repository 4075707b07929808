"""The model band with and without model-form terms, on the same known-truth studies.

Each study runs once with ``band_model_form="semi-empirical"``
(:mod:`pas.strategies.model_form`); its bootstrap replicates give, from the
same fits, the MPMs of the model (the default band's) and of the
semi-empirical distribution, so both bands are read from one run and the
comparison is paired.  The MPM, and so every error, is the default's.  Per
run it writes ``runs.csv`` (``--out``): the truth, the MPM, the sampling band
(``sampling_low/high``), the model-only band (``model_low/high``, with the
sampling band the default U95) and the semi-empirical replicates' band
(``se_low/high``); and it prints, per group and per type, the U95 coverage
and median band width of the default and of the mended band (their union).

Run: python benchmarks/studies/known_truth_band_forms.py N [--types ho2] [--held-out]
     [--first 0] [--out DIR]
     python benchmarks/studies/known_truth_band_forms.py --table RUNS.csv[,MORE.csv]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pas.api import make_study
from pas.strategies import model_form
from pas.study.flat import from_flat

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import TYPES, add_study_arguments, select_types  # noqa: E402


def run_forms(problem, max_hf: int = 160) -> dict:
    """One default study of ``problem`` with the semi-empirical band: both bands' ends."""
    captured = {}
    band_ends = model_form.band_ends

    def capture(values):
        kept = np.asarray([v for v in values if v is not None], dtype=float)
        captured["values"] = kept
        return band_ends(values)

    t0 = time.perf_counter()
    model_form.band_ends = capture  # bootstrap_band reads it from the module when it runs
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            objects = from_flat({"eps1": problem.eps1, "max_hf": max_hf,
                                 "band_model_form": "semi-empirical"})
            res = make_study(objects.pop("strategy"), problem.lf, n_waves=problem.n_waves,
                             p_exp=problem.p_exp, threshold=problem.threshold,
                             seed=problem.replication, **objects).optimize(problem.oracle())
    finally:
        model_form.band_ends = band_ends
    values = captured.get("values", np.full((1, 2), np.nan))
    low, high = np.percentile(values, 2.5, axis=0), np.percentile(values, 97.5, axis=0)
    return {"type": problem.type.name, "replication": problem.replication,
            "truth": problem.truth_mpm, "mpm": res.mpm, "error": res.mpm / problem.truth_mpm - 1,
            "sampling_low": res.mpm_band_sampling[0], "sampling_high": res.mpm_band_sampling[1],
            "model_low": low[0], "model_high": high[0], "se_low": low[1], "se_high": high[1],
            "n_hf": res.n_hf, "converged": bool(res.converged),
            "seconds": time.perf_counter() - t0}


def scored(runs: pd.DataFrame) -> pd.DataFrame:
    """``runs`` with the default U95 (sampling ∪ model) and the mended one (∪ semi-empirical):
    covered or not, and width relative to the truth."""
    lo = np.minimum(runs["sampling_low"], runs["model_low"])
    hi = np.maximum(runs["sampling_high"], runs["model_high"])
    mlo, mhi = np.minimum(lo, runs["se_low"]), np.maximum(hi, runs["se_high"])
    t = runs["truth"]
    return runs.assign(covered=(lo <= t) & (t <= hi), covered_mended=(mlo <= t) & (t <= mhi),
                       width=(hi - lo) / t, width_mended=(mhi - mlo) / t,
                       abs_error=runs["error"].abs(),
                       group=runs["type"].map(_group))


def _group(name: str) -> str:
    """``ho-miss``, ``ho2-reg``, … for a held-out type; the first part of a tuning type's name."""
    parts = name.split("-")
    return "-".join(parts[:2]) if parts[0].startswith("ho") else parts[0]


def table(runs: pd.DataFrame, by: str) -> pd.DataFrame:
    """Per ``by`` (``group`` or ``type``): runs, median |error|, coverage and median width of
    the default and of the mended U95."""
    return runs.groupby(by, sort=False).agg(
        n=("error", "size"), median_abs=("abs_error", "median"),
        coverage=("covered", "mean"), coverage_mended=("covered_mended", "mean"),
        width=("width", "median"), width_mended=("width_mended", "median")).reset_index()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_study_arguments(ap, n=2)
    ap.add_argument("--out", default="pas-output/known-truth-band-forms")
    ap.add_argument("--table", help="only tabulate these runs.csv files (comma-separated)")
    args = ap.parse_args(argv)
    if args.table:
        runs = pd.concat([pd.read_csv(p) for p in args.table.split(",")], ignore_index=True)
    else:
        try:
            names = select_types(args.types, held_out=args.held_out)
        except ValueError as exc:
            ap.error(str(exc))
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        rows = []
        for name in names:
            for r in range(args.first, args.first + args.n):
                rows.append(run_forms(make_problem(TYPES[name], r), args.max_hf))
                x = scored(pd.DataFrame(rows[-1:])).iloc[0]
                print(f"{name} r{r}: err {x['error']:+.3f} covered {x['covered']} -> "
                      f"{x['covered_mended']} width {x['width']:.3f} -> {x['width_mended']:.3f} "
                      f"({x['seconds']:.0f} s)", flush=True)
                pd.DataFrame(rows).to_csv(out / "runs.csv", index=False)
        runs = pd.DataFrame(rows)
    runs = scored(runs)
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        for by in ("group", "type"):
            print(table(runs, by).round(3).to_string(index=False))
        print(f"all {len(runs)} runs: coverage {runs['covered'].mean():.3f} -> "
              f"{runs['covered_mended'].mean():.3f}, median width {runs['width'].median():.3f} -> "
              f"{runs['width_mended'].median():.3f}")
    return runs


if __name__ == "__main__":
    main()
