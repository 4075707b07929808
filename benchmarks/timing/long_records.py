"""Benchmark: long LF records, this tree beside a baseline commit, in one run.

The problem of ``benchmarks/timing/study_parts.py`` (a Gumbel copula to a
Weibull HF load, 80 pairs) at longer records, each figure in a fresh process
(peak RSS is a process's high-water mark):

* one iteration at n = 15 k / 150 k / 1.5 M (default families, Gaussian,
  Student-t) with ``pas`` of ``--baseline`` (old: a commit, unpacked with ``git
  archive``; the default 9224ca2 drew all ``z × n`` values and sorted them)
  against this tree's (new: only the uniforms that can reach the top of a
  realisation, :mod:`pas.strategies.tail_draws`), CPU ms, peak RSS and the MPM
  change;
* one ``run_pas`` at 1.5 M to 8 HF, old and new, peak RSS;
* a band replicate's full sort against the partial one.

Run: python benchmarks/timing/long_records.py [--baseline 9224ca2] [--json out.json]
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
from harness.timing_problem import N_W, P_EXP, N, scenario  # noqa: E402

BASELINE = "9224ca2"
"""The last commit whose iterations drew every value and sorted it."""


def long_iterations(n, families, repeats):
    """``(median CPU ms of an iteration at 80 pairs, MPM)`` at ``n`` LF peaks, after a first
    iteration that draws the common uniforms."""
    from pas.strategies.band import ModelBand
    from pas.strategies.base import Pairs
    from pas.strategies.pas import PAS
    from pas.strategies.screening import LFSet

    lf, hf = scenario(n)
    lfset = LFSet(lf, n_waves=int(round(n * N_W / N)), p_exp=P_EXP)
    pos = np.unique(np.round(np.geomspace(1, lfset.n, 80)).astype(int) - 1)
    pairs = Pairs(pos, lfset.lf[pos], hf[lfset.index[pos]], lfset.d[pos])
    del lf, hf
    strat = PAS(families=families, band=ModelBand(n_bootstrap=0))
    strat.reset(0)
    strat.predict(pairs, lfset, np.random.default_rng(0))
    times = []
    for k in range(repeats):
        t = time.process_time()
        pred = strat.predict(pairs, lfset, np.random.default_rng(k))
        times.append(time.process_time() - t)
    return 1e3 * float(np.median(times)), pred.mpm


def long_run(n, max_hf=8):
    """``(wall s, MPM)`` of one ``run_pas`` at ``n`` LF peaks to ``max_hf`` HF, band off."""
    import pas

    lf, hf = scenario(n)
    t = time.perf_counter()
    res = pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=int(round(n * N_W / N)),
                      p_exp=P_EXP, seed=0, eps1=1e-12, max_hf=max_hf,
                      strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    assert len(res.distribution) == n  # the whole distribution, drawn when read
    return time.perf_counter() - t, float(res.mpm)


def long_child(args):
    """One measurement in a fresh process (peak RSS is a process's high-water mark):
    prints ``[ms or s, MB peak RSS, MPM]`` as JSON."""
    import resource

    what, n = args[0], int(args[1])
    if what == "iteration":
        value, mpm = long_iterations(n, tuple(args[3].split(",")), int(args[4]))
    else:
        value, mpm = long_run(n)
    print(json.dumps([value, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, mpm]))


def in_child(src, *args):
    """:func:`long_child` of ``args`` in a fresh interpreter with ``pas`` from ``src``."""
    env = dict(os.environ, PYTHONPATH=str(src), MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, str(HERE), "--long-child", *map(str, args)],
                         capture_output=True, text=True, check=True, env=env)
    return json.loads(out.stdout.strip().splitlines()[-1])


def part_long(old_src):
    """Per-iteration CPU time, peak RSS and MPM at n = 15 k / 150 k / 1.5 M, and one
    ``run_pas`` at 1.5 M: old = ``pas`` of ``old_src``, new = this tree's."""
    import pas.models.copulas
    import pas.stats.exceedance

    print("-- long records, one iteration at 80 pairs: old = the baseline's pas, new = this "
          "tree's; each in a fresh process (peak RSS)")
    srcs = {"old": old_src, "new": ROOT / "src"}
    out = {}
    for n, repeats in ((15000, 7), (150000, 5), (1500000, 3)):
        for label, families in (("default", ",".join(pas.models.copulas.PAPER_FAMILIES)),
                                ("gaussian", "gaussian"), ("student", "student")):
            row = {path: in_child(srcs[path], "iteration", n, families, repeats)
                   for path in ("old", "new")}
            (t0, m0, v0), (t1, m1, v1) = row["old"], row["new"]
            print(f"  n = {n:>9,}, {label:>8}: old {t0:7.1f} ms {m0:5.0f} MB, new {t1:7.1f} ms "
                  f"{m1:5.0f} MB, time ratio {t1 / t0:.3f}; MPM change {abs(v1 / v0 - 1):.1e}")
            out[f"{n}_{label}"] = row
    row = {path: in_child(srcs[path], "run", 1500000) for path in ("old", "new")}
    (t0, m0, v0), (t1, m1, v1) = row["old"], row["new"]
    print(f"  run_pas at n = 1,500,000 to 8 HF, band off, whole distribution read: old "
          f"{t0:5.1f} s {m0:5.0f} MB, new {t1:5.1f} s {m1:5.0f} MB peak RSS; MPM change "
          f"{abs(v1 / v0 - 1):.1e}")
    out["run_pas_1500000"] = row
    sort_n = 10 * 150000
    h = np.random.default_rng(0).weibull(1.5, (10, sort_n // 10))
    t = time.process_time()
    np.sort(h, axis=1)
    t_full = time.process_time() - t
    t = time.process_time()
    pas.stats.exceedance.mean_top_order_statistics(h, int(np.ceil(P_EXP * 16364)) + 1)
    t_top = time.process_time() - t
    print(f"  a band replicate's sort, 10 x 150 000 draws: full {1e3 * t_full:.1f} ms, top only "
          f"(np.partition) {1e3 * t_top:.1f} ms")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=BASELINE,
                        help=f"the commit the old figures are measured with (default {BASELINE})")
    parser.add_argument("--json", help="write the figures here")
    parser.add_argument("--long-child", nargs="+", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.long_child:
        return long_child(args.long_child)
    with tempfile.TemporaryDirectory() as tmp:
        out = part_long(baseline_tree(args.baseline, tmp))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh)


if __name__ == "__main__":
    main()
