"""Measured effect of each departure from the paper: switch one setting back at a time.

For every setting in which the package's defaults differ from
``PAS.paper()`` (with ``Stopping.paper()`` and ``Budget.paper()``), run the known-truth
tuning problems (:mod:`harness.known_truth`) with the defaults except that one setting at
its paper value, and print the median and worst |MPM error|, the U95
coverage and the median HF count beside the defaults and the full paper
preset.  This is the "measured effect" column of ``docs/explanation/departures.md``.

Run: python benchmarks/studies/departures.py [N] [--types core,miss,...] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from pas.strategies.estimators import SelectedSample
from pas.strategies.pas import PAS
from pas.study.settings import Budget, Stopping

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import make_problem  # noqa: E402
from harness.known_truth_runs import TYPES, run_one, select_types  # noqa: E402

PAPER = {**PAS.paper().settings(), **Stopping.paper().flat(), **Budget.paper().flat()}
DEFAULT = {**PAS().settings(), **Stopping().flat(), **Budget().flat()}
"""The flat settings of the paper preset and of the defaults (the settings objects')."""


def default_value(name):
    """The package default of a flat setting; for an option of the paper's estimator, that
    estimator's default."""
    return DEFAULT[name] if name in DEFAULT else getattr(SelectedSample(), name)


def variants():
    """``{label: settings}``: defaults, the paper preset, one paper setting at a time on the
    defaults (those that act there), and (labels ``paper+name=value``) one default at a time
    on the paper preset — also for settings that act only inside the paper's selected-space
    estimator."""
    out = {"default": {}, "paper": {"preset": "paper"}}
    changed = [name for name, value in PAPER.items() if DEFAULT.get(name, value) != value
               or name not in DEFAULT]
    for name in changed:
        if name in DEFAULT:  # copula_fit, marginals_from: options of the paper's estimator
            out[f"{name}={PAPER[name]}"] = {name: PAPER[name]}
    for name in changed:
        value = default_value(name)
        if value != PAPER[name]:
            out[f"paper+{name}={value}"] = {"preset": "paper", name: value}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=5, help="replications per type")
    ap.add_argument("--types", default="core,tail,miss,outlier,floor,reg")
    ap.add_argument("--variants", default=None, help="comma-separated labels (default all)")
    ap.add_argument("--out", default="pas-output/departures")
    args = ap.parse_args(argv)
    names = [n for n in select_types(args.types) if not TYPES[n].held_out]
    chosen = variants()
    if args.variants:
        chosen = {k: v for k, v in chosen.items() if k in args.variants.split(",")}
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for label, settings in chosen.items():
        for name in names:
            for r in range(args.n):
                row = run_one(make_problem(TYPES[name], r), **settings)
                row["variant"] = label
                rows.append(row)
            print(f"{label} {name} done", flush=True)
        pd.DataFrame(rows).to_csv(out / "runs.csv", index=False)
    runs = pd.DataFrame(rows).assign(abs_error=lambda t: t["error"].abs())
    table = runs.groupby("variant", sort=False).agg(
        median_abs=("abs_error", "median"), p90_abs=("abs_error", lambda x: x.quantile(0.9)),
        worst_abs=("abs_error", "max"), coverage=("covered", "mean"),
        n_hf=("n_hf", "median"), converged=("converged", "mean")).reset_index()
    table.to_csv(out / "summary.csv", index=False)
    with pd.option_context("display.width", 200):
        print(table.round(3).to_string(index=False))


if __name__ == "__main__":
    main()
