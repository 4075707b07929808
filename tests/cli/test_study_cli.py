"""``pas study create/ask/tell/status``: a campaign, concurrent tells and one-line errors."""

import json
import multiprocessing as mp

import numpy as np
import pandas as pd
import pytest

from pas.cli import main
from pas.study.store import StudyStore

N = 2000

TOML = """
n_waves = 2000
p_exp = 0.01
eps1 = 0.01
seed = 3
{extra}
[lf]
file = "peaks.csv"
column = "lf"
id_column = "event"
meta_columns = ["seed", "t_start"]

[settings]
n_bootstrap = 0
"""


def write_case(folder, extra="max_hf = 30", toml=None):
    rng = np.random.default_rng(0)
    pd.DataFrame({"event": [f"e{i}" for i in range(N)], "lf": rng.rayleigh(1.0, N),
                  "seed": np.arange(N) % 50, "t_start": np.arange(N) * 20.0}
                 ).to_csv(folder / "peaks.csv", index=False)
    (folder / "study.toml").write_text(toml if toml is not None else TOML.format(extra=extra))
    return str(folder / "study.toml")


def cli(*argv):
    try:
        return main(list(argv))
    except SystemExit as exc:  # argparse usage errors
        return exc.code


def hf_of(lf):
    return 1.2 * np.asarray(lf) ** 1.1


@pytest.mark.slow
def test_campaign_through_the_cli(tmp_path, capsys):
    cfg = write_case(tmp_path)
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    for _ in range(4):
        assert (
            cli("study", "ask", db, "-n", "3", "--format", "csv", "-o", str(tmp_path / "a.csv"))
            == 0
        )
        asked = pd.read_csv(tmp_path / "a.csv")
        assert list(asked.columns) == ["id", "index", "lf", "d", "seed", "t_start"]
        np.testing.assert_array_equal(asked["t_start"], asked["index"] * 20.0)
        asked["hf"] = hf_of(asked["lf"])
        asked.loc[asked.index[-1], "error"] = "mesh failure" if _ == 1 else None
        asked[["id", "hf", "error"]].to_csv(tmp_path / "r.csv", index=False)
        assert cli("study", "tell", db, "--csv", str(tmp_path / "r.csv")) == 0
    capsys.readouterr()
    assert cli("study", "ask", db, "--format", "json") == 0
    (nxt,) = json.loads(capsys.readouterr().out)
    assert set(nxt) == {"id", "index", "lf", "d", "seed", "t_start"}
    assert cli("study", "tell", db, nxt["id"], repr(float(hf_of(nxt["lf"])))) == 0
    capsys.readouterr()
    assert cli("study", "status", db, "--json") == 0
    status = json.loads(capsys.readouterr().out)
    assert (status["n_hf"], status["n_failed"], status["n_pending"]) == (13, 1, 0)
    assert status["n_evaluated"] == 14 and status["n_loads"] + status["n_no_impact"] == 13
    assert status["mpm"] > 0 and status["results_not_yet_used"] == 1
    assert cli("study", "status", db) == 0
    text = capsys.readouterr().out
    assert "MPM so far" in text and "14 evaluated: " in text
    assert "1 failed (left out of the fit)" in text
    with StudyStore(db, create=False) as store:
        ev = store.events()
        assert (ev["source"] == "cli").all() and (ev["attempts"] == 1).all()
        assert (ev["state"] == "failed").sum() == 1


def _tell_many(db, items):
    for key, value in items:
        assert main(["study", "tell", db, key, repr(value)]) == 0


@pytest.mark.slow
def test_eight_processes_tell_200_results(tmp_path, capsys):
    cfg = write_case(tmp_path, extra="max_hf = 400")  # above the default budget of 160
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    assert (
        cli("study", "ask", db, "-n", "200", "--format", "csv", "-o", str(tmp_path / "a.csv")) == 0
    )
    asked = pd.read_csv(tmp_path / "a.csv")
    assert len(asked) == 200
    items = list(zip(asked["id"], hf_of(asked["lf"]).tolist()))
    ctx = mp.get_context("forkserver")
    ctx.set_forkserver_preload(["pas", "pas.cli.study"])
    procs = [ctx.Process(target=_tell_many, args=(db, items[i::8])) for i in range(8)]
    for p in procs:
        p.start()
    for p in procs:
        p.join()
    assert [p.exitcode for p in procs] == [0] * 8
    with StudyStore(db, create=False) as store:
        ev = store.events().set_index("key")
    assert len(ev) == 200 and (ev["state"] == "done").all()
    assert ev["result_seq"].is_unique
    np.testing.assert_array_equal(ev.loc[asked["id"], "hf"], hf_of(asked["lf"]))


BAD_TOML = [
    ("n_waves", TOML.format(extra="").replace("n_waves = 2000", "")),
    ("n_waves", TOML.format(extra="").replace("n_waves = 2000", 'n_waves = "many"')),
    ("p_exp", TOML.format(extra="").replace("p_exp = 0.01", "p_exp = 2.0")),
    ("eps1", TOML.format(extra="").replace("eps1 = 0.01", "eps1 = -1")),
    ("strategy", TOML.format(extra='strategy = "gpr"')),
    ("max_hf", TOML.format(extra="max_hf = 2.5")),
    ("colour", TOML.format(extra='colour = "red"')),
    ("lf.file", TOML.format(extra="").replace('file = "peaks.csv"', "")),
    ("lf.meta_columns", TOML.format(extra="").replace('["seed", "t_start"]', '"seed"')),
    (
        "lf.column: column 'height'",
        TOML.format(extra="").replace('column = "lf"', 'column = "height"'),
    ),
    ("z", TOML.format(extra="").replace("n_bootstrap = 0", "z = 1")),
    ("'lf'", "NAN_IN_LF"),
    ("oracle.timeout", TOML.format(extra="") + '[oracle]\ncommand = ["x"]\ntimeout = "long"\n'),
    ("oracle.command", TOML.format(extra="") + '[oracle]\nroot = "r"\n'),
    ("unknown placeholder {sede}", TOML.format(extra="") + '[oracle]\ncommand = ["x", "{sede}"]\n'),
    ("oracle: id_column: column 'id'", TOML.format(extra="") + '[oracle]\ntable = "peaks.csv"\n'),
    ("batch_size", TOML.format(extra="batch_size = 0")),
    ("max_hf must be an integer ≥ 4", TOML.format(extra="max_hf = 2")),  # the file's key
]


@pytest.mark.parametrize("argv,field", [
    (["study", "create", "{db}", "--config", "{cfg}", "BAD:" + str(i)], f)
    for i, (f, _) in enumerate(BAD_TOML)] + [
    (["study", "ask", "{db}", "-n", "0"], "-n"),
    (["study", "ask", "{db}", "--format", "xml"], "--format"),
    (["study", "ask"], "STUDY.db"),
    (["study", "ask", "{dir}/missing.db"], "missing.db"),
    (["study", "tell", "{db}", "e764", "abc"], "VALUE"),
    (["study", "tell", "{db}", "e764", "-3"], "VALUE"),
    (["study", "tell", "{db}", "e764"], "VALUE"),
    (["study", "tell", "{db}"], "EVENT"),
    (["study", "tell", "{db}", "e5", "1.0"], "e5"),
    (["study", "tell", "{db}", "--csv", "{dir}/nocol.csv"], "'hf'"),
    (["study", "tell", "{db}", "--csv", "{dir}/nan.csv"], "'hf'"),
    (["study", "create", "{db}", "--config", "{cfg}"], "already exists"),
    (["study", "status", "{db}", "--colour"], "--colour"),
    (["study", "run", "{db}"], "no oracle"),
])
def test_bad_inputs_exit_2_naming_the_field(tmp_path, capsys, argv, field):
    cfg = write_case(tmp_path)
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    assert cli("study", "ask", db, "-n", "1") == 0
    pd.DataFrame({"id": ["e764"], "load": [1.0]}).to_csv(tmp_path / "nocol.csv", index=False)
    pd.DataFrame({"id": ["e764", "e914"], "hf": [1.0, None]}).to_csv(tmp_path / "nan.csv",
                                                                        index=False)
    if argv[-1].startswith("BAD:"):
        text = BAD_TOML[int(argv[-1][4:])][1]
        if text == "NAN_IN_LF":
            text = TOML.format(extra="")
            peaks = pd.read_csv(tmp_path / "peaks.csv")
            peaks.loc[17, "lf"] = np.nan
            peaks.to_csv(tmp_path / "peaks.csv", index=False)
        (tmp_path / "bad.toml").write_text(text)
        argv = argv[:-1]
        argv[2], argv[4] = str(tmp_path / "new.db"), str(tmp_path / "bad.toml")
    argv = [a.format(db=db, cfg=cfg, dir=tmp_path) for a in argv]
    capsys.readouterr()
    assert cli(*argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert field in err[-1], err
    assert err[-1].startswith("pas") and ": error: " in err[-1]
    assert not (tmp_path / "new.db").exists()


@pytest.mark.slow
def test_study_run_with_command_oracle_survives_sigkill(tmp_path, capsys):
    """``python -m pas study run`` killed once, then continued: nothing lost or re-run."""
    import os
    import signal
    import subprocess
    import sys
    from collections import Counter
    from pathlib import Path

    import _campaign

    import pas

    script = _campaign.write_script(tmp_path)
    log = tmp_path / "hf.log"
    oracle = (f'[oracle]\ncommand = ["{sys.executable}", "{script}", "{{id}}", "{{index}}", '
              f'"{{lf}}", "{{result}}", "{log}"]\nroot = "runs"\ntimeout = 60\n')
    cfg = write_case(tmp_path, extra="max_hf = 14\nbatch_size = 2")
    Path(cfg).write_text(Path(cfg).read_text() + oracle)
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(Path(pas.__file__).parents[1]), os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.Popen([sys.executable, "-m", "pas", "study", "run", db],
                            stdout=subprocess.PIPE, env=env)
    proc.stdout.readline()  # the first HF result is in
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    proc.stdout.close()
    capsys.readouterr()
    assert cli("study", "run", db) == 0
    assert "14 evaluated: " in capsys.readouterr().out
    with StudyStore(db, create=False) as store:
        ev = store.events()
    done = Counter(log.read_text().split())
    assert len(ev) == 14 and set(ev["state"]) == {"done"} and max(done.values()) == 1
    assert set(done) == set(ev["key"])
    np.testing.assert_array_equal(ev["hf"], _campaign.oracle_value(ev["lf"], ev["idx"]))


def _answer_all(db, tmp_path):
    """Ask until the study has nothing to ask, telling the HF value of every event."""
    for _ in range(60):
        assert cli("study", "ask", db, "-n", "2", "--format", "csv",
                   "-o", str(tmp_path / "a.csv")) == 0
        if not (tmp_path / "a.csv").exists():
            return
        asked = pd.read_csv(tmp_path / "a.csv")
        (tmp_path / "a.csv").unlink()
        asked.assign(hf=hf_of(asked["lf"]))[["id", "hf"]].to_csv(tmp_path / "r.csv", index=False)
        assert cli("study", "tell", db, "--csv", str(tmp_path / "r.csv")) == 0
    pytest.fail("the study did not finish")


@pytest.mark.slow
def test_status_does_not_claim_convergence_beside_results_it_has_not_used(tmp_path, capsys):
    cfg = write_case(tmp_path, toml=TOML.format(extra="max_hf = 40").replace(
        "eps1 = 0.01", "eps1 = 0.05"))
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    assert (
        cli("study", "ask", db, "-n", "30", "--format", "csv", "-o", str(tmp_path / "a.csv")) == 0
    )
    asked = pd.read_csv(tmp_path / "a.csv")
    asked.assign(hf=hf_of(asked["lf"]))[["id", "hf"]].to_csv(tmp_path / "r.csv", index=False)
    assert cli("study", "tell", db, "--csv", str(tmp_path / "r.csv")) == 0
    capsys.readouterr()
    assert cli("study", "status", db, "--json") == 0
    status = json.loads(capsys.readouterr().out)
    assert status["results_not_yet_used"] == 30 and status["converged"] is None
    assert status["converged_with_waiting"] is True  # the 30 results would converge it
    assert status["mpm"] > 0 and status["finished"] is None
    assert cli("study", "status", db) == 0
    text = capsys.readouterr().out
    assert "30 result(s) told since the last ask" in text
    assert ("undecided until the study uses the waiting results (with them it would be "
            "converged)") in text
    assert "converged (at" not in text
    # once an ask has used them, the verdict is the study's own
    assert cli("study", "ask", db) == 0
    capsys.readouterr()
    assert cli("study", "status", db, "--json") == 0
    status = json.loads(capsys.readouterr().out)
    assert status["results_not_yet_used"] == 0 and status["converged"] is True
    assert status["converged_at_n_hf"] <= 30


@pytest.mark.slow
def test_set_tightens_eps1_and_grows_the_budget_of_a_converged_study(tmp_path, capsys):
    cfg = write_case(tmp_path, toml=TOML.format(extra="max_hf = 40").replace(
        "eps1 = 0.01", "eps1 = 0.05"))
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    _answer_all(db, tmp_path)
    capsys.readouterr()
    assert cli("study", "status", db, "--json") == 0
    before = json.loads(capsys.readouterr().out)
    assert before["converged"] and before["n_hf"] < 40
    assert cli("study", "set", db, "--eps1", "0.001", "--max-hf", "45") == 0
    out = capsys.readouterr().out
    assert f"{db}: eps1 0.05 -> 0.001" in out and f"{db}: max_hf 40 -> 45" in out
    assert "not finished" in out
    assert cli("study", "ask", db, "--format", "json") == 0
    assert len(json.loads(capsys.readouterr().out)) == 1  # asking again
    assert cli("study", "status", db) == 0
    text = capsys.readouterr().out
    assert "setting changed: eps1 0.05 -> 0.001" in text and "limit eps1 0.001" in text
    with StudyStore(db, create=False) as store:
        before = store.settings()
    # settings that decide what is asked cannot change; bad values are named
    for argv, needle in ((["--eps1", "-1"], "--eps1"), (["--max-hf", "2"], "--max-hf"),
                         (["--max-hf", "-3"], "--max-hf must be a positive integer"),
                         (["--k1", "-3"], "--k1"), ([], "--eps1")):
        assert cli("study", "set", db, *argv) == 2
        assert needle in capsys.readouterr().err
    with StudyStore(db, create=False) as store:  # a refused value is not recorded
        kept = store.settings()
    assert kept == before and (kept["eps1"], kept["max_hf"]) == (0.001, 45)


def test_the_documented_study_file_creates_a_study(tmp_path, capsys):
    """The complete example of docs/guide/study-file.md is a valid study file."""
    from pathlib import Path

    page = Path(__file__).parents[2] / "docs" / "guide" / "study-file.md"
    doc = page.read_text(encoding="utf-8")
    toml = doc.split("```toml\n", 1)[1].split("```", 1)[0]
    rng = np.random.default_rng(0)
    n = 16000
    pd.DataFrame({"event": [f"s{i % 50:02d}-w{i}" for i in range(n)],
                  "rwe": rng.rayleigh(6.0, n), "seed": np.arange(n) % 50,
                  "t_start": np.arange(n) * 6.0, "t_end": np.arange(n) * 6.0 + 20.0}
                 ).to_csv(tmp_path / "peaks.csv", index=False)
    (tmp_path / "study.toml").write_text(toml)
    db = str(tmp_path / "campaign.db")
    assert cli("study", "create", db, "--config", str(tmp_path / "study.toml")) == 0
    with StudyStore(db, create=False) as store:
        s = store.settings()
        assert store.get("oracle")["command"][:2] == ["python", "cfd_event.py"]
        assert store.get("batch_size") == 2
    assert (s["eps1"], s["threshold"], s["max_hf"], s["strategy_settings"]["z"]) == (
        20.0,
        12.0,
        60,
        10,
    )


def test_status_names_failed_events_and_ask_prints_what_it_asks_after_a_retry(tmp_path, capsys):
    """A new user's reproduction: after 'pas study retry', 'ask -n 2' printed no event (the
    events asked again had kept results) and status said '1 failed' without naming it."""
    cfg = write_case(tmp_path)
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0

    def ask(n):
        capsys.readouterr()
        assert cli("study", "ask", db, "-n", str(n), "--format", "json") == 0
        out, err = capsys.readouterr()
        return (json.loads(out) if out.strip() else []), err

    first, _ = ask(4)
    for i, ev in enumerate(first):
        value = ["--error", "mesh file missing"] if i == 1 else [str(hf_of(ev["lf"]))]
        assert cli("study", "tell", db, str(ev["id"]), *value) == 0
    for _ in range(2):
        for ev in ask(2)[0]:
            assert cli("study", "tell", db, str(ev["id"]), str(hf_of(ev["lf"]))) == 0
    capsys.readouterr()
    assert cli("study", "status", db) == 0
    text = capsys.readouterr().out
    assert (f"failed: {first[1]['id']} (mesh file missing) - left out of the fit; "
            f"'pas study retry {db}' asks them again") in text
    assert cli("study", "retry", db) == 0
    capsys.readouterr()
    assert cli("study", "status", db) == 0
    text = capsys.readouterr().out
    assert "failed:" not in text and "counted above, too few for a model yet" in text
    again, err = ask(2)
    assert len(again) == 2 and "took their kept result" in err
    assert not {ev["id"] for ev in again} & {ev["id"] for ev in first}


def test_ask_output_takes_its_format_from_the_file_name(tmp_path, capsys):
    """'ask -o n2.csv' wrote a fixed-width table into a .csv file."""
    cfg = write_case(tmp_path)
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", cfg) == 0
    assert cli("study", "ask", db, "-n", "2", "-o", str(tmp_path / "n2.csv")) == 0
    asked = pd.read_csv(tmp_path / "n2.csv")
    assert list(asked.columns[:3]) == ["id", "index", "lf"] and len(asked) >= 2  # initial: 4
    assert cli("study", "ask", db, "-n", "1", "-o", str(tmp_path / "n1.json")) == 0
    assert len(json.loads((tmp_path / "n1.json").read_text())) == 1
    assert cli("study", "ask", db, "-n", "1", "-o", str(tmp_path / "n1.txt")) == 0
    assert (tmp_path / "n1.txt").read_text().split()[:3] == ["id", "index", "lf"]


@pytest.mark.parametrize("action", ["create", "ask", "tell", "run", "status", "set", "retry",
                                    "refit", "backup"])
def test_every_study_action_help_says_what_it_does(action, capsys):
    with pytest.raises(SystemExit):
        main(["study", action, "--help"])
    lines = capsys.readouterr().out.splitlines()
    text = lines[lines.index("", 1) + 1]  # the paragraph after the usage lines
    assert text[0].isupper() and len(text.split()) >= 4 and not text.startswith("positional")


def test_a_study_file_takes_fit_check_at_the_top_as_its_page_lists_it(tmp_path, capsys):
    toml = write_case(tmp_path, extra='precision = "10%"\nfit_check = 0.05')
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", toml) == 0
    with StudyStore(db) as store:
        settings = store.settings()
    assert (settings["precision"], settings["fit_check"]) == (0.1, 0.05)


def test_status_of_a_pas_run_folder_reads_its_study_sqlite(tmp_path, capsys):
    cfg = write_case(tmp_path)
    out = tmp_path / "out"  # as 'pas run --out out' names its store
    out.mkdir()
    db = str(out / "study.sqlite")
    assert cli("study", "create", db, "--config", cfg) == 0
    capsys.readouterr()
    assert cli("study", "status", db, "--json") == 0
    by_file = json.loads(capsys.readouterr().out)
    assert cli("study", "status", str(out), "--json") == 0
    assert json.loads(capsys.readouterr().out) == by_file
    assert by_file["study"] == db
    assert cli("study", "status", str(tmp_path)) == 2  # a folder without one
    assert capsys.readouterr().err == (f"pas study: error: STUDY: {tmp_path} is a folder with no "
                                       "study.sqlite in it (give a study store, or the --out "
                                       "folder of pas run)\n")
