"""Ctrl-C and closed pipes: one line on stderr, the exit codes of a shell, nothing lost.

Each test runs ``python -m pas`` in a child process, as a user's shell would,
and interrupts it while its oracle is busy; what comes before and after the
interruption (creating a study, resuming) runs in this process through
``pas.cli.main``, where a process start is not the point.
"""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _campaign import sigint_as_in_a_shell

from pas.cli import main

pytestmark = pytest.mark.slow  # child processes, signals, resumed studies

N, NW, P = 3000, 3200, 3e-3
ORACLE = textwrap.dedent("""\
    import os, time

    def load(event):
        with open(os.environ["PAS_TEST_LOG"], "a") as f:
            f.write(f"{event.id}\\n")
        time.sleep(float(os.environ.get("PAS_TEST_SLEEP", "0")))
        return 1.2 * event.lf ** 1.1
    """)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("stops")
    lf = np.random.default_rng(0).rayleigh(2.0, N)
    ids = [f"ev{i:05d}" for i in range(N)]
    pd.DataFrame({"id": ids, "rwe": lf}).to_csv(d / "lf.csv", index=False)
    (d / "slow.py").write_text(ORACLE)
    return d


def _pas(args, env, **kw):
    import pas

    path = os.pathsep.join([str(Path(pas.__file__).parents[1]), os.environ.get("PYTHONPATH", "")])
    return subprocess.Popen([sys.executable, "-m", "pas", *map(str, args)],
                            env={**os.environ, "PYTHONPATH": path, **env},
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=sigint_as_in_a_shell, **kw)


def _wait_for_lines(path, n, proc, timeout=90.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if path.exists() and len(path.read_text().splitlines()) >= n:
            return
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    pytest.fail(f"the oracle was not called {n} times in {timeout} s")


def _run_args(d, out, *extra):
    return ["run", d / "lf.csv", "--lf-column", "rwe", "--oracle", f"python:{d / 'slow.py'}:load",
            "--n-waves", NW, "--p-exp", P, "--eps1", 0.2, "--seed", 1, "--max-hf", 16,
            "--out", out, *extra]


def _stored_ids(db):
    import sqlite3

    with sqlite3.connect(db) as c:
        return {json.loads(r[0]) for r in c.execute(
            "SELECT event_id FROM events WHERE result_seq IS NOT NULL")}


def test_ctrl_c_writes_the_partial_result_and_says_how_to_resume(inputs, tmp_path, monkeypatch,
                                                                  capsys):
    out, log = tmp_path / "run", tmp_path / "calls.log"
    proc = _pas(_run_args(inputs, out), {"PAS_TEST_LOG": str(log), "PAS_TEST_SLEEP": "0.1"})
    _wait_for_lines(log, 6, proc)  # 5 results in, the 6th call running
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130
    assert "Traceback" not in stderr and stdout == ""
    line = stderr.splitlines()[-1]
    assert line.startswith("pas run: interrupted after ")
    for needle in (f"partial result written to {out}/", f"every HF result is in {out}/study.sqlite",
                   "run the same 'pas run' command again to resume"):
        assert needle in line, needle
    summary = json.loads((out / "summary.json").read_text())
    assert summary["inputs"]["stopped_early"] is True and summary["n_hf"] >= 5
    stored = _stored_ids(out / "study.sqlite")
    # resuming runs only events without a stored result and finishes the study
    log2 = tmp_path / "calls2.log"
    monkeypatch.setenv("PAS_TEST_LOG", str(log2))
    assert main([str(a) for a in _run_args(inputs, out, "--quiet")]) == 0, capsys.readouterr().err
    again = set(log2.read_text().split()) if log2.exists() else set()
    assert not again & stored
    summary = json.loads((out / "summary.json").read_text())
    # finished: converged or at its budget of 16 HF, not stopped early
    assert summary["converged"] or summary["n_hf"] == 16
    assert "stopped_early" not in summary["inputs"]


def test_ctrl_c_does_not_wait_for_running_worker_calls(inputs, tmp_path):
    out, log = tmp_path / "run", tmp_path / "calls.log"
    proc = _pas(_run_args(inputs, out, "--workers", 2),
                {"PAS_TEST_LOG": str(log), "PAS_TEST_SLEEP": "600"})
    _wait_for_lines(log, 2, proc)  # two calls asleep in the pool
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130 and time.monotonic() - t0 < 30
    assert stderr.splitlines()[-1].startswith("pas run: interrupted after 0 HF result(s)")


def test_closed_stderr_pipe_still_writes_the_output_folder(inputs, tmp_path):
    # pas run ... 2>&1 | head -n 2
    out, log = tmp_path / "run", tmp_path / "calls.log"
    proc = _pas(_run_args(inputs, out), {"PAS_TEST_LOG": str(log), "PAS_TEST_SLEEP": "0.1"})
    first = [proc.stderr.readline() for _ in range(2)]
    assert all(ln.startswith("[pas] it") for ln in first)
    proc.stderr.close()
    proc.wait(timeout=60)
    assert proc.stdout.read() == ""
    assert proc.returncode == 141
    summary = json.loads((out / "summary.json").read_text())
    assert summary["inputs"]["stopped_early"] is True and summary["n_hf"] >= 2


def test_closed_stdout_pipe_of_study_run_says_how_to_resume(inputs, tmp_path):
    # pas study run STUDY.db | head -n 2   (its progress goes to stdout)
    (tmp_path / "study.toml").write_text(textwrap.dedent(f"""\
        n_waves = {NW}
        p_exp = {P}
        eps1 = 0.2
        seed = 1
        max_hf = 16
        [lf]
        file = "{inputs / 'lf.csv'}"
        column = "rwe"
        id_column = "id"
        [oracle]
        command = ["{sys.executable}", "-c",
                   "import sys, time; time.sleep(0.1); open(sys.argv[1], 'w').write(sys.argv[2])",
                   "{{result}}", "{{lf}}"]
        root = "runs"
        """))
    db = tmp_path / "s.db"
    assert main(["study", "create", str(db), "--config", str(tmp_path / "study.toml")]) == 0
    proc = _pas(["study", "run", db], {})
    first = [proc.stdout.readline() for _ in range(2)]
    assert all(ln.startswith("[pas] it") for ln in first)
    proc.stdout.close()
    stderr = proc.stderr.read()
    proc.wait(timeout=60)
    assert proc.returncode == 141 and "Traceback" not in stderr
    (line,) = stderr.splitlines()
    assert line.startswith("pas study run: output pipe closed after ")
    assert f"every HF result is in {db}; run 'pas study run {db}' again to resume" in line
