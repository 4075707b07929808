"""HF programs a run started are never orphaned silently; a changed command is said on resume.

A stand-in "CFD" program hangs (sleeps) while a file ``hang`` exists next to
it.  The driver that started it is killed (``SIGKILL``: a crashed run, a lost
node) or interrupted (Ctrl-C); the lock of the event's folder names the
program, a resumed run waits for it only until its own time-out counted
from its start, then ends it and runs the event again, and ``pas study
hf-programs`` / ``hf-stop`` list and end it.
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
from pas.cli import main
from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle
from pas.study.oracles import OracleError
from pas.study.store import StudyStore

SRC = str(Path(pas.__file__).resolve().parents[1])
EV = Event(index=3, id="ev3", lf=2.5, d=0.01, meta={})

# writes its PID to started.<event>, hangs when ./hang exists as it starts, else writes 2 * LF
CFD = """\
import os, sys, time
here = os.path.dirname(os.path.abspath(__file__))
event, lf, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
with open(os.path.join(here, "started." + event), "w") as f:
    f.write(str(os.getpid()))
if os.path.exists(os.path.join(here, "hang")):
    time.sleep(120)
with open(out, "w") as f:
    f.write(repr(2.0 * lf))
"""

# a driver in a process of its own: runs EV's program, prints nothing
DRIVER = """\
import sys
from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle
oracle = CommandOracle([sys.executable, "cfd.py", "{id}", "{lf}", "{result}"], root=sys.argv[1],
                       timeout=float(sys.argv[2]))
oracle(Event(index=3, id="ev3", lf=2.5, d=0.01, meta={}))
"""


@pytest.fixture
def folder(tmp_path, monkeypatch):
    (tmp_path / "cfd.py").write_text(CFD)
    (tmp_path / "driver.py").write_text(DRIVER)
    monkeypatch.chdir(tmp_path)
    yield tmp_path
    for started in tmp_path.glob("started.*"):  # never leave a stand-in program behind
        try:
            os.killpg(int(started.read_text()), signal.SIGKILL)
        except (ProcessLookupError, ValueError, PermissionError):
            pass


def _gone(pid: int) -> bool:
    """The process ended (a zombie no one has reaped yet counts as ended)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        return True


def _wait_for(path: Path, proc=None) -> int:
    """The PID a stand-in program wrote to ``path`` once started."""
    for _ in range(400):
        if path.exists() and path.read_text():
            return int(path.read_text())
        if proc is not None and proc.poll() is not None:
            raise AssertionError(f"the driver ended first: {proc.communicate()}")
        time.sleep(0.05)
    raise AssertionError(f"{path} was never written")


def _orphan(folder, root, timeout) -> int:
    """A hanging program whose driver was killed (SIGKILL): its PID."""
    (folder / "hang").write_text("")
    env = {**os.environ, "PYTHONPATH": SRC}
    driver = subprocess.Popen([sys.executable, "driver.py", str(root), str(timeout)], cwd=folder,
                              env=env)
    pid = _wait_for(folder / "started.ev3", driver)
    driver.kill()
    driver.wait()
    assert not _gone(pid)
    return pid


def _oracle(root, timeout):
    return CommandOracle([sys.executable, "cfd.py", "{id}", "{lf}", "{result}"], root=root,
                         timeout=timeout)


def test_a_resumed_run_ends_an_orphan_past_its_own_time_out_and_runs_the_event_again(folder):
    pid = _orphan(folder, folder / "runs", timeout=1.5)
    (folder / "hang").unlink()  # the event's program would now finish: it runs again, once
    os.rename(folder / "started.ev3", folder / "started.orphan")
    # the orphan hangs on: its own time-out (1.5 s from its start) passes, it is ended
    with pytest.warns(RuntimeWarning, match=f"ended its HF program .*PID {pid}"):
        assert _oracle(folder / "runs", timeout=1.5)(EV) == 5.0
    assert _gone(pid)
    assert (folder / "started.ev3").exists()  # run again


def test_a_lock_held_on_another_host_is_named_not_taken(folder):
    from pas.study import hf_programs

    holder = folder / "holder.py"
    holder.write_text(
        "import os, sys, time, fcntl\n"
        "from pas.study import hf_programs\n"
        "fd = os.open(sys.argv[1], os.O_RDWR | os.O_CREAT)\n"
        "fcntl.flock(fd, fcntl.LOCK_EX)\n"
        "rec = hf_programs.holder(4242, event='ev3', timeout=0.5)\n"
        "hf_programs.write_holder(fd, {**rec, 'host': 'node17', 'started': rec['started'] - 60})\n"
        "print('locked', flush=True)\n"
        "time.sleep(30)\n")
    (folder / "runs" / "ev3").mkdir(parents=True)
    proc = subprocess.Popen([sys.executable, str(holder), str(folder / "runs" / "ev3" / ".lock")],
                            env={**os.environ, "PYTHONPATH": SRC}, stdout=subprocess.PIPE,
                            text=True)
    try:
        assert proc.stdout.readline().strip() == "locked"
        assert [r["host"] for r in hf_programs.running(str(folder / "runs"))] == ["node17"]
        with pytest.raises(OracleError, match="host node17, which cannot be checked from here"):
            _oracle(folder / "runs", timeout=0.5)(EV)
    finally:
        proc.kill()
        proc.wait()
    assert _oracle(folder / "runs", timeout=5)(EV) == 5.0  # a free lock is taken over


def test_pas_study_lists_and_stops_a_running_program(folder, capsys):
    out = folder / "out"
    out.mkdir()
    StudyStore(out / "study.sqlite").close()  # as 'pas run --out out' makes it
    pid = _orphan(folder, out / "hf-runs", timeout=600)
    assert main(["study", "hf-programs", str(out)]) == 0
    listed = capsys.readouterr().out
    assert f"event ev3: PID {pid}" in listed and "time-out 600 s" in listed
    assert "an orphan" in listed  # its driver was killed
    assert main(["study", "hf-programs", str(out), "--json"]) == 0
    assert [r["pid"] for r in json.loads(capsys.readouterr().out)] == [pid]
    assert main(["study", "hf-stop", str(out), "ev3"]) == 0
    assert f"ended event ev3: PID {pid}" in capsys.readouterr().out
    assert _gone(pid)
    assert main(["study", "hf-programs", str(out)]) == 0
    assert "no HF program of this study runs now" in capsys.readouterr().out
    # its result is not taken: the event runs again
    (folder / "hang").unlink()
    assert _oracle(out / "hf-runs", timeout=5)(EV) == 5.0


def _lf_file(folder, n=600):
    lf = np.random.default_rng(3).rayleigh(2.0, n)
    pd.DataFrame({"id": [f"e{i}" for i in range(n)], "lf": lf}).to_csv(folder / "lf.csv",
                                                                        index=False)


def _run_args(script_args, max_hf):
    spec = f"command:{sys.executable} {script_args}"
    return ["run", "lf.csv", "--oracle", spec, "--n-waves", "600", "--p-exp", "1e-2", "--eps1",
            "1e-4", "--seed", "2", "--max-hf", str(max_hf), "--out", "out", "--preset", "paper",
            "--quiet"]


@pytest.mark.slow
def test_ctrl_c_ends_the_programs_of_the_run_and_says_which(folder):
    _lf_file(folder)
    (folder / "hang").write_text("")
    argv = [sys.executable, "-m", "pas"] + _run_args("cfd.py {id} {lf} {result}", 4)
    proc = subprocess.Popen(argv, cwd=folder, text=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, preexec_fn=sigint_as_in_a_shell,
                            env={**os.environ, "PYTHONPATH": SRC, "MPLBACKEND": "Agg"})
    started = None
    for _ in range(600):
        started = next(iter(folder.glob("started.*")), None)
        if started is not None and started.read_text() or proc.poll() is not None:
            break
        time.sleep(0.05)
    assert proc.poll() is None, proc.communicate()
    pid, event = int(started.read_text()), started.suffix[1:]
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert f"ended the HF program(s) still running: event {event}: PID {pid}" in err
    assert "their events run again on resume" in err
    assert _gone(pid)


def test_a_changed_command_is_said_once_on_resume_and_recorded(folder, capsys):
    _lf_file(folder)
    assert main(_run_args("cfd.py {id} {lf} {result}", 4)) == 0
    capsys.readouterr()
    # an extra argument the script ignores: the same results, another command
    assert main(_run_args("cfd.py {id} {lf} {result} --mesh=fine", 5)) == 0
    err = capsys.readouterr().err
    old = [sys.executable, "cfd.py", "{id}", "{lf}", "{result}"]
    new = old + ["--mesh=fine"]
    lines = [line for line in err.splitlines() if "HF command changed" in line]
    assert lines == [f"pas run: the HF command changed on resuming: it was {old}, now {new} "
                     "(recorded in the study store; events already run keep their results)"]
    assert main(_run_args("cfd.py {id} {lf} {result} --mesh=fine", 6)) == 0
    assert "HF command changed" not in capsys.readouterr().err  # said once
    with StudyStore(folder / "out" / "study.sqlite", create=False) as store:
        changes = store.get("oracle_command_changes")
        assert store.get("oracle_command") == new
    assert [(c["old"], c["new"]) for c in changes] == [(old, new)]


def test_a_missing_relative_script_is_reported_where_it_was_looked_for(tmp_path):
    start = tmp_path / "campaign"
    start.mkdir()
    oracle = CommandOracle([sys.executable, "../hf/cfd_gww.py", "{result}"], root="hf-runs",
                           cwd=start)
    with pytest.raises(OracleError) as err:
        oracle(EV)
    assert f"looked for {tmp_path / 'hf' / 'cfd_gww.py'}" in str(err.value)
    assert f"against {start}, the folder the study was started from" in str(err.value)


def test_on_interrupt_takes_end_or_leave(tmp_path):
    from pas.study.oracle_spec import oracle_from_spec

    spec = {"command": ["prog", "{result}"], "root": "runs", "cwd": str(tmp_path)}
    assert oracle_from_spec(spec).on_interrupt == "end"
    assert oracle_from_spec({**spec, "on_interrupt": "leave"}).on_interrupt == "leave"
    with pytest.raises(ValueError, match="on_interrupt must be 'end' or 'leave', got 'keep'"):
        oracle_from_spec({**spec, "on_interrupt": "keep"})
