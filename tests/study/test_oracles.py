"""Table and command oracles: lookups, failures recorded with a message (never 0), pickling."""

import pickle
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd
import pytest

from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle, parse_result
from pas.study.oracles import OracleError, TableOracle, call_oracle

EV = Event(index=3, id="ev3", lf=2.5, d=0.01, meta={"seed": 11, "t_start": 120.0})

SCRIPT = r'''
import os, sys
mode, value, out = sys.argv[1], sys.argv[2], sys.argv[3]
with open("calls.log", "a") as f:
    f.write(" ".join(sys.argv[1:]) + "\n")
if mode == "fail":
    sys.stderr.write("solver diverged at t=12.5\n")
    sys.exit(3)
if mode == "partial":  # a running peak written, then the solver fails
    with open(out, "w") as f:
        f.write(value)
    sys.exit(3)
if mode == "sleep":
    import time; time.sleep(30)
if mode != "nofile":
    with open(out, "w") as f:
        f.write(value)
'''


@pytest.fixture
def script(tmp_path):
    path = tmp_path / "hf.py"
    path.write_text(SCRIPT)
    return str(path)


def command(script, root, mode, value="{lf}", **kw):
    return CommandOracle([sys.executable, script, mode, value, "{result}"], root=root, **kw)


def test_table_oracle_csv_and_parquet(tmp_path):
    df = pd.DataFrame({"event": ["ev1", "ev3", "ev4"], "hf": [1.0, 4.25, np.nan]})
    df.to_csv(tmp_path / "basin.csv", index=False)
    df.to_parquet(tmp_path / "basin.parquet")
    for name in ("basin.csv", "basin.parquet"):
        oracle = pickle.loads(pickle.dumps(TableOracle(tmp_path / name, id_column="event")))
        assert call_oracle(oracle, EV) == (4.25, None)
        value, err = call_oracle(oracle, Event(index=9, id="ev9", lf=1.0, d=0.5))
        assert value is None and "ev9 is not in" in err  # missing id is a failure, not 0
        value, err = call_oracle(oracle, Event(index=4, id="ev4", lf=1.0, d=0.5))
        assert value is None and "no valid value for event ev4" in err


def test_table_oracle_bad_tables(tmp_path):
    with pytest.raises(ValueError, match="value_column: column 'hf' is missing"):
        TableOracle(pd.DataFrame({"id": [1], "load": [2.0]}))
    with pytest.raises(ValueError, match="id: event id '1' appears more than once"):
        TableOracle(pd.DataFrame({"id": [1, 1], "hf": [2.0, 3.0]}))
    with pytest.raises(FileNotFoundError):
        TableOracle(tmp_path / "nope.csv")
    ints = TableOracle(pd.DataFrame({"id": [3], "hf": [0.0]}))
    assert call_oracle(ints, Event(index=3, id=3, lf=1.0, d=0.1)) == (0.0, None)


def test_command_oracle_runs_without_shell_in_event_folder(tmp_path, script):
    oracle = command(script, tmp_path / "runs", "ok", "{lf}")
    assert call_oracle(oracle, EV) == (2.5, None)
    folder = tmp_path / "runs" / "ev3"
    assert (folder / "result.txt").read_text() == "2.5"
    # shell metacharacters reach the program verbatim: there is no shell
    weird = command(script, tmp_path / "runs", "ok", "1.5; rm -rf / $(echo x) {seed}")
    value, err = call_oracle(weird, Event(index=5, id="a b/c", lf=1.0, d=0.1, meta={"seed": 4}))
    assert value is None and "not a number" in err
    calls = (tmp_path / "runs" / "a_b_c-5" / "calls.log").read_text()
    assert "1.5; rm -rf / $(echo x) 4" in calls


@pytest.mark.parametrize("mode,value,message", [
    ("fail", "1", "exited with code 3: solver diverged at t=12.5"),
    ("nofile", "1", "wrote no result file"),
    ("ok", "abc", "holds 'abc', not a number"),
    ("ok", "nan", "oracle returned nan"),
    ("ok", "-2.0", "negative load"),
    ("sleep", "1", "timed out after 0.5 s"),
])
def test_command_oracle_failures_are_recorded_never_zero(tmp_path, script, mode, value, message):
    oracle = command(script, tmp_path, mode, value, timeout=0.5)
    got, err = call_oracle(oracle, EV)
    assert got is None and message in err


def test_command_oracle_json_result_and_reuse(tmp_path, script):
    oracle = command(script, tmp_path, "ok", '{{"value": 7.5}}')
    assert oracle(EV) == 7.5
    # a valid result left by an earlier (e.g. orphaned) run of the same command is reused,
    # not recomputed, and the user is told
    with pytest.warns(RuntimeWarning, match="ev3: took .*result.txt, left by an earlier run "
                                            "of the same command"):
        assert oracle(EV) == 7.5
    assert len((tmp_path / "ev3" / "calls.log").read_text().splitlines()) == 1
    rerun = command(script, tmp_path, "ok", '{{"value": 7.5}}', reuse=False)
    assert rerun(EV) == 7.5
    assert len((tmp_path / "ev3" / "calls.log").read_text().splitlines()) == 2


def test_command_oracle_never_takes_the_result_of_another_command(tmp_path, script):
    """A second study run into the same root (here: another argument list) finds the first
    one's result: an error naming the folder, not the old load; the old file stays."""
    first = command(script, tmp_path, "ok", "7.5")
    assert first(EV) == 7.5
    for reuse in (True, False):
        other = command(script, tmp_path, "ok", "8.5", reuse=reuse)
        value, err = call_oracle(other, EV)
        assert value is None and "holds the result of another command" in err
        assert "give this study a root of its own" in err
    assert (tmp_path / "ev3" / "result.txt").read_text().strip() == "7.5"
    assert len((tmp_path / "ev3" / "calls.log").read_text().splitlines()) == 1
    # a placeholder typo is an error before any kept result is looked at
    typo = CommandOracle([sys.executable, script, "ok", "{sede}", "{result}"], root=tmp_path)
    value, err = call_oracle(typo, EV)
    assert value is None and "unknown placeholder {sede}" in err
    # a format spec is a one-line error: the fields are text
    spec = CommandOracle([sys.executable, script, "ok", "{lf:.3f}", "{result}"], root=tmp_path)
    value, err = call_oracle(spec, EV)
    assert value is None and "write {lf}, not {lf:.3f}" in err
    # a result no record names (a folder of an earlier pas) is taken, with a warning
    (tmp_path / "ev3" / ".pas-command.json").unlink()
    with pytest.warns(RuntimeWarning, match="a command it did not record"):
        assert command(script, tmp_path, "ok", "8.5")(EV) == 7.5


def test_command_oracle_checks_and_pickles(tmp_path, script):
    with pytest.raises(ValueError, match="args must be a non-empty list"):
        CommandOracle("python cfd.py {id}", root=tmp_path)
    with pytest.raises(ValueError, match="timeout"):
        CommandOracle(["x"], root=tmp_path, timeout=-1)
    with pytest.raises(OracleError, match="unknown placeholder {nope}"):
        CommandOracle(["x", "{nope}"], root=tmp_path).command(EV, str(tmp_path))
    assert parse_result(" 3.25\n") == 3.25
    oracle = command(script, tmp_path / "pool", "ok", "{lf}")
    events = [Event(index=i, id=f"e{i}", lf=1.0 + i, d=0.1) for i in range(3)]
    with ProcessPoolExecutor(2) as pool:
        got = list(pool.map(call_oracle, [oracle] * 3, events))
    assert got == [(1.0, None), (2.0, None), (3.0, None)]


def test_table_oracle_keys_on_sea_state_and_id_when_the_table_has_sea_states():
    table = pd.DataFrame({"sea_state": ["a", "a", "b"], "id": [1, 2, 1], "hf": [1.0, 2.0, 3.0]})
    oracle = TableOracle(table)
    assert oracle(Event(index=0, id=1, lf=1.0, d=0.1, sea_state="b")) == 3.0
    assert oracle(Event(index=0, id=1, lf=1.0, d=0.1, sea_state="a")) == 1.0
    with pytest.raises(OracleError, match="event 2 of sea state b is not in the table"):
        oracle(Event(index=1, id=2, lf=1.0, d=0.1, sea_state="b"))
    # a study of no sea state looks up the ids that appear once only
    assert oracle(Event(index=1, id=2, lf=1.0, d=0.1)) == 2.0
    with pytest.raises(OracleError, match="event 1 is not in the table"):
        oracle(Event(index=0, id=1, lf=1.0, d=0.1))
    with pytest.raises(ValueError, match=r"event id '1' appears more than once \(within its "
                                         r"sea state\)"):
        TableOracle(pd.DataFrame({"sea_state": ["a", "a"], "id": [1, 1], "hf": [1.0, 2.0]}))


def test_events_of_two_sea_states_with_one_id_run_in_two_folders(tmp_path):
    from pas.study.workdirs import event_dir

    a, b = (Event(index=5, id=5, lf=1.0, d=0.1, sea_state=s) for s in ("Hs 2 m", "Hs 4 m"))
    assert event_dir(a) != event_dir(b)
    assert event_dir(Event(index=5, id=5, lf=1.0, d=0.1)) == "5"  # a single study: as before
    assert event_dir(Event(index=5, id=5, lf=1.0, d=0.1, sea_state="H1")) == "H1/5".replace(
        "/", __import__("os").sep)
    oracle = CommandOracle([sys.executable, "cfd.py", "{sea_state}", "{id}"], root=tmp_path)
    assert oracle.command(a, "w")[-2:] == ["Hs 2 m", "5"]


def test_the_result_a_failed_run_left_is_not_reused(tmp_path, script):
    """A solver that writes its running peak and then fails (or times out) leaves a valid
    file: a retry runs the program again instead of taking it."""
    partial = command(script, tmp_path, "partial", "1.0")
    value, err = call_oracle(partial, EV)
    assert value is None and "exited with code 3" in err
    value, err = call_oracle(partial, EV)
    assert value is None and "exited with code 3" in err
    assert len((tmp_path / "ev3" / "calls.log").read_text().splitlines()) == 2


def test_a_moved_campaign_folder_reuses_its_results(tmp_path):
    """The record keeps the command as given, the folders as placeholders: a campaign
    folder moved elsewhere (a killed driver resumed there) takes its kept results."""
    first = tmp_path / "A"
    first.mkdir()
    (first / "hf.py").write_text(SCRIPT)
    oracle = CommandOracle([sys.executable, "hf.py", "ok", "{lf}", "{result}"], root="runs",
                           cwd=first)
    assert oracle(EV) == 2.5
    moved = tmp_path / "B"
    first.rename(moved)
    again = CommandOracle([sys.executable, "hf.py", "ok", "{lf}", "{result}"], root="runs",
                          cwd=moved)
    with pytest.warns(RuntimeWarning, match="of the same command"):
        assert again(EV) == 2.5
    assert len((moved / "runs" / "ev3" / "calls.log").read_text().splitlines()) == 1


def test_event_meta_is_plain_json_data_before_and_after_a_store():
    """A NaN meta value reached the command as 'nan' in the first run and as 'None' once
    stored and resumed (the store keeps JSON), so a resumed study refused its own result."""
    from pas.strategies.screening import LFSet

    lf = np.linspace(1.0, 3.0, 20)
    meta = [{"gap": np.nan, "seed": np.int64(i), "t0": np.float32(0.5)} for i in range(20)]
    ev = LFSet(lf, n_waves=20, p_exp=0.1, meta=meta).event(0)
    assert ev.meta == {"gap": None, "seed": 19, "t0": 0.5}
    assert type(ev.meta["seed"]) is int
