"""Benchmark: the precision stopping rule and its forecast on problems with known truths (issue 28).

Per problem type, precision target (``--precisions``, default 0.05, 0.10,
0.20) and budget (``--budgets``, default 160 and 400), over ``N`` data sets:
the share of studies that reach the target within the budget; of those, the
share whose U95 holds the truth and whose MPM is within ±10 % of it; the
median HF count at the stop; and the forecast made halfway (in HF count) to
where a study reached the target against the HF it then still needed (the
share of the studies that reached the target whose halfway forecast was within
a factor 1.5 — none halfway counts as a miss —, the median ratio, and how often
the forecast's 95 % interval held the HF then needed).  With two or more
copula + Weibull problems (``core-*``) their studies are also pooled in one row;
``--pool-groups`` adds one for the held-out types (``ho*``) and one for the
analogues.  Every report also counts the studies that stopped on a band wider
than their target (there must be none) and lists any.

A run with budget 400 asks what the run with budget 160 asks up to 160 HF
(the budget decides when a study stops, never which event it asks for), so
each (problem, data set, target) is run once, to the largest budget, and the
smaller budgets are read off it (``--max-budget-for`` lowers the largest for
a target, to keep the measurement modest).

Problems: known-truth types of :mod:`harness.known_truth` (``--types``)
and validation analogues (``--cases``, :func:`pas.validation.generate_case`
with the data redrawn per set, ``--scale`` of the paper's duration).

``--cost HF``: instead, the CPU time per HF of the loop on the problem of
``harness.timing_problem`` (that of ``benchmarks/timing/study_parts.py``) (stopping off, ``HF``
evaluations) with ``eps1``
(no model band in the loop), with a target it never reaches (the growth
schedule alone) and with one it reaches early (the schedule and the gated
bands), and the model bands each computed.

``--write [PAGE]`` puts the table it made (the summary, or with ``--cost``
the cost table) between the markers of ``docs/results/precision.md``
(``<!-- BEGIN precision_stop.py summary -->``, or the markers ``--section``
names, e.g. ``held-out``, and ``… cost``).  ``--histories DIR`` keeps each
study's history (``benchmarks/investigations/forecast_variants.py`` replays
forecasts on them); ``--first`` is the first data set (fresh seeds).

Run: ``python benchmarks/studies/precision_stop.py [N] [--types a,b] [--cases 1a,3a]
[--precisions 0.05,0.1,0.2] [--budgets 160,400] [--csv runs.csv] [--markdown]
[--from-csv runs.csv,...] [--cost 80] [--write] [--section held-out] [--histories DIR] [--first 21]
[--pool-groups]``
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

import pas

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness import timing_problem  # noqa: E402
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import TYPES as KNOWN_TRUTH  # noqa: E402
from harness.result_tables import rewrite_page  # noqa: E402

TYPES = ("core-gumbel-t0.6", "core-gaussian-t0.75", "tail-gaussian-mix", "miss-low-gaussian-t0.7")
CASES = ("1a", "3a")
FACTOR = 1.5  # "within a factor 1.5" of the HF still needed
POOLED = "copula + Weibull types, pooled"
GROUPS = {"held-out types, pooled": "ho", "analogues, pooled": "analogue-"}  # --pool-groups
PAGE, TAG = Path("docs/results/precision.md"), "precision_stop.py"


def problems(types, cases, n, scale, first=1):
    """``(problem name, data set, lf, oracle, run_pas arguments, truth)`` for every data set."""
    for name in types:
        for rep in range(first, first + n):
            p = make_problem(KNOWN_TRUTH[name], rep)
            yield name, rep, p.lf, p.oracle(), {"n_waves": p.n_waves, "p_exp": p.p_exp,
                                                "threshold": p.threshold}, p.truth_mpm
    for case in cases:
        from pas.validation import generate_case

        for rep in range(first, first + n):
            d = generate_case(case, seed=rep, scale=scale)
            kw = {k: v for k, v in d.run_kwargs().items() if k != "eps1"}
            yield f"analogue-{case}", rep, d.lf, d.oracle(), kw, d.truth_mpm


def halfway_forecast(fitted: pd.DataFrame, n_stop: int):
    """``(forecast further HF, its 95 % low, high, HF then still needed)`` from the last fit
    at or below half of ``n_stop`` HF with a finite forecast, or NaNs."""
    if "forecast_hf" not in fitted:
        return (np.nan,) * 4
    early = fitted[(fitted["n_hf"] <= n_stop / 2) & np.isfinite(fitted["forecast_hf"])]
    if early.empty:
        return (np.nan,) * 4
    row = early.iloc[-1]
    return (float(row["forecast_hf"]), float(row["forecast_hf_low"]),
            float(row["forecast_hf_high"]), float(n_stop - row["n_hf"]))


def run_one(lf, oracle, kw, truth, *, seed, target, max_hf, history=None,
            fit_check=pas.Stopping.fit_check) -> dict:
    """One study with ``precision=target`` (and the fit check at level ``fit_check``, None:
    none); what the table needs of it.

    ``history``: a CSV path to keep the study's history at (its band widths per fit,
    for evaluating forecasts offline: ``benchmarks/investigations/forecast_variants.py``).
    """
    t0 = time.perf_counter()
    stopping = pas.Stopping(precision=target, fit_check=fit_check)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if "n_waves_convention" in kw:  # an analogue states its n_w: make_study takes that
            res = pas.make_study("pas", lf, **kw, stopping=stopping, seed=seed,
                                 max_hf=max_hf).optimize(oracle)
        else:
            res = pas.run_pas(lf, oracle, **kw, stopping=stopping, seed=seed, max_hf=max_hf)
    if history is not None:
        res.history.assign(truth=truth).to_csv(history, index=False)
    lo, hi = res.mpm_band
    forecast, low, high, needed = (halfway_forecast(res.fitted, res.n_hf) if res.converged
                                   else (np.nan,) * 4)
    return {"precision": target, "max_hf": max_hf, "converged": bool(res.converged),
            "n_hf": res.n_hf, "mpm": res.mpm, "truth": truth, "error": res.mpm / truth - 1,
            "band_low": lo, "band_high": hi, "covered": bool(lo <= truth <= hi),
            "halfwidth": max(hi - res.mpm, res.mpm - lo) / res.mpm,
            "forecast_halfway": forecast, "needed_halfway": needed,
            "forecast_halfway_low": low, "forecast_halfway_high": high,
            "n_bands": int(res.history.get("halfwidth", pd.Series(dtype=float)).notna().sum()),
            "fit_check": np.nan if fit_check is None else fit_check,
            "misfit_checks": int(res.history.get("fit_misfit", pd.Series(dtype=object))
                                 .notna().sum()),
            "seconds": time.perf_counter() - t0}


def table(runs: pd.DataFrame, budgets, pool_groups: bool = False) -> pd.DataFrame:
    """Per problem, target and budget: the shares the module docs list; with two or more
    copula + Weibull problems (``core-*``) also their studies pooled (:data:`POOLED`), and
    with ``pool_groups`` those of the held-out types and of the analogues (:data:`GROUPS`)."""
    out = []
    pools = {POOLED: "core-", **(GROUPS if pool_groups else {})}
    groups = list(runs.groupby(["problem", "precision"], sort=False))
    for label, prefix in pools.items():
        of = runs["problem"].str.startswith(prefix)
        if runs.loc[of, "problem"].nunique() > 1:
            groups += [((label, target), g) for target, g in
                       runs[of].groupby("precision", sort=False)]
    for (name, target), g in groups:
        for budget in budgets:
            if g["max_hf"].max() < budget:
                continue
            reached = g[g["converged"] & (g["n_hf"] <= budget)]
            ratio = reached["forecast_halfway"] / reached["needed_halfway"]
            ok = ratio.dropna()
            held = _interval_held(reached.loc[ok.index])
            out.append({"problem": name, "precision": target, "budget": budget, "n": len(g),
                        "reached": len(reached) / len(g),
                        "covered": reached["covered"].mean() if len(reached) else np.nan,
                        "within_10pct": ((reached["error"].abs() <= 0.10).mean()
                                         if len(reached) else np.nan),
                        "median_hf": reached["n_hf"].median() if len(reached) else np.nan,
                        "short_halfwidth": (g.loc[~g.index.isin(reached.index), "halfwidth"]
                                            .median() if len(reached) < len(g) else np.nan),
                        # of the studies that reached the target: none halfway is a miss
                        "forecast_ok": (((ok <= FACTOR) & (ok >= 1 / FACTOR)).sum()
                                        / len(reached) if len(reached) else np.nan),
                        "interval_held": held,
                        "n_forecasts": len(ok),
                        "forecast_ratio": ok.median() if len(ok) else np.nan,
                        "seconds": g["seconds"].median()})
    return pd.DataFrame(out)


def wide_stops(runs: pd.DataFrame) -> pd.DataFrame:
    """The studies that reached their target with a U95 wider than it (issue 28: there must
    be none): ``converged`` while the band's wider side exceeds ``precision × MPM``."""
    return runs[runs["converged"] & (runs["halfwidth"] > runs["precision"] * (1 + 1e-12))]


def _interval_held(reached: pd.DataFrame) -> float:
    """Share of the halfway forecasts whose 95 % interval held the HF then needed (NaN: none,
    or runs recorded without the interval)."""
    if reached.empty or "forecast_halfway_low" not in reached:
        return np.nan
    needed = reached["needed_halfway"]
    return float(((reached["forecast_halfway_low"] <= needed)
                  & (needed <= reached["forecast_halfway_high"])).mean())


def loop_cost(max_hf: int) -> pd.DataFrame:
    """CPU seconds per HF of the loop (final band excluded) with and without the precision rule."""
    lf, hf = timing_problem.scenario()
    out = []
    for name, stop in (("eps1 (no band in the loop)", {"eps1": 1e-9}),
                       ("precision 0.01 (never reached)", {"precision": 0.01}),
                       ("precision 0.5 (reached early)", {"precision": 0.5})):
        study = pas.make_study(
            "pas",
            lf,
            n_waves=timing_problem.N_W,
            p_exp=timing_problem.P_EXP,
            seed=1,
            max_hf=max_hf,
            stop_on_convergence=False,
            **stop,
        )
        t0 = timing_problem.cpu_seconds()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            study.optimize(lambda ev: float(hf[ev.index]))
        loop = timing_problem.cpu_seconds() - t0
        bands = int(study.history().get("model_low", pd.Series(dtype=float)).notna().sum())
        out.append({"loop": name, "cpu_s_per_hf": loop / max_hf, "model_bands": bands})
    base = out[0]["cpu_s_per_hf"]
    return pd.DataFrame([{**r, "ratio": r["cpu_s_per_hf"] / base} for r in out])


def markdown(summary: pd.DataFrame) -> str:
    """The summary table as Markdown, shares in per cent (the docs page's table)."""
    cols = ["problem", "precision", "budget", "n", "reached", "covered", "within_10pct",
            "median_hf", "short_halfwidth", "n_forecasts", "forecast_ok", "forecast_ratio",
            "interval_held"]
    head = ["problem", "target", "budget", "studies", "reached", "U95 holds truth¹",
            "within ±10 %¹", "median HF¹", "U95 of the others²", "halfway forecasts¹",
            "within ×1.5¹", "median ratio", "95 % interval held"]

    def cell(col, x):
        if isinstance(x, float) and np.isnan(x):
            return "–"
        if col == "precision":
            return f"±{100 * x:g} %"
        if col in ("reached", "covered", "within_10pct", "forecast_ok", "interval_held"):
            return f"{100 * x:.0f} %"
        if col == "short_halfwidth":
            return f"±{100 * x:.0f} %"
        if col == "forecast_ratio":
            return f"{x:.2f}"
        return f"{x:.0f}" if isinstance(x, float) else str(x)

    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for _, r in summary.iterrows():
        lines.append("| " + " | ".join(cell(c, r[c]) for c in cols) + " |")
    return "\n".join(lines)


def cost_markdown(cost: pd.DataFrame) -> str:
    """The cost table of :func:`loop_cost` as Markdown (the docs page's second table)."""
    lines = ["| loop | CPU s per HF | model bands | ratio |", "|---|---|---|---|"]
    for _, r in cost.iterrows():
        lines.append(f"| {r['loop']} | {r['cpu_s_per_hf']:.3g} | {int(r['model_bands'])} | "
                     f"{r['ratio']:.3g} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=3, help="data sets per problem")
    ap.add_argument("--types", default=",".join(TYPES))
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--scale", type=float, default=0.5, help="analogue duration / the paper's")
    ap.add_argument("--precisions", default="0.05,0.1,0.2")
    ap.add_argument("--budgets", default="160,400")
    ap.add_argument("--max-budget-for", default="0.05:160",
                    help="target:budget pairs lowering the largest budget for a target")
    ap.add_argument("--csv", default="precision_runs.csv")
    ap.add_argument("--histories", type=Path, metavar="DIR",
                    help="keep each study's history as DIR/<problem>_<set>_<target>.csv")
    ap.add_argument("--first", type=int, default=1, help="first data set (fresh seeds)")
    ap.add_argument("--cost", type=int, metavar="HF", help="measure the loop's cost instead")
    ap.add_argument("--from-csv", metavar="A.csv,B.csv",
                    help="tabulate the runs of earlier --csv files instead of running")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--section", default="summary",
                    help="the markers --write fills with the summary (summary, held-out)")
    ap.add_argument("--no-fit-check", action="store_true",
                    help="stop on the band alone, without the fit check (fit_check=None)")
    ap.add_argument("--pool-groups", action="store_true",
                    help="add rows pooling the held-out types (ho*) and the analogues")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"write the table between the markers of PAGE (default {PAGE})")
    args = ap.parse_args(argv)
    budgets = sorted(int(x) for x in args.budgets.split(","))
    if args.from_csv:
        runs = pd.concat([pd.read_csv(f) for f in args.from_csv.split(",")], ignore_index=True)
        return _report(runs, budgets, args)
    if args.cost:
        cost = loop_cost(args.cost)
        print(cost.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
        if args.write:
            rewrite_page(args.write, {"cost": cost_markdown(cost)}, TAG)
        return
    split = [s for s in args.types.split(",") if s], [s for s in args.cases.split(",") if s]
    targets = [float(x) for x in args.precisions.split(",")]
    cap = {float(k): int(v) for k, v in
           (item.split(":") for item in args.max_budget_for.split(",") if item)}
    rows = []
    for name, rep, lf, oracle, kw, truth in problems(*split, args.n, args.scale, args.first):
        for target in targets:
            budget = min(budgets[-1], cap.get(target, budgets[-1]))
            history = None
            if args.histories:
                args.histories.mkdir(parents=True, exist_ok=True)
                history = args.histories / f"{name}_{rep}_{target:g}.csv"
            row = {"problem": name, "data_set": rep,
                   **run_one(lf, oracle, kw, truth, seed=rep, target=target, max_hf=budget,
                             history=history,
                             fit_check=None if args.no_fit_check else pas.Stopping.fit_check)}
            rows.append(row)
            print(f"{name} set {rep} ±{target:.0%}: {'reached' if row['converged'] else 'not'} "
                  f"at {row['n_hf']} HF, error {row['error']:+.1%}, covered {row['covered']}, "
                  f"forecast halfway {row['forecast_halfway']:.3g} vs {row['needed_halfway']:.3g}"
                  f", {row['n_bands']} bands, {row['seconds']:.0f} s", flush=True)
            pd.DataFrame(rows).to_csv(args.csv, index=False)
    _report(pd.DataFrame(rows), budgets, args)


def _report(runs: pd.DataFrame, budgets, args) -> None:
    """Print the summary (as Markdown with ``--markdown``) and the studies that stopped on a
    band wider than their target (:func:`wide_stops`), and write the summary with ``--write``."""
    summary = table(runs, budgets, args.pool_groups)
    wide = wide_stops(runs)
    print(f"stopped on a band wider than the target: {len(wide)} of "
          f"{int(runs['converged'].sum())} stops")
    if len(wide):
        print(wide.to_string(index=False))
    if args.markdown:
        print(markdown(summary))
    else:
        with pd.option_context("display.width", 200, "display.max_columns", 20):
            print(summary.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    if args.write:
        rewrite_page(args.write, {args.section: markdown(summary)}, TAG)


if __name__ == "__main__":
    main()
