"""Benchmark: where a PAS run spends its time, each figure beside its baseline (issue 27).

One scenario throughout: 15 000 Rayleigh LF peaks, ``n_w`` 16 364, a Gumbel
(θ = 3) copula to a Weibull HF load, stopping off, 80 HF (``--max-hf``), its data
drawn from ``--seed`` (default 1, the data the issue's targets were set on).
Every ratio is measured in this one run, the old path beside the new (CPU
time, the forked band workers' included; wall time on a shared machine, whose
speed at the time a fixed piece of work measures at the start and the end:
``pas.validation.timing_problem.reference_seconds``); the
whole runs of ``fit`` and the bands of ``band`` are each the median of
``--repeats`` runs (default 5: one run of the band on two cores varied by
±8 % on the 2-core machine):

* ``fit``: the whole run and a Student-t-only run with the Student-t joint
  fit by numerical differences (scipy's L-BFGS-B default, the old path)
  against its analytic gradient; the largest change of MPM and band ends
  and whether the family sequence is the same;
* ``fit`` also: every family refitted in every iteration (``PRUNE_AIC=None``,
  old) against a family more than 100 AIC behind left unrefitted
  (``estimators.PRUNE_AIC``): loop median and worst, the fits' CPU, the
  largest change of MPM and band ends, whether the family sequence is the
  same and how far the unrefitted families' recorded AIC is above their refit;
* ``cold``: the study's periodic cold starts all at once every tenth fit
  (old) against the families in turn (``steps.cold_turns``): loop median and
  worst, the largest change of MPM and band ends;
* ``band``: the final model band of 80 and 160 pairs with its replicates
  fitted one after another (old: warm from the final fits, Student-t also
  cold, the families that can win each replicate) against each candidate
  fitted to all replicates at once (``band.BATCHED``), on 1 and 2 cores, the
  band ends and the largest change of a replicate MPM; fitted together, Student-t's
  ν derivative by a difference (old) vs the t quantiles' (``joint_batch.IMPLICIT_NU``),
  and Student-t started warm and cold vs once from its restarted final fit
  (``band.STUDENT_RESTART``);
* ``driver``: the loop's fits by ``scipy.optimize.minimize`` (old) vs ``pas.models.lbfgsb``.

Long LF records are timed by ``benchmarks/timing/long_records.py``.

Run: python benchmarks/timing/study_parts.py [--parts fit,cold,band,driver] [--max-hf 80] [--repeats 5]
     [--seed 1] [--json out.json]
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import time

import numpy as np

import pas
import pas.models.joint
import pas.models.joint_mixture
from pas.study.flat import from_flat
from pas.validation.timing_problem import (
    N_W,
    P_EXP,
    REFERENCE_QUIET,
    N,
    cpu_seconds,
    reference_seconds,
    scenario,
)


@contextlib.contextmanager
def module_setting(module, name, value):
    """``module.name = value`` while the block runs."""
    mod = importlib.import_module(module)
    saved = getattr(mod, name)
    setattr(mod, name, value)
    try:
        yield
    finally:
        setattr(mod, name, saved)


@contextlib.contextmanager
def numerical_student():
    """The old path: the Student-t joint fit by scipy's numerical differences."""
    old = tuple(f for f in pas.models.joint.GRADIENT_FAMILIES if f != "student")
    with module_setting("pas.models.joint", "GRADIENT_FAMILIES", old), module_setting(
            "pas.models.joint_mixture", "GRADIENT_FAMILIES", old):
        yield


DATA_SEED = 1
"""The seed the scenario's LF peaks and HF values are drawn from (``--seed``)."""


def run(max_hf, n=N, n_waves=N_W, fit_seconds=None, **settings):
    """One run with stopping off: ``(result, CPU s per loop iteration, CPU s of the final
    band, wall s of the final band)``; ``fit_seconds``: a list the CPU s of each of the
    study's joint fits (``fit_joint_all``) is appended to."""
    if fit_seconds is not None:
        with timed_joint_fits(fit_seconds):
            return run(max_hf, n, n_waves, **settings)
    lf, hf = scenario(n, seed=DATA_SEED)
    stamps = []

    def callback(study, row):
        stamps.append((cpu_seconds(), time.perf_counter()))

    t0 = cpu_seconds()
    objects = from_flat({"eps1": 1e-12, "max_hf": max_hf, **settings})  # flat names
    res = pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=n_waves, p_exp=P_EXP, seed=0,
                      callback=callback, **objects)
    cpu = np.r_[t0, [c for c, _ in stamps]]
    return res, np.diff(cpu), cpu_seconds() - cpu[-1], time.perf_counter() - stamps[-1][1]


@contextlib.contextmanager
def timed_joint_fits(seconds):
    """Append the CPU s of every ``fit_joint_all`` call to ``seconds``."""
    original = pas.models.joint_mixture.fit_joint_all

    def timed(*args, **kwargs):
        t = cpu_seconds()
        out = original(*args, **kwargs)
        seconds.append(cpu_seconds() - t)
        return out

    pas.models.joint_mixture.fit_joint_all = timed
    try:
        yield
    finally:
        pas.models.joint_mixture.fit_joint_all = original


def part_prune(max_hf):
    """Every family refitted in every iteration (old) against far-behind families left
    unrefitted (new), no band."""
    from pas.strategies import estimators

    print(f"-- the study's fits: every family refitted (old) vs a family more than "
          f"{estimators.PRUNE_AIC_TRIED:g} AIC behind not refitted (new; off by default)")
    out, histories = {}, {}
    for label, limit in (("old", None), ("new", estimators.PRUNE_AIC_TRIED)):
        with module_setting("pas.strategies.estimators", "PRUNE_AIC", limit):
            res, loop, _, _ = run(max_hf, fit_seconds=(fits := []), n_bootstrap=0)
        out[label], histories[label] = summary(res), res.history
        out[label]["times"] = [float(np.median(loop)), float(loop.max()), float(np.sum(fits))]
        print(f"  {label}: loop median {1e3 * np.median(loop):5.1f} ms, worst "
              f"{1e3 * loop.max():6.1f} ms; joint fits {1e3 * np.sum(fits):6.0f} ms CPU in all")
    rel, same = largest_change(out["old"], out["new"])
    aic = [c for c in histories["old"].columns if c.startswith("aic_")]
    above = float(np.nanmax((histories["new"][aic] - histories["old"][aic]).to_numpy(float)))
    t_old, t_new = out["old"]["times"], out["new"]["times"]
    print(f"  ratio new/old: loop median {t_new[0] / t_old[0]:.2f}, worst {t_new[1] / t_old[1]:.2f}, "
          f"joint fits {t_new[2] / t_old[2]:.2f}; largest relative change of MPM and band ends "
          f"{rel:.1e}; family sequence {'the same' if same else 'DIFFERENT'}; recorded AIC of "
          f"an unrefitted family at most {above:.2g} above its refit")
    return out


def part_cold(max_hf):
    """Cold starts all at once (old) against the families in turn (new), no band."""
    print("-- the study's cold starts: all families every tenth fit (old) vs in turn (new)")
    out = {}
    for label, in_turn in (("old", False), ("new", True)):
        with module_setting("pas.strategies.estimators", "COLD_IN_TURN", in_turn):
            res, loop, _, _ = run(max_hf, n_bootstrap=0)
        out[label] = summary(res)
        out[label]["times"] = [float(np.median(loop)), float(loop.max())]
        print(f"  {label}: loop median {1e3 * np.median(loop):5.1f} ms, worst "
              f"{1e3 * loop.max():6.1f} ms, 95th percentile {1e3 * np.percentile(loop, 95):5.1f} ms")
    rel, same = largest_change(out["old"], out["new"])
    print(f"  ratio new/old: loop median {out['new']['times'][0] / out['old']['times'][0]:.2f}, "
          f"worst {out['new']['times'][1] / out['old']['times'][1]:.2f}; largest relative change "
          f"of MPM and band ends {rel:.1e}; family sequence {'the same' if same else 'DIFFERENT'}")
    return out


def summary(res):
    """What must not change: MPM, band ends and the family sequence."""
    return {"mpm": float(res.mpm), "band": [float(x) for x in res.mpm_band],
            "model_band": None if res.mpm_band_model is None else
            [float(x) for x in res.mpm_band_model],
            "families": [str(f) for f in res.history["family"].fillna("")]}


def largest_change(a, b):
    """Largest relative change between two summaries' MPM and band ends, and whether the
    family sequences are the same."""
    x = np.r_[a["mpm"], a["band"], a["model_band"] or []]
    y = np.r_[b["mpm"], b["band"], b["model_band"] or []]
    return float(np.max(np.abs(x - y) / np.abs(x))), a["families"] == b["families"]


def student_iterations(max_hf):
    """CPU ms of the loop iterations of a Student-t-only run (no band): median, worst."""
    _, loop, _, _ = run(max_hf, families=("student",), n_bootstrap=0)
    return 1e3 * float(np.median(loop)), 1e3 * float(loop.max())


def part_fit(max_hf, repeats=5):
    """The Student-t gradient: the whole run and Student-t alone, numerical vs analytic;
    each figure the median of its own over ``repeats`` runs (so the figures of a line may
    come from different runs), whose results must be the same."""
    print("-- Student-t joint fit: numerical differences (old) vs analytic gradient (new)"
          + (f"; median of {repeats} runs (least-largest ms/HF)" if repeats > 1 else ""))
    out = {}
    for label, ctx in (("old", numerical_student), ("new", contextlib.nullcontext)):
        times, results = [], []
        with ctx():
            for _ in range(repeats):
                res, loop, band, band_wall = run(max_hf)
                st = student_iterations(max_hf)
                times.append([loop.sum() + band, float(np.median(loop)), float(loop.max()),
                              band, band_wall, *st])
                results.append(summary(res))
        if any(r != results[0] for r in results):
            raise RuntimeError(f"{label}: the repeated runs gave different results")
        out[label] = results[0]
        total, loop_median, loop_worst, band, band_wall, *st = np.median(times, axis=0)
        spread = (f" ({1e3 * min(t[0] for t in times) / max_hf:.1f}-"
                  f"{1e3 * max(t[0] for t in times) / max_hf:.1f})" if repeats > 1 else "")
        print(f"  {label}: run_pas {max_hf} HF {1e3 * total / max_hf:6.1f} ms/HF (CPU){spread}; "
              f"loop median {1e3 * loop_median:5.1f} ms, worst {1e3 * loop_worst:6.1f} ms; final "
              f"band {band:5.2f} s CPU, {band_wall:5.2f} s wall; Student-t-only run: loop "
              f"median {st[0]:5.1f} ms, worst {st[1]:5.1f} ms")
        out[label]["times"] = [float(total), float(loop_median), float(loop_worst), float(band),
                               *map(float, st)]
    rel, same = largest_change(out["old"], out["new"])
    t_old, t_new = out["old"]["times"], out["new"]["times"]
    print(f"  ratio new/old: run {t_new[0] / t_old[0]:.2f}, loop median {t_new[1] / t_old[1]:.2f}, "
          f"Student-t alone {t_new[4] / t_old[4]:.2f}; largest relative change of MPM and band "
          f"ends {rel:.1e}; family sequence {'the same' if same else 'DIFFERENT'}")
    out["prune"] = part_prune(max_hf)
    return out


def final_study(max_hf):
    """The study of an 80-HF (``max_hf``) run without its band, and the band's generator."""
    lf, hf = scenario(seed=DATA_SEED)
    seen = []
    pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=N_W, p_exp=P_EXP, eps1=1e-12, seed=0,
                max_hf=max_hf, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                callback=lambda study, row: seen.append(study))
    study = seen[-1]
    study.strategy.band = pas.ModelBand(n_bootstrap=50)
    return study, lambda: np.random.default_rng([study.seed, len(study.rows), 1])


def band_seconds(study, rng, n_jobs, repeats=1):
    """``(wall s, CPU s with the workers', band, replicate MPMs, (least, largest wall s))`` of
    the final model band; the times are the medians of ``repeats`` runs, whose bands must be
    the same."""
    walls, cpus, bands = [], [], []
    for _ in range(repeats):
        t, c = time.perf_counter(), cpu_seconds()
        low, high, mpms = study.strategy.model_band(study.pairs(), study.lfset, rng(),
                                                    n_jobs=n_jobs)
        walls.append(time.perf_counter() - t)
        cpus.append(cpu_seconds() - c)
        bands.append(np.r_[low, high, np.array(mpms, float)])
    if any(not np.array_equal(b, bands[0], equal_nan=True) for b in bands):
        raise RuntimeError("the repeated bands differ")
    return (float(np.median(walls)), float(np.median(cpus)), (low, high), mpms,
            (min(walls), max(walls)))


def part_band(max_hf, repeats=5):
    """Band replicates one after another (old) vs fitted together (new), on 1 and 2 cores,
    each the median of ``repeats`` runs (the shared machine's wall times vary by ±8 %)."""
    print("-- final model band (50 replicates): old = one replicate after another, new = each "
          f"candidate fitted to all replicates at once (pas.models.joint_batch); median of "
          f"{repeats} runs (least-largest wall)")
    out = {}
    for m in (max_hf, 2 * max_hf):
        study, rng = final_study(m)
        rows = {}
        for label, batched, jobs in (("old 1 core", False, 1), ("old 2 cores", False, 2),
                                     ("new 1 core", True, 1), ("new 2 cores", True, 2)):
            with module_setting("pas.strategies.band", "BATCHED", batched):
                rows[label] = band_seconds(study, rng, jobs, repeats)
            wall, cpu, (low, high), _, (least, largest) = rows[label]
            print(f"  {m:3d} pairs, {label:>11}: {wall:5.2f} s wall ({least:4.2f}-{largest:4.2f}), "
                  f"{cpu:5.2f} s CPU; band [{low:.8g}, {high:.8g}]")
        old, new, new2 = rows["old 1 core"], rows["new 1 core"], rows["new 2 cores"]
        change = np.abs(new[3] / old[3] - 1)
        print(f"  {m:3d} pairs: new/old CPU {new[1] / old[1]:.2f} on one core, wall on two "
              f"{new2[0] / rows['old 2 cores'][0]:.2f}; new on 2 cores / 1 core wall "
              f"{new2[0] / new[0]:.2f}; band identical on 1 and 2 cores: "
              f"{bool(np.array_equal(new2[3], new[3]))}; band ends new/old "
              f"{new[2][0] / old[2][0] - 1:+.1e}, {new[2][1] / old[2][1] - 1:+.1e}; replicate "
              f"MPMs: largest relative change {change.max():.1e}, {int(np.sum(change > 1e-6))} "
              f"of {change.size} by more than 1e-6")
        for module, name, value, label, ratio in (
                ("pas.models.joint_batch", "IMPLICIT_NU", False,
                 "fitted together, ν by difference (old)", "implicit (new) / old"),
                ("pas.strategies.band", "STUDENT_RESTART", True,
                 "Student-t restarted once instead of warm + cold", "warm + cold / restart")):
            with module_setting(module, name, value):
                other = band_seconds(study, rng, 1, repeats)
            change = np.abs(new[3] / other[3] - 1)
            print(f"  {m:3d} pairs, {label}: {other[0]:5.2f} s wall, {other[1]:5.2f} s CPU; "
                  f"{ratio} CPU {new[1] / other[1]:.2f}; band ends "
                  f"{new[2][0] / other[2][0] - 1:+.1e}, {new[2][1] / other[2][1] - 1:+.1e}; "
                  f"replicate MPMs: largest relative change {change.max():.1e}")
            rows[f"new 1 core, {name}={value}"] = other
        out[m] = {k: [v[0], v[1], list(v[2])] for k, v in rows.items()}
    return out


def part_driver(max_hf, rounds=2):
    """The loop's fits by scipy.optimize.minimize (old) vs the setulb driver, ``rounds`` times."""
    from scipy import optimize

    print("-- the loop's joint fits: scipy.optimize.minimize (old) vs pas.models.lbfgsb (new), no band")
    out, results = {"old": [], "new": []}, {}
    for _ in range(rounds):
        for label, driver in (("old", lambda grad, x0, bounds: optimize.minimize(
                grad, x0, jac=True, method="L-BFGS-B", bounds=bounds)),  # minimise_bounded's old line
                              ("new", pas.models.joint.minimise_one)):
            with module_setting("pas.models.joint", "minimise_one", driver):
                results[label], loop, _, _ = run(max_hf, n_bootstrap=0)
            out[label].append([float(loop.sum()), float(np.median(loop)), float(loop.max())])
            print(f"  {label}: loop {loop.sum():5.2f} s CPU, median {1e3 * np.median(loop):5.1f} ms,"
                  f" worst {1e3 * loop.max():6.1f} ms")
    old, new = (np.median(out[k], axis=0) for k in ("old", "new"))
    same = results["old"].mpm == results["new"].mpm and results["old"].history.equals(results["new"].history)
    print(f"  ratio new/old (medians of the rounds): loop {new[0] / old[0]:.2f}, median "
          f"{new[1] / old[1]:.2f}; MPM and history {'the same' if same else 'DIFFERENT'}")
    return out


def positive_int(text):
    """``--repeats``: a whole number of at least 1."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"takes a whole number of at least 1, got {text!r}")
    return int(text)


def main():
    global DATA_SEED
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-hf", type=int, default=80)
    parser.add_argument("--parts", default="fit",
                        help="comma-separated: fit, cold, band, driver")
    parser.add_argument("--repeats", type=positive_int, default=5,
                        help="runs of each band timing and of each whole run of the fit "
                             "part, the median printed (default 5)")
    parser.add_argument("--seed", type=int, default=DATA_SEED,
                        help="the seed the scenario's data are drawn from (default 1)")
    parser.add_argument("--json", help="write the figures here")
    args = parser.parse_args()
    DATA_SEED = args.seed
    out = {}
    before = reference_seconds()
    print(f"machine speed: a fixed piece of work took {before:.2f} s CPU "
          f"({REFERENCE_QUIET:.2f} s when this machine was quiet); data seed {args.seed}")
    parts = {"fit": part_fit, "cold": part_cold, "band": part_band, "driver": part_driver}
    for part in args.parts.split(","):
        out[part] = (parts[part](args.max_hf, args.repeats) if part in ("band", "fit")
                     else parts[part](args.max_hf))
    after = reference_seconds()
    print(f"machine speed: the fixed piece of work took {after:.2f} s CPU at the end "
          f"({before:.2f} s at the start)")
    out["reference_seconds"] = [before, after]
    out["seed"] = args.seed
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh)


if __name__ == "__main__":
    main()
