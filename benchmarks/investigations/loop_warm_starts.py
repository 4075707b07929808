"""Do a study's warm-started fits find the optimum?  Each fit against a start from the data.

A study's joint fits start from the previous iteration's fits, and only every
``COLD_EVERY``-th fit also from the data (``pas.strategies.estimators``).
This script runs known-truth studies with the defaults and, at every fit that
started warm only, fits the same candidates again with the start from the data
too, without letting that change the study.  It prints per study how many
candidate fits the cold start improved (log-likelihood gain > 1e-3, > 1) and
in how many fits it would have selected another candidate, then both per
pair-count bin.  Writes ``loop_warm_starts.csv``; ``--write [PAGE]
--from-csv FILE,…`` puts the probe's per-bin table between the
``loop_warm_starts.py probe`` markers of PAGE (default
``docs/results/investigations.md``).

Run: python benchmarks/investigations/loop_warm_starts.py [N] [--types all] [--held-out]
     [--first 0] [--out pas-output/loop-warm]
     python benchmarks/investigations/loop_warm_starts.py --write --from-csv A.csv,B.csv
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

import pandas as pd

from pas.models.copulas import select_family
from pas.strategies import estimators

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import (  # noqa: E402
    TYPES,
    add_study_arguments,
    known_truth_study,
    select_types,
)
from harness.result_tables import rewrite_page  # noqa: E402

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


def study_of(name, replication, max_hf, **settings):
    """The known-truth study as the defaults run it, with its own ε1 stop."""
    problem = make_problem(TYPES[name], replication)
    return problem, known_truth_study(problem, max_hf=max_hf, **settings)


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
                probe_one(name, r, args.max_hf, rows)
                pd.DataFrame(rows).to_csv(out / "loop_warm_starts.csv", index=False)
    d = pd.DataFrame(rows)
    print(per_bin(d).to_string())


if __name__ == "__main__":
    main()
