"""Bias of record statistics on Rayleigh crests (Hs 10 m, 400 waves per one-hour seed).

Prints, for the issue-15 fixes, numbers measured in one run:

1. seed-maxima MPM bias at N = 3, 10, 20 seeds, 20 000 replications, with
   ``k/(N+1)`` (default) and the old ``k/N`` ranks (exact MPM: the e⁻¹
   quantile of the maximum of 400 crests);
2. the q = 0.9 quantile of the hourly maximum from the pooled peaks of 10
   seeds, Gringorten (default) against the paper's ``k/n``, 2000 replications;
3. R(N) of fresh N-seed campaigns against the finite-population corrected
   R(N) from 30 records of M = 40 seeds (and the raw subset RMS), with the
   coverage of the R(N) band.

Not a test. Run: ``python benchmarks/studies/records_bias.py``.
"""

import argparse
import time

import numpy as np

from pas.records import (
    mpm_convergence,
    mpm_pooled,
    quantile_pooled,
    rayleigh_crest_quantile,
    read_at_exceedance,
)

HS, N_W = 10.0, 400


def maxima(rng, shape):
    u = rng.random(shape)
    return HS * np.sqrt(-np.log(-np.expm1(np.log(u) / N_W)) / 8.0)


def seed_maxima_bias(rng, reps=20000):
    exact = rayleigh_crest_quantile(HS, N_W, np.exp(-1.0))
    print(f"1. seed-maxima MPM, {reps} replications (exact {exact:.3f} m):")
    for n in (3, 10, 20):
        m = -np.sort(-maxima(rng, (reps, n)), axis=1)
        for pos in ("weibull", "k/n"):
            e = read_at_exceedance(m, n, 1 - 0.368, positions=pos, scale="linear")
            print(
                f"   N = {n:2d}  {pos:8s} bias {e.mean() - exact:+.3f} m "
                f"(s.e. {e.std() / np.sqrt(reps):.3f}, "
                f"RMS {np.sqrt(np.mean((e - exact) ** 2)):.3f})"
            )


def pooled_q90_bias(rng, reps=2000, m=10):
    exact = rayleigh_crest_quantile(HS, N_W, 0.9)
    print(f"2. q = 0.9 of the hourly maximum from {m} pooled seeds, {reps} replications "
          f"(exact {exact:.3f} m):")
    est = {"gringorten": [], "k/n": []}
    for _ in range(reps):
        crests = list(rng.rayleigh(HS / 4, (m, N_W)))
        for pos in est:
            est[pos].append(quantile_pooled(crests, m * N_W, 0.9, positions=pos))
    for pos, e in est.items():
        e = np.array(e)
        print(f"   {pos:10s} bias {e.mean() - exact:+.3f} m (s.e. {e.std() / np.sqrt(reps):.3f})")


def r_of_n(rng, records=30, m=40, n_w=100, fresh_reps=4000):
    ns = [5, 10, 20, 30, 35]
    exact = HS * np.sqrt(np.log(n_w) / 8.0)
    fresh = np.array([np.sqrt(np.mean((np.array(
        [mpm_pooled(list(rng.rayleigh(HS / 4, (n, n_w))), n * n_w) for _ in range(fresh_reps)])
        - exact) ** 2)) for n in ns])
    rms, raw, inside = [], [], []
    for _ in range(records):
        cv = mpm_convergence(list(rng.rayleigh(HS / 4, (m, n_w))), m * n_w, n_values=ns, n_boot=200,
                             n_subsets=500, n_subsets_fit=0, seed=int(rng.integers(1 << 30)))
        rms.append(cv.rms["pooled"])
        raw.append(cv.rms_subsets["pooled"])
        inside.append((cv.rms_low["pooled"] <= fresh) & (fresh <= cv.rms_high["pooled"]))
    rms, raw, inside = np.mean(rms, 0), np.mean(raw, 0), np.mean(inside, 0)
    print(f"3. R(N), {records} records of M = {m} seeds x {n_w} crests; fresh: {fresh_reps} "
          "campaigns about the exact MPM")
    for i, n in enumerate(ns):
        print(f"   N = {n:2d} ({n / m:.2f} M): fresh {fresh[i]:.3f} m | corrected {rms[i]:.3f} m "
              f"({rms[i] / fresh[i] - 1:+.1%}) | raw subsets {raw[i]:.3f} m "
              f"({raw[i] / fresh[i] - 1:+.1%}) | band covers fresh in {inside[i]:.0%}")


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    rng = np.random.default_rng(2026)
    for f in (seed_maxima_bias, pooled_q90_bias, r_of_n):
        t0 = time.perf_counter()
        f(rng)
        print(f"   ({time.perf_counter() - t0:.1f} s)")
