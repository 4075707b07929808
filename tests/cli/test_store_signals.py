"""One file is the study, and SIGTERM stops a run like Ctrl-C.

The ``.sqlite`` file of a finished (or stopped) run holds every result by
itself, ``pas study backup`` copies a study in one file, and SIGTERM — what a
batch scheduler sends at a job's time limit — leaves the partial result, a
line saying how to resume and exit code 143; the resume ends where an
uninterrupted run does.
"""

import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _campaign import sigint_as_in_a_shell

from pas.cli import build_parser, main

N, NW, P = 3000, 3200, 3e-3
ORACLE = textwrap.dedent("""\
    import os, time

    def load(event):
        log = os.environ.get("PAS_TEST_LOG")
        if log:
            with open(log, "a") as f:
                f.write(f"{event.id}\\n")
        time.sleep(float(os.environ.get("PAS_TEST_SLEEP", "0")))
        return 1.2 * event.lf ** 1.1
    """)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("store-signals")
    lf = np.random.default_rng(0).rayleigh(2.0, N)
    ids = [f"ev{i:05d}" for i in range(N)]
    pd.DataFrame({"id": ids, "rwe": lf}).to_csv(d / "lf.csv", index=False)
    (d / "slow.py").write_text(ORACLE)
    return d


def _run_args(d, out, *extra):
    return [str(a) for a in ("run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
                             f"python:{d / 'slow.py'}:load", "--n-waves", NW, "--p-exp", P,
                             "--eps1", 0.2, "--seed", 1, "--max-hf", 16, "--out", out, *extra)]


def _told(db):
    """Event ids with a result in the file ``db`` read alone (no -wal file beside it)."""
    with sqlite3.connect(db) as c:
        return sorted(json.loads(r[0]) for r in c.execute(
            "SELECT event_id FROM events WHERE result_seq IS NOT NULL"))


def test_the_sqlite_file_alone_holds_every_result_after_a_run(inputs, tmp_path, capsys):
    out = tmp_path / "run"
    assert main(_run_args(inputs, out, "--quiet")) == 0, capsys.readouterr().err
    history = pd.read_csv(out / "history.csv")
    alone = tmp_path / "copy" / "study.sqlite"
    alone.parent.mkdir()
    shutil.copy(out / "study.sqlite", alone)  # the .sqlite only, as a user archives it
    assert _told(alone) == sorted(history["event_id"].astype(str))
    capsys.readouterr()
    assert main(["study", "status", str(alone), "--json"]) == 0, capsys.readouterr().err
    assert json.loads(capsys.readouterr().out)["n_hf"] == len(history)


def test_study_backup_copies_a_study_that_is_still_open(inputs, tmp_path, capsys):
    from pas.study.store import StudyStore

    out = tmp_path / "run"
    assert main(_run_args(inputs, out, "--quiet")) == 0
    n = len(_told(out / "study.sqlite"))
    with StudyStore(out / "study.sqlite") as store:  # another process holds it open and writes
        store.put("note", "written after the run")
        assert main(["study", "backup", str(out / "study.sqlite"), str(tmp_path / "b.db")]) == 0
        assert not Path(str(tmp_path / "b.db") + "-wal").exists()
        with sqlite3.connect(tmp_path / "b.db") as c:
            assert c.execute("SELECT value FROM meta WHERE key = 'note'").fetchone() == \
                ('"written after the run"',)
        assert len(_told(tmp_path / "b.db")) == n
        capsys.readouterr()
        code = main(["study", "backup", str(out / "study.sqlite"), str(tmp_path / "b.db")])
        assert code == 2 and "b.db exists" in capsys.readouterr().err


def test_a_study_started_in_an_existing_empty_store_says_so(inputs, tmp_path):
    import pas

    empty = tmp_path / "empty.sqlite"
    sqlite3.connect(empty).execute("CREATE TABLE t (x)").connection.close()  # not a study
    lf = pd.read_csv(inputs / "lf.csv")["rwe"].to_numpy()
    with pytest.warns(UserWarning, match="exists but holds no study"):
        pas.make_study(pas.PAS, lf, n_waves=NW, p_exp=P, eps1=0.2, seed=1, store=empty)


def test_help_lists_sigterm_exit_code(capsys):
    helps = [build_parser().format_help()]
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    helps.append(capsys.readouterr().out)
    for text in helps:
        assert "143" in text and "SIGTERM" in text


@pytest.mark.slow
def test_sigterm_writes_the_partial_result_and_the_resume_matches(inputs, tmp_path, monkeypatch,
                                                                   capsys):
    import pas

    out, log = tmp_path / "run", tmp_path / "calls.log"
    path = os.pathsep.join([str(Path(pas.__file__).parents[1]), os.environ.get("PYTHONPATH", "")])
    proc = subprocess.Popen(
        [sys.executable, "-m", "pas", *_run_args(inputs, out)],
        env={**os.environ, "PYTHONPATH": path, "PAS_TEST_LOG": str(log),
             "PAS_TEST_SLEEP": "0.1"},
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=sigint_as_in_a_shell)
    deadline = time.monotonic() + 90
    while not (log.exists() and len(log.read_text().splitlines()) >= 6):
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 143, stderr
    assert "Traceback" not in stderr and stdout == ""
    line = stderr.splitlines()[-1]
    assert line.startswith("pas run: terminated (SIGTERM) after ")
    for needle in (f"partial result written to {out}/",
                   "run the same 'pas run' command again to resume"):
        assert needle in line, needle
    summary = json.loads((out / "summary.json").read_text())
    assert summary["inputs"]["stopped_early"] is True and summary["n_hf"] >= 5
    stored = set(_told(out / "study.sqlite"))  # the .sqlite alone, right after SIGTERM
    assert len(stored) >= 5
    # the resume reuses every stored result and ends where an uninterrupted run ends
    log2 = tmp_path / "calls2.log"
    monkeypatch.setenv("PAS_TEST_LOG", str(log2))
    assert main(_run_args(inputs, out, "--quiet")) == 0, capsys.readouterr().err
    assert not set(log2.read_text().split() if log2.exists() else []) & stored
    monkeypatch.delenv("PAS_TEST_LOG")
    assert main(_run_args(inputs, tmp_path / "straight", "--quiet")) == 0
    resumed = json.loads((out / "summary.json").read_text())
    straight = json.loads((tmp_path / "straight" / "summary.json").read_text())
    assert resumed["mpm"] == straight["mpm"] and resumed["n_hf"] == straight["n_hf"]
    assert "stopped_early" not in resumed["inputs"]
    assert pd.read_csv(out / "history.csv")["event_id"].tolist() == \
        pd.read_csv(tmp_path / "straight" / "history.csv")["event_id"].tolist()


def test_sigterm_stops_a_python_run_like_ctrl_c_with_every_result_in_the_file(inputs, tmp_path):
    import pas
    from pas.study.signals import Terminated

    lf = pd.read_csv(inputs / "lf.csv")["rwe"].to_numpy()
    calls = []

    def oracle(event):
        calls.append(event.index)
        if len(calls) == 6:
            os.kill(os.getpid(), signal.SIGTERM)  # the scheduler's time limit, mid-call
        return 1.2 * event.lf ** 1.1

    db = tmp_path / "api.sqlite"
    with pytest.raises(Terminated):
        pas.run_pas(lf, oracle, n_waves=NW, p_exp=P, eps1=0.2, seed=1, max_hf=16, study=db)
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # restored
    alone = tmp_path / "alone.sqlite"
    shutil.copy(db, alone)
    assert len(_told(alone)) >= 5
