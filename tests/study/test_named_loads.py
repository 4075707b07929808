"""Several loads per HF event: screening on a target, keeping all, refitting another load.

One CFD run gives a deck force, a panel pressure and a sensor signal.  The
expected values are the oracle's own formulas or a second study told the other
load in the first place, never numbers computed by the code under test.
"""

import json
import shutil
import sqlite3
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import pas
from pas import PAS, ModelBand
from pas.cli import main
from pas.strategies.screening import Event
from pas.study.command_oracle import CommandOracle, parse_result
from pas.study.loads import stored_loads
from pas.study.oracle_spec import oracle_from_spec, parse_oracle_spec
from pas.study.oracles import TableOracle, call_oracle_loads
from pas.study.result import OUTPUT_FILES
from pas.study.resume import open_study

N = 300
LF = np.random.default_rng(3).rayleigh(1.0, N)
KW = dict(n_waves=N, p_exp=0.01, eps1=0.01, seed=5, max_hf=8, stop_on_convergence=False)
FAST = PAS(families=("gaussian", "gumbel"), band=ModelBand(n_bootstrap=0))


def run(oracle, target=None, store=None):
    """The 8-event study of these tests (no stop on convergence) screening on ``target``."""
    return pas.make_study(FAST, LF, target=target, store=store, **KW).optimize(oracle)


def deck(i):
    return 2.0 * LF[i] ** 1.2


def panel(i):  # > 0 wherever deck is: the same true/false positives, so the same asks
    return 0.6 * LF[i] ** 1.7 + 0.05 * (i % 7)


def sensor(i):  # a signal that dropped out on every third event
    return float("nan") if i % 3 == 0 else 0.1 * LF[i] + 0.01 * (i % 5)


def all_loads(ev):
    return {"deck": deck(ev.index), "panel": panel(ev.index), "sensor": sensor(ev.index)}


def deck_only(ev):
    return deck(ev.index)


class Counting:
    def __init__(self):
        self.calls = 0

    def __call__(self, ev):
        self.calls += 1
        return all_loads(ev)


def cli(*argv):
    try:
        return main([str(a) for a in argv])
    except SystemExit as exc:  # argparse usage errors
        return exc.code


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The study screened on deck (stored), the same on a float oracle, and on panel."""
    store = tmp_path_factory.mktemp("named") / "deck.sqlite"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        on_deck = run(all_loads, target="deck", store=store)
        on_float = run(deck_only)
        on_panel = run(all_loads, target="panel")
    return store, on_deck, on_float, on_panel


def test_mapping_answer_gives_the_mpm_of_its_target_alone(runs):
    _, on_deck, on_float, _ = runs
    assert on_deck.mpm == pytest.approx(on_float.mpm, rel=1e-9)
    assert on_deck.mpm_band == pytest.approx(on_float.mpm_band, rel=1e-9)
    np.testing.assert_allclose(on_deck.history["hf"], on_float.history["hf"], rtol=1e-12)
    assert (on_deck.settings["target"], on_float.settings["target"]) == ("deck", None)


def test_store_keeps_every_named_load_and_a_nan_one_as_missing(runs):
    store, on_deck, _, _ = runs
    with pas.StudyStore(store, create=False) as s:
        loads = stored_loads(s)
        events = s.events()
    asked = [int(i) for i in on_deck.history["event_index"]]
    assert sorted(loads) == sorted(asked) and len(asked) == 8
    for i in asked:
        assert loads[i]["deck"][0] == pytest.approx(deck(i), rel=1e-12)
        assert loads[i]["panel"][0] == pytest.approx(panel(i), rel=1e-12)
        if i % 3 == 0:
            assert loads[i]["sensor"] == (None, "oracle returned nan")
        else:
            assert loads[i]["sensor"] == (pytest.approx(sensor(i), rel=1e-12), None)
    assert any(i % 3 == 0 for i in asked)          # the case exercises a dropped-out signal
    assert set(events["state"]) == {"done"}         # a NaN sensor does not fail its event


def test_refit_on_another_load_equals_a_study_told_that_load(runs):
    store, on_deck, _, on_panel = runs
    assert list(on_panel.history["event_index"]) == list(on_deck.history["event_index"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        refit = pas.refit(store, target="panel")
    assert refit.mpm == pytest.approx(on_panel.mpm, rel=1e-9)
    assert refit.mpm_band == pytest.approx(on_panel.mpm_band, rel=1e-9)
    assert not np.isclose(refit.mpm, on_deck.mpm, rtol=0.05)
    assert refit.refit == {"target": "panel", "chosen_for": "deck", "n_missing": 0}
    assert "events chosen for 'deck', so the sample is not adapted to 'panel'" in refit.summary()


def test_refit_on_the_own_target_gives_the_study_result(runs):
    store, on_deck, _, _ = runs
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        refit = pas.refit(store, target="deck")
    assert refit.mpm == pytest.approx(on_deck.mpm, rel=1e-9)
    assert refit.mpm_band == pytest.approx(on_deck.mpm_band, rel=1e-9)
    assert "not adapted" not in refit.summary()


def test_refit_counts_events_lacking_the_load_as_failed(runs):
    store, on_deck, _, _ = runs
    lacking = sum(int(i) % 3 == 0 for i in on_deck.history["event_index"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        refit = pas.refit(store, target="sensor")
    assert (refit.n_failed, refit.n_hf) == (lacking, 8 - lacking)
    assert refit.refit["n_missing"] == lacking
    assert f"({lacking} event(s) lack 'sensor', counted failed)" in refit.summary()


def test_refit_of_an_unknown_load_is_a_one_line_error(runs, capsys):
    store = runs[0]
    with pytest.raises(ValueError, match=r"^target: 'nope' is not a load stored in .*"
                                         r"\(its loads: deck, panel, sensor\)$"):
        pas.refit(store, target="nope")
    assert cli("study", "refit", store, "--target", "nope") == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "'nope' is not a load" in err


def test_answers_fail_on_a_missing_or_invalid_target_never_as_zero():
    study = pas.make_study(PAS(), LF, n_waves=N, p_exp=0.01, eps1=0.01, seed=5, target="deck")
    a, b, c, d = study.ask(4)
    assert study.tell(a, {"panel": 2.0})["error"] == \
        "oracle's answer has no load 'deck' (the target; it has panel)"
    assert study.tell(b, {"deck": float("nan"), "panel": 1.0})["error"] == \
        "load 'deck': oracle returned nan"
    assert study.tell(c, {"deck": "12 kN"})["error"] == \
        "load 'deck': oracle returned '12 kN', not a number"
    assert study.tell(d, {"deck": 0.0, "panel": 3.0})["status"] == "false_positive"
    assert (study.n_failed, study.n_false_positive) == (3, 1)
    with pytest.raises(ValueError, match="^target must be the name of one load"):
        pas.make_study(PAS(), LF, n_waves=N, p_exp=0.01, eps1=0.01, target=3)


def test_several_loads_without_target_stop_at_once_and_resume_with_it(tmp_path, runs):
    store, on_deck = tmp_path / "s.sqlite", runs[1]
    oracle = Counting()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(ValueError, match=r"^event \d+: oracle returned 3 loads \(deck, panel, "
                                             r"sensor\) and the study has no target: .*target="):
            run(oracle, store=store)
        assert oracle.calls == 1
        with pas.StudyStore(store, create=False) as s:
            assert len(stored_loads(s)) == 1       # the one HF run is kept
        resumed = run(oracle, target="deck", store=store)
    assert oracle.calls == 8                       # its answer was not asked for again
    assert resumed.mpm == pytest.approx(on_deck.mpm, rel=1e-9)


def test_table_oracle_with_several_value_columns(tmp_path):
    df = pd.DataFrame({"id": ["a", "b"], "deck": [812.0, 0.0], "panel_p3": [41.2, np.nan]})
    df.to_csv(tmp_path / "basin.csv", index=False)
    ev = Event(index=0, id="b", lf=1.0, d=0.1)
    oracle = oracle_from_spec(f"table:{tmp_path / 'basin.csv'}:id:deck,panel_p3")
    got = oracle(Event(index=0, id="a", lf=1.0, d=0.1))
    assert got == {"deck": 812.0, "panel_p3": 41.2}
    assert call_oracle_loads(oracle, ev, "deck") == (
        0.0, None, {"deck": (0.0, None), "panel_p3": (None, "oracle returned nan")})
    assert call_oracle_loads(oracle, ev, "panel_p3")[:2] == (
        None, "load 'panel_p3': oracle returned nan")
    assert parse_oracle_spec("table:b.csv:id:deck,panel_p3")["value_column"] == ["deck", "panel_p3"]
    with pytest.raises(ValueError, match="^value_column: give one column or several different"):
        TableOracle(df, value_column=["deck", "deck"])
    with pytest.raises(ValueError, match="^value_column: column 'force' is missing"):
        TableOracle(df, value_column=["deck", "force"])
    with pytest.raises(ValueError, match="empty name in the value columns"):
        parse_oracle_spec("table:b.csv:id:deck,")


def test_command_result_file_may_hold_named_loads(tmp_path):
    assert parse_result('{"deck_force": 812.0, "panel_p3": 41.2}') == {
        "deck_force": 812.0, "panel_p3": 41.2}
    assert parse_result('{"value": 3.5}') == 3.5
    script = tmp_path / "cfd.py"
    script.write_text("import json, sys\njson.dump({'deck_force': 812.0, 'panel_p3': 41.2}, "
                      "open(sys.argv[1], 'w'))\n")
    oracle = CommandOracle([sys.executable, str(script), "{result}"], root=tmp_path / "runs")
    ev = Event(index=4, id="e4", lf=1.0, d=0.1)
    assert call_oracle_loads(oracle, ev, "deck_force")[:2] == (812.0, None)
    script.write_text("raise SystemExit(1)\n")  # a second call reuses the result file
    assert call_oracle_loads(oracle, ev, "panel_p3")[:2] == (41.2, None)


@pytest.fixture()
def asked_store(tmp_path):
    """A stored study screening on deck with its 4 initial events asked."""
    db = tmp_path / "s.db"
    study = pas.make_study(PAS(), LF, n_waves=N, p_exp=0.01, eps1=0.01, seed=5, target="deck",
                           store=db)
    events = study.ask(4)
    study.store.close()
    return db, events


def test_tell_with_named_loads_from_the_cli(asked_store, capsys):
    db, events = asked_store
    key = str(events[0].id)
    assert cli("study", "tell", db, key, "--load", "deck=812", "--load", "panel_p3=41.2") == 0
    assert "stored the loads of 1 event(s)" in capsys.readouterr().out
    with pas.StudyStore(db, create=False) as s:
        assert stored_loads(s)[events[0].index] == {"deck": (812.0, None),
                                                    "panel_p3": (41.2, None)}
        row = s.events().set_index("key").loc[key]
        assert row["state"] == "done" and row["hf"] == pytest.approx(812.0, rel=1e-12)


def test_tell_a_results_table_with_several_load_columns(asked_store, tmp_path, capsys):
    db, events = asked_store
    pd.DataFrame({"id": [ev.id for ev in events[:3]], "deck": [812.0, 0.0, np.nan],
                  "panel_p3": [41.2, "broken", 3.0], "error": [None, None, "gauge lost"]}
                 ).to_csv(tmp_path / "basin.csv", index=False)
    assert cli("study", "tell", db, "--csv", tmp_path / "basin.csv",
               "--value-column", "deck,panel_p3") == 0
    assert "stored the loads of 3 event(s)" in capsys.readouterr().out
    with pas.StudyStore(db, create=False) as s:
        loads = stored_loads(s)
        state = s.events().set_index("idx")["state"]
    a, b, c = (ev.index for ev in events[:3])
    assert loads[a] == {"deck": (812.0, None), "panel_p3": (41.2, None)}
    assert loads[b] == {"deck": (0.0, None),
                        "panel_p3": (None, "oracle returned 'broken', not a number")}
    assert c not in loads and (state[a], state[b], state[c]) == ("done", "false_positive", "failed")
    pd.DataFrame({"id": [events[3].id], "deck": ["12 kN"], "panel_p3": [1.0]}).to_csv(
        tmp_path / "bad.csv", index=False)
    assert cli("study", "tell", db, "--csv", tmp_path / "bad.csv",
               "--value-column", "deck,panel_p3") == 2
    assert "bad.csv, data row 1: the screened load deck must be finite" in capsys.readouterr().err
    assert cli("study", "tell", db, "--csv", tmp_path / "bad.csv", "--value-column", "a,b") == 2
    assert "--value-column: " in capsys.readouterr().err


@pytest.mark.parametrize("loads, message", [
    (["deck=abc"], "--load deck: the load must be a number, got 'abc'"),
    (["panel_p3=41.2"], "screens on 'deck', which is not among the loads given (panel_p3)"),
    (["deck"], "--load must be NAME=VALUE"),
    (["deck=-3"], "--load: the screened load deck must be finite and >= 0"),
    (["deck=1", "deck=2"], "--load: load 'deck' is given twice"),
])
def test_bad_named_loads_in_tell_are_one_line_errors(asked_store, capsys, loads, message):
    db, events = asked_store
    argv = ["study", "tell", db, events[0].id]
    for item in loads:
        argv += ["--load", item]
    assert cli(*argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err
    with pas.StudyStore(db, create=False) as s:
        assert stored_loads(s) == {} and s.unconsumed() == []


def test_cli_run_target_then_refit_writes_the_run_files(tmp_path, capsys):
    idx = np.arange(N)
    pd.DataFrame({"id": idx, "lf": LF}).to_csv(tmp_path / "lf.csv", index=False)
    pd.DataFrame({"id": idx, "deck": deck(idx), "panel": panel(idx)}).to_csv(
        tmp_path / "hf.csv", index=False)
    out = tmp_path / "run"
    common = ["run", tmp_path / "lf.csv", "--oracle", f"table:{tmp_path / 'hf.csv'}:id:deck,panel",
              "--n-waves", N, "--p-exp", 0.01, "--eps1", 0.01, "--seed", 5, "--max-hf", 5,
              "--preset", "paper", "--out", out, "--quiet"]  # paper: no bootstrap, fast
    assert cli(*common) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--target NAME" in err
    assert cli(*common, "--target", "deck") == 0
    assert "target changed from None to deck" in capsys.readouterr().err
    assert cli("study", "refit", out / "study.sqlite", "--target", "panel", "--out",
               out / "panel") == 0
    assert "events chosen for 'deck'" in capsys.readouterr().out
    summary = json.loads((out / "panel" / "summary.json").read_text())
    assert summary["refit"] == {"target": "panel", "chosen_for": "deck", "n_missing": 0}
    assert summary["n_hf"] == 5 and np.isfinite(summary["mpm"])
    assert all((out / "panel" / name).exists() for name in OUTPUT_FILES)


def test_study_file_target_and_old_stores_gain_the_loads_table(tmp_path):
    pd.DataFrame({"lf": LF}).to_csv(tmp_path / "peaks.csv", index=False)
    (tmp_path / "s.toml").write_text('n_waves = 300\np_exp = 0.01\neps1 = 0.01\ntarget = "deck"\n'
                                     '[lf]\nfile = "peaks.csv"\ncolumn = "lf"\n')
    assert cli("study", "create", tmp_path / "s.db", "--config", tmp_path / "s.toml") == 0
    assert pas.StudyStore(tmp_path / "s.db", create=False).settings()["target"] == "deck"
    old = tmp_path / "v1.sqlite"
    shutil.copy(Path(__file__).parents[1] / "data" / "store_v1.sqlite", old)
    open_study(old).store.close()
    with sqlite3.connect(old) as c:
        assert c.execute("SELECT COUNT(*) FROM event_loads").fetchone() == (0,)
    with pytest.raises(ValueError, match="its loads: none, its oracle gave one number"):
        pas.refit(old, target="deck")
