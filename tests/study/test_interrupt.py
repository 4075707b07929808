"""Ctrl-C during ``pas run`` with a command oracle: a quick exit, nothing lost on resume.

Ctrl-C took 6 s to exit (here 33 s on a loaded machine), spent on
the bootstrap refits of the partial result's model band and on the
interpreter's collections at exit.  The tests interrupt a real ``pas run``
process, and a Python campaign, while the HF program runs; the ``pas run`` is
resumed with the same command and compared with an uninterrupted run.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _campaign import sigint_as_in_a_shell

import pas

SRC = str(Path(pas.__file__).resolve().parents[1])

N_BEFORE, MAX_HF = 3, 8

# logs each start; after N_BEFORE calls sleeps as long as sleep.txt (next to it) says;
# logs each finish and writes its result atomically
SLOW_CFD = f"""\
import os, sys, time
here = os.path.dirname(os.path.abspath(__file__))
event, lf, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
with open(os.path.join(here, "calls.log"), "a") as f:
    f.write(event + "\\n")
if len(open(os.path.join(here, "calls.log")).read().split()) > {N_BEFORE}:
    time.sleep(float(open(os.path.join(here, "sleep.txt")).read()))
with open(os.path.join(here, "finished.log"), "a") as f:
    f.write(event + "\\n")
with open(out + ".tmp", "w") as f:
    f.write(repr(1.2 * lf ** 1.1))
os.replace(out + ".tmp", out)
"""

SLEEP = 20.0
"""How long the interrupted event's program runs: a quick exit is one that comes before it ends."""


def _finished(folder) -> int:
    log = folder / "finished.log"
    return len(log.read_text().split()) if log.exists() else 0


def _folder(path, sleep):
    path.mkdir()
    lf = np.random.default_rng(5).rayleigh(2.0, 600)
    pd.DataFrame({"id": [f"e{i}" for i in range(600)], "lf": lf}).to_csv(path / "lf.csv",
                                                                        index=False)
    (path / "slow_cfd.py").write_text(SLOW_CFD)
    (path / "sleep.txt").write_text(str(sleep))
    return path


def _pas_run(folder, **kw):
    argv = [sys.executable, "-m", "pas", "run", "lf.csv", "--oracle",
            f"command:{sys.executable} slow_cfd.py {{id}} {{lf}} {{result}}", "--n-waves", "600",
            "--p-exp", "1e-2", "--eps1", "1e-4", "--seed", "2", "--max-hf", str(MAX_HF),
            "--preset", "paper", "--out", "out"]
    env = {**os.environ, "PYTHONPATH": SRC, "MPLBACKEND": "Agg"}
    return subprocess.Popen(argv, cwd=folder, env=env, text=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, preexec_fn=sigint_as_in_a_shell, **kw)


@pytest.mark.slow
def test_ctrl_c_exits_quickly_writes_the_partial_result_and_resume_loses_nothing(tmp_path):
    folder = _folder(tmp_path / "interrupted", sleep=SLEEP)
    proc = _pas_run(folder)
    seen = 0
    for line in proc.stderr:  # one progress line per told result
        seen += line.startswith("[pas] it")
        if seen == N_BEFORE:
            break
    time.sleep(0.5)  # the next event's program is running now
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    err = proc.stderr.read()
    proc.wait(timeout=60)
    took = time.monotonic() - sent
    assert proc.returncode == 130, err
    # a quick exit, without a timed assertion: pas ended while the interrupted event's
    # program (SLEEP s) still ran (0.5 s measured here; 2.1-2.7 s before, 33 s with the bootstrap)
    assert _finished(folder) == N_BEFORE, f"pas waited for the HF program ({took:.1f} s)"
    assert f"interrupted after {N_BEFORE} HF result(s); partial result written to out/" in err
    interrupted = (folder / "calls.log").read_text().split()[-1]
    # the interrupted event's program is ended, not left holding its cores until its end
    assert f"ended the HF program(s) still running: event {interrupted}: PID" in err
    summary = json.loads((folder / "out" / "summary.json").read_text())
    assert summary["inputs"]["stopped_early"] is True
    partial = pd.read_csv(folder / "out" / "history.csv")
    assert len(partial) == N_BEFORE

    (folder / "sleep.txt").write_text("0")
    resumed = _pas_run(folder)
    _, err = resumed.communicate(timeout=300)
    assert resumed.returncode == 0, err
    final = pd.read_csv(folder / "out" / "history.csv")
    pd.testing.assert_frame_equal(final.iloc[:N_BEFORE][["event_id", "hf"]],
                                  partial[["event_id", "hf"]])
    calls = (folder / "calls.log").read_text().split()
    # every event ran once, the interrupted one (ended) once more
    assert len(set(calls)) == MAX_HF and len(calls) == MAX_HF + 1
    assert calls.count(interrupted) == 2

    fresh_folder = _folder(tmp_path / "fresh", sleep=0)
    fresh = _pas_run(fresh_folder)
    _, err = fresh.communicate(timeout=300)
    assert fresh.returncode == 0, err
    fresh_history = pd.read_csv(fresh_folder / "out" / "history.csv")
    assert list(final["event_id"]) == list(fresh_history["event_id"])
    got = json.loads((folder / "out" / "summary.json").read_text())
    want = json.loads((fresh_folder / "out" / "summary.json").read_text())
    assert got["mpm"] == pytest.approx(want["mpm"], rel=1e-9)


INTERRUPTING_ORACLE = """\
calls = []

def load(event):
    calls.append(event.id)
    if len(calls) > 6:
        raise KeyboardInterrupt  # Ctrl-C while the 7th HF evaluation runs (a model is fitted)
    return 1.2 * event.lf ** 1.1
"""


def test_partial_result_after_ctrl_c_skips_the_bootstrap_refits(tmp_path, monkeypatch, capsys):
    from pas.cli import main
    from pas.strategies.pas import PAS

    folder = _folder(tmp_path / "run", sleep=0)
    (folder / "oracle.py").write_text(INTERRUPTING_ORACLE)
    refits = []
    monkeypatch.setattr(PAS, "model_band", lambda self, *a: refits.append(1))
    monkeypatch.chdir(folder)
    code = main(["run", "lf.csv", "--oracle", "python:oracle.py:load", "--n-waves", "600",
                 "--p-exp", "1e-2", "--eps1", "1e-4", "--seed", "2", "--out", "out", "--quiet"])
    err = capsys.readouterr().err
    assert code == 130, err
    assert "interrupted after 6 HF result(s); partial result written to out/" in err
    summary = json.loads((folder / "out" / "summary.json").read_text())
    assert summary["inputs"]["stopped_early"] is True and summary["n_hf"] == 6
    assert np.isfinite(summary["mpm"])
    assert refits == []


PYTHON_CAMPAIGN = """\
import sys
import pandas as pd
import pas

lf = pd.read_csv("lf.csv")["lf"].to_numpy()
oracle = pas.CommandOracle([sys.executable, "slow_cfd.py", "{id}", "{lf}", "{result}"],
                           root="runs")
pas.run_pas(lf, oracle, n_waves=600, p_exp=1e-2, eps1=1e-4, seed=2, max_hf=8,
            strategy=pas.PAS.paper(), study="campaign.db",
            callback=lambda study, row: print("told", file=sys.stderr, flush=True))
"""


@pytest.mark.slow
def test_ctrl_c_in_a_python_campaign_exits_quickly_with_every_result_stored(tmp_path):
    from pas.study.store import StudyStore

    folder = _folder(tmp_path / "py", sleep=SLEEP)
    (folder / "campaign.py").write_text(PYTHON_CAMPAIGN)
    env = {**os.environ, "PYTHONPATH": SRC}
    proc = subprocess.Popen([sys.executable, "campaign.py"], cwd=folder, env=env, text=True,
                            stderr=subprocess.PIPE, preexec_fn=sigint_as_in_a_shell)
    seen = 0
    for line in proc.stderr:
        seen += line.startswith("told")
        if seen == N_BEFORE:
            break
    time.sleep(0.5)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    err = proc.stderr.read()
    proc.wait(timeout=60)
    took = time.monotonic() - sent
    assert "KeyboardInterrupt" in err
    # ended while the interrupted event's program still ran (0.5 s here, 2.3 s before)
    assert _finished(folder) == N_BEFORE, f"the campaign waited for the HF program ({took:.1f} s)"
    with StudyStore(folder / "campaign.db", create=False) as store:
        events = store.events()
    assert (events["state"] == "done").sum() == N_BEFORE
