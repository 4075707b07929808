"""Coverage of the long-term U95 on a problem with a closed-form truth (issue 29).

The problem of ``tests/_longterm_problem.py``: five sea states with Rayleigh
LF peaks (5 000 encounters each), an HF load that is a strictly increasing
function of the LF peak (``smooth``) or 0 below an LF level and steep above
(``impact``); truth ``g(x_p)`` with the closed-form long-term LF quantile
``x_p``.  Each run redraws the LF records (data seed) and runs
:func:`pas.run_long_term` with PAS defaults; the script prints one line per
run and the coverage and error summary per problem, and writes ``runs.csv``.

Usage: ``python benchmarks/long_term_coverage.py [--n 12] [--max-hf 40] [--p 1e-3]``
(≈ 25 s per run on the shared two-core machine).
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import _longterm_problem as problem

import pas


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=12, help="redrawn data sets per problem")
    ap.add_argument("--max-hf", type=int, default=40)
    ap.add_argument("--p", type=float, default=1e-3, help="p_exceed per wave encounter")
    ap.add_argument("--out", default="runs.csv")
    args = ap.parse_args(argv)
    rows = []
    for name, g in (("smooth", problem.hf_smooth), ("impact", problem.hf_impact)):
        truth = problem.true_value(args.p, g)
        for seed in range(args.n):
            t0 = time.perf_counter()
            res = pas.run_long_term(problem.table(), problem.lf_peaks(seed), problem.Oracle(g),
                                    p_exceed=args.p, max_hf=args.max_hf, seed=100 + seed)
            lo, hi = res.band
            row = {"problem": name, "seed": seed, "truth": truth, "value": res.value,
                   "low": lo, "high": hi, "error": res.value / truth - 1,
                   "covered": lo <= truth <= hi, "n_hf": res.n_hf,
                   "n_sea_states_hf": int((res.contributions["n_hf"] > 0).sum()),
                   "seconds": time.perf_counter() - t0}
            rows.append(row)
            print(", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                            for k, v in row.items()), flush=True)
    df = pd.DataFrame(rows)
    df.to_csv(args.out, index=False)
    for name, d in df.groupby("problem"):
        print(f"{name}: coverage {d['covered'].mean():.0%} of {len(d)}, median |error| "
              f"{np.median(np.abs(d['error'])):.1%}, worst {np.abs(d['error']).max():.1%}, "
              f"median band width {np.median((d['high'] - d['low']) / d['truth']):.1%}, "
              f"median {np.median(d['seconds']):.0f} s per run")


if __name__ == "__main__":
    main()
