"""Benchmark: one PAS iteration at paper scale, and the paper's stack for the draws.

One iteration = Step 7–12 (outlier removal, five copula fits with AIC
selection — by default joint fits of copula and HF marginal (``pas.models.joint``;
``hf_marginal="both"`` fits a Weibull and a log-normal marginal with each copula),
with ``estimator="selected"`` MLE copulas and two Weibull LS marginals — z = 10
conditional realisations over n0 ≈ 15 000 LF peaks, mean distribution and
MPM) plus the MD proposal.
The paper's stack draws the same conditional samples with the `copulas`
package (`percent_point`, a brentq root per sample); it is timed on a slice
and scaled to the full 150 000 draws.

Run: python benchmarks/timing/iteration.py
Targets (SPEC §7): median ≤ 50 ms per iteration for every family (Student-t
included, issue 14), ≥ 100× the paper's stack.
"""

from __future__ import annotations

import argparse
import time

import copulas.bivariate as cb
import numpy as np
import pyvinecopulib as pv
from scipy import stats

from pas.strategies.base import Pairs
from pas.strategies.pas import PAS
from pas.strategies.screening import LFSet

N, N_W, P_EXP, Z = 15000, 16364, 2.55e-3, 10


def make_pairs(lfset, m, rng):
    pos = np.unique(np.round(np.geomspace(1, lfset.n, m)).astype(int) - 1)
    while pos.size < m:
        pos = np.unique(np.r_[pos, rng.integers(0, lfset.n)])
    cop = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[4.0]]))
    u = stats.rankdata(-lfset.lf[pos]) / (m + 1)
    v = cop.hinv1(np.column_stack([1 - u, rng.uniform(size=m)]))
    return Pairs(pos, lfset.lf[pos], stats.weibull_min(1.5, scale=5).ppf(v), lfset.d[pos])


def time_iteration(lfset, pairs, repeats, **settings):
    strat = PAS.from_flat(settings)  # flat names, e.g. hf_marginal="both"
    times, families = [], []
    for k in range(repeats):
        rng = np.random.default_rng(k)
        t = time.perf_counter()
        pred = strat.predict(pairs, lfset, rng)
        avail = np.ones(lfset.n, bool)
        avail[pairs.position] = False
        strat.propose(pairs.d, lfset, avail, pred)
        times.append(time.perf_counter() - t)
        families.append(pred.record["family"])
    return float(np.median(times)), max(set(families), key=families.count)


def paper_stack_draws(family, theta, u, n_total, n_slice=1500):
    """Seconds for ``n_total`` conditional draws with copulas' percent_point (timed on a slice)."""
    cop = cb.Bivariate.from_dict({"copula_type": family.upper(), "theta": theta, "tau": None})
    r = np.random.default_rng(0).uniform(1e-6, 1 - 1e-6, n_slice)
    t = time.perf_counter()
    cop.percent_point(r, u[:n_slice])
    return (time.perf_counter() - t) * n_total / n_slice


def pas_draws(family, theta, u, n_total):
    fam = getattr(pv.BicopFamily, family)
    b = pv.Bicop(family=fam, parameters=np.array([[theta]]))
    from pas.models.copulas import conditional_quantile
    rng = np.random.default_rng(0)
    t = time.perf_counter()
    conditional_quantile(b, np.tile(u, n_total // u.size), rng.uniform(1e-6, 1 - 1e-6, n_total))
    return time.perf_counter() - t


def student_draws(u, n_total, rho=0.6, nu=4.3):
    """Seconds for ``n_total`` Student-t conditional draws: pas (interpolated t quantile and
    CDF) and the same closed form with scipy's ``stdtrit``/``stdtr`` (the previous code)."""
    from scipy import special

    from pas.models.copulas import conditional_quantile

    b = pv.Bicop(family=pv.BicopFamily.student, parameters=np.array([[rho], [nu]]))
    uu, rr = (
        np.tile(u, n_total // u.size),
        np.random.default_rng(0).uniform(1e-6, 1 - 1e-6, n_total),
    )

    def scipy_inverse():
        x1 = special.stdtrit(nu, uu)
        scale = np.sqrt((nu + x1**2) * (1 - rho**2) / (nu + 1.0))
        return special.stdtr(nu, rho * x1 + scale * special.stdtrit(nu + 1.0, rr))

    times = []
    for f in (lambda: conditional_quantile(b, uu, rr), scipy_inverse):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
        times.append(out)
    (t_pas, v_pas, t_sp, v_sp) = times
    return t_pas, t_sp, float(np.max(np.abs(v_pas - v_sp)))


def main():
    rng = np.random.default_rng(1)
    lfset = LFSet(rng.rayleigh(2.5, N), n_waves=N_W, p_exp=P_EXP)
    print(f"PAS iteration, n = {N} LF peaks, z = {Z} (median of repeats; the joint fits start")
    print("from the previous iteration's, as in a study)")
    print(f"{'estimator':>13} {'pairs m':>8} {'family':>9} {'ms/iter':>9}  {'forced family':>14} "
          f"{'ms/iter':>9}")
    variants = {"conditional": {"hf_marginal": "weibull"},
                "cond.+lognorm": {"hf_marginal": "both"},
                "selected": {"estimator": "selected"}}
    for label, settings in variants.items():
        for m in (20, 80, 160):
            pairs = make_pairs(lfset, m, rng)
            t, fam = time_iteration(lfset, pairs, 15, **settings)
            worst = []
            for forced in ("gaussian", "student", "clayton", "gumbel", "frank"):
                tf, _ = time_iteration(lfset, pairs, 7, families=(forced,), **settings)
                worst.append((tf, forced))
            tw, fw = max(worst)
            print(f"{label:>13} {m:>8} {fam:>9} {1e3 * t:>9.1f}  {fw + ' (slowest)':>14} "
                  f"{1e3 * tw:>9.1f}")
    u = np.sort(rng.uniform(0.001, 0.999, N))
    n_total = N * Z
    print(f"\nConditional draws, {n_total} quantiles (n0 = {N}, z = {Z})")
    draws = {}
    for family, theta in (("gumbel", 2.5), ("frank", 8.0), ("clayton", 2.0)):
        ours = pas_draws(family, theta, u, n_total)
        paper = paper_stack_draws(family, theta, u, n_total)
        draws[family] = (ours, paper)
        print(f"  {family:>8}: pas {1e3 * ours:8.1f} ms   copulas package {paper:8.2f} s   "
              f"ratio {paper / ours:8.0f}x")
    t_pas, t_sp, err = student_draws(u, n_total)
    print(f"   student: pas {1e3 * t_pas:8.1f} ms   scipy stdtrit/stdtr {1e3 * t_sp:6.1f} ms   "
          f"ratio {t_sp / t_pas:6.1f}x   max |dv| {err:.1e}")
    print("\nWhole iteration, m = 160 pairs, selected family drawn by each stack:")
    for family in ("gumbel", "frank"):
        t_iter, _ = time_iteration(lfset, pairs, 7, families=(family,))
        ours, paper = draws[family]
        print(f"  {family:>8}: pas {1e3 * t_iter:7.1f} ms   paper's stack "
              f"{t_iter - ours + paper:7.2f} s   ratio {(t_iter - ours + paper) / t_iter:6.0f}x")


if __name__ == "__main__":
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
