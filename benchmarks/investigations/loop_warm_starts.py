"""Do a study's warm-started fits find the optimum?  Each fit against a start from the data.

A study's joint fits start from the previous iteration's fits, and only every
``COLD_EVERY``-th fit also from the data (``pas.strategies.estimators``).
This script runs known-truth studies with the defaults and, at every fit that
started warm only, fits the same candidates again with the start from the data
too, without letting that change the study.  It prints per study how many
candidate fits the cold start improved (log-likelihood gain > 1e-3, > 1) and
in how many fits it would have selected another candidate, then both per
pair-count bin.  ``--compare`` instead runs each study twice, as it is and
with ``estimators.COLD_UP_TO = 20`` (``--up-to``: every fit on 20 pairs or
fewer also starts from the data; ``--precision``: both with the precision
stop instead of ε1), and prints per group the median |error| of the MPM
against the exact truth, how often the U95 held it, the mean HF count and the
loop's CPU time, both ways.  Writes ``loop_warm_starts.csv``; ``--write [PAGE]
--from-csv FILE,…`` puts the probe's per-bin table between the
``loop_warm_starts.py probe`` markers of PAGE (default
``docs/results/investigations.md``).

Run: python benchmarks/investigations/loop_warm_starts.py [N] [--types all] [--held-out]
     [--first 0] [--compare [--up-to 20] [--precision P]] [--out pas-output/loop-warm]
     python benchmarks/investigations/loop_warm_starts.py --write --from-csv A.csv,B.csv
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pas.models.copulas import select_family
from pas.strategies import estimators
from pas.validation.known_truth import make_problem
from pas.validation.known_truth_runs import (
    TYPES,
    add_study_arguments,
    known_truth_study,
    select_types,
)
from pas.validation.result_tables import rewrite_page
from pas.validation.timing_problem import cpu_seconds

BINS = [0, 10, 20, 40, 80, 10_000]
BIN_LABELS = ["≤ 10", "11–20", "21–40", "41–80", "> 80"]
PAGE = Path("docs/results/investigations.md")


def selected(joint):
    """The candidate a fit selects, without the study's hysteresis (:func:`select_family`)."""
    return select_family({f: j.copula for f, j in joint.items()}, exclude_at_bound=True)


def probing(records, labels):
    """``estimators.fit_hf_candidates`` recording, at each warm-only fit, what a start from
    the data as well would have found (the study goes on with the warm fits)."""
    fit = estimators.fit_hf_candidates

    def probe(u, h, families, choice, *, starts=None, cold=True, **kw):
        every, joint = fit(u, h, families, choice, starts=starts, cold=cold, **kw)
        if cold is False and starts:
            every_cold, joint_cold = fit(u, h, families, choice, starts=starts, cold=True, **kw)
            for key, f in every.items():
                records.append(labels | {"m": len(h), "key": "/".join(key),
                                         "gain": every_cold[key].copula.loglik - f.copula.loglik})
            a, b = selected(joint), selected(joint_cold)
            records.append(labels | {"m": len(h), "key": "selected", "gain": float(a != b),
                                     "aic_gap": joint[a].copula.aic - joint_cold[b].copula.aic})
        return every, joint

    return probe


def study_of(name, replication, max_hf, precision=None, **settings):
    """The known-truth study as the defaults run it: its own ε1 stop, or with ``precision``
    the precision stop."""
    problem = make_problem(TYPES[name], replication)
    stop = {} if precision is None else {"eps1": None, "precision": precision}
    return problem, known_truth_study(problem, max_hf=max_hf, **stop, **settings)


def probe_one(name, replication, max_hf, records):
    labels = {"type": name, "group": name.split("-")[0], "replication": replication}
    saved = estimators.fit_hf_candidates
    estimators.fit_hf_candidates = probing(records, labels)
    try:
        problem, study = study_of(name, replication, max_hf, n_bootstrap=0)  # the loop only
        res = study.optimize(problem.oracle())
    finally:
        estimators.fit_hf_candidates = saved
    d = pd.DataFrame([r for r in records if r["type"] == name and r["replication"] == replication])
    fits, sel = d[d.key != "selected"], d[d.key == "selected"]
    print(f"{name:36s} {replication:3d} {res.n_hf:4d} HF  fits {len(fits):5d}  gain > 1e-3 "
          f"{int((fits.gain > 1e-3).sum()):4d}, > 1 {int((fits.gain > 1).sum()):3d} (max "
          f"{fits.gain.max():6.2f})  selection changed {int(sel.gain.sum())} of {len(sel)}",
          flush=True)


def compare_one(name, replication, max_hf, precision=None, up_to=20):
    row = {"type": name, "group": name.split("-")[0], "replication": replication}
    histories = {}
    for label, limit in (("now", estimators.COLD_UP_TO), ("cold20", up_to)):
        saved, estimators.COLD_UP_TO = estimators.COLD_UP_TO, limit
        try:
            problem, study = study_of(name, replication, max_hf, precision)
            t = cpu_seconds()
            res = study.optimize(problem.oracle())
            cpu = cpu_seconds() - t
        finally:
            estimators.COLD_UP_TO = saved
        histories[label] = study.history()
        lo, hi = res.mpm_band
        row |= {f"{label}_n_hf": res.n_hf, f"{label}_error": res.mpm / problem.truth_mpm - 1,
                f"{label}_covered": bool(lo <= problem.truth_mpm <= hi), f"{label}_cpu": cpu}
    a, b = histories["now"], histories["cold20"]
    k = min(len(a), len(b))
    row["same_events"] = bool(len(a) == len(b) and np.array_equal(a.event_index, b.event_index))
    row["family_changed"] = int(np.sum(a.family[:k].astype(str).values
                                       != b.family[:k].astype(str).values))
    with np.errstate(all="ignore"):
        change = np.abs(b.mpm[:k].to_numpy(float) / a.mpm[:k].to_numpy(float) - 1)
    row["mpm_change"] = float(np.nanmax(change)) if k else np.nan
    row["mpm_change_above_20"] = float(np.nanmax(change[a.n_pairs[:k].to_numpy(float) > 20],
                                                 initial=0.0))
    print(f"{name:36s} {replication:3d}  HF {row['now_n_hf']:4d} / {row['cold20_n_hf']:4d}  "
          f"error {row['now_error']:+.3f} / {row['cold20_error']:+.3f}  covered "
          f"{row['now_covered']:d}/{row['cold20_covered']:d}  same events {row['same_events']:d}  "
          f"family changed in {row['family_changed']} iterations, MPM by up to "
          f"{row['mpm_change']:.1e} ({row['mpm_change_above_20']:.1e} above 20 pairs)", flush=True)
    return row


def per_bin(records: pd.DataFrame):
    """The probe's candidate fits and fits by pair-count bin (:data:`BINS`)."""
    fits = records[records.key != "selected"].assign(pairs=lambda d: pd.cut(d.m, BINS))
    sel = records[records.key == "selected"].assign(pairs=lambda d: pd.cut(d.m, BINS))
    by_fit = fits.groupby("pairs", observed=False).gain.agg(
        fits="size", improved=lambda g: int((g > 1e-3).sum()),
        by_over_1=lambda g: int((g > 1).sum()), largest="max")
    by_fit["selection_changed"] = sel.groupby("pairs", observed=False).gain.sum().astype(int)
    by_fit["selections"] = sel.groupby("pairs", observed=False).size()
    return by_fit


def probe_table(records: pd.DataFrame) -> str:
    """The page's table of :func:`per_bin`."""
    lines = ["| pairs in the fit | candidate fits | better from the data by > 1 in "
             "log-likelihood (largest) | fits selecting another candidate |", "|---|---|---|---|"]
    for label, (_, r) in zip(BIN_LABELS, per_bin(records).iterrows()):
        largest = f"{r.largest:.1f}" if r.largest >= 1 else f"{r.largest:.2f}"
        lines.append(f"| {label} | {int(r.fits):,} | {int(r.by_over_1)} ({largest}) | "
                     f"{int(r.selection_changed)} of {int(r.selections)} |".replace(",", " "))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_study_arguments(ap, n=1)
    ap.add_argument("--compare", action="store_true")
    ap.add_argument("--up-to", type=int, default=20,
                    help="--compare: COLD_UP_TO of the second run (its columns keep the name cold20)")
    ap.add_argument("--precision", type=float,
                    help="--compare: stop on this precision target instead of ε1")
    ap.add_argument("--out", default="pas-output/loop-warm")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"write the probe's table between the markers of PAGE (default {PAGE})")
    ap.add_argument("--from-csv", help="comma-separated loop_warm_starts.csv files of probe runs")
    args = ap.parse_args(argv)
    if args.write:
        if not args.from_csv:
            ap.error("--write needs --from-csv FILE,… (the probe runs' loop_warm_starts.csv)")
        records = pd.concat([pd.read_csv(f) for f in args.from_csv.split(",")])
        rewrite_page(args.write, {"probe": probe_table(records)}, "loop_warm_starts.py")
        return
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in select_types(args.types, held_out=args.held_out):
            for r in range(args.first, args.first + args.n):
                if args.compare:
                    rows.append(compare_one(name, r, args.max_hf, args.precision, args.up_to))
                else:
                    probe_one(name, r, args.max_hf, rows)
                pd.DataFrame(rows).to_csv(out / "loop_warm_starts.csv", index=False)
    d = pd.DataFrame(rows)
    if args.compare:
        summary = d.groupby("group").agg(
            studies=("type", "size"),
            err_now=("now_error", lambda e: np.median(np.abs(e))),
            err_cold20=("cold20_error", lambda e: np.median(np.abs(e))),
            covered_now=("now_covered", "mean"), covered_cold20=("cold20_covered", "mean"),
            hf_now=("now_n_hf", "mean"), hf_cold20=("cold20_n_hf", "mean"))
        print(summary.round(3).to_string())
        print(f"\n{len(d)} studies: median |error| {np.median(np.abs(d.now_error)):.4f} -> "
              f"{np.median(np.abs(d.cold20_error)):.4f}; U95 held {int(d.now_covered.sum())} -> "
              f"{int(d.cold20_covered.sum())}; HF {d.now_n_hf.mean():.1f} -> "
              f"{d.cold20_n_hf.mean():.1f}; study CPU cold20/now "
              f"{d.cold20_cpu.sum() / d.now_cpu.sum():.3f}; MPM changed (> 1e-6) in "
              f"{int((abs(d.cold20_error - d.now_error) > 1e-6).sum())}; the same events in "
              f"{int(d.same_events.sum())}; an iteration's family changed in "
              f"{int((d.family_changed > 0).sum())} studies ({int(d.family_changed.sum())} "
              f"iterations); an iteration's MPM changed by up to {d.mpm_change.max():.2e} "
              f"({d.mpm_change_above_20.max():.2e} above 20 pairs)")
        return
    print(per_bin(d).to_string())


if __name__ == "__main__":
    main()
