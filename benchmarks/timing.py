"""Benchmark: where a PAS run spends its time, each figure beside its baseline (issue 27).

One scenario throughout: 15 000 Rayleigh LF peaks, ``n_w`` 16 364, a Gumbel
(θ = 3) copula to a Weibull HF load, stopping off, 80 HF (``--max-hf``).
Every ratio is measured in this one run, the old path beside the new:

* the Student-t joint fit with numerical differences (scipy's L-BFGS-B
  default, the old path) against its analytic gradient;
* the final model band cold-and-warm started (old) against warm started,
  on 1 and 2 cores (``n_jobs``);
* the long-record path at n = 15 k / 150 k / 1.5 M (``--long``).

Run: python benchmarks/timing.py [--max-hf 80] [--long] [--json out.json]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import time

import numpy as np
import pyvinecopulib as pv
from scipy import stats

import pas
import pas.joint
import pas.joint_mixture

N, N_W, P_EXP = 15000, 16364, 2.55e-3


def scenario(n=N, seed=1):
    """LF peaks and the oracle's HF value for each (a Gumbel copula, Weibull HF)."""
    rng = np.random.default_rng(seed)
    lf = rng.rayleigh(2.5, n)
    u = stats.rankdata(lf) / (n + 1.0)
    cop = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[3.0]]))
    v = cop.hinv1(np.column_stack([u, rng.uniform(size=n)]))
    return lf, stats.weibull_min(1.5, scale=5.0).ppf(np.clip(v, 1e-12, 1 - 1e-12))


@contextlib.contextmanager
def numerical_student():
    """The old path: the Student-t joint fit by scipy's numerical differences."""
    saved = pas.joint.GRADIENT_FAMILIES, pas.joint_mixture.GRADIENT_FAMILIES
    old = tuple(f for f in saved[0] if f != "student")
    pas.joint.GRADIENT_FAMILIES = pas.joint_mixture.GRADIENT_FAMILIES = old
    try:
        yield
    finally:
        pas.joint.GRADIENT_FAMILIES, pas.joint_mixture.GRADIENT_FAMILIES = saved


def run(max_hf, n=N, n_waves=N_W, **settings):
    """One run with stopping off: ``(result, CPU s per loop iteration, CPU s of the final band)``."""
    lf, hf = scenario(n)
    stamps = []

    def callback(study, row):
        stamps.append(time.process_time())

    t0 = time.process_time()
    res = pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=n_waves, p_exp=P_EXP,
                      eps1=1e-12, seed=0, max_hf=max_hf, callback=callback, **settings)
    return res, np.diff(np.r_[t0, stamps]), time.process_time() - stamps[-1]


def summary(res):
    """What must not change: MPM, band ends and the family sequence."""
    return {"mpm": float(res.mpm), "band": [float(x) for x in res.mpm_band],
            "model_band": None if res.mpm_band_model is None else
            [float(x) for x in res.mpm_band_model],
            "families": [str(f) for f in res.history["family"].fillna("")]}


def largest_change(a, b):
    """Largest relative change between two summaries' MPM and band ends, and whether the
    family sequences are the same."""
    x = np.r_[a["mpm"], a["band"], a["model_band"] or []]
    y = np.r_[b["mpm"], b["band"], b["model_band"] or []]
    return float(np.max(np.abs(x - y) / np.abs(x))), a["families"] == b["families"]


def student_iterations(m=80, repeats=9):
    """CPU ms of one Student-t-only iteration (median over warm-started repeats) at ``m`` pairs."""
    from pas.screening import LFSet
    from pas.strategies.base import Pairs
    from pas.strategies.pas import PAS

    lf, hf = scenario()
    lfset = LFSet(lf, n_waves=N_W, p_exp=P_EXP)
    pos = np.unique(np.round(np.geomspace(1, lfset.n, m)).astype(int) - 1)
    pairs = Pairs(pos, lfset.lf[pos], hf[lfset.index[pos]], lfset.d[pos])
    strat = PAS(families=("student",))
    times = []
    for k in range(repeats):
        t = time.process_time()
        strat.predict(pairs, lfset, np.random.default_rng(k))
        times.append(time.process_time() - t)
    return 1e3 * float(np.median(times)), 1e3 * float(np.max(times))


def part_fit(max_hf):
    """The Student-t gradient: the whole run and Student-t alone, numerical vs analytic."""
    print(f"-- Student-t joint fit: numerical differences (old) vs analytic gradient (new)")
    out = {}
    for label, ctx in (("old", numerical_student), ("new", contextlib.nullcontext)):
        with ctx():
            res, loop, band = run(max_hf)
            st = student_iterations()
        out[label] = summary(res)
        total = loop.sum() + band
        print(f"  {label}: run_pas {max_hf} HF {1e3 * total / max_hf:6.1f} ms/HF; loop median "
              f"{1e3 * np.median(loop):5.1f} ms, worst {1e3 * loop.max():6.1f} ms; final band "
              f"{band:5.2f} s; Student-t alone (80 pairs) median {st[0]:5.1f} ms, "
              f"worst {st[1]:5.1f} ms")
        out[label]["times"] = [total, float(np.median(loop)), float(loop.max()), band, *st]
    rel, same = largest_change(out["old"], out["new"])
    t_old, t_new = out["old"]["times"], out["new"]["times"]
    print(f"  ratio new/old: run {t_new[0] / t_old[0]:.2f}, loop median {t_new[1] / t_old[1]:.2f}, "
          f"Student-t alone {t_new[4] / t_old[4]:.2f}; largest relative change of MPM and band "
          f"ends {rel:.1e}; family sequence {'the same' if same else 'DIFFERENT'}")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-hf", type=int, default=80)
    parser.add_argument("--parts", default="fit", help="comma-separated: fit, band, long")
    parser.add_argument("--json", help="write the figures here")
    args = parser.parse_args()
    out = {}
    parts = {"fit": part_fit}
    for part in args.parts.split(","):
        out[part] = parts[part](args.max_hf)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh)


if __name__ == "__main__":
    main()
