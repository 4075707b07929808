"""Benchmark: where a PAS run spends its time, this tree beside a baseline commit.

One scenario throughout: 15 000 Rayleigh LF peaks, ``n_w`` 16 364, a Gumbel
(θ = 3) copula to a Weibull HF load, stopping off, 80 HF (``--max-hf``), its data
drawn from ``--seed`` (default 1).  Each part runs in a fresh process, once with
``pas`` of ``--baseline`` (a commit, unpacked with ``git archive``; none: this
tree only) and once with this tree's; each reports CPU time (the forked band
workers' included) and what must not change (MPM, band ends, the family
sequence), and the ratios and the largest change are printed.  Wall times on
a shared machine are read against a fixed piece of work timed at the start
and the end (``harness.timing_problem.reference_seconds``).  The whole runs and
the bands are each the median of ``--repeats`` runs.

* ``fit``: the whole run, its loop's median and worst iteration, the final
  band, and a Student-t-only run's loop;
* ``band``: the final model band (50 replicates) of 80 and 160 pairs on one
  and on two cores.

Long LF records are timed by ``benchmarks/timing/long_records.py``.

Run: python benchmarks/timing/study_parts.py [--parts fit,band] [--max-hf 80] [--repeats 5]
     [--seed 1] [--baseline COMMIT] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve()
ROOT = HERE.parents[2]
sys.path.insert(0, str(HERE.parents[1]))  # benchmarks/: the harness
import numpy as np  # noqa: E402
from harness.baseline import baseline_tree  # noqa: E402
from harness.timing_problem import (  # noqa: E402
    N_W,
    P_EXP,
    REFERENCE_QUIET,
    N,
    cpu_seconds,
    reference_seconds,
    scenario,
)


def run(max_hf, seed, n=N, n_waves=N_W, **settings):
    """One run with stopping off: ``(result, CPU s per loop iteration, CPU s of the final
    band, wall s of the final band)``."""
    import pas
    from pas.study.flat import from_flat

    lf, hf = scenario(n, seed=seed)
    stamps = []

    def callback(study, row):
        stamps.append((cpu_seconds(), time.perf_counter()))

    t0 = cpu_seconds()
    objects = from_flat({"eps1": 1e-12, "max_hf": max_hf, **settings})  # flat names
    res = pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=n_waves, p_exp=P_EXP, seed=0,
                      callback=callback, **objects)
    cpu = np.r_[t0, [c for c, _ in stamps]]
    return res, np.diff(cpu), cpu_seconds() - cpu[-1], time.perf_counter() - stamps[-1][1]


def summary(res):
    """What must not change: MPM, band ends and the family sequence."""
    return {"mpm": float(res.mpm), "band": [float(x) for x in res.mpm_band],
            "model_band": None if res.mpm_band_model is None else
            [float(x) for x in res.mpm_band_model],
            "families": [str(f) for f in res.history["family"].fillna("")]}


def part_fit(max_hf, seed, repeats):
    """The whole run and a Student-t-only run: CPU times (medians of ``repeats``)."""
    times, results = [], []
    for _ in range(repeats):
        res, loop, band, band_wall = run(max_hf, seed)
        _, st_loop, _, _ = run(max_hf, seed, families=("student",), n_bootstrap=0)
        times.append([loop.sum() + band, float(np.median(loop)), float(loop.max()), band,
                      band_wall, float(np.median(st_loop)), float(st_loop.max())])
        results.append(summary(res))
    if any(r != results[0] for r in results):
        raise RuntimeError("the repeated runs gave different results")
    return {"times": [float(t) for t in np.median(times, axis=0)], "result": results[0]}


def final_study(max_hf, seed):
    """The study of a ``max_hf``-HF run without its band, and the band's generator."""
    import pas

    lf, hf = scenario(seed=seed)
    seen = []
    pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=N_W, p_exp=P_EXP, eps1=1e-12, seed=0,
                max_hf=max_hf, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                callback=lambda study, row: seen.append(study))
    study = seen[-1]
    study.strategy.band = pas.ModelBand(n_bootstrap=50)
    return study, lambda: np.random.default_rng([study.seed, len(study.rows), 1])


def part_band(max_hf, seed, repeats):
    """The final model band at ``max_hf`` and twice as many pairs, on 1 and 2 cores: wall
    and CPU s (medians of ``repeats``), the band ends and the replicate MPMs."""
    out = {}
    for m in (max_hf, 2 * max_hf):
        study, rng = final_study(m, seed)
        for jobs in (1, 2):
            walls, cpus, bands = [], [], []
            for _ in range(repeats):
                t, c = time.perf_counter(), cpu_seconds()
                low, high, mpms = study.strategy.model_band(study.pairs(), study.lfset, rng(),
                                                            n_jobs=jobs)
                walls.append(time.perf_counter() - t)
                cpus.append(cpu_seconds() - c)
                bands.append(np.r_[low, high, np.ravel(np.array(mpms, float))])
            if any(not np.array_equal(b, bands[0], equal_nan=True) for b in bands):
                raise RuntimeError("the repeated bands differ")
            out[f"{m} pairs, {jobs} core{'s' if jobs > 1 else ''}"] = {
                "wall": float(np.median(walls)), "cpu": float(np.median(cpus)),
                "band": [float(x) for x in bands[0]]}
    return out


PARTS = {"fit": part_fit, "band": part_band}


def worker(args):
    """The parts of ``args`` with the ``pas`` on this process's path, as JSON on stdout."""
    out = {part: PARTS[part](args.max_hf, args.seed, args.repeats)
           for part in args.parts.split(",")}
    print(json.dumps(out))


def _run(src, args):
    env = dict(os.environ, PYTHONPATH=str(src), MPLBACKEND="Agg")
    cmd = [sys.executable, str(HERE), "--worker", "--parts", args.parts, "--max-hf",
           str(args.max_hf), "--repeats", str(args.repeats), "--seed", str(args.seed)]
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _print(label, out):
    if "fit" in out:
        total, median, worst, band, band_wall, st_median, st_worst = out["fit"]["times"]
        print(f"  {label}: loop median {1e3 * median:5.1f} ms, worst {1e3 * worst:6.1f} ms; "
              f"final band {band:5.2f} s CPU, {band_wall:5.2f} s wall; whole run "
              f"{total:5.2f} s CPU; Student-t-only loop median {1e3 * st_median:5.1f} ms, worst "
              f"{1e3 * st_worst:6.1f} ms")
    for key, row in out.get("band", {}).items():
        print(f"  {label}: band of {key}: {row['wall']:5.2f} s wall, {row['cpu']:5.2f} s CPU; "
              f"band [{row['band'][0]:.8g}, {row['band'][1]:.8g}]")


def _compare(old, new):
    if "fit" in old:
        t0, t1 = old["fit"]["times"], new["fit"]["times"]
        a, b = old["fit"]["result"], new["fit"]["result"]
        x = np.r_[a["mpm"], a["band"], a["model_band"] or []]
        y = np.r_[b["mpm"], b["band"], b["model_band"] or []]
        print(f"  new/old: whole run {t1[0] / t0[0]:.2f}, loop median {t1[1] / t0[1]:.2f}, final "
              f"band {t1[3] / t0[3]:.2f}; largest relative change of MPM and band ends "
              f"{float(np.max(np.abs(x - y) / np.abs(x))):.1e}; family sequence "
              f"{'the same' if a['families'] == b['families'] else 'DIFFERENT'}")
    for key in old.get("band", {}):
        o, n = old["band"][key], new["band"][key]
        change = np.abs(np.array(n["band"]) / np.array(o["band"]) - 1)
        print(f"  new/old, band of {key}: CPU {n['cpu'] / o['cpu']:.2f}, wall "
              f"{n['wall'] / o['wall']:.2f}; largest relative change of a band end or replicate "
              f"MPM {np.nanmax(change):.1e}")


def positive_int(text):
    """``--repeats``: a whole number of at least 1."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"takes a whole number of at least 1, got {text!r}")
    return int(text)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-hf", type=int, default=80)
    parser.add_argument("--parts", default="fit", help="comma-separated: fit, band")
    parser.add_argument("--repeats", type=positive_int, default=5,
                        help="runs of each timing, the median printed (default 5)")
    parser.add_argument("--seed", type=int, default=1,
                        help="the seed the scenario's data are drawn from (default 1)")
    parser.add_argument("--baseline", help="a commit to compare with (default: none)")
    parser.add_argument("--json", help="write the figures here")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    unknown = set(args.parts.split(",")) - set(PARTS)
    if unknown:
        parser.error(f"--parts: unknown {', '.join(sorted(unknown))}; use fit, band")
    if args.worker:
        return worker(args)
    before = reference_seconds()
    print(f"machine speed: a fixed piece of work took {before:.2f} s CPU "
          f"({REFERENCE_QUIET:.2f} s when this machine was quiet); data seed {args.seed}")
    out = {"new": _run(ROOT / "src", args)}
    _print("new", out["new"])
    if args.baseline:
        with tempfile.TemporaryDirectory() as tmp:
            out["old"] = _run(baseline_tree(args.baseline, tmp), args)
        _print("old", out["old"])
        _compare(out["old"], out["new"])
    after = reference_seconds()
    print(f"machine speed: the fixed piece of work took {after:.2f} s CPU at the end "
          f"({before:.2f} s at the start)")
    out |= {"reference_seconds": [before, after], "seed": args.seed,
            "baseline": args.baseline}
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh)


if __name__ == "__main__":
    main()
