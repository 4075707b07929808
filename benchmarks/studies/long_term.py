"""The long-term validation table: four methods on the same redrawn data sets (issue 29).

Run: python benchmarks/studies/long_term.py run ANALOGUE --seeds N --out DIR   (one analogue: 3 or 2)
     python benchmarks/studies/long_term.py write DIR [DIR ...] --page docs/results/long-term.md

``run`` generates data sets ``1 … N`` of a long-term analogue
(:func:`pas.validation.long_term_compare.long_term_data`: the North-Atlantic
scatter, the cells a pilot keeps with 100 one-hour realisations each, the
others 4), computes the brute-force truth at 5e-6, 2e-6 and 1e-6 per
encounter on the whole set and on its two halves (odd and even
realisations: the convergence check) and the 20-year level, then runs the
four methods (:data:`~pas.validation.long_term_compare.METHODS`) at
``P_VALIDATED``; it writes ``runs_<a>.csv``, ``truth_<a>.csv`` and
``cells_<a>.csv`` into DIR, appending seed by seed (a killed run keeps what
it finished; ``run`` again skips the finished seeds).  ``write`` puts the
tables between the page's markers (``<!-- BEGIN long_term.py NAME -->`` …
``<!-- END … NAME -->``): the page's numbers are this script's output, never
edited by hand.  ≈ 8 min per green-water data set, ≈ 5 min per VBM one here.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pas.validation.result_tables import write_between_markers

LEVELS = (5e-6, 2e-6, 1e-6)
KEPT_HOURS = 100      # one-hour realisations per kept cell (long_term_compare.KEPT_HOURS)
TARGET_CV = 0.02      # the truth's spread the green-water goal needs


def _truth_row(data, seconds, plan):
    from pas.validation.long_term import value_at_exceedance_long_term
    from pas.validation.long_term_compare import P_VALIDATED

    row = {"analogue": data.analogue, "data_seed": data.seed, "generation_s": seconds,
           "hf_events": int(sum(v.size for v in data.hf.values()))}
    for half in (0, 1):
        hf = {s: data.hf[s][data.meta[s]["seed_no"].to_numpy() % 2 == half] for s in data.hf}
        for p in LEVELS:
            row[f"half{half}_{p:g}"] = value_at_exceedance_long_term(p, data.weights, hf)
    for p in LEVELS:
        row[f"truth_{p:g}"] = data.truth(p)
    p20 = data.p_exceed_of_return_period(20)
    share = data.contributions(P_VALIDATED).set_index("sea_state")
    dropped = list(plan["name"][~plan["kept"]])
    row.update({"p_20y": p20, "truth_20y": data.truth(p20),
                "dropped_share": share.loc[dropped, "share"].sum(),
                "dropped_share_u95": share.loc[dropped, "share_u95"].sum()})
    return row


def run(analogue, seeds, out, methods):
    from pas.validation.long_term_compare import P_VALIDATED, compare, long_term_data
    from pas.validation.long_term_compare import _lf_only as lf_only

    out.mkdir(parents=True, exist_ok=True)
    runs_file, truth_file = out / f"runs_{analogue}.csv", out / f"truth_{analogue}.csv"
    done = set(pd.read_csv(truth_file)["data_seed"]) if truth_file.exists() else set()
    for seed in range(1, seeds + 1):
        if seed in done:
            continue
        t0 = time.perf_counter()
        data, plan = long_term_data(analogue, seed=seed, progress=None)
        truth = _truth_row(data, time.perf_counter() - t0, plan)
        truth["lf_only_20y"] = lf_only(data, truth["p_20y"])[0]
        kept = list(plan["name"][plan["kept"]])
        table = compare(data, P_VALIDATED, kept=kept, methods=methods, seed=0,
                        progress=lambda m: print(m, flush=True))
        table.to_csv(runs_file, mode="a", header=not runs_file.exists(), index=False)
        pd.DataFrame([truth]).to_csv(truth_file, mode="a", header=not truth_file.exists(),
                                     index=False)
        plan.assign(l_min=plan.attrs["l_min"]).to_csv(out / f"cells_{analogue}.csv", index=False)
        print(f"seed {seed}: truth {truth[f'truth_{P_VALIDATED:g}']:.5g}, "
              f"{time.perf_counter() - t0:.0f} s", flush=True)


def truth_only(analogue, seeds, out):
    """Rewrite ``truth_<a>.csv`` from the cached data sets (no method is run)."""
    from pas.validation.long_term_compare import _lf_only as lf_only
    from pas.validation.long_term_compare import long_term_data

    rows = []
    for seed in range(1, seeds + 1):
        t0 = time.perf_counter()
        data, plan = long_term_data(analogue, seed=seed)
        rows.append(_truth_row(data, time.perf_counter() - t0, plan))
        rows[-1]["lf_only_20y"] = lf_only(data, rows[-1]["p_20y"])[0]
    out.mkdir(parents=True, exist_ok=True)
    pd.DataFrame(rows).to_csv(out / f"truth_{analogue}.csv", index=False)


def _fmt(v):
    return "n/a" if not np.isfinite(v) else f"{v:.4g}"


def _pct(v):
    return "n/a" if not np.isfinite(v) else f"{100 * v:+.1f} %"


def _truth_cv(g, p):
    """CV of the truth over data sets at level ``p``: of the halves (every half its own value)
    and of the full sets."""
    full = g[f"truth_{p:g}"].to_numpy(float)
    halves = np.concatenate([g[f"half0_{p:g}"], g[f"half1_{p:g}"]]).astype(float)
    return (float(np.std(halves, ddof=1) / np.mean(halves)),
            float(np.std(full, ddof=1) / np.mean(full)))


def _hours_for(cv, hours, target=TARGET_CV):
    """The record length (hours per kept cell) at which ``cv`` measured at ``hours`` falls to
    ``target``, extrapolated as 1/√length."""
    return hours * (cv / target) ** 2


def _summary_row(analogue, method, g):
    """One method's line of a comparison table over the runs ``g``."""
    if g["value"].isna().all():
        return f"| {analogue} | {method} | {len(g)} | not run: {g['note'].iloc[0]} | | | | | | |"
    err = g["error"].abs()
    cov = g["covered"].dropna()
    width = ((g["band_high"] - g["band_low"]) / g["truth"]).median()
    return (f"| {analogue} | {method} | {len(g)} | {100 * err.median():.1f} % | "
            f"{100 * err.max():.1f} % | {_pct(g['error'].median())} | "
            + (f"{int(cov.astype(bool).sum())}/{len(cov)}" if len(cov) else "–")
            + f" | {f'{100 * width:.1f} %' if np.isfinite(width) else '–'} | "
            f"{g['n_hf'].median():g} | {g['seconds'].median():.0f} s |")


def tables(dirs):
    runs = pd.concat([pd.read_csv(f) for d in dirs for f in sorted(Path(d).glob("runs_*.csv"))])
    truth = pd.concat([pd.read_csv(f) for d in dirs
                       for f in sorted(Path(d).glob("truth_*.csv"))])
    cells = {f.stem[-1]: pd.read_csv(f) for d in dirs for f in sorted(Path(d).glob("cells_*.csv"))}
    for t in (runs, truth):
        t["analogue"] = [str(int(float(a))) for a in t["analogue"]]
    # a later folder (e.g. a rerun of one method) wins; a method that was run beats "not run"
    truth = truth.drop_duplicates(["analogue", "data_seed"], keep="last")
    # rows of a process started before pas.run_long_term was in the build: not a result
    runs = runs[~runs["note"].fillna("").str.contains("not available in this build")]
    from pas.validation.long_term_compare import METHODS
    runs = runs.assign(order=runs["method"].map(METHODS.index)).sort_values(
        ["analogue", "order", "data_seed"], ascending=[False, True, True], kind="stable")
    truth = truth.sort_values(["analogue", "data_seed"], ascending=[False, True], kind="stable")
    runs = (runs.assign(ran=runs["value"].notna()).sort_values("ran", kind="stable")
            .drop_duplicates(["analogue", "data_seed", "method"], keep="last")
            .sort_index(kind="stable"))
    labels = {"3": "green water (kN)", "2": "hogging VBM (N m)"}

    def name(a):
        return labels[str(int(float(a)))]

    comp = ["| analogue | method | data sets | median \\|error\\| | worst \\|error\\| | "
            "median error | U95 coverage | median band width | HF spent (median) | "
            "wall time (median) |", "|---|---|---|---|---|---|---|---|---|---|"]
    runs = runs.assign(order=runs["method"].map(METHODS.index)).sort_values(
        ["analogue", "order", "data_seed"], ascending=[False, True, True], kind="stable")
    common = {a: set.intersection(*(set(g2["data_seed"]) for _, g2 in g.groupby("method")))
              for a, g in runs.groupby("analogue")}
    same = runs[[s in common[a] for a, s in zip(runs["analogue"], runs["data_seed"])]]
    per_run = ["| analogue | data set | method | truth | value | error | U95 | HF | wall time |",
               "|---|---|---|---|---|---|---|---|---|"]
    for _, r in runs.iterrows():
        per_run.append(f"| {name(r['analogue'])} | {int(r['data_seed'])} | {r['method']} | "
                       f"{_fmt(r['truth'])} | {_fmt(r['value'])} | {_pct(r['error'])} | "
                       f"{_fmt(r['band_low'])} … {_fmt(r['band_high'])} | {int(r['n_hf'])} | "
                       f"{r['seconds']:.0f} s |")
    every = [comp[0].replace("U95 coverage", "U95 coverage (≥ 10 runs to claim it)"), comp[1]]
    for rows, frame in ((comp, same), (every, runs)):
        for (a, m), g in frame.groupby(["analogue", "method"], sort=False):
            rows.append(_summary_row(name(a), m, g))
    conv = ["| analogue | data set | HF events | truth 5e-6 | halves | truth 2e-6 | halves | "
            "truth 1e-6 | halves | 20-year level | brute force | LF-only | build (cache) |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for _, r in truth.iterrows():
        cols = []
        for p in LEVELS:
            cols += [_fmt(r[f"truth_{p:g}"]),
                     f"{_fmt(r[f'half0_{p:g}'])} / {_fmt(r[f'half1_{p:g}'])}"]
        conv.append(f"| {name(r['analogue'])} | {int(r['data_seed'])} | "
                    f"{int(r['hf_events'])} | " + " | ".join(cols)
                    + f" | {r['p_20y']:.3g} | {_fmt(r['truth_20y'])} (not validated) | "
                    f"{_fmt(r['lf_only_20y'])} | {r['generation_s']:.0f} s |")
    spread = ["| analogue | level | CV of the truth over data sets | median \\|half − half\\| / truth |",
              "|---|---|---|---|"]
    for a, g in truth.groupby("analogue", sort=False):
        for p in LEVELS:
            t = g[f"truth_{p:g}"]
            half = (g[f"half0_{p:g}"] - g[f"half1_{p:g}"]).abs() / t
            spread.append(f"| {name(a)} | {p:g} | {100 * t.std() / t.mean():.1f} % | "
                          f"{100 * half.median():.1f} % |")
    hours = ["| analogue | level | data sets | CV at 50 h per kept cell (halves) | CV at 100 h "
             "(full sets) | full/half | hours per kept cell for a 2 % CV, from 50 h | "
             "from 100 h |", "|---|---|---|---|---|---|---|---|"]
    for a, g in truth.groupby("analogue", sort=False):
        for p in LEVELS:
            cv_half, cv_full = _truth_cv(g, p)
            hours.append(f"| {name(a)} | {p:g} | {len(g)} | {100 * cv_half:.1f} % | "
                         f"{100 * cv_full:.1f} % | {cv_half / cv_full:.2f} (√2 = 1.41) | "
                         f"{_hours_for(cv_half, KEPT_HOURS / 2):.0f} h | "
                         f"{_hours_for(cv_full, KEPT_HOURS):.0f} h |")
    plan = ["| analogue | cells | kept | dropped: estimated share of Q | largest dropped | "
            "dropped: measured share (data sets, median) | its 95 % upper bound | l_min (LF) |",
            "|---|---|---|---|---|---|---|---|"]
    for a, c in cells.items():
        dropped = c[~c["kept"]]
        t = truth[truth["analogue"].astype(float) == float(a)]
        measured = (f"{100 * t['dropped_share'].median():.2f} % | "
                    f"{100 * t['dropped_share_u95'].median():.1f} %"
                    if "dropped_share" in t else "– | –")
        plan.append(f"| {name(a)} | {len(c)} | {int(c['kept'].sum())} | "
                    f"{100 * dropped['share_rayleigh'].sum():.2f} % | "
                    f"{100 * dropped['share_rayleigh'].max():.2f} % | {measured} | "
                    f"{_fmt(c['l_min'].iloc[0])} |")
    return {"comparison": "\n".join(comp), "every_run": "\n".join(every),
            "runs": "\n".join(per_run),
            "convergence": "\n".join(conv),
            "spread": "\n".join(spread), "truth_hours": "\n".join(hours),
            "cells": "\n".join(plan)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("analogue", choices=("3", "2"))
    r.add_argument("--seeds", type=int, default=5)
    r.add_argument("--out", type=Path, required=True)
    r.add_argument("--methods", default="pas-long-term,uniform,contour,lf-only")
    t = sub.add_parser("truth", help="only the truth table, from the cached data sets")
    t.add_argument("analogue", choices=("3", "2"))
    t.add_argument("--seeds", type=int, default=5)
    t.add_argument("--out", type=Path, required=True)
    w = sub.add_parser("write")
    w.add_argument("dirs", nargs="+", type=Path)
    w.add_argument("--page", type=Path)
    args = parser.parse_args(argv)
    if args.cmd == "run":
        run(args.analogue, args.seeds, args.out, tuple(args.methods.split(",")))
        return
    if args.cmd == "truth":
        truth_only(args.analogue, args.seeds, args.out)
        return
    blocks = tables(args.dirs)
    print(*blocks.values(), sep="\n\n")
    if args.page:
        page = args.page.read_text(encoding="utf-8")
        args.page.write_text(write_between_markers(page, blocks, "long_term.py"),
                             encoding="utf-8")


if __name__ == "__main__":
    main()
