"""PAS's final samples on an analogue refitted with other estimator settings, and
the same studies run to the HF budget without stopping.

For each of ``N`` data sets PAS runs with its defaults; its final sample
(true and false positives) is then refitted with each setting below and the
MPM error printed ("censor c": the smallest fraction c of the loads enter the
joint likelihood left-censored, :func:`pas.models.joint.fit_joint`), with the median and worst |error| over the data sets.
``--every-event`` refits the default, the censored settings and the Weibull
mixture to every event of each data set instead (no sampling: the model's
own bias).  ``--only NAME,NAME`` keeps the listed settings.
``--to-budget`` instead runs each study to 160 HF (ε1 = 1e-12) and prints the
error along the way: whether a miss is an early stop or stays.
``--md-weighted`` fits every event again, each repeated as often as MD's
design would include it (:func:`md_design_positions`): the fit PAS's samples
scatter about, without their sampling noise.

Run: python benchmarks/final_sample_refits.py CASE [N] [--to-budget | --every-event |
     --md-weighted] [--only NAME,NAME]
"""

from __future__ import annotations

import dataclasses
import functools
import sys
import warnings

import numpy as np

import pas.strategies.estimators as fit_module  # the module whose fit_hf_candidates PAS calls
import pas.strategies.pas as pas_module
from pas.strategies.base import Pairs
from pas.strategies.screening import LFSet
from pas.validation import generate_case
from pas.validation.reproduce import run_case

# name: (PAS settings, keyword of the joint fit)
VARIANTS = {
    "default": ({}, {}),
    "hf_location=False": ({"hf_location": False}, {}),
    "hf_marginal=both": ({"hf_marginal": "both"}, {}),
    "hf_marginal=weibull_mixture": ({"hf_marginal": "weibull_mixture"}, {}),
    "censor 0.2": ({}, {"censor": 0.2}),  # the paper's upper-tail mode (upper 80 %), §2.3
    "censor 0.3": ({}, {"censor": 0.3}),
    "censor 0.5": ({}, {"censor": 0.5}),
    "censor 0.7": ({}, {"censor": 0.7}),  # with every event told: the truth's top 30 %
    "bootstrap median": ({"n_bootstrap": 50}, {}),
}


def pool_of(data):
    """The data set's LF pool and the HF load of each pool peak (0: no impact)."""
    lfset = LFSet(data.lf, n_waves=data.n_waves, p_exp=data.p_exp, threshold=data.threshold)
    return lfset, np.asarray(data.hf, float)[lfset.index]


def evaluated_positions(data, lfset, res):
    """Pool positions of the events a study evaluated."""
    position = np.full(len(data.lf), -1)
    position[lfset.index] = np.arange(lfset.n)
    return position[res.history["event_index"].dropna().to_numpy(int)]


def pairs_at(lfset, hf_pool, positions):
    """The true-positive pairs and false positives of pool ``positions``, in their order
    (the order decides which pairs a bootstrap replicate draws)."""
    idx = np.asarray(positions)
    tp, fp = idx[hf_pool[idx] > 0], idx[hf_pool[idx] == 0]
    return Pairs(tp, lfset.lf[tp], hf_pool[tp], lfset.d[tp], lfset.lf[fp], fp)


def error_at(data, lfset, hf_pool, positions, seed, settings=None, joint_kw=None):
    """MPM error of PAS (``settings``; no band) fitted to the events at pool ``positions``.

    ``joint_kw`` goes to the joint fit (e.g. ``censor``); a setting
    ``n_bootstrap`` > 0 reads the median of the bootstrap MPMs instead.
    """
    settings, joint_kw = settings or {}, joint_kw or {}
    pairs = pairs_at(lfset, hf_pool, positions)
    original = fit_module.fit_hf_candidates
    fit_module.fit_hf_candidates = functools.partial(original, **joint_kw)
    try:
        strategy = pas_module.PAS.from_flat({"n_bootstrap": 0, **settings})
        strategy.reset(seed)
        mpm = strategy.predict(pairs, lfset, np.random.default_rng(seed)).mpm
        if settings.get("n_bootstrap"):
            mpm = float(np.median(strategy.model_band(pairs, lfset,
                                                      np.random.default_rng(seed))[2]))
    finally:
        fit_module.fit_hf_candidates = original
    return mpm / data.truth_mpm - 1


def md_design_positions(n, k=160, copies=10, seed=0):
    """Pool positions repeated as MD's design includes them: ``copies · min(1, c / rank)``
    times (stochastic rounding), with ``c`` such that ``k`` events are expected.

    MD spreads ``k`` events uniformly over ``ln d``, so the event of LF rank ``i``
    (its ln-d interval ``≈ 1/i`` wide) is included with probability ``≈ min(1, c/i)``.
    """
    rank = np.arange(1, n + 1)
    lo, hi = 1e-3, float(n)
    for _ in range(100):
        c = np.sqrt(lo * hi)
        lo, hi = (c, hi) if np.minimum(1.0, c / rank).sum() < k else (lo, c)
    weight = copies * np.minimum(1.0, c / rank)
    times = np.floor(weight + np.random.default_rng(seed).uniform(size=n)).astype(int)
    return np.repeat(np.arange(n), times)


def refit_error(data, res, seed, settings, joint_kw):
    """:func:`error_at` on the events ``res`` evaluated (None: every event of the data set)."""
    lfset, hf_pool = pool_of(data)
    idx = np.arange(lfset.n) if res is None else evaluated_positions(data, lfset, res)
    return error_at(data, lfset, hf_pool, idx, seed, settings, joint_kw)


def main(case, n="10", *flags):
    if n.startswith("--"):
        n, flags = "10", (n, *flags)
    only = flags[flags.index("--only") + 1].split(",") if "--only" in flags else list(VARIANTS)
    unknown = [name for name in only if name not in VARIANTS]
    if unknown:
        raise SystemExit(f"unknown setting {', '.join(unknown)}; known: {', '.join(VARIANTS)}")
    variants = {name: VARIANTS[name] for name in only}
    errors = {name: [] for name in variants}
    for seed in range(int(n)):
        data = generate_case(case, seed=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if "--every-event" in flags:
                loads = data.hf[data.hf > 0]
                below = np.mean(loads < data.info["weibull"]["theta"])
                line = [(f"{case} {seed} every event told ({below:.0%} of the impacts below "
                         f"the truth Weibull's location)")]
                for name, (settings, joint_kw) in variants.items():
                    if name.startswith(("default", "censor", "hf_marginal=weibull_mixture")):
                        errors[name].append(refit_error(data, None, seed, settings, joint_kw))
                        line.append(f"{name} {errors[name][-1]:+.2f}")
                print(" | ".join(line), flush=True)
                continue
            if "--md-weighted" in flags:
                lfset, hf_pool = pool_of(data)
                line = [f"{case} {seed}"]
                for name, (settings, joint_kw) in variants.items():
                    every = error_at(data, lfset, hf_pool, np.arange(lfset.n), seed, settings,
                                     joint_kw)
                    errors[name].append(error_at(data, lfset, hf_pool,
                                                 md_design_positions(lfset.n, seed=seed), seed,
                                                 settings, joint_kw))
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
            line = [f"{case} {seed} study {row['M2']:+.2f} ({row['n_hf']} HF)"]
            for name, (settings, joint_kw) in variants.items():
                errors[name].append(refit_error(data, res, seed, settings, joint_kw))
                line.append(f"{name} {errors[name][-1]:+.2f}")
        print(" | ".join(line), flush=True)
    for name, e in errors.items():
        if e:
            a = np.abs(e)
            print(f"{name:20s} median |error| {np.median(a):.3f}  worst {a.max():.3f}  "
                  f"median error {np.median(e):+.3f}")


if __name__ == "__main__":
    main(*sys.argv[1:])
