"""Benchmark: what the precision stop's fit check (``Stopping(fit_check=0.01)``) changes, paired.

The fit check only ever holds a study back, and it draws no random number: a
study whose model passed every check it met runs exactly as it would without
the check.  So the runs without it are the runs with it, except those the
check held back at least once (``misfit_checks > 0``), which ``--run OFF.csv``
runs again with ``fit_check=None`` (the same problem, data set and seed) and
writes, with the others copied, to ``OFF.csv``.

The table pools the studies by group (held-out known-truth types ``ho*``,
copula + Weibull types ``core-*``, other tuning types, analogues): studies;
how many reached ±target without and with the check; of those, how many
held the truth in their U95 and how many were within ±10 % of it; how many
studies the check held back at least once, and how many of the stops it
took away had held the truth.

Run: ``python benchmarks/studies/precision_stop.py N --csv ON.csv …`` (with
the check, the default), then ``python benchmarks/studies/fit_check_paired.py
ON.csv --run OFF.csv``, then ``… ON.csv --off OFF.csv [--write [PAGE]]``.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import rewrite_page  # noqa: E402

_SPEC = importlib.util.spec_from_file_location(
    "precision_stop", Path(__file__).with_name("precision_stop.py"))
precision_stop = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(precision_stop)

PAGE, TAG = Path("docs/results/precision.md"), "fit_check_paired.py"
GROUPS = (("held-out types", "ho"), ("copula + Weibull tuning types", "core-"),
          ("analogues", "analogue-"))
OTHER = "other tuning types"
"""Known-truth types of neither group above: the tail, miss and outlier tuning types."""


def group_of(problem: str) -> str:
    return next((label for label, prefix in GROUPS if problem.startswith(prefix)), OTHER)


def run_off(on: pd.DataFrame, scale: float = 0.5) -> pd.DataFrame:
    """The runs of ``on`` without the check: those the check held back run again, the
    others copied (module docs)."""
    rows = []
    for _, r in on.iterrows():
        if r["misfit_checks"] == 0:
            rows.append({**r.to_dict(), "fit_check": float("nan")})
            continue
        types, cases = ([], [r["problem"][len("analogue-"):]]) if r["problem"].startswith(
            "analogue-") else ([r["problem"]], [])
        (name, rep, lf, oracle, kw, truth), = precision_stop.problems(
            types, cases, 1, scale, first=int(r["data_set"]))
        row = precision_stop.run_one(lf, oracle, kw, truth, seed=rep, target=r["precision"],
                                     max_hf=int(r["max_hf"]), fit_check=None)
        rows.append({"problem": name, "data_set": rep, **row})
        print(f"{name} set {rep}: without the check {'reached' if row['converged'] else 'not'}"
              f" at {row['n_hf']} HF, error {row['error']:+.1%}, covered {row['covered']}",
              flush=True)
    return pd.DataFrame(rows)


def paired(on: pd.DataFrame, off: pd.DataFrame) -> pd.DataFrame:
    """Per group and target (module docs), plus every held-out study pooled as
    ``all held-out``; the columns the page's table shows."""
    key = ["problem", "data_set", "precision"]
    both = on.merge(off, on=key, suffixes=("_on", "_off"), validate="one_to_one")
    if len(both) != len(on) or len(both) != len(off):
        raise ValueError("the runs with and without the check are not the same studies")
    both["group"] = both["problem"].map(group_of)
    out = []
    for (group, target), g in both.groupby(["group", "precision"], sort=False):
        row = {"group": group, "precision": target, "studies": len(g),
               "held_back": int((g["misfit_checks_on"] > 0).sum())}
        for arm in ("off", "on"):
            stop = g[g[f"converged_{arm}"]]
            row[f"reached_{arm}"] = len(stop)
            row[f"covered_{arm}"] = int(stop[f"covered_{arm}"].sum())
            row[f"within_{arm}"] = int((stop[f"error_{arm}"].abs() <= 0.10).sum())
        lost = g[g["converged_off"] & ~g["converged_on"]]
        row["lost_stops"], row["lost_covered"] = len(lost), int(lost["covered_off"].sum())
        out.append(row)
    order = {label: i for i, (label, _) in enumerate((*GROUPS, (OTHER, "")))}
    return pd.DataFrame(out).sort_values("group", key=lambda s: s.map(order), kind="stable")


def markdown(table: pd.DataFrame) -> str:
    """The paired table as Markdown: counts ``without → with`` the check."""
    head = ["group", "target", "studies", "reached", "of those, U95 held the truth",
            "within ±10 %", "held back by the check", "stops it took away (had held the truth)"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]

    def pair(r, col):
        return f"{r[f'{col}_off']} → {r[f'{col}_on']}"

    for _, r in table.iterrows():
        lines.append(f"| {r['group']} | ±{100 * r['precision']:g} % | {r['studies']} | "
                     f"{pair(r, 'reached')} | {pair(r, 'covered')} | {pair(r, 'within')} | "
                     f"{r['held_back']} | {r['lost_stops']} ({r['lost_covered']}) |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("on", help="precision_stop.py runs with the check (the default)")
    ap.add_argument("--run", type=Path, metavar="OFF.csv",
                    help="run the held-back studies again without the check, write OFF.csv")
    ap.add_argument("--off", metavar="OFF.csv", help="the runs without the check (--run's)")
    ap.add_argument("--scale", type=float, default=0.5, help="analogue duration / the paper's")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"write the table between the markers of PAGE (default {PAGE})")
    args = ap.parse_args(argv)
    on = pd.read_csv(args.on)
    if args.run:
        off = run_off(on, args.scale)
        off.to_csv(args.run, index=False)
    elif args.off:
        off = pd.read_csv(args.off)
    else:
        ap.error("give --run OFF.csv or --off OFF.csv")
    table = paired(on, off)
    print(markdown(table))
    if args.write:
        rewrite_page(args.write, {"paired": markdown(table)}, TAG)


if __name__ == "__main__":
    main()
