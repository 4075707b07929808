"""Where the error at strong dependence comes from: the LF ranks or the HF loads.

PAS's conditional estimator puts the copula on the LF sample's mid-ranks; the
known-truth generator (:mod:`harness.known_truth`), like nature, puts it on the LF
population's CDF (the Rayleigh CDF).  This script runs PAS at a fixed number of
HF samples without stopping (``stop_on_convergence=False``) in three ways:

* ``population`` — the problem as generated (loads on the Rayleigh CDF);
* ``ranks`` — the same LF peaks, the loads generated on the sample's own
  mid-ranks (what the estimator takes the CDF to be), truth recomputed;
* ``redraw`` — one LF data set (``--data-set``), only the loads redrawn.

and prints per run the error of the MPM, the model band (both relative to
the truth), whether the reported U95 holds the truth and the selected family,
then the summary: standard deviation and mean of the error, the median
standard deviation the model band implies (its width / 3.92), coverage.  Settings as in
:mod:`harness.known_truth` (``--set NAME=VALUE``).

Run: ``python benchmarks/investigations/lf_ranks.py population core-gumbel-t0.9 --hf 30 --runs 20``
"""

from __future__ import annotations

import argparse
import sys
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

import pas
from pas.study.flat import from_flat

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness import known_truth as kt  # noqa: E402
from harness.known_truth_runs import settings_from_args  # noqa: E402


def _loads(problem, u, rng):
    ptype = problem.type
    bicop = kt.copula(ptype.family, ptype.tau)
    h = kt.copula_loads(ptype, bicop, u, rng.uniform(1e-9, 1 - 1e-9, u.size))
    truth = kt.truth_mpm(lambda x: ptype.exceedance_count(x, problem.lf, u), problem.n_waves,
                         problem.p_exp)
    return replace(problem, hf=h, truth_mpm=truth, eps1=0.015 * truth)


def problem_for(mode, ptype, run, data_set):
    """The ``run``-th problem of ``mode`` (module docs)."""
    from pas.stats.dependence import weighted_ranks

    if ptype.model != "copula" or ptype.misses != "none" or ptype.outlier_p or ptype.threshold:
        raise ValueError("lf_ranks.py takes the copula types without misses, outliers or "
                         "threshold (core-*, tail-*)")
    if mode == "population":
        return kt.make_problem(ptype, run)
    if mode == "ranks":
        p = kt.make_problem(ptype, run)
        return _loads(p, weighted_ranks(p.lf, np.ones(p.lf.size)), np.random.default_rng([77, run]))
    p = kt.make_problem(ptype, data_set)
    return _loads(p, kt.pool_cdf(p.lf, None), np.random.default_rng([99, data_set, run]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("population", "ranks", "redraw"))
    ap.add_argument("type", help="a known_truth problem type, e.g. core-gumbel-t0.9")
    ap.add_argument("--hf", type=int, default=30, help="HF samples (no stopping)")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--data-set", type=int, default=0, help="the LF data set of 'redraw'")
    ap.add_argument("--set", action="append", default=[], help="PAS setting NAME=VALUE")
    args = ap.parse_args(argv)
    settings = settings_from_args(args.set)
    ptype = kt.TUNING_TYPES[args.type]
    rows = []
    for run in range(args.first, args.first + args.runs):
        p = problem_for(args.mode, ptype, run, args.data_set)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            objects = from_flat({"eps1": p.eps1, "max_hf": args.hf, **settings})
            res = pas.make_study(objects.pop("strategy"), p.lf, n_waves=p.n_waves,
                                 p_exp=p.p_exp,
                                 seed=args.data_set if args.mode == "redraw" else run,
                                 stop_on_convergence=False, **objects).optimize(p.oracle())
        t = p.truth_mpm
        model = res.mpm_band_model or (np.nan, np.nan)
        rows.append({"run": run, "error": res.mpm / t - 1,
                     "covered": bool(res.mpm_band[0] <= t <= res.mpm_band[1]),
                     "model_sd": (model[1] - model[0]) / (2 * 1.96 * t), "family": res.family})
        print(f"{args.type} {args.mode} run {run}: error {rows[-1]['error']:+.4f} model band "
              f"[{model[0] / t - 1:+.4f}, {model[1] / t - 1:+.4f}] covered "
              f"{rows[-1]['covered']} {res.family}", flush=True)
    r = pd.DataFrame(rows)
    print(f"\n{args.type} {args.mode}, {len(r)} runs at {args.hf} HF: error sd "
          f"{100 * r.error.std():.2f} %, mean {100 * r.error.mean():+.2f} %, mean |error| "
          f"{100 * r.error.abs().mean():.2f} %; model band sd (median) "
          f"{100 * r.model_sd.median():.2f} %; U95 coverage {100 * r.covered.mean():.0f} %; "
          f"families {r.family.value_counts().to_dict()}")


if __name__ == "__main__":
    main()
