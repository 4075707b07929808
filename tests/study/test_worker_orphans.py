"""A run killed with SIGKILL leaves no idle pool workers behind (they end with their parent)."""

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(),
                                reason="reads the process table from /proc")

RUN = textwrap.dedent("""
    import time
    import numpy as np
    import pas

    def slow(event):
        time.sleep(120)
        return 1.0

    if __name__ == "__main__":
        lf = np.random.default_rng(0).rayleigh(1.0, 500)
        pas.run_pas(lf, slow, n_waves=500, p_exp=1e-2, eps1=0.1, seed=1, executor=2,
                    batch_size=2)
""")


def _children(pid: int) -> list[int]:
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            out.append(int(stat.parent.name))
    return out


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def test_pool_workers_end_when_their_run_is_killed(tmp_path):
    script = tmp_path / "run.py"
    script.write_text(RUN)
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2] / "src")}
    run = subprocess.Popen([sys.executable, str(script)], env=env, cwd=tmp_path)
    workers = []
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and len(workers) < 2:
            time.sleep(0.2)
            workers = _children(run.pid)
        assert len(workers) >= 2, "the run did not start its two workers"
        run.send_signal(signal.SIGKILL)
        run.wait()
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.2)
        assert not any(_alive(w) for w in workers), "a worker outlived its killed run"
    finally:
        run.kill()
        for w in workers:  # the test leaves no process behind, whatever it found
            try:
                os.kill(w, signal.SIGKILL)
            except OSError:
                pass
