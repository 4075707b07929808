"""Record analysis of the case-1 analogue sea: crest MPM two ways, R(N), seeds needed.

Condition A (SPEC §4): JONSWAP Hs 10 m, Tp 11 s, γ 3.3, depth 30 m, 50 one-hour
seeds (df = 1/3600 Hz, FFT random phase), linear crests per zero-up-crossing
wave and the linear + second-order (Sharma & Dean, 0–5 rad/s) crest of the
same wave (:func:`pas.stats.matched_peaks`). Each seed is one exposure
duration (1 h); encounters are the counted linear zero up-crossings.

Prints the crest MPM from the pooled peaks, the seed maxima and a Weibull fit
(top 30 %), the Rayleigh and Forristall (2000, long-crested) theory, the
RMS error R(N) of fresh N-seed campaigns estimated from subsets of the 50 seeds
(W = 500 subsets, fits on 100 subsets; finite-population corrected) at
N = 1, 5, 10, 25, 40, and the seeds needed for R ≤ 3 % of Hs.
``--write [PAGE]`` also puts the MPM table between the ``records_case1.py``
markers of ``docs/results/investigations.md``.
Not a test. Run: ``python benchmarks/investigations/records_case1.py [--plot DIR] [--write]``.
"""

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import pas.waves as W
from pas.records import (
    analyse_record,
    forristall_crest_mpm,
    mpm_convergence,
    mpm_pooled,
    rayleigh_crest_mpm,
)
from pas.stats import matched_peaks, mean_period_from_peak_period

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import rewrite_page  # noqa: E402

HS, TP, GAMMA, DEPTH = 10.0, 11.0, 3.3, 30.0
N_SEEDS, DURATION, DT = 50, 3600.0, 0.1
CRITERION = 0.03 * HS
PAGE = Path("docs/results/investigations.md")


def spectrum(w):
    return W.jonswap(w, HS, TP, gamma=GAMMA)


def record():
    kernel = W.second_order_kernel(W.linear_sea(spectrum, DURATION, seed=0, depth=DEPTH))
    lin, nl, enc, m0 = [], [], [], []
    for seed in range(N_SEEDS):
        sea = W.linear_sea(spectrum, DURATION, seed=seed, depth=DEPTH)
        _, eta1 = sea.elevation(DT)
        _, eta2 = W.second_order_elevation(sea, DT, kernel=kernel)
        c1, c2, _, _ = matched_peaks(eta1, eta1 + eta2)
        lin.append(c1)
        nl.append(c2)
        enc.append(c1.size)
        m0.append(sea.m0)
    return lin, nl, np.array(enc), float(np.mean(m0))


def mpm_table(analyses, theory) -> str:
    """The page's table: each crest's MPM by the three estimators and by theory.

    ``analyses``: :func:`pas.records.analyse_record` of the linear and the
    second-order crest; ``theory``: ``(label, MPM)`` of each.
    """
    lines = ["| crest | pooled peaks | seed maxima (0.368 quantile) | Weibull, top 30 % | theory |",
             "|---|---|---|---|---|"]
    for crest, a, (label, value) in zip(("linear", "second order"), analyses, theory):
        lines.append(f"| {crest} | {a.mpm_pooled:.2f} m | {a.mpm_seed_maxima:.2f} m | "
                     f"{a.mpm_fit:.2f} m | {label} {value:.2f} m |")
    return "\n".join(lines)


def main(plot_dir=None, page=None):
    t0 = time.perf_counter()
    lin, nl, enc, m0 = record()
    t_gen = time.perf_counter() - t0
    n_t = enc.mean()
    t1 = mean_period_from_peak_period(TP, GAMMA)
    print(f"case-1 analogue, condition A: {N_SEEDS} x 1 h seeds, {enc.sum()} linear zero "
          f"up-crossings ({n_t:.1f} per hour, P_t = 1/{n_t:.1f} = {1 / n_t:.3e}); "
          f"realised Hs {4 * np.sqrt(m0):.3f} m; generated in {t_gen:.1f} s")
    theory = (("Rayleigh", rayleigh_crest_mpm(4 * np.sqrt(m0), n_t)),
              ("Forristall (2000, long-crested)", forristall_crest_mpm(HS, t1, DEPTH, n_t)))
    print(f"theory over {n_t:.0f} waves: Rayleigh {theory[0][1]:.2f} m, "
          f"Forristall 2D (T1 = Tp/1.198 = {t1:.2f} s) {theory[1][1]:.2f} m")
    results = {}
    for name, peaks in (("linear crest", lin), ("2nd-order crest", nl)):
        a = analyse_record(peaks, enc, top_fraction=0.3)
        results[name] = a
        print(f"{name:16s} MPM: pooled peaks {a.mpm_pooled:6.2f} m | seed maxima (0.368 q) "
              f"{a.mpm_seed_maxima:6.2f} m | Weibull top 30 % {a.mpm_fit:6.2f} m")
    with warnings.catch_warnings():  # 20 851 counted waves > 16 364 = 50 h / Tp: expected
        warnings.simplefilter("ignore", UserWarning)
        table = mpm_pooled(nl, 16364, exposure_encounters=1 / 2.55e-3)
    print(f"2nd-order crest MPM with the paper's Table 2 convention (n_w = 16 364, "
          f"P_exp = 2.55e-3): {table:.2f} m (paper: 10.53 m)")
    if page:
        rewrite_page(page, {"mpm": mpm_table(list(results.values()), theory)},
                     "records_case1.py")

    for name, peaks, w_fit in (("linear crest", lin, 0), ("2nd-order crest", nl, 100)):
        t0 = time.perf_counter()
        cv = mpm_convergence(peaks, enc, n_subsets=500, n_subsets_fit=w_fit, seed=2023)
        dt = time.perf_counter() - t0
        print(f"\n{name}: R(N) from the 50-seed pooled MPM {cv.reference:.2f} m "
              f"(W = 500 subsets{', fit on 100' if w_fit else ''}; {dt:.1f} s)")
        for n in (1, 5, 10, 25, 40):
            line = (f"  N = {n:2d}: R pooled {cv.rms['pooled'][n - 1]:.3f} m "
                    f"({100 * cv.rms['pooled'][n - 1] / HS:.2f} % Hs), "
                    f"R seed maxima {cv.rms['seed maxima'][n - 1]:.3f} m")
            if w_fit:
                line += (f", R fit {cv.rms['fit'][n - 1]:.3f} m "
                         f"(bias {cv.bias['fit'][n - 1]:+.3f} m)")
            print(line)
        # R(N) is the fresh-campaign estimate (finite-population corrected), NaN at N = 50
        need = {v: cv.seeds_needed(CRITERION, v) for v in cv.rms}
        print(f"  seeds needed for R <= 3 % Hs = {CRITERION:.2f} m: "
              + ", ".join(f"{v} {need[v]}" for v in need))
        if plot_dir:
            import matplotlib

            matplotlib.use("Agg")
            from pas.plotting import plot_record_analysis, plot_record_convergence

            fig, _ = plot_record_convergence(cv, criterion=CRITERION, units="m",
                                             variable=f"{name} MPM")
            fig.savefig(f"{plot_dir}/records_case1_convergence_{name[:3]}.png", dpi=110)
            fig, _ = plot_record_analysis(results[name], units="m", variable=name)
            fig.savefig(f"{plot_dir}/records_case1_exceedance_{name[:3]}.png", dpi=110)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plot", metavar="DIR", help="also save the figures to DIR")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"also write the MPM table between the markers of PAGE (default {PAGE})")
    args = ap.parse_args()
    main(args.plot, args.write)
