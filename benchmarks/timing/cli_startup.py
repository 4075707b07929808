"""Benchmark: wall time of fresh ``pas`` processes that should start fast.

Times ``pas --help`` and ``pas study tell STUDY EVENT VALUE`` (a new result
into a study store), each in a new process as a shell runs it, against a bare
``python -c pass`` started the same way, and reports which heavy libraries a
``pas study tell`` process imported.

Run: python benchmarks/timing/cli_startup.py [repeats]
Target (issue 14): both under 1 s.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def wall(argv, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        times.append(time.perf_counter() - t)
    return float(np.median(times)), float(np.min(times))


def main(repeats: int = 7) -> None:
    import pas

    exe = shutil.which("pas") or f"{sys.executable} -m pas"
    pas_cmd = exe.split()
    tmp = Path(tempfile.mkdtemp())
    db = tmp / "s.db"
    study = pas.make_study("pas", np.random.default_rng(0).rayleigh(1.0, 2000), n_waves=2000,
                           p_exp=0.01, eps1=0.1, seed=1, store=db)
    events = study.ask(1) + study.ask(repeats)
    study.store.close()
    base = wall([sys.executable, "-c", "pass"], repeats)
    hlp = wall(pas_cmd + ["--help"], repeats)
    tells = []
    for ev in events[:repeats - 1]:
        t = time.perf_counter()
        subprocess.run(pas_cmd + ["study", "tell", str(db), str(ev.id), "2.5"], check=True,
                       capture_output=True)
        tells.append(time.perf_counter() - t)
    probe = subprocess.run(
        [sys.executable, "-c", "import sys; from pas.cli import main; "
         f"main(['study', 'tell', {str(db)!r}, {str(events[-1].id)!r}, '2.5']); "
         "print(sorted({m.split('.')[0] for m in sys.modules} & "
         "{'matplotlib', 'sklearn', 'pyvinecopulib', 'scipy', 'pandas'}))"],
        check=True, capture_output=True, text=True).stdout.strip().splitlines()[-1]
    print(f"fresh processes, median (min) of {repeats}:")
    print(f"  python -c pass          {base[0]:6.3f} s ({base[1]:.3f})")
    print(f"  pas --help              {hlp[0]:6.3f} s ({hlp[1]:.3f})")
    print(f"  pas study tell          {np.median(tells):6.3f} s ({np.min(tells):.3f})")
    print(f"  heavy libraries imported by the tell path: {probe}")
    shutil.rmtree(tmp)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("repeats", nargs="?", type=int, default=7)
    main(ap.parse_args().repeats)
