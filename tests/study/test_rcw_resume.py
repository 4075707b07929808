"""A design-wave run killed mid-ladder resumes from its study store, evaluating nothing twice.

The episodes of :func:`pas.run_rcw` are the events of a study, so the study
loop stores each HF result the moment it arrives; a ``kill -9`` loses only
the episode that was running.  The resumed run takes the stored results, runs
the rest, and gives what an uninterrupted run gives.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import pas
from pas.waves import jonswap, response_surrogate

SRC = str(Path(pas.__file__).resolve().parents[1])
LEVELS = [2e-2, 1e-2, 5e-3, 2e-3, 5e-4]
P_EXP, N_BEFORE = 1e-3, 3

# the surrogate and the run as a script; after N_BEFORE finished calls the oracle hangs
RUN = f"""\
import os, sys, time
import numpy as np
import pas
from pas.waves import jonswap, response_surrogate

surrogate = response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: np.ones_like(w),
                               duration=300.0, depth=30.0, omega_max=2.0, second_order=False)
log = sys.argv[2]

def oracle(ep):
    done = open(log).read().split() if os.path.exists(log) else []
    if len(done) >= {N_BEFORE}:
        open(log + ".running", "w").write(ep.id)
        time.sleep(600)
    with open(log, "a") as f:
        f.write(ep.id + "\\n")
    return 1.3 * ep.target + 0.1 * ep.target ** 2

pas.run_rcw(surrogate, oracle, p_exp={P_EXP}, levels={LEVELS}, study=sys.argv[1])
"""


def _surrogate():
    return response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: np.ones_like(w),
                              duration=300.0, depth=30.0, omega_max=2.0, second_order=False)


@pytest.mark.slow
def test_a_killed_run_resumes_with_its_stored_results_and_evaluates_nothing_twice(tmp_path):
    (tmp_path / "run.py").write_text(RUN)
    store, log = tmp_path / "rcw.sqlite", tmp_path / "calls.log"
    env = {**os.environ, "PYTHONPATH": SRC, "MPLBACKEND": "Agg"}
    proc = subprocess.Popen([sys.executable, "run.py", str(store), str(log)], cwd=tmp_path,
                            env=env, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (tmp_path / "calls.log.running").exists():
        assert proc.poll() is None, proc.stderr.read()
        assert time.monotonic() < deadline, "the run never reached its fourth episode"
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    before = log.read_text().split()
    assert len(before) == N_BEFORE
    assert pas.StudyStore(store).events()["hf"].notna().sum() == N_BEFORE

    surrogate, after = _surrogate(), []

    def oracle(ep):
        after.append(ep.id)
        return 1.3 * ep.target + 0.1 * ep.target ** 2

    resumed = pas.run_rcw(surrogate, oracle, p_exp=P_EXP, levels=LEVELS, study=store)
    assert not set(after) & set(before)
    assert after[0] == (tmp_path / "calls.log.running").read_text()  # the killed one runs again
    assert before + after == list(resumed.history["episode_id"])
    fresh = pas.run_rcw(surrogate, oracle, p_exp=P_EXP, levels=LEVELS)
    assert resumed.converged and resumed.n_hf == len(LEVELS) + 1
    assert resumed.mpm == pytest.approx(fresh.mpm, rel=1e-12)
    assert np.allclose(resumed.history["hf"], fresh.history["hf"], rtol=1e-12, atol=0)
