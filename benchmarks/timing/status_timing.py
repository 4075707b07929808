"""Benchmark: wall time of ``pas study status`` on a 160-pair study, stored result against replay.

Builds (or reuses) a study store of 15 000 Rayleigh LF peaks, stopping off,
160 HF results from a Python oracle, then times fresh processes as a shell
runs them: ``pas study status STUDY`` (reads the result stored for the
current log, :mod:`pas.study.stored_results`), ``pas study status STUDY
--refresh`` (replays the log and recomputes the band, as every status did
before) and ``pas --help``.

Run: python benchmarks/timing/status_timing.py [STUDY.db] [repeats]
Target (issue 27): status <= 1 s at 160 pairs; ``pas --help`` < 0.5 s.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

N, N_WAVES, P_EXP, MAX_HF = 15_000, 16_364, 1e-3, 160


def build(db) -> float:
    """Write the 160-pair study to ``db``; returns the wall seconds it took."""
    import pas

    rng = np.random.default_rng(0)
    lf = rng.rayleigh(1.0, N)
    hf = 1.3 * lf ** 1.1 * rng.lognormal(0.0, 0.05, N)
    t = time.perf_counter()
    study = pas.make_study("pas", lf, n_waves=N_WAVES, p_exp=P_EXP, eps1=1e-12, seed=0,
                           max_hf=MAX_HF, store=db)
    study.optimize(lambda e: float(hf[e.index]))
    study.store.close()
    return time.perf_counter() - t


def wall(argv, repeats) -> list[float]:
    """Wall seconds of ``repeats`` fresh processes running ``argv``."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return times


def main(db=None, repeats: int = 3) -> None:
    db = db or str(Path(tempfile.mkdtemp()) / "s160.db")
    if not os.path.exists(db):
        print(f"built {db} ({MAX_HF} HF) in {build(db):.1f} s")
    pas_cmd = [sys.executable, "-m", "pas"]
    replay = wall(pas_cmd + ["study", "status", db, "--refresh"], repeats)
    stored = wall(pas_cmd + ["study", "status", db], repeats)
    hlp = wall(pas_cmd + ["--help"], repeats)
    print(f"fresh processes, median (min, max) of {repeats}:")
    for label, t in (("status --refresh (replay)", replay), ("status (stored result)", stored),
                     ("pas --help", hlp)):
        print(f"  {label:26s} {np.median(t):6.3f} s ({min(t):.3f}, {max(t):.3f})")
    print(f"  replay / stored: {np.median(replay) / np.median(stored):.1f}x")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("db", nargs="?", default=None, help="study store to reuse (default: a new one)")
    ap.add_argument("repeats", nargs="?", type=int, default=3)
    args = ap.parse_args()
    main(args.db, args.repeats)
