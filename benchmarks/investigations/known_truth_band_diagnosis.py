"""Why a band misses on a held-out known-truth type: bias of the model, or a band too narrow?

For each data set of ``TYPE`` it prints, relative to that data set's truth,
the MPM error and the U95 band of

* ``study``: PAS with its defaults (as ``known_truth.py``);
* ``every event``: the estimator fitted to every event of the data set (no
  sampling: what is left is the model's own bias);
* ``to budget``: the study run to ``--max-hf`` without stopping (is a miss an
  early stop?);
* ``without M``: the same data set with one mechanism removed (``--remove
  outliers`` or ``misses``: the same LF peaks and main loads, its own truth) —
  does coverage recover without it?

Run: python benchmarks/investigations/known_truth_band_diagnosis.py TYPE [N] [--remove outliers]
     [--only study,every,budget,without]
"""

from __future__ import annotations

import argparse
import dataclasses
import warnings

import numpy as np

from pas.strategies.screening import LFSet
from pas.validation.known_truth import make_problem
from pas.validation.known_truth_runs import TYPES, run_one
from pas.validation.refits import error_at

PARTS = ("study", "every", "budget", "without")


def every_event_error(problem) -> float:
    """Error of the estimator fitted to every event of ``problem`` (defaults, no band)."""
    lfset = LFSet(problem.lf, n_waves=problem.n_waves, p_exp=problem.p_exp,
                  threshold=problem.threshold)
    hf_pool = np.asarray(problem.hf, float)[lfset.index]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return error_at(problem, lfset, hf_pool, np.arange(lfset.n), problem.replication)


def _line(label, row):
    t = row["truth"]
    return (f"  {label:16s} error {row['error']:+.3f} band [{row['band_low'] / t - 1:+.3f}, "
            f"{row['band_high'] / t - 1:+.3f}] covered {row['covered']!s:5s} HF {row['n_hf']} "
            f"converged {row['converged']}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("type", help="a known-truth type, e.g. ho-outlier-contaminate-bb7")
    ap.add_argument("n", nargs="?", type=int, default=5, help="data sets")
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--remove", choices=("outliers", "misses"), default="outliers")
    ap.add_argument("--only", default=",".join(PARTS), help=f"subset of {','.join(PARTS)}")
    ap.add_argument("--max-hf", type=int, default=160)
    args = ap.parse_args(argv)
    if args.type not in TYPES:
        ap.error(f"type {args.type!r} is not a known-truth type; see known_truth.py --types")
    parts = args.only.split(",")
    ptype = TYPES[args.type]
    without = dataclasses.replace(ptype, **{args.remove: "none"})
    for r in range(args.first, args.first + args.n):
        problem = make_problem(ptype, r)
        print(f"{args.type} data set {r} (truth {problem.truth_mpm:.1f})", flush=True)
        if "study" in parts:
            print(_line("study", run_one(problem, max_hf=args.max_hf)), flush=True)
        if "every" in parts:
            print(f"  every event      error {every_event_error(problem):+.3f}", flush=True)
        if "budget" in parts:
            row = run_one(problem, max_hf=args.max_hf, stop_on_convergence=False)
            print(_line("to budget", row), flush=True)
        if "without" in parts:
            other = make_problem(without, r)
            print(_line(f"without {args.remove}", run_one(other, max_hf=args.max_hf)) +
                  f" (truth {other.truth_mpm:.1f})", flush=True)


if __name__ == "__main__":
    main()
