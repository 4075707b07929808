"""``import pas`` and a command-oracle study run where ``fcntl``, ``os.killpg`` and
``os.setsid`` do not exist (Windows), and give the MPM they give on POSIX.

Each run is a fresh interpreter; the POSIX-only names are taken away before
``pas`` is imported (``sys.modules['fcntl'] = None`` makes ``import fcntl``
raise ImportError, as on Windows).
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import pas

SRC = str(Path(pas.__file__).resolve().parents[1])

WITHOUT_POSIX = """\
import os, sys
sys.modules["fcntl"] = None
del os.killpg, os.setsid
"""

CAMPAIGN = """\
import json, sys
import numpy as np
try:
    import fcntl
    has_fcntl = True
except ImportError:
    has_fcntl = False
import pas
from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle
from pas.study.oracles import OracleError

write_hf = "import sys; open(sys.argv[2], 'w').write(repr(1.2 * float(sys.argv[1]) ** 1.1))"
hf = [sys.executable, "-c", write_hf, "{lf}", "{result}"]
lf = np.random.default_rng(4).rayleigh(2.0, 600)
res = pas.run_pas(lf, CommandOracle(hf, root="runs"), n_waves=600, p_exp=1e-2, eps1=1e-4,
                  seed=3, max_hf=8, strategy=pas.PAS.paper(), study="campaign.db")
sleeper = CommandOracle([sys.executable, "-c", "import time; time.sleep(30)"], root="slow",
                        timeout=0.5)
try:
    sleeper(Event(index=0, id="s", lf=1.0, d=0.1))
    timed_out = None
except OracleError as exc:
    timed_out = str(exc)
print(json.dumps({"has_fcntl": has_fcntl, "mpm": res.mpm, "n_hf": res.n_hf,
                  "n_failed": res.n_failed, "timed_out": timed_out}))
"""


def _campaign(folder, prelude=""):
    folder.mkdir()
    out = subprocess.run([sys.executable, "-c", prelude + CAMPAIGN], cwd=folder, text=True,
                         capture_output=True, env={**os.environ, "PYTHONPATH": SRC}, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_a_study_runs_without_fcntl_and_killpg_and_gives_the_same_mpm(tmp_path):
    posix = _campaign(tmp_path / "posix")
    windows_like = _campaign(tmp_path / "no-fcntl", WITHOUT_POSIX)
    assert posix["has_fcntl"] and not windows_like["has_fcntl"]
    for run in (posix, windows_like):
        assert run["n_hf"] == 8 and run["n_failed"] == 0
        assert run["timed_out"] is not None and "timed out after 0.5 s" in run["timed_out"]
    # the same code path on the same machine: the lock and the kill do not touch the numbers
    assert windows_like["mpm"] == pytest.approx(posix["mpm"], rel=1e-12)
