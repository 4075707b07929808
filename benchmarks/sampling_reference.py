"""What k impact loads can tell: a sampling reference for the impact analogues.

PAS on cases 3–4 is scored against a truth read from the *whole* HF record (a
3-parameter Weibull fitted to the top 30 % of the non-zero HF peaks, the
paper's truth).  How close can any method come with k HF values?  This script
gives a reference that asks for no model of LF–HF dependence at all: an
oracle that knows which events are impacts draws k of them at random (no
false positive ever evaluated) and applies

* ``truth-estimator``: the truth's own estimator (the same Weibull fit, top
  30 % of the k loads, scaled by the known impact rate), and
* ``empirical``: the empirical quantile of the k loads at the MPM's
  exceedance probability among impacts, ``P_exp / rate``.

With ``--pas-runs`` it also runs **PAS's own estimator on random pool events**:
for each data set, as many events as PAS evaluated there (its HF count),
drawn at random from the LF pool (over the threshold; impacts and misses
alike, no MD), 5 draws per data set.  Beside PAS's result this separates
the two things PAS does differently from the oracle: how it chooses events
(MD against random) and how it estimates (its conditional fit against the
truth's Weibull on impacts).

Per case and k it prints the median and 90th percentile of |error| over data
seeds 0…N−1 (new analogue data sets) × R random subsamples each, and
``P(worst of 10 ≤ 25 %)`` = ``P(|error| ≤ 25 %)¹⁰`` — the chance that ten
independent data sets all land within ±25 %.  PAS, which must find the
impacts and also spends HF on misses, is measured on the same data sets by
``benchmarks/validation_spread.py``; compare at its number of true-positive
pairs (``--pas-runs`` reads them from that script's runs.csv).

Run: python benchmarks/sampling_reference.py [N] [--k 50,100,160] [--cases 3a,3b,4a,4b]
[--subsamples 40] [--pas-runs pas-output/spread/runs.csv]
"""

from __future__ import annotations

import argparse

import numpy as np

from pas.stats.weibull import fit_weibull3_ls
from pas.validation import generate_case


def reference_errors(data, k: int, subsamples: int, seed: int):
    """Relative MPM errors of both reference estimators on ``subsamples`` draws of k impacts."""
    hf = np.asarray(data.hf, float)
    impacts = hf[hf > 0]
    q = data.p_exp / (impacts.size / data.n_waves)  # exceedance probability among impacts
    rng = np.random.default_rng([seed, k])
    truth_est, empirical = [], []
    for _ in range(subsamples):
        s = rng.choice(impacts, size=min(k, impacts.size), replace=False)
        truth_est.append(fit_weibull3_ls(s, top_fraction=0.3).isf(q) / data.truth_mpm - 1.0)
        empirical.append(np.quantile(s, 1.0 - q) / data.truth_mpm - 1.0)
    return np.asarray(truth_est), np.asarray(empirical)


def pas_on_random_events(data, k: int, draws: int, seed: int):
    """Relative MPM errors of PAS's default estimator on ``draws`` random sets of k pool events."""
    from pas.screening import LFSet
    from pas.strategies.base import Pairs
    from pas.strategies.pas import PAS

    s = LFSet(data.lf, n_waves=data.n_waves, p_exp=data.p_exp, threshold=data.threshold)
    hs = np.asarray(data.hf, float)[s.index]
    rng = np.random.default_rng([seed, k, 7])
    errors = []
    for _ in range(draws):
        pick = np.sort(rng.choice(s.n, size=min(k, s.n), replace=False))
        tp, fp = pick[hs[pick] > 0], pick[hs[pick] == 0]
        if tp.size < PAS.min_pairs:
            continue
        strategy = PAS(n_bootstrap=0)
        strategy.reset(seed)
        pairs = Pairs(tp, s.lf[tp], hs[tp], s.d[tp], s.lf[fp], fp)
        try:
            mpm = strategy.predict(pairs, s, np.random.default_rng(0)).mpm
        except ValueError:
            continue
        errors.append(mpm / data.truth_mpm - 1.0)
    return np.asarray(errors)


def _row(errors):
    a = np.abs(errors)
    return (f"{100 * np.median(a):5.1f} % {100 * np.quantile(a, 0.9):6.1f} % "
            f"{np.mean(a <= 0.25) ** 10:6.2f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10, help="data seeds 0…N−1")
    ap.add_argument("--k", default="50,100,160")
    ap.add_argument("--cases", default="3a,3b,4a,4b")
    ap.add_argument("--subsamples", type=int, default=40)
    ap.add_argument("--pas-runs", default=None,
                    help="runs.csv of validation_spread.py: adds k = PAS's median pairs")
    args = ap.parse_args(argv)
    cases = args.cases.split(",")
    ks = {c: [int(x) for x in args.k.split(",")] for c in cases}
    if args.pas_runs:
        import pandas as pd

        runs = pd.read_csv(args.pas_runs)
        runs = runs[runs.strategy == "pas"]
        for c in cases:
            g = runs[runs.case == c]
            if len(g):
                ks[c] = sorted(set(ks[c]) | {int(np.median(g.n_hf - g.n_false_positive))})
    print("| case | k impacts | truth-estimator: median / p90 \\|error\\| / P(worst of 10 ≤ 25 %) "
          "| empirical quantile: same |")
    print("|---|---|---|---|")
    data_sets = {c: [generate_case(c, seed=s) for s in range(args.n)] for c in cases}
    for c in cases:
        data = data_sets[c]
        for k in ks[c]:
            errs = [reference_errors(d, k, args.subsamples, s) for s, d in enumerate(data)]
            t = np.concatenate([e[0] for e in errs])
            e = np.concatenate([e[1] for e in errs])
            print(f"| {c} | {k} | {_row(t)} | {_row(e)} |", flush=True)
    if not args.pas_runs:
        return
    print("\n| case | PAS on random pool events (k = PAS's HF count per data set): median / p90 "
          "\\|error\\| / P(worst of 10 ≤ 25 %) | PAS (MD): median / worst \\|M2\\| |")
    print("|---|---|---|")
    for c in cases:
        g = runs[runs.case == c].set_index("seed")
        if not len(g):
            continue
        errs = np.concatenate([pas_on_random_events(d, int(g.n_hf[s]), 5, s)
                               for s, d in enumerate(data_sets[c]) if s in g.index])
        pas_m2 = g.M2.abs()
        print(f"| {c} | {_row(errs)} | {100 * pas_m2.median():.1f} % / {100 * pas_m2.max():.1f} % |",
              flush=True)


if __name__ == "__main__":
    main()
