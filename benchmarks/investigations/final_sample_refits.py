"""PAS's final samples on an analogue refitted with other estimator settings, and
the same studies run to the HF budget without stopping.

For each of ``N`` data sets PAS runs with its defaults; its final sample
(true and false positives) is then refitted with each setting below and the
MPM error printed, with the median and worst |error| over the data sets.
``--every-event`` refits the default, the log-normal and the Weibull
mixture to every event of each data set instead (no sampling: the model's
own bias).  ``--only NAME,NAME`` keeps the listed settings.
``--to-budget`` instead runs each study to 160 HF (ε1 = 1e-12) and prints the
error along the way: whether a miss is an early stop or stays.
``--md-weighted`` fits every event again, each repeated as often as MD's
design would include it (:func:`harness.refits.md_design_positions`): the fit PAS's samples
scatter about, without their sampling noise.

``--csv FILE`` saves every error (case, mode, setting, data seed; the
study's own error as setting ``study``); ``--write [PAGE] --from-csv A,B,…``
runs nothing and writes the three tables of
``docs/results/investigations.md`` from such files, between its
``final_sample_refits.py`` markers.

Run: python benchmarks/investigations/final_sample_refits.py CASE [N] [--to-budget | --every-event |
     --md-weighted] [--only NAME,NAME] [--csv FILE]
     python benchmarks/investigations/final_sample_refits.py --write --from-csv A.csv,B.csv,…
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pas.validation import generate_case
from pas.validation.reproduce import run_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.error_tables import (  # noqa: E402
    add_write_options,
    grid_table,
    saved_results,
    write_tables,
)
from harness.refits import (  # noqa: E402
    error_at,
    evaluated_positions,
    md_design_positions,
    pool_of,
)

# name: (PAS settings, keyword of the joint fit)
VARIANTS = {
    "default": {},
    "hf_location=False": {"hf_location": False},
    "hf_marginal=both": {"hf_marginal": "both"},
    "hf_marginal=lognormal": {"hf_marginal": "lognormal"},
    "hf_marginal=weibull_mixture": {"hf_marginal": "weibull_mixture"},
    "bootstrap median": {"n_bootstrap": 50},
}


PAGE, TAG = Path("docs/results/investigations.md"), "final_sample_refits.py"
MODES = {None: "final", "--every-event": "every", "--md-weighted": "md-weighted",
         "--to-budget": "to-budget"}
"""The ``mode`` column of ``--csv`` for each mode flag (none: PAS's final samples)."""

STUDY = ("PAS's studies themselves (not refitted)", {"setting": "study"})
IMPACT_CASES = [(case, {"case": case}) for case in ("3a", "3b", "4a", "4b")]
TABLES = {
    "hf-marginal": ("HF marginal", [
        ("Weibull (default), every event told", {"mode": "every", "setting": "default"}),
        ("Weibull mixture, every event told",
         {"mode": "every", "setting": "hf_marginal=weibull_mixture"}),
        ("Weibull (default), PAS's final samples refitted",
         {"mode": "final", "setting": "default"}),
        ("Weibull mixture, PAS's final samples refitted",
         {"mode": "final", "setting": "hf_marginal=weibull_mixture"}),
        ("Weibull mixture, every event weighted as MD includes events (`--md-weighted`, below)",
         {"mode": "md-weighted", "setting": "hf_marginal=weibull_mixture"})], IMPACT_CASES),
    "settings": ("setting", [
        STUDY, ("default, refitted", {"setting": "default"}),
        ("`hf_location=False`", {"setting": "hf_location=False"}),
        ('`hf_marginal="both"`', {"setting": "hf_marginal=both"}),
        ("the median of the 50 bootstrap MPMs", {"setting": "bootstrap median"})],
        [(case, {"case": case, "mode": "final"}) for case in ("3a", "3b")]),
}
"""The page's tables: marker name to (corner, rows, columns[, cell]) of :func:`grid_table`."""


def tables(results: pd.DataFrame) -> dict[str, str]:
    """The three tables of the page, median / worst |error| over the data sets in each cell."""
    return {name: grid_table(results, *spec) for name, spec in TABLES.items()}


def save_errors(path, case: str, mode: str, errors: dict) -> None:
    """Write ``errors`` (setting: one error per data seed, in seed order) to ``path`` (if given)."""
    if path:
        pd.DataFrame([{"case": case, "mode": mode, "setting": name, "seed": seed, "error": e}
                      for name, es in errors.items() for seed, e in enumerate(es)]
                     ).to_csv(path, index=False)


def refit_error(data, res, seed, settings):
    """:func:`error_at` on the events ``res`` evaluated (None: every event of the data set)."""
    lfset, hf_pool = pool_of(data)
    idx = np.arange(lfset.n) if res is None else evaluated_positions(data, lfset, res)
    return error_at(data, lfset, hf_pool, idx, seed, settings)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", nargs="?")
    ap.add_argument("n", nargs="?", type=int, default=10, help="data seeds 0 … N-1")
    mode = ap.add_mutually_exclusive_group()
    for flag in ("--to-budget", "--every-event", "--md-weighted"):
        mode.add_argument(flag, dest="mode", action="store_const", const=flag)
    ap.add_argument("--only", default=",".join(VARIANTS),
                    help=f"comma-separated settings of: {', '.join(VARIANTS)}")
    add_write_options(ap, PAGE)
    args = ap.parse_args(argv)
    if args.write:
        results = saved_results(ap, args)
        return write_tables(args.write, tables(results), TAG)
    if args.case is None:
        ap.error("give a CASE (e.g. 3a), or --write --from-csv A.csv,B.csv")
    case, n, flags = args.case, args.n, (args.mode,)
    only = args.only.split(",")
    unknown = [name for name in only if name not in VARIANTS]
    if unknown:
        ap.error(f"--only: unknown setting {', '.join(unknown)}; known: {', '.join(VARIANTS)}")
    variants = {name: VARIANTS[name] for name in only}
    errors = {name: [] for name in variants}
    for seed in range(int(n)):
        save_errors(args.csv, case, MODES[args.mode], errors)  # the data seeds done so far
        data = generate_case(case, seed=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if "--every-event" in flags:
                loads = data.hf[data.hf > 0]
                below = np.mean(loads < data.info["weibull"]["theta"])
                line = [(f"{case} {seed} every event told ({below:.0%} of the impacts below "
                         f"the truth Weibull's location)")]
                for name, settings in variants.items():
                    if name.startswith(("default", "hf_marginal=weibull_mixture",
                                     "hf_marginal=lognormal")):
                        errors[name].append(refit_error(data, None, seed, settings))
                        line.append(f"{name} {errors[name][-1]:+.2f}")
                print(" | ".join(line), flush=True)
                continue
            if "--md-weighted" in flags:
                lfset, hf_pool = pool_of(data)
                line = [f"{case} {seed}"]
                for name, settings in variants.items():
                    every = error_at(data, lfset, hf_pool, np.arange(lfset.n), seed, settings)
                    errors[name].append(error_at(data, lfset, hf_pool,
                                                 md_design_positions(lfset.n, seed=seed), seed,
                                                 settings))
                    line.append(f"{name}: every event {every:+.2f}, weighted as MD includes "
                                f"events {errors[name][-1]:+.2f}")
                print(" | ".join(line), flush=True)
                continue
            if "--to-budget" in flags:
                res, row = run_case(dataclasses.replace(data, eps1=1e-12), seed=seed)
                h = res.history.dropna(subset=["mpm"])
                err = h["mpm"].to_numpy(float) / data.truth_mpm - 1
                at = {k: err[np.searchsorted(h["n_hf"].to_numpy(), k, side="right") - 1]
                      for k in (60, 80, 100, 120, 140)}
                print(f"{case} {seed} " + " ".join(f"{k}: {v:+.2f}" for k, v in at.items())
                      + f"  160: {row['M2']:+.2f}", flush=True)
                errors.setdefault("default", []).append(row["M2"])
                continue
            res, row = run_case(data, seed=seed)
            errors.setdefault("study", []).append(row["M2"])
            line = [f"{case} {seed} study {row['M2']:+.2f} ({row['n_hf']} HF)"]
            for name, settings in variants.items():
                errors[name].append(refit_error(data, res, seed, settings))
                line.append(f"{name} {errors[name][-1]:+.2f}")
        print(" | ".join(line), flush=True)
    save_errors(args.csv, case, MODES[args.mode], errors)
    for name, e in errors.items():
        if e:
            a = np.abs(e)
            print(f"{name:20s} median |error| {np.median(a):.3f}  worst {a.max():.3f}  "
                  f"median error {np.median(e):+.3f}")


if __name__ == "__main__":
    main()
