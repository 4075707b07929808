"""Median time of one AS iteration (predict + MVPD propose) at paper scale.

n = 15 000 Rayleigh LF peaks, n_w = 16 000, P_exp = 2.5e-3, a noisy HF
(``1.2 l^1.1`` times lognormal(0, 0.25) noise), m = 20, 80, 160 true-positive
pairs placed like an AS run places them (the two initial extremes, the rest
clustered on ln d around P_exp).  The one-off multi-fidelity ``GP_L`` fit on
the thinned LF curve (cached per LF set) is timed separately.

Run: ``python3 benchmarks/timing/as_iteration.py``
"""

import argparse
import time

import numpy as np

from pas.strategies.as_ import AS
from pas.strategies.base import Pairs
from pas.strategies.screening import LFSet

N, N_W, P_EXP, REPEATS = 15_000, 16_000, 2.5e-3, 15


def pairs_for(lfset, hf, m, rng):
    centre = np.log(P_EXP / 2)
    targets = np.sort(centre + rng.normal(0.0, 0.8, m - 2))
    pos = {0, lfset.n - 1}
    for t in targets:
        order = np.argsort(np.abs(lfset.ln_d - t))
        pos.add(int(next(p for p in order if p not in pos)))
    pos = np.array(sorted(pos))
    return Pairs(pos, lfset.lf[pos], hf[lfset.index[pos]], lfset.d[pos])


def main():
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(1.0, N)
    hf = 1.2 * lf**1.1 * rng.lognormal(0.0, 0.25, N)
    lfset = LFSet(lf, n_waves=N_W, p_exp=P_EXP)
    for fidelity in ("multi", "single"):
        strategy = AS(fidelity=fidelity)
        if fidelity == "multi":
            t0 = time.perf_counter()
            strategy.predict(pairs_for(lfset, hf, 20, rng), lfset, rng)
            print(f"multi: one-off GP_L fit on the thinned LF curve "
                  f"({strategy.lf_model_.n_points} points) + first iteration: "
                  f"{1e3 * (time.perf_counter() - t0):.0f} ms")
        for m in (20, 80, 160):
            pairs = pairs_for(lfset, hf, m, rng)
            strategy.predict(pairs, lfset, rng)  # warm the caches
            times = []
            for _ in range(REPEATS):
                avail = np.ones(lfset.n, bool)
                avail[pairs.position] = False
                t0 = time.perf_counter()
                pred = strategy.predict(pairs, lfset, rng)
                strategy.propose(pairs.d, lfset, avail, pred, q=1)
                times.append(time.perf_counter() - t0)
            print(f"{fidelity:6s} m = {m:3d}: median iteration {1e3 * np.median(times):6.1f} ms "
                  f"(min {1e3 * min(times):.1f}, max {1e3 * max(times):.1f}; {REPEATS} repeats)")


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
