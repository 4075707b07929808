"""PAS run on the known-truth problems (:mod:`harness.known_truth`) and scored.

:func:`run_one` runs one data set (the study of :func:`known_truth_study`) and scores
its MPM error and U95 coverage,
:func:`summarise` tabulates runs per type, :func:`select_types` reads a
``--types`` list, :func:`add_study_arguments` declares the options every
benchmark script that runs these types takes, and :func:`settings_from_args`
the ``--set NAME=VALUE`` options of the benchmark scripts.
"""

from __future__ import annotations

import ast
import time
import warnings
from dataclasses import asdict

import numpy as np
import pandas as pd

from pas.api import make_study
from pas.study.flat import from_flat

from .known_truth import TUNING_TYPES, Problem
from .known_truth_held_out import FRESH_TYPES, HELD_OUT_TYPES

TYPES = {**TUNING_TYPES, **HELD_OUT_TYPES, **FRESH_TYPES}
"""Every known-truth type by name: the tuning types, then the held-out ones (both rounds)."""

CHECKPOINTS = (20, 40, 80, 160)
"""HF counts at which :func:`run_one` scores the MPM predicted then (``err@k``)."""


def add_study_arguments(parser, *, n: int) -> None:
    """The options of a benchmark script that runs known-truth types: ``n`` (data sets per
    type, default ``n``), ``--types``, ``--held-out``, ``--first`` and ``--max-hf``."""
    parser.add_argument("n", nargs="?", type=int, default=n, help="data sets per type")
    parser.add_argument("--types", default="all",
                        help="comma-separated type names or groups (core, tail, miss, outlier, …)")
    parser.add_argument("--held-out", action="store_true",
                        help="with --types all: the held-out types, never used to choose settings")
    parser.add_argument("--first", type=int, default=0, help="first data set (replication)")
    parser.add_argument("--max-hf", type=int, default=160)


def select_types(spec: str = "all", *, held_out: bool = False) -> list[str]:
    """The type names a comma-separated ``spec`` of names or groups picks.

    ``"all"`` is every tuning type, or with ``held_out=True`` every held-out
    type of the first round (the second: ``"ho2"``); a group (``core``, ``miss``, …) is the types
    whose name starts
    with it and a dash.  A name that picks nothing is a ValueError.
    """
    if spec == "all":
        return [n for n, t in TYPES.items() if t.held_out == held_out and n not in FRESH_TYPES]
    names = []
    for item in spec.split(","):
        picked = [n for n in TYPES if n == item or n.startswith(item + "-")]
        if not picked:
            raise ValueError(f"--types: {item!r} is no known-truth type or group; "
                             f"groups are the first part of the names, e.g. "
                             f"{', '.join(sorted({n.split('-')[0] for n in TYPES}))}")
        names += [n for n in picked if n not in names]
    return names


def known_truth_study(problem: Problem, *, seed=None, max_hf=160, preset=None, **flat):
    """The :class:`~pas.study.study.Study` of ``problem`` as the benchmarks run it: its own
    ε1 stop (``eps1=None`` with ``precision=…`` for the precision stop), budget ``max_hf``,
    seed the data set's unless given, and the flat settings ``flat``."""
    objects = from_flat({"eps1": problem.eps1, "max_hf": max_hf, **flat}, preset=preset)
    return make_study(objects.pop("strategy"), problem.lf, n_waves=problem.n_waves,
                      p_exp=problem.p_exp, threshold=problem.threshold,
                      seed=problem.replication if seed is None else seed, **objects)


def run_one(problem: Problem, *, seed=None, max_hf=160, **settings) -> dict:
    """Run PAS on ``problem`` with ``settings``; score MPM error and U95 coverage.

    Also the error of the MPM predicted after 20, 40, 80 and 160 HF samples
    (``err@k``, NaN when the run stopped earlier): with
    ``stop_on_convergence=False`` this is the estimator's accuracy against
    its cost, free of the stopping rule.
    """
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = known_truth_study(problem, seed=seed, max_hf=max_hf,
                                **settings).optimize(problem.oracle())
    lo, hi = res.mpm_band
    hist = res.history.dropna(subset=["mpm"])
    at = {f"err@{k}": (float(hist.loc[hist["n_hf"] <= k, "mpm"].iloc[-1]) / problem.truth_mpm - 1
                       if (hist["n_hf"] <= k).any() and res.n_hf >= k else np.nan)
          for k in CHECKPOINTS}
    return {**at, "type": problem.type.name, "replication": problem.replication,
            "truth": problem.truth_mpm, "mpm": res.mpm, "error": res.mpm / problem.truth_mpm - 1,
            "band_low": lo, "band_high": hi,
            "covered": bool(lo <= problem.truth_mpm <= hi), "n_hf": res.n_hf,
            "n_fp": res.n_false_positive, "converged": bool(res.converged),
            "family": res.family, "seconds": time.perf_counter() - t0,
            **{f"type_{k}": v for k, v in asdict(problem.type).items() if k != "name"}}


def summarise(runs: pd.DataFrame) -> pd.DataFrame:
    """Per type: median and worst |error|, median error, coverage, HF count, convergence."""
    runs = runs.assign(abs_error=runs["error"].abs())
    return runs.groupby("type", sort=False).agg(
        n=("error", "size"), median_abs=("abs_error", "median"), worst_abs=("abs_error", "max"),
        median_err=("error", "median"), coverage=("covered", "mean"),
        n_hf=("n_hf", "median"), converged=("converged", "mean"),
        seconds=("seconds", "median"),
        **{f"mae@{k}": (f"err@{k}", lambda x: x.abs().median()) for k in CHECKPOINTS},
    ).reset_index()


def settings_from_args(items) -> dict:
    """``["NAME=VALUE", …]`` → settings, each value a Python literal or else the string.

    An item without ``=`` is a ValueError naming it.
    """
    settings = {}
    for item in items:
        if "=" not in item:
            raise ValueError(f"--set {item!r}: write NAME=VALUE, e.g. --set hf_marginal=both")
        k, v = item.split("=", 1)
        try:
            settings[k] = ast.literal_eval(v)
        except (ValueError, SyntaxError):
            settings[k] = v
    return settings
