"""Benchmark: one PAS long-term analysis, the old code beside the new, in one run (issue 29).

The problem: a long-term analogue (:func:`pas.validation.long_term_compare.long_term_data`,
``--scale`` of its hours per kept cell, data seed 1) with case 3's LF
threshold where a sea state has four peaks over it (as the comparison runs
it), at p = 2e-6, ``--max-hf`` HF events.  The same analysis runs twice in
fresh processes, once with ``pas`` of ``--baseline`` (a commit, unpacked with
``git archive``) and once with this tree's; each reports its wall time and
CPU time, split into the allocation loop and the result (the combination and,
with ``--model-band``, every study's bootstrap band), the sequence of asked
events and the value and band.  CPU time is the analysis's process's alone:
the band workers' is not in it, so with ``--model-band`` read the wall time.  The
ratios and whether the two asked the same events in the same order are
printed, and written as JSON with ``--json``.

Run: python benchmarks/timing/long_term_speed.py [--analogue 2] [--scale 0.2] [--max-hf 60]
     [--baseline 9224ca2] [--model-band] [--json out.json]
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
from harness.baseline import baseline_tree  # noqa: E402


def _problem(analogue, scale):
    import numpy as np
    import pandas as pd

    from pas.validation.long_term_compare import _case, long_term_data

    data, _ = long_term_data(analogue, seed=1, scale=scale)
    table = data.sea_states.copy()
    threshold = _case(data).threshold
    if threshold is not None:  # written out: the baseline has no helper for it
        table["threshold"] = [threshold if int(np.sum(data.lf[s] > threshold)) >= 4 else np.nan
                              for s in table["name"]]
    peaks = {s: pd.DataFrame({"lf": data.lf[s], "id": data.ids[s]}) for s in data.lf}
    return data, table, peaks, _case(data).eps1


def worker(analogue, scale, max_hf, model_band):
    """One analysis in this process: a JSON line with times, asked events and the value."""
    import pas.longterm.result as result_module
    from pas.longterm import run_long_term

    data, table, peaks, eps1 = _problem(analogue, scale)
    asked, build = [], {}
    original = result_module.LongTermResult.build.__func__

    def timed_build(cls, *args, **kwargs):
        t0, c0 = time.perf_counter(), time.process_time()
        out = original(cls, *args, **kwargs)
        build.update(wall=time.perf_counter() - t0, cpu=time.process_time() - c0)
        return out

    result_module.LongTermResult.build = classmethod(timed_build)
    t0, c0 = time.perf_counter(), time.process_time()
    res = run_long_term(
        table,
        peaks,
        data.oracle(),
        p_exceed=2e-6,
        seed=0,
        max_hf=max_hf,
        eps1=eps1,
        model_band=model_band,
        callback=lambda name, st, row: asked.append([name, int(row["event_index"])]),
    )
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(json.dumps({"wall": wall, "cpu": cpu, "result_wall": build["wall"],
                      "result_cpu": build["cpu"], "value": res.value,
                      "band": [float(b) for b in res.band], "n_hf": res.n_hf, "asked": asked}))


def _run(src, args):
    env = dict(os.environ, PYTHONPATH=str(src), MPLBACKEND="Agg")
    cmd = [sys.executable, str(HERE), "--worker", "--analogue", args.analogue,
           "--scale", str(args.scale), "--max-hf", str(args.max_hf)]
    cmd += ["--model-band"] if args.model_band else []
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--analogue", choices=("2", "3"), default="2")
    parser.add_argument("--scale", type=float, default=0.2)
    parser.add_argument("--max-hf", type=int, default=60)
    parser.add_argument("--baseline", default="9224ca2")
    parser.add_argument("--model-band", action="store_true")
    parser.add_argument("--json", type=Path)
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:
        worker(args.analogue, args.scale, args.max_hf, args.model_band)
        return
    _problem(args.analogue, args.scale)  # the data set into the cache, outside the timing
    with tempfile.TemporaryDirectory() as tmp:
        old = _run(baseline_tree(args.baseline, tmp), args)
    new = _run(ROOT / "src", args)
    out = {"analogue": args.analogue, "scale": args.scale, "max_hf": args.max_hf,
           "model_band": args.model_band, "baseline": args.baseline,
           "same_events_in_order": old["asked"] == new["asked"],
           "value_relative_change": new["value"] / old["value"] - 1.0,
           "band_relative_change": [n / o - 1.0 for n, o in zip(new["band"], old["band"])]}
    for part in ("wall", "cpu", "result_wall", "result_cpu"):
        out[part] = {"old": old[part], "new": new[part], "ratio": old[part] / new[part]}
    for part in ("wall", "cpu"):
        o, n = old[part] - old[f"result_{part}"], new[part] - new[f"result_{part}"]
        out[f"loop_{part}"] = {"old": o, "new": n, "ratio": o / n}
    for key, v in out.items():
        print(f"{key}: {v}")
    if args.json:
        args.json.write_text(json.dumps(out, indent=2), encoding="utf-8")


if __name__ == "__main__":
    main()
