"""Record analysis: does the Weibull-mixture candidate help `compare_load_distributions`?

The AIC-best of the load-distribution candidates (:mod:`pas.records.load_fits`) is
read at the MPM's exceedance probability among impacts, with and without the
two-component Weibull mixture among the candidates:

* **known laws** — ``N`` samples of n loads from a Fréchet, a log-normal, a
  Weibull (β 0.7), a gamma and a bore + impulse mixture, each with its exact
  quantile at q = 0.017 (about 4a's ``P_exp / rate``);
* **analogue records** — every impact load of ten data sets of 3a, 3b, 4a and 4b,
  against the data set's truth (a Weibull fitted to the top 30 % of the same
  loads, read at ``P_exp / rate``).

Run: python benchmarks/studies/load_fits_mixture.py [N] [--skip-records]
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np
from scipy import stats

from pas.records.load_fits import compare_load_distributions
from pas.stats.weibull_mixture import WeibullMixture
from pas.validation import generate_case

MIXTURE = "weibull_mixture"
LAWS = {
    "frechet": stats.invweibull(4.0, loc=0.0, scale=1000.0),
    "lognormal": stats.lognorm(0.8, loc=100.0, scale=500.0),
    "weibull": stats.weibull_min(0.7, loc=100.0, scale=300.0),
    "gamma": stats.gamma(2.0, loc=0.0, scale=300.0),
    "bore + impulse": WeibullMixture(100.0, 0.6, 150.0, 3.5, 550.0, 1.1),
}


def best_errors(loads, q: float, truth: float):
    """Relative quantile errors of the AIC-best candidate without and with the mixture,
    and the name of the best with it."""
    table = compare_load_distributions(loads)
    without = table[table.index != MIXTURE].index[0]
    return tuple(table.loc[name, "dist"].isf(q) / truth - 1.0
                 for name in (without, table.index[0])) + (table.index[0],)


def _line(label, errors, picks):
    a = np.abs(np.asarray(errors, float))
    names, counts = np.unique(picks, return_counts=True)
    return (f"{label}: median |error| without / with the mixture {np.median(a[:, 0]):.3f} / "
            f"{np.median(a[:, 1]):.3f}, worst {a[:, 0].max():.3f} / {a[:, 1].max():.3f}; "
            f"best with it: {', '.join(f'{n} {c}' for n, c in zip(names, counts))}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", nargs="?", type=int, default=10, help="draws per law")
    ap.add_argument("--skip-records", action="store_true", help="only the known laws")
    args = ap.parse_args(argv)
    n_draws = args.n
    warnings.simplefilter("ignore")
    q = 0.017
    for n in (400, 1700):
        for name, law in LAWS.items():
            rng = np.random.default_rng([n, 7])
            runs = [best_errors(law.isf(rng.uniform(size=n)), q, float(law.isf(q)))
                    for _ in range(n_draws)]
            print(_line(f"n {n}, {name}", [r[:2] for r in runs], [r[2] for r in runs]),
                  flush=True)
    if args.skip_records:
        return
    for case in ("3a", "3b", "4a", "4b"):
        runs = []
        for seed in range(10):
            data = generate_case(case, seed=seed)
            hf = np.asarray(data.hf, float)
            loads = hf[hf > 0]
            runs.append(best_errors(loads, data.p_exp / (loads.size / data.n_waves),
                                    data.truth_mpm))
        print(_line(f"{case}, every impact of 10 data sets", [r[:2] for r in runs],
                    [r[2] for r in runs]), flush=True)


if __name__ == "__main__":
    main()
