"""Correcting a told result: ``tell --replace`` keeps the old value and refits.

The reference of the fit test is a second store holding the same events with
the new value told in the first place, driven by the same code: a replacement
must give the fit the new value would have given.
"""

import json
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest

import pas
from pas import PAS, ModelBand
from pas.cli import main
from pas.study import amend, open_study
from pas.study.store import SCHEMA_VERSION, StoredResult, StoreError, StudyStore

N = 400
LF = np.random.default_rng(0).rayleigh(1.0, N)
KW = dict(n_waves=N, p_exp=1e-2, eps1=1e-3, seed=5, max_hf=30)
TYPO, RIGHT = 999.0, 12.5


def good(ev):
    return 2.0 * ev.lf ** 1.2


def _campaign(db, n_events, last_value=None, n_bootstrap=0):
    """Ask and tell ``n_events`` events; the last one told ``last_value`` (when given)."""
    study = pas.make_study(PAS(band=ModelBand(n_bootstrap=n_bootstrap)), LF, store=db, **KW)
    told = 0
    while told < n_events:
        for ev in study.ask():
            told += 1
            study.tell(ev, last_value if told == n_events and last_value is not None else good(ev))
    return study, ev


def _fit(study):
    res = study.result()
    return res.mpm, res.mpm_band


@pytest.mark.parametrize("n_bootstrap", [0, pytest.param(10, marks=pytest.mark.slow)])
def test_replacing_the_last_value_gives_the_fit_of_the_value_told_first(tmp_path, capsys,
                                                                         n_bootstrap):
    typo, ref = str(tmp_path / "typo.db"), str(tmp_path / "ref.db")
    study, ev = _campaign(typo, 8, TYPO, n_bootstrap=n_bootstrap)   # 10: a model band too
    study.store.close()
    reference, ref_ev = _campaign(ref, 8, RIGHT, n_bootstrap=n_bootstrap)
    assert ref_ev.index == ev.index
    # reproduction: the second tell was refused as "already told"
    assert main(["study", "tell", typo, str(ev.id), str(RIGHT)]) == 2
    assert "already told" in capsys.readouterr().err
    assert main(["study", "tell", typo, str(ev.id), str(RIGHT), "--replace"]) == 0
    assert "stored 1 result(s)" in capsys.readouterr().out
    corrected = open_study(typo)
    mpm, band = _fit(corrected)
    ref_mpm, ref_band = _fit(reference)
    assert (corrected.result().mpm_band_model is not None) == (n_bootstrap > 0)
    assert mpm == pytest.approx(ref_mpm, rel=1e-9)
    assert band == pytest.approx(ref_band, rel=1e-9)
    assert corrected.value[corrected.lfset.position_of(ev.index)] == RIGHT
    corrected.store.close()
    reference.store.close()
    with StudyStore(typo, create=False) as store:
        (audit,) = store.replacements()
        assert (audit["old_hf"], audit["new_hf"], audit["source"]) == (TYPO, RIGHT, "cli")
        assert audit["consumed_seq"] > 0 and "MD gaps and threshold raises" in audit["note"]
    assert main(["study", "status", typo, "--events"]) == 0
    text = capsys.readouterr().out
    assert f"replaced: event {ev.id} 999 -> 12.5" in text and "events (in ask order)" in text
    assert main(["study", "status", typo, "--events", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["replacements"][0]["old_hf"] == TYPO and len(info["events"]) == 8


def test_replace_in_python_and_an_earlier_value_keeps_the_asks(tmp_path):
    db = str(tmp_path / "s.db")
    study, _ = _campaign(db, 12)
    asks = list(study.store.events()["idx"])
    early = study.rows[5]
    with pytest.raises(ValueError, match="replace=True"):
        study.tell(early["event_index"], 3.0)
    row = study.tell(early["event_index"], 3.0, replace=True)
    assert (row["replaced_hf"], row["hf"]) == (early["hf"], 3.0)
    live = study.result().mpm
    nxt = [ev.index for ev in study.ask()]
    study.store.close()
    again = open_study(db)                     # the replacement replays where it was applied
    assert list(again.store.events()["idx"])[:len(asks)] == asks
    assert again.rows[12]["mpm"] == pytest.approx(live, rel=1e-12)
    assert [ev.index for ev in again.pending] == nxt
    pairs = again.pairs()
    assert 3.0 in pairs.hf and early["hf"] not in pairs.hf
    first_order = [r["position"] for r in study.rows[:12] if r["status"] == "true_positive"]
    assert list(pairs.position).index(early["position"]) == first_order.index(early["position"])
    again.store.close()


def test_a_value_after_an_error_and_a_replacement_waiting_for_the_driver(tmp_path, capsys):
    """Reproduction: a real value after --error was refused as "already told"."""
    db = str(tmp_path / "s.db")
    study = pas.make_study(PAS(band=ModelBand(n_bootstrap=0)), LF, store=db, **KW)
    first = study.ask()
    study.tell(first[0], error="basin wave maker tripped")
    for ev in first[1:]:
        study.tell(ev, good(ev))
    study.store.close()
    assert main(["study", "tell", db, str(first[0].id), "8.0"]) == 2
    assert "--replace" in capsys.readouterr().err
    assert main(["study", "tell", db, str(first[0].id), "8.0", "--replace"]) == 0
    with StudyStore(db, create=False) as store:
        waiting = StoredResult(idx=first[0].index, hf=8.0, error=None)
        assert store.unconsumed() == [waiting]   # not applied yet
    reopened = open_study(db)                    # the next driver applies it
    assert reopened.n_failed == 0 and reopened.rows[-1]["replaced_error"] is not None
    reopened.store.close()
    with StudyStore(db, create=False) as store:
        assert store.unconsumed() == []
        assert store.replacements()[0]["old_error"] == "basin wave maker tripped"
        assert store.tell_by_key(first[0].id, 8.0, replace=True) is False   # identical


def test_a_replace_is_one_transaction(tmp_path, monkeypatch):
    db = str(tmp_path / "s.db")
    study, ev = _campaign(db, 5)
    study.store.close()
    calls = []

    def dies_after_the_audit_row():
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt   # the process stops between the audit row and the update
        return "2026-12-01T00:00:00.000+00:00"

    monkeypatch.setattr(amend, "_now", dies_after_the_audit_row)
    with StudyStore(db, create=False) as store:
        before = store.events()
        with pytest.raises(KeyboardInterrupt):
            store.tell_by_key(ev.id, 1.0, replace=True)
        assert store.replacements() == []
        assert store.events()["hf"].tolist() == before["hf"].tolist()


def test_a_version_1_store_is_upgraded_and_takes_a_replacement(tmp_path):
    path = tmp_path / "v1.sqlite"
    shutil.copy(Path(__file__).parents[1] / "data" / "store_v1.sqlite", path)
    with sqlite3.connect(path) as c:
        assert c.execute("PRAGMA user_version").fetchone()[0] == 1
    study = open_study(path)
    mpm = study.rows[-1]["mpm"]
    study.tell(230, 1.0, replace=True)
    assert study.rows[-1]["mpm"] != mpm
    study.store.close()
    with sqlite3.connect(path) as c:
        assert c.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION
        assert c.execute("SELECT version FROM schema_version").fetchone()[0] == SCHEMA_VERSION
    again = open_study(path)
    assert again.rows[-1]["mpm"] == pytest.approx(study.rows[-1]["mpm"], rel=1e-12)
    again.store.close()
    with pytest.raises(StoreError, match="was not asked for"):
        with StudyStore(path, create=False) as store:
            store.tell_by_key("no-such-event", 1.0, replace=True)


def _replace_forever(db, key):
    with StudyStore(db, create=False) as store:
        for i in range(100_000):
            store.tell_by_key(key, float(i % 7 + 1), replace=True, source=f"r{i}")


@pytest.mark.slow
def test_sigkill_during_replacements_leaves_a_consistent_trail(tmp_path):
    import multiprocessing as mp
    import os
    import signal
    import time

    db = str(tmp_path / "s.db")
    study, ev = _campaign(db, 5)
    study.store.close()
    proc = mp.get_context("spawn").Process(target=_replace_forever, args=(db, ev.id))
    proc.start()
    deadline = time.time() + 60
    while time.time() < deadline:
        with sqlite3.connect(db, timeout=30) as c:
            if c.execute("SELECT COUNT(*) FROM replacements").fetchone()[0] >= 5:
                break
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.join()
    with StudyStore(db, create=False) as store:
        trail = store.replacements()
        row = store.events().set_index("idx").loc[ev.index]
    assert len(trail) >= 5
    assert trail[0]["old_hf"] == pytest.approx(good(ev), rel=1e-12)
    for before, after in zip(trail, trail[1:]):       # every replacement whole, none lost
        assert after["old_hf"] == before["new_hf"] and after["old_source"] == before["source"]
    assert (row["hf"], row["source"]) == (trail[-1]["new_hf"], trail[-1]["source"])
    again = open_study(db)                              # and the study applies the last one
    assert again.value[again.lfset.position_of(ev.index)] == trail[-1]["new_hf"]
    again.store.close()
