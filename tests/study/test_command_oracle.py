"""Command oracles run from where the campaign was started; oracles are checked callable first.

A command's relative program or script (``python cfd_event.py``) means a file
in the directory the study was started from, not in the event's run folder
``root/<id>/``: in Python (``cwd=``, pickled to workers), in
``pas run`` (recorded in its store, so a resume from another folder runs the
same script) and in ``pas study create`` (the TOML file's folder).
"""

import os
import pickle
import re
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pandas as pd
import pytest

import pas
from pas.cli import main
from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle, resolve_paths
from pas.study.oracle_spec import START_DIR_KEY, oracle_from_spec
from pas.study.store import StudyStore

EV = Event(index=3, id="ev3", lf=2.5, d=0.01, meta={"seed": 11})

# HF = 2 * LF, times a factor read from a data file next to the script, located by {cwd}
SCRIPT = """\
import sys
lf, factor_file, out = float(sys.argv[1]), sys.argv[2], sys.argv[3]
factor = float(open(factor_file).read())
open(out, "w").write(repr(2.0 * lf * factor))
"""


@pytest.fixture
def campaign(tmp_path, monkeypatch):
    """A start folder with the script and its data, and another folder to stand in."""
    start = tmp_path / "campaign"
    start.mkdir()
    (start / "cfd.py").write_text(SCRIPT)
    (start / "factor.txt").write_text("1.5")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(start)
    return start, elsewhere


def test_resolve_paths_rule(tmp_path):
    (tmp_path / "cfd.py").write_text("")
    (tmp_path / "run.sh").write_text("")
    (tmp_path / "mesh").mkdir()
    args = ["python", "cfd.py", "--mesh", "mesh", "--out", "{result}", "missing.py", ".",
            "-v", "/abs/tool", "{cwd}/factor.txt"]
    expected = ["python", str(tmp_path / "cfd.py"), "--mesh", str(tmp_path / "mesh"), "--out",
                "{result}", "missing.py", ".", "-v", "/abs/tool", "{cwd}/factor.txt"]
    assert resolve_paths(args, str(tmp_path)) == expected
    # the program: resolved when it has a separator (existing or not) or is a file there
    assert resolve_paths(["./run.sh", "x"], str(tmp_path))[0] == str(tmp_path / "run.sh")
    assert resolve_paths(["bin/solver"], str(tmp_path)) == [str(tmp_path / "bin" / "solver")]
    assert resolve_paths(["run.sh"], str(tmp_path)) == [str(tmp_path / "run.sh")]
    assert resolve_paths(["solver"], str(tmp_path)) == ["solver"]  # left to the PATH


def test_relative_script_runs_from_the_start_folder(campaign):
    start, _ = campaign
    oracle = CommandOracle([sys.executable, "cfd.py", "{lf}", "{cwd}/factor.txt", "{result}"],
                           root="runs")
    assert oracle.cwd == str(start) and oracle.root == str(start / "runs")
    assert oracle(EV) == pytest.approx(2.0 * 2.5 * 1.5, rel=1e-12)
    assert (start / "runs" / "ev3" / "result.txt").exists()  # the run folder is root/<id>/


def test_pickled_oracle_runs_the_same_files_from_another_folder(campaign, monkeypatch):
    start, elsewhere = campaign
    oracle = CommandOracle([sys.executable, "cfd.py", "{lf}", "{cwd}/factor.txt", "{result}"],
                           root="runs", reuse=False)
    monkeypatch.chdir(elsewhere)  # a Dask worker or a resumed session standing elsewhere
    moved = pickle.loads(pickle.dumps(oracle))
    assert moved(EV) == pytest.approx(7.5, rel=1e-12)
    assert not (elsewhere / "runs").exists()


def test_spec_cwd_wins_over_the_current_folder(campaign, monkeypatch):
    start, elsewhere = campaign
    monkeypatch.chdir(elsewhere)
    spec = {"command": [sys.executable, "cfd.py", "{lf}", "{cwd}/factor.txt", "{result}"],
            "root": str(elsewhere / "runs"), "cwd": str(start)}
    oracle = oracle_from_spec(spec)
    assert oracle.args[1] == str(start / "cfd.py")
    assert oracle(EV) == pytest.approx(7.5, rel=1e-12)


def test_cwd_must_be_a_folder(tmp_path):
    with pytest.raises(ValueError, match="^cwd: .*not a directory"):
        CommandOracle(["solver"], root=tmp_path, cwd=tmp_path / "nope")


def _lf_file(folder, n=600):
    lf = np.random.default_rng(3).rayleigh(2.0, n)
    pd.DataFrame({"id": [f"e{i}" for i in range(n)], "lf": lf}).to_csv(folder / "lf.csv",
                                                                        index=False)


def _pas_run(capsys, lf_file, out, max_hf):
    spec = f"command:{sys.executable} cfd.py {{lf}} {{cwd}}/factor.txt {{result}}"
    code = main(["run", str(lf_file), "--oracle", spec, "--n-waves", "600", "--p-exp", "1e-2",
                 "--eps1", "1e-4", "--seed", "2", "--max-hf", str(max_hf), "--out", str(out),
                 "--preset", "paper", "--quiet"])  # paper: no bootstrap refits, a fast test
    return code, *capsys.readouterr()


def test_pas_run_resumed_from_another_folder_runs_the_first_runs_script(campaign, monkeypatch,
                                                                        capsys):
    start, elsewhere = campaign
    _lf_file(start)
    code, _, err = _pas_run(capsys, "lf.csv", "out", 5)
    assert code == 0, err
    assert StudyStore(start / "out" / "study.sqlite", create=False).get(START_DIR_KEY) == str(start)
    monkeypatch.chdir(elsewhere)  # no cfd.py here
    code, _, err = _pas_run(capsys, start / "lf.csv", start / "out", 8)
    assert code == 0, err
    assert f"resolve against {start}, where the study was started" in err
    hist = pd.read_csv(start / "out" / "history.csv")
    assert len(hist) == 8 and (hist["status"] == "true_positive").all()
    np.testing.assert_allclose(hist["hf"], 3.0 * hist["lf"], rtol=1e-12)
    assert not (elsewhere / "out").exists()


def test_study_file_command_runs_next_to_the_toml(campaign, monkeypatch, capsys):
    start, elsewhere = campaign
    _lf_file(start)
    (start / "study.toml").write_text(
        "n_waves = 600\np_exp = 1e-2\neps1 = 1e-4\nseed = 2\nmax_hf = 5\n"
        "[settings]\nn_bootstrap = 0\n"
        "[lf]\nfile = \"lf.csv\"\ncolumn = \"lf\"\nid_column = \"id\"\n"
        "[oracle]\ncommand = [" + ", ".join(
            f'"{a}"' for a in (sys.executable, "cfd.py", "{lf}", "{cwd}/factor.txt", "{result}"))
        + "]\n")
    db = elsewhere / "campaign.db"
    monkeypatch.chdir(elsewhere)
    assert main(["study", "create", str(db), "--config", str(start / "study.toml")]) == 0
    code = main(["study", "run", str(db), "--quiet"])
    err = capsys.readouterr().err
    assert code == 0, err
    with StudyStore(db, create=False) as store:
        rows = store.events()
    assert len(rows) == 5 and (rows["state"] == "done").all()
    np.testing.assert_allclose(rows["hf"], 3.0 * rows["lf"], rtol=1e-12)


NOT_CALLABLE = [42, "cfd_event.py", ["python", "cfd.py"]]


@pytest.mark.parametrize("oracle", NOT_CALLABLE)
@pytest.mark.parametrize("run", [pas.run_pas, pas.run_as])
def test_run_functions_refuse_a_non_callable_oracle_before_any_store(tmp_path, run, oracle):
    lf = np.random.default_rng(0).rayleigh(2.0, 300)
    with pytest.raises(TypeError, match="^oracle must be a callable") as info:
        run(lf, oracle, n_waves=300, p_exp=1e-2, eps1=0.05, study=tmp_path / "s.db")
    assert "\n" not in str(info.value)
    assert not (tmp_path / "s.db").exists()


@pytest.mark.parametrize("executor", [None, "threads"])
def test_study_optimize_refuses_a_non_callable_oracle_before_the_first_call(executor):
    lf = np.random.default_rng(0).rayleigh(2.0, 300)
    study = pas.make_study(pas.PAS, lf, n_waves=300, p_exp=1e-2, eps1=0.05, seed=0)
    pool = ThreadPoolExecutor(1) if executor else None  # an executor as Dask's get_executor()
    try:
        with pytest.raises(TypeError, match="^oracle must be a callable.*got int 7$"):
            study.optimize(7, executor=pool)
    finally:
        if pool is not None:
            pool.shutdown()
    assert study.rows == [] and study.pending == []


def test_command_placeholder_cwd_is_the_start_folder(tmp_path):
    oracle = CommandOracle(["tool", "{cwd}", "{workdir}"], root="r", cwd=tmp_path)
    assert oracle.command(EV, "/w") == ["tool", str(tmp_path), "/w"]
    assert os.path.isabs(oracle.root) and oracle.root == str(tmp_path / "r")


KNOWN = "{id}, {index}, {lf}, {d}, {workdir}, {cwd}, {result}, {seed}"


@pytest.mark.parametrize("placeholder, message", [
    ("{idd}", re.escape(f"command: unknown placeholder {{idd}} (known: {KNOWN})")),
    ("{seed[0]}", r"args: a placeholder indexes .* not \{seed\[0\]\}"),
])
def test_a_placeholder_no_event_fills_is_refused_before_any_event(tmp_path, placeholder,
                                                                  message):
    lf = np.random.default_rng(0).rayleigh(2.0, 300)
    table = pd.DataFrame({"lf": lf, "seed": np.arange(300)})
    study = pas.make_study(pas.PAS, table, n_waves=300, p_exp=1e-2, eps1=0.05, seed=0)
    (tmp_path / "cfd.py").write_text(SCRIPT)
    oracle = CommandOracle([sys.executable, "cfd.py", placeholder, "{result}"], root="runs",
                           cwd=tmp_path)
    with pytest.raises(ValueError, match=f"^{message}$"):
        study.optimize(oracle)
    assert study.rows == [] and not (tmp_path / "runs").exists()


def test_pas_run_refuses_an_unknown_placeholder_before_its_folder(campaign, capsys):
    start, _ = campaign
    _lf_file(start)
    pd.read_csv(start / "lf.csv").assign(seed=1).to_csv(start / "lf.csv", index=False)
    code = main(["run", "lf.csv", "--meta-columns", "seed", "--oracle",
                 f"command:{sys.executable} cfd.py {{lf}} {{idd}} {{result}}", "--n-waves",
                 "600", "--p-exp", "1e-2", "--eps1", "1e-4", "--seed", "2", "--out", "out"])
    err = capsys.readouterr().err
    assert code == 2
    assert err == f"pas run: error: command: unknown placeholder {{idd}} (known: {KNOWN})\n"
    assert not (start / "out").exists()


def test_run_long_term_refuses_an_unknown_placeholder_before_any_event(tmp_path):
    import _longterm_problem as problem

    oracle = CommandOracle(["solver", "{sea_state}", "{lf}", "{sede}"], root="runs", cwd=tmp_path)
    with pytest.raises(ValueError, match=r"^command: unknown placeholder \{sede\} \(known: "
                                         r"\{id\}, .*\{sea_state\}\)$"):
        pas.run_long_term(problem.table(), problem.lf_peaks(0), oracle, p_exceed=1e-4,
                          study=tmp_path / "lt.sqlite")
    assert not (tmp_path / "runs").exists()


def test_a_missing_interpreter_script_is_refused_before_any_event(tmp_path):
    lf = np.random.default_rng(0).rayleigh(2.0, 300)
    study = pas.make_study(pas.PAS, lf, n_waves=300, p_exp=1e-2, eps1=0.05, seed=0)
    (tmp_path / "hf.py").write_text(SCRIPT)
    oracle = CommandOracle([sys.executable, "hff.py", "{lf}", "{result}"], root="runs",
                           cwd=tmp_path)
    with pytest.raises(ValueError) as info:
        study.optimize(oracle)
    assert str(info.value) == (f"command: hff.py not found: looked for {tmp_path / 'hff.py'} "
                               f"(relative paths resolve against {tmp_path}, the folder the "
                               "study was started from)")
    assert study.rows == [] and not (tmp_path / "runs").exists()


@pytest.mark.parametrize("args", [
    ["python3", "hf.py", "{lf}"],               # there
    ["python3", "-u", "missing.py"],            # not clearly the script: an option first
    ["python3", "{cwd}/missing.py"],            # a placeholder: left to the event
    ["mpirun", "missing.py"],                   # not an interpreter this check knows
    ["bash", "-c", "missing.sh"],
    ["python3", "data.csv"],                    # no script
])
def test_the_up_front_check_leaves_commands_it_cannot_be_sure_of(tmp_path, args):
    (tmp_path / "hf.py").write_text(SCRIPT)
    CommandOracle(args, root="runs", cwd=tmp_path).check(EV)


def test_pas_run_refuses_a_missing_script_before_its_folder(campaign, capsys):
    start, _ = campaign
    _lf_file(start)
    code = main(["run", "lf.csv", "--oracle", "command:bash run.sh {lf} {result}", "--n-waves",
                 "600", "--p-exp", "1e-2", "--eps1", "1e-4", "--seed", "2", "--out", "out"])
    err = capsys.readouterr().err
    assert code == 2
    assert err == (f"pas run: error: command: run.sh not found: looked for {start / 'run.sh'} "
                   f"(relative paths resolve against {start}, the folder the study was "
                   "started from)\n")
    assert not (start / "out").exists()


def test_a_resumed_pas_run_refuses_a_missing_script_before_recording_it(campaign, capsys):
    start, _ = campaign
    _lf_file(start)
    code, _, err = _pas_run(capsys, "lf.csv", "out", 4)
    assert code == 0, err
    spec = f"command:{sys.executable} cfdd.py {{lf}} {{cwd}}/factor.txt {{result}}"
    code = main(["run", "lf.csv", "--oracle", spec, "--n-waves", "600", "--p-exp", "1e-2",
                 "--eps1", "1e-4", "--seed", "2", "--max-hf", "5", "--out", "out",
                 "--preset", "paper", "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "HF command changed" not in err
    assert err.splitlines()[-1] == (f"pas run: error: command: cfdd.py not found: looked for "
                                    f"{start / 'cfdd.py'} (relative paths resolve against "
                                    f"{start}, the folder the study was started from)")
    with StudyStore(start / "out" / "study.sqlite", create=False) as store:
        assert store.get("oracle_command") == [sys.executable, "cfd.py", "{lf}",
                                               "{cwd}/factor.txt", "{result}"]
        assert store.get("oracle_command_changes") is None
        assert store.settings()["max_hf"] == 4 and store.get("settings_changes") is None
