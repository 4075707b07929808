"""Does the model band need Student-t's cold start?  The same final band with and without it.

Each known-truth study runs as the defaults have it (its own ε1 stop, budget
``--max-hf``); its final model band is then fitted again with Student-t's
replicate fits started from the final fit only (``band.COLD_FAMILIES = ()``),
from the same random numbers.  Per study: the U95 both ways (the sampling band
widened to hold the model band), whether each holds the exact truth, the
largest relative change of a band end and of a replicate MPM, how many of the
50 replicate MPMs moved by more than 1e-6, and the band's CPU time both ways
(one process).  Writes ``band_student_cold.csv``; prints per group and overall.

Run: python benchmarks/investigations/band_student_cold.py [N] [--types all] [--held-out]
     [--first 0] [--out pas-output/band-cold]
"""

from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pas.strategies import band
from pas.study.precision import union
from pas.validation.known_truth import make_problem
from pas.validation.known_truth_runs import (
    TYPES,
    add_study_arguments,
    known_truth_study,
    select_types,
)
from pas.validation.timing_problem import cpu_seconds


def final_bands(study):
    """``{label: (low, high, replicate MPMs, CPU s)}`` of the study's final model band with
    Student-t's cold start (as the study's result has it) and without."""
    out = {}
    for label, cold in (("cold", ("student",)), ("warm", ())):
        saved, band.COLD_FAMILIES = band.COLD_FAMILIES, cold
        try:
            rng = np.random.default_rng([study.seed, study.n_told, 1])  # precision.model_band's
            t = cpu_seconds()
            low, high, mpms = study.strategy.model_band(study.pairs(), study.lfset, rng, n_jobs=1)
            out[label] = (float(low), float(high), np.asarray(mpms, float), cpu_seconds() - t)
        finally:
            band.COLD_FAMILIES = saved
    return out


def one(name, replication, max_hf):
    problem = make_problem(TYPES[name], replication)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        study = known_truth_study(problem, max_hf=max_hf)
        res = study.optimize(problem.oracle())
        bands = final_bands(study)
    truth = problem.truth_mpm
    row = {"type": name, "group": name.split("-")[0], "held_out": TYPES[name].held_out,
           "replication": replication, "n_hf": res.n_hf, "mpm": res.mpm, "truth": truth}
    if res.mpm_band_model is not None:  # the result's band is the cold one: a check
        row["result_is_cold"] = bool(np.allclose(res.mpm_band_model, bands["cold"][:2],
                                                 rtol=1e-12))
    for label, (low, high, _, cpu) in bands.items():
        lo, hi = union(res.mpm_band_sampling, (low, high))
        row |= {f"{label}_low": lo, f"{label}_high": hi, f"{label}_covered": lo <= truth <= hi,
                f"{label}_cpu": cpu}
    c, w = bands["cold"], bands["warm"]
    row["band_end_change"] = float(max(abs(w[0] / c[0] - 1), abs(w[1] / c[1] - 1)))
    change = np.abs(w[2] / c[2] - 1)
    row["replicate_change"] = float(np.nanmax(change))
    row["replicates_moved"] = int(np.sum(change > 1e-6))
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_study_arguments(ap, n=2)
    ap.add_argument("--out", default="pas-output/band-cold")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in select_types(args.types, held_out=args.held_out):
        for r in range(args.first, args.first + args.n):
            t = time.perf_counter()
            rows.append(one(name, r, args.max_hf))
            x = rows[-1]
            print(f"{name:38s} {r:3d} {x['n_hf']:4d} HF  covered cold/warm "
                  f"{x['cold_covered']:d}/{x['warm_covered']:d}  band end change "
                  f"{x['band_end_change']:.1e}  replicates moved {x['replicates_moved']:2d}  "
                  f"CPU warm/cold {x['warm_cpu'] / x['cold_cpu']:.2f}  "
                  f"({time.perf_counter() - t:.0f} s)", flush=True)
            pd.DataFrame(rows).to_csv(out / "band_student_cold.csv", index=False)
    runs = pd.DataFrame(rows)
    summary = runs.groupby("group").agg(
        studies=("type", "size"), covered_cold=("cold_covered", "mean"),
        covered_warm=("warm_covered", "mean"), worst_end_change=("band_end_change", "max"),
        studies_any_moved=("replicates_moved", lambda m: int((m > 0).sum())),
        cpu_ratio=("warm_cpu", "sum"))
    summary["cpu_ratio"] /= runs.groupby("group")["cold_cpu"].sum()
    print(summary.round(3).to_string())
    print(f"\n{len(runs)} studies: U95 held the truth cold {runs['cold_covered'].sum()} / warm "
          f"{runs['warm_covered'].sum()}; coverage changed in "
          f"{int((runs['cold_covered'] != runs['warm_covered']).sum())}; band ends moved by more "
          f"than 1e-6 in {int((runs['band_end_change'] > 1e-6).sum())}, by more than 1 % in "
          f"{int((runs['band_end_change'] > 0.01).sum())}; replicate MPMs moved "
          f"{int(runs['replicates_moved'].sum())} of {50 * len(runs)}; band CPU warm/cold "
          f"{runs['warm_cpu'].sum() / runs['cold_cpu'].sum():.2f} in all")


if __name__ == "__main__":
    main()
