"""Control for ``final_sample_refits.py --md-weighted``: does a correctly specified model
move when every event is weighted as MD includes events?

On known-truth problems whose law the fitted model contains (the bore + impulse mixtures with
``hf_marginal="weibull_mixture"``, single-Weibull HF with the default), every event of a data
set is fitted once as told and once repeated as MD's design includes it
(:func:`harness.refits.md_design_positions`), and scored against the exact truth.  A
model that is right should stay centred under the weighting; one that shifts on every data
set (as the mixture does on the green-water analogues) is misspecified there.

Run: python benchmarks/investigations/md_weighting_control.py [N]
"""

from __future__ import annotations

import argparse
import sys
import types
import warnings
from pathlib import Path

import numpy as np

from pas.strategies.screening import LFSet

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness import known_truth as kt  # noqa: E402
from harness.refits import error_at, md_design_positions  # noqa: E402

CONTROLS = (("tail-gaussian-mix", {"hf_marginal": "weibull_mixture"}),
            ("tail-clayton-mix", {"hf_marginal": "weibull_mixture"}),
            ("core-gaussian-t0.6", {}), ("core-clayton-t0.6", {}))


def main(n="5"):
    for name, settings in CONTROLS:
        errors = []
        for r in range(int(n)):
            problem = kt.make_problem(kt.TUNING_TYPES[name], r)
            lfset = LFSet(problem.lf, n_waves=problem.n_waves, p_exp=problem.p_exp,
                          threshold=problem.threshold)
            hf_pool = np.asarray(problem.hf, float)[lfset.index]
            truth = types.SimpleNamespace(truth_mpm=problem.truth_mpm)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                every = error_at(truth, lfset, hf_pool, np.arange(lfset.n), r, settings)
                weighted = error_at(truth, lfset, hf_pool, md_design_positions(lfset.n, seed=r),
                                    r, settings)
            errors.append((every, weighted))
            print(f"{name} r{r} {settings}: every event {every:+.3f}  weighted as MD includes "
                  f"events {weighted:+.3f}", flush=True)
        e = np.array(errors)
        print(f"{name}: median error every event {np.median(e[:, 0]):+.3f}, weighted "
              f"{np.median(e[:, 1]):+.3f}; weighted below -5 % on {np.sum(e[:, 1] < -0.05)} of "
              f"{len(e)}", flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", nargs="?", type=int, default=5, help="data sets per problem type")
    main(ap.parse_args().n)
