"""Benchmark: what the HF a precision study spends after its forecast says "out of reach" buy.

From the fit where the forecast first says that more HF are not expected to
reach the precision target (an infinite forecast: the U95 has not narrowed
with the pairs), a study goes on to its budget.  Per known-truth problem
(`benchmarks/harness/known_truth.py`, the types of ``precision_stop.py``) and
data set, run once to the budget (``--budget``, default 80 HF) per precision
target (``--targets``, default ±5 % and ±10 %), and compare the
study at that first "out of reach" fit with the study at its end: the MPM's
error against the truth, whether the U95 (the latest one the loop computed,
at the end the result's) holds the truth, its half-width, and whether the
study reached its target after all.  Studies whose forecast never said "out of
reach" are counted, not compared.

``--write`` puts the table between the ``<!-- BEGIN precision_out_of_reach.py
table -->`` markers of ``docs/results/precision.md``.

Run: ``python benchmarks/studies/precision_out_of_reach.py [N] [--types a,b]
[--targets 0.05,0.1] [--budget 80] [--csv runs.csv] [--from-csv runs.csv] [--write]``
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

import pas

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import TYPES as KNOWN_TRUTH  # noqa: E402
from harness.result_tables import rewrite_page  # noqa: E402

TYPES = ("core-gumbel-t0.6", "core-gaussian-t0.75", "core-clayton-t0.6", "core-frank-t0.6",
         "core-gaussian-t0.45", "core-gumbel-t0.3", "tail-gaussian-mix", "tail-gumbel-b3",
         "miss-low-gaussian-t0.7", "miss-spread-clayton-t0.4", "outlier-gumbel-t0.5",
         "reg-power-s0.3")
PAGE, TAG = Path("docs/results/precision.md"), "precision_out_of_reach.py"


def _band_at(history: pd.DataFrame, upto: int):
    """The U95 (model part widened by the sampling part) of the latest fit at or before row
    ``upto`` that computed one, as ``(low, high, that fit's MPM)``, or None."""
    rows = history.iloc[: upto + 1]
    if "model_low" not in rows:
        return None
    done = rows[rows["model_low"].notna()]
    if done.empty:
        return None
    r = done.iloc[-1]
    return min(r["model_low"], r["mpm_low"]), max(r["model_high"], r["mpm_high"]), r["mpm"]


def run_one(name, rep, lf, oracle, kw, truth, *, target, budget) -> dict:
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = pas.run_pas(lf, oracle, **kw, stopping=pas.Stopping(precision=target), seed=rep,
                          max_hf=budget)
    h = res.history.reset_index(drop=True)
    gave_up = h.index[np.isinf(h.get("forecast_hf", pd.Series(np.nan, index=h.index)))]
    out = {"problem": name, "data_set": rep, "target": target, "budget": budget,
           "truth": truth, "n_hf_end": res.n_hf, "reached": bool(res.converged),
           "error_end": res.mpm / truth - 1}
    lo, hi = res.mpm_band
    out.update(covered_end=bool(lo <= truth <= hi),
               halfwidth_end=max(hi - res.mpm, res.mpm - lo) / res.mpm)
    if len(gave_up):
        i = int(gave_up[0])
        row = h.iloc[i]
        band = _band_at(h, i)
        out.update(n_hf_gave_up=int(row["n_hf"]), error_gave_up=row["mpm"] / truth - 1,
                   covered_gave_up=(None if band is None else bool(band[0] <= truth <= band[1])),
                   halfwidth_gave_up=(math.nan if band is None else
                                      max(band[1] - band[2], band[2] - band[0]) / band[2]),
                   reached_after=bool(res.converged),
                   out_of_reach_at_end=bool(np.isinf(h["forecast_hf"].iloc[-1])))
    out["cpu_seconds"] = time.process_time() - t0
    return out


def table(runs: pd.DataFrame) -> str:
    gave = runs[runs["n_hf_gave_up"].notna()]
    lines = ["| problem | studies | forecast said out of reach | at HF (median) | HF spent after "
             "(median) | reached the target after | still out of reach at the end | median abs. "
             "error: then → end | U95 holds truth: then → end | median U95 half-width: then → "
             "end |",
             "|---|---|---|---|---|---|---|---|---|---|"]

    def row(label, all_, g):
        if g.empty:
            return f"| {label} | {len(all_)} | 0 | – | – | – | – | – | – | – |"
        pct = lambda x: f"{100 * np.nanmedian(np.abs(x)):.1f} %"  # noqa: E731
        share = lambda x: f"{int(np.sum(x.astype(bool)))}/{len(x)}"  # noqa: E731
        return (f"| {label} | {len(all_)} | {len(g)} | {np.median(g['n_hf_gave_up']):.0f} | "
                f"{np.median(g['n_hf_end'] - g['n_hf_gave_up']):.0f} | "
                f"{int(g['reached_after'].astype(bool).sum())}/{len(g)} | "
                f"{int(g['out_of_reach_at_end'].astype(bool).sum())}/{len(g)} | "
                f"{pct(g['error_gave_up'])} → {pct(g['error_end'])} | "
                f"{share(g['covered_gave_up'].astype(str).eq('True'))} → "
                f"{share(g['covered_end'])} | "
                f"±{100 * np.nanmedian(g['halfwidth_gave_up']):.0f} % → "
                f"±{100 * np.nanmedian(g['halfwidth_end']):.0f} % |")

    for (name, target), all_ in runs.groupby(["problem", "target"], sort=False):
        lines.append(row(f"{name} ±{100 * target:g} %", all_,
                         gave[(gave["problem"] == name) & (gave["target"] == target)]))
    for target, all_ in runs.groupby("target"):
        lines.append(row(f"all, ±{100 * target:g} %", all_, gave[gave["target"] == target]))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("n", nargs="?", type=int, default=2, help="data sets per problem")
    ap.add_argument("--types", default=",".join(TYPES))
    ap.add_argument("--targets", default="0.05,0.1")
    ap.add_argument("--budget", type=int, default=80)
    ap.add_argument("--csv", type=Path)
    ap.add_argument("--from-csv", type=Path)
    ap.add_argument("--write", action="store_true")
    args = ap.parse_args(argv)
    if args.from_csv:
        runs = pd.read_csv(args.from_csv)
    else:
        rows = []
        for name, rep in ((t, r) for t in args.types.split(",") if t
                          for r in range(1, args.n + 1)):
            p = make_problem(KNOWN_TRUTH[name], rep)  # the data sets of precision_stop.py
            kw = {"n_waves": p.n_waves, "p_exp": p.p_exp, "threshold": p.threshold}
            for target in map(float, args.targets.split(",")):
                rows.append(run_one(name, rep, p.lf, p.oracle(), kw, p.truth_mpm, target=target,
                                    budget=args.budget))
            print(rows[-1], flush=True)
            runs = pd.DataFrame(rows)
            if args.csv:
                runs.to_csv(args.csv, index=False)
    text = table(runs)
    print(text)
    if args.write:
        rewrite_page(PAGE, {"table": text}, TAG)


if __name__ == "__main__":
    main()
