"""Does the model band need Student-t's cold start?  The same final band with and without it.

Each known-truth study runs as the defaults have it (its own ε1 stop, budget
``--max-hf``); its final model band is then fitted again with Student-t's
replicate fits started from the final fit only (``band.COLD_FAMILIES = ()``), and
once more started once from the final fit moved off the edges that trap a warm
start (``band.STUDENT_RESTART``: ν's start that of the data, or ``restart:C``
ν's optimiser value C, the location's gap at least e⁻⁴ of the span), all from
the same random numbers.  Per study and way:
the U95 (the sampling band widened to hold the model band), whether it holds the
exact truth, the largest relative change of a band end and of a replicate MPM
against today's band, how many of the 50 replicate MPMs moved by more than 1e-6,
and the band's CPU time (one process).  Writes ``band_student_cold.csv``;
prints per group and overall.

Run: python benchmarks/investigations/band_student_cold.py [N] [--types all] [--held-out]
     [--first 0] [--ways warm,restart,restart:1] [--out pas-output/band-cold]
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

SETTINGS = ("COLD_FAMILIES", "STUDENT_RESTART", "RESTART_NU")


def way(label: str) -> tuple:
    """``(band.COLD_FAMILIES, band.STUDENT_RESTART, band.RESTART_NU)`` of a way: ``cold``
    (today's), ``warm``, ``restart`` or ``restart:C`` (ν's optimiser value C, 0 being ν 26)."""
    fixed = {"cold": (("student",), False, 0.0), "warm": ((), False, 0.0),
             "restart": (("student",), True, 0.0)}
    if label in fixed:
        return fixed[label]
    if label.startswith("restart:"):
        return ("student",), True, float(label.partition(":")[2])
    raise ValueError(f"--ways: {label!r} is none of cold, warm, restart, restart:C")


def final_bands(study, ways):
    """``{label: (low, high, replicate MPMs, CPU s)}`` of the study's final model band each
    way (``cold`` first: as the study's result has it), from the same random numbers."""
    out = {}
    for label in ("cold", *ways):
        saved = [getattr(band, k) for k in SETTINGS]
        for k, v in zip(SETTINGS, way(label)):
            setattr(band, k, v)
        try:
            rng = np.random.default_rng([study.seed, study.n_told, 1])  # precision.model_band's
            t = cpu_seconds()
            low, high, mpms = study.strategy.model_band(study.pairs(), study.lfset, rng, n_jobs=1)
            out[label] = (float(low), float(high), np.asarray(mpms, float), cpu_seconds() - t)
        finally:
            for k, v in zip(SETTINGS, saved):
                setattr(band, k, v)
    return out


def one(name, replication, max_hf, ways):
    problem = make_problem(TYPES[name], replication)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        study = known_truth_study(problem, max_hf=max_hf)
        res = study.optimize(problem.oracle())
        bands = final_bands(study, ways)
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
    c = bands["cold"]
    for label in ways:
        w = bands[label]
        row[label + "_band_end_change"] = float(max(abs(w[0] / c[0] - 1), abs(w[1] / c[1] - 1)))
        change = np.abs(w[2] / c[2] - 1)
        row[label + "_replicate_change"] = float(np.nanmax(change))
        row[label + "_replicates_moved"] = int(np.sum(change > 1e-6))
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_study_arguments(ap, n=2)
    ap.add_argument("--out", default="pas-output/band-cold")
    ap.add_argument("--ways", default="warm,restart,restart:1",
                    help="compared with today's band (cold): warm, restart, restart:C")
    args = ap.parse_args(argv)
    ways = [w for w in args.ways.split(",") if w and w != "cold"]
    for label in ways:
        way(label)  # a bad name fails before the first study
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in select_types(args.types, held_out=args.held_out):
        for r in range(args.first, args.first + args.n):
            t = time.perf_counter()
            rows.append(one(name, r, args.max_hf, ways))
            x = rows[-1]
            print(f"{name:38s} {r:3d} {x['n_hf']:4d} HF  held the truth: cold "
                  f"{x['cold_covered']:d}, " + ", ".join(
                      f"{w} {x[w + '_covered']:d} (end {x[w + '_band_end_change']:.1e}, CPU "
                      f"{x[w + '_cpu'] / x['cold_cpu']:.2f})" for w in ways)
                  + f"  ({time.perf_counter() - t:.0f} s)", flush=True)
            pd.DataFrame(rows).to_csv(out / "band_student_cold.csv", index=False)
    runs = pd.DataFrame(rows)
    for label in ways:
        prefix = label + "_"
        summary = runs.groupby("group").agg(
            studies=("type", "size"), covered_cold=("cold_covered", "mean"),
            covered=(f"{label}_covered", "mean"),
            worst_end_change=(prefix + "band_end_change", "max"),
            studies_any_moved=(prefix + "replicates_moved", lambda m: int((m > 0).sum())),
            cpu_ratio=(f"{label}_cpu", "sum"))
        summary["cpu_ratio"] /= runs.groupby("group")["cold_cpu"].sum()
        print(f"-- {label} against cold (today's band)")
        print(summary.round(3).to_string())
        end = runs[prefix + "band_end_change"]
        print(f"{len(runs)} studies: U95 held the truth cold {runs['cold_covered'].sum()} / "
              f"{label} {runs[f'{label}_covered'].sum()}; coverage changed in "
              f"{int((runs['cold_covered'] != runs[f'{label}_covered']).sum())}; band ends "
              f"moved by more than 1e-6 in {int((end > 1e-6).sum())}, by more than 1 % in "
              f"{int((end > 0.01).sum())} (largest {end.max():.1e}); replicate MPMs moved "
              f"{int(runs[prefix + 'replicates_moved'].sum())} of {50 * len(runs)}; band CPU "
              f"{label}/cold {runs[f'{label}_cpu'].sum() / runs['cold_cpu'].sum():.2f} in all\n")

if __name__ == "__main__":
    main()
