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
* ``check``: do the evaluated events show the misfit?  The final model's
  probability integral transforms ``t = F(h | l)`` of the evaluated true
  positives (uniform under a right model: the Kolmogorov–Smirnov p-value and
  the largest ``t``) and the error of the semi-empirical MPM (the evaluated
  events at their observed loads, :mod:`pas.strategies.model_form`) — a band
  built from the evaluated events can only see a bias they show.

Run: python benchmarks/investigations/known_truth_band_diagnosis.py TYPE [N] [--remove outliers]
     [--only study,every,budget,without,check]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np
from scipy import stats

from pas.api import make_study
from pas.stats.exceedance import mpm_of_realisations
from pas.strategies import model_form
from pas.strategies.screening import LFSet
from pas.study.flat import from_flat

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import TYPES, run_one  # noqa: E402
from harness.refits import error_at  # noqa: E402

PARTS = ("study", "every", "budget", "without", "check")


def every_event_error(problem) -> float:
    """Error of the estimator fitted to every event of ``problem`` (defaults, no band)."""
    lfset = LFSet(problem.lf, n_waves=problem.n_waves, p_exp=problem.p_exp,
                  threshold=problem.threshold)
    hf_pool = np.asarray(problem.hf, float)[lfset.index]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return error_at(problem, lfset, hf_pool, np.arange(lfset.n), problem.replication)


def evaluated_fit_check(problem, max_hf=160) -> dict:
    """The ``check`` part (module docs) on the final state of a default study of ``problem``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        objects = from_flat({"eps1": problem.eps1, "max_hf": max_hf, "n_bootstrap": 0})
        study = make_study(objects.pop("strategy"), problem.lf, n_waves=problem.n_waves,
                           p_exp=problem.p_exp, threshold=problem.threshold,
                           seed=problem.replication, **objects)
        study.optimize(problem.oracle())
    strategy, pairs, lfset = study.strategy, study.pairs(), study.lfset
    model = strategy.fit(pairs, lfset, update=False)
    inside = pairs.position < model.n0
    u = np.clip(model.u_cond[pairs.position[inside]], 1e-12, 1 - 1e-12)
    v = np.clip(model.hf_marginal.cdf(pairs.hf[inside]), 1e-12, 1 - 1e-12)
    t = model.copula.bicop.hfunc1(np.column_stack([u, v]))
    draws = strategy._draws(model, np.random.default_rng(0))
    semi = mpm_of_realisations(model_form.semi_empirical(draws, pairs), lfset.n_waves,
                               lfset.p_exp)
    return {"pairs": len(pairs), "ks_p": float(stats.kstest(t, "uniform").pvalue),
            "top_t": float(t.max()),
            "model_error": mpm_of_realisations(draws, lfset.n_waves, lfset.p_exp)
            / problem.truth_mpm - 1, "semi_error": semi / problem.truth_mpm - 1}


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
    without = dataclasses.replace(ptype, **{args.remove: "none"}) if "without" in parts else None
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
        if "check" in parts:
            c = evaluated_fit_check(problem, args.max_hf)
            print(f"  check            {c['pairs']} pairs, PIT KS p {c['ks_p']:.3f}, largest "
                  f"t {c['top_t']:.4f}; error model {c['model_error']:+.3f}, semi-empirical "
                  f"{c['semi_error']:+.3f}", flush=True)


if __name__ == "__main__":
    main()
