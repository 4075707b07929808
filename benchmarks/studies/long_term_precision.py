"""The long-term precision target on the long-term analogues: does a reached target tell the truth?

Run: python benchmarks/studies/long_term_precision.py run ANALOGUE --seeds N --out DIR
         [--first F] [--precisions 0.05,0.1,0.2] [--max-hf 400]
     python benchmarks/studies/long_term_precision.py write DIR_OR_CSV [...] [--page PAGE]

``run`` takes the data sets of :mod:`benchmarks.studies.long_term` (the same
cache: VBM, analogue 2, at p = 2e-6 with 100 h per kept cell; green water,
analogue 3, at p = 5e-6 with 200 h per kept cell) and runs
:func:`pas.run_long_term` on each with every ``precision`` target, the
sea-state studies without a stopping rule of their own (the target and the
budget decide), budget ``--max-hf``.  A row per run: whether it reached the
target, its error against the data set's brute-force truth, whether its U95
holds the truth, its HF count, and the forecast made halfway (in HF) to where
it reached the target against the HF it then still needed.  ``write`` puts
the summary table between ``<!-- BEGIN long_term_precision.py summary -->``
and its END marker of the page (default ``docs/results/long-term.md``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import write_between_markers  # noqa: E402

# analogue -> (p_exceed, scale of 100 h per kept cell)
LEVEL = {"2": (2e-6, 1.0), "3": (5e-6, 2.0)}
FACTOR = 1.5
PAGE, TAG = Path("docs/results/long-term.md"), "long_term_precision.py"


def halfway(history, n_stop):
    """``(forecast, needed, held)`` of the round halfway (in HF) to ``n_stop``: the further HF
    it forecast, the HF then still needed, and whether its 95 % interval held them."""
    h = history[history["n_hf"] >= n_stop / 2.0]
    if h.empty or not np.isfinite(h["forecast_hf"].iloc[0]):
        return np.nan, np.nan, None
    row = h.iloc[0]
    needed = n_stop - row["n_hf"]
    held = bool(row["forecast_hf_low"] <= needed <= row["forecast_hf_high"])
    return float(row["forecast_hf"]), float(needed), held


def one_run(data, p, precision, max_hf):
    from pas.longterm import run_long_term
    from pas.strategies.forecast import relative_half_width
    from pas.validation.long_term_compare import _with_thresholds

    peaks = {s: pd.DataFrame({"lf": data.lf[s], "id": data.ids[s]}) for s in data.lf}
    t0 = time.perf_counter()
    res = run_long_term(_with_thresholds(data), peaks, data.oracle(), p_exceed=p, seed=0,
                        max_hf=max_hf, precision=precision)
    seconds = time.perf_counter() - t0
    truth = data.truth(p)
    lo, hi = res.band
    forecast, needed, held = (halfway(res.history, res.n_hf) if res.converged
                              else (np.nan, np.nan, None))
    return {"analogue": data.analogue, "data_seed": data.seed, "p_exceed": p,
            "precision": precision, "max_hf": max_hf, "truth": truth, "value": res.value,
            "error": res.value / truth - 1.0, "band_low": lo, "band_high": hi,
            "halfwidth": relative_half_width(res.value, res.band),
            "floor": (res.forecast or {}).get("sampling_halfwidth", np.nan),
            "covered": bool(lo <= truth <= hi), "reached": bool(res.converged),
            "n_hf": int(res.n_hf), "forecast_halfway": forecast, "needed_halfway": needed,
            "interval_held": held, "seconds": seconds,
            "fit_seconds": float(res.contributions["fit_seconds"].sum()),
            "busiest_sea_state_seconds": float(res.contributions["fit_seconds"].max()),
            "sea_states_with_hf": int((res.contributions["n_hf"] > 0).sum())}


def run(analogue, seeds, out, precisions, max_hf, first=1):
    from pas.validation.long_term_compare import long_term_data

    p, scale = LEVEL[analogue]
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"precision_{analogue}.csv"
    done = set()
    if path.exists():
        old = pd.read_csv(path)
        done = set(zip(old["data_seed"], old["precision"]))
    for seed in range(first, seeds + 1):
        data = None
        for precision in precisions:
            if (seed, precision) in done:
                continue
            if data is None:
                data, _ = long_term_data(analogue, seed=seed, scale=scale, p_exceed=p)
            row = one_run(data, p, precision, max_hf)
            old = [pd.read_csv(path)] if path.exists() else []
            pd.concat([*old, pd.DataFrame([row])], ignore_index=True).to_csv(path, index=False)
            print(
                f"{analogue} seed {seed} ±{100 * precision:g} %: reached {row['reached']} at "
                f"{row['n_hf']} HF, error {row['error']:+.1%}, U95 ±{100 * row['halfwidth']:.1f} % "
                f"covered {row['covered']}, {row['seconds']:.0f} s",
                flush=True,
            )


NAMES = {"2": "hogging VBM", "3": "green water"}


def summary(runs) -> pd.DataFrame:
    rows = []
    for (a, prec, budget), g in runs.groupby(["analogue", "precision", "max_hf"], sort=True):
        r = g[g["reached"]]
        held = r["interval_held"].astype(str)
        others = g[~g["reached"]]
        ratio = r["forecast_halfway"] / r["needed_halfway"]
        within = ((ratio >= 1 / FACTOR) & (ratio <= FACTOR)).sum()
        rows.append({
            "analogue": NAMES.get(str(a), str(a)), "level": f"{g['p_exceed'].iloc[0]:g}",
            "target": f"±{100 * prec:g} %", "budget": int(budget), "runs": len(g),
            "reached": f"{len(r)}/{len(g)}",
            "U95 holds truth¹": f"{int(r['covered'].sum())}/{len(r)}" if len(r) else "–",
            "within ±10 %¹": f"{int((r['error'].abs() <= 0.10).sum())}/{len(r)}" if len(r) else "–",
            "median \\|error\\|¹": f"{100 * r['error'].abs().median():.1f} %" if len(r) else "–",
            "median HF¹": f"{r['n_hf'].median():g}" if len(r) else "–",
            "U95 of the others²": (f"±{100 * others['halfwidth'].median():.0f} %"
                                   if len(others) else "–"),
            "of it, what HF cannot narrow²": (f"±{100 * others['floor'].median():.0f} %"
                                              if len(others) else "–"),
            "halfway forecast within ×1.5¹": f"{int(within)}/{len(r)}" if len(r) else "–",
            "its interval held": (f"{int((held == 'True').sum())}"
                                  f"/{int(held.isin(['True', 'False']).sum())}") if len(r) else "–",
            "U95 holds truth (all runs)": f"{int(g['covered'].sum())}/{len(g)}",
        })
    return pd.DataFrame(rows)


def at_budget(runs) -> pd.DataFrame:
    """The runs that ended at their budget, one per data set (the lowest target that did not
    stop it): the analysis as the budget alone leaves it, the sea states without a stop."""
    rows = []
    for a, g in runs[~runs["reached"]].groupby("analogue", sort=True):
        one = g.sort_values("precision").drop_duplicates("data_seed")
        err = one["error"]
        rows.append({
            "analogue": NAMES.get(str(a), str(a)), "level": f"{one['p_exceed'].iloc[0]:g}",
            "data sets": len(one), "HF": f"{one['n_hf'].median():g}",
            "median \\|error\\|": f"{100 * err.abs().median():.1f} %",
            "worst \\|error\\|": f"{100 * err.abs().max():.1f} %",
            "median error": f"{100 * err.median():+.1f} %",
            "U95 holds truth": f"{int(one['covered'].sum())}/{len(one)}",
            "median U95 half-width": f"±{100 * one['halfwidth'].median():.0f} %",
            "wall time (median)": f"{one['seconds'].median():.0f} s"})
    return pd.DataFrame(rows)


def markdown(table) -> str:
    head = "| " + " | ".join(table.columns) + " |\n|" + "---|" * len(table.columns) + "\n"
    return head + "".join("| " + " | ".join(str(v) for v in row) + " |\n"
                          for row in table.itertuples(index=False))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("analogue", choices=sorted(LEVEL))
    r.add_argument("--seeds", type=int, default=5)
    r.add_argument("--first", type=int, default=1)
    r.add_argument("--out", type=Path, required=True)
    r.add_argument("--precisions", default="0.05,0.1,0.2")
    r.add_argument("--max-hf", type=int, default=400)
    w = sub.add_parser("write")
    w.add_argument("dirs", nargs="+", type=Path, help="run folders or their csv files")
    w.add_argument("--page", type=Path)
    args = ap.parse_args(argv)
    if args.cmd == "run":
        run(args.analogue, args.seeds, args.out,
            [float(x) for x in args.precisions.split(",") if x], args.max_hf, args.first)
        return 0
    files = [f for d in args.dirs
             for f in ([d] if d.is_file() else sorted(d.glob("precision_*.csv")))]
    runs = pd.concat([pd.read_csv(f) for f in files], ignore_index=True)
    blocks = {"summary": markdown(summary(runs)), "at-budget": markdown(at_budget(runs))}
    print("\n".join(blocks.values()))
    if args.page is not None:
        args.page.write_text(write_between_markers(args.page.read_text(), blocks, TAG))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
