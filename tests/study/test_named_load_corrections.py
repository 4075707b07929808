"""Correcting named loads told before: the new values are stored, the old ones audited.

A basin test gives a deck force (screened) and a panel pressure; a typo in
either is corrected with ``--replace`` / ``replace=True``.  The expected values
are the numbers told, never ones computed by the code under test.
"""

import warnings

import numpy as np
import pytest
from conftest import no_band

import pas
from pas.cli import main
from pas.study.loads import stored_loads
from pas.study.resume import open_study
from pas.study.schema import StoreError

N = 300
LF = np.random.default_rng(3).rayleigh(1.0, N)


def cli(*argv):
    try:
        return main([str(a) for a in argv])
    except SystemExit as exc:
        return exc.code


@pytest.fixture()
def told(tmp_path):
    """A stored study screening on deck, its 4 initial events told deck and panel loads."""
    db = tmp_path / "s.db"
    study = pas.make_study(no_band(), LF, n_waves=N, p_exp=0.01, eps1=0.01, seed=5,
                           target="deck", store=db)
    events = study.ask(4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k, ev in enumerate(events):
            study.tell(ev, {"deck": 100.0 + k, "panel": 10.0 + k})
    return study, events, db


def test_cli_corrects_a_load_that_is_not_screened_and_keeps_the_old_value(told, capsys):
    study, events, db = told
    study.store.close()
    key, idx = str(events[1].id), events[1].index
    assert cli("study", "tell", db, key, "--load", "deck=101", "--load", "panel=99") == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--replace" in err
    assert cli("study", "tell", db, key, "--load", "deck=101", "--load", "panel=12.5",
               "--replace") == 0
    assert "replaced the loads of 1 event(s)" in capsys.readouterr().out
    with pas.StudyStore(db, create=False) as s:
        assert stored_loads(s)[idx] == {"deck": (101.0, None), "panel": (12.5, None)}
        audit = s.load_replacements()
        assert [(r["idx"], r["name"], r["old_value"], r["new_value"]) for r in audit] == \
            [(idx, "panel", 11.0, 12.5)]
        assert s.replacements() == []            # the screened load did not change
        assert s.events().set_index("idx").loc[idx, "hf"] == pytest.approx(101.0, rel=1e-12)
    assert cli("study", "status", db, "--events") == 0
    assert f"replaced load 'panel' of event {key}: 11 -> 12.5" in capsys.readouterr().out


def test_cli_correcting_the_screened_load_replaces_the_result_and_the_load(told, capsys):
    study, events, db = told
    study.store.close()
    key, idx = str(events[2].id), events[2].index
    assert cli("study", "tell", db, key, "--load", "deck=150", "--replace") == 0
    with pas.StudyStore(db, create=False) as s:
        assert stored_loads(s)[idx] == {"deck": (150.0, None), "panel": (12.0, None)}
        (r,) = s.replacements()
        assert (r["old_hf"], r["new_hf"]) == (102.0, 150.0)
        assert [(a["name"], a["old_value"], a["new_value"]) for a in s.load_replacements()] == \
            [("deck", 102.0, 150.0)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        resumed = open_study(db)
    assert resumed.rows[-1]["hf"] == pytest.approx(150.0, rel=1e-12)
    assert resumed.rows[-1]["replaced_hf"] == pytest.approx(102.0, rel=1e-12)
    resumed.store.close()


def test_python_tell_corrects_an_unscreened_load_without_a_refit(told):
    study, events, db = told
    rows = len(study.rows)
    out = study.tell(events[0], {"deck": 100.0, "panel": 10.5}, replace=True)
    assert len(study.rows) == rows and out["hf"] == pytest.approx(100.0, rel=1e-12)
    assert stored_loads(study.store)[events[0].index]["panel"] == (10.5, None)
    with pytest.raises(StoreError, match="already holds this result"):
        study.tell(events[0], {"deck": 100.0, "panel": 10.5}, replace=True)
    study.tell(events[3], {"deck": 130.0, "panel": 13.0}, replace=True)
    assert len(study.rows) == rows + 1 and study.rows[-1]["replaced_hf"] == 103.0
    loads = stored_loads(study.store)[events[3].index]
    assert loads == {"deck": (130.0, None), "panel": (13.0, None)}
    # panel 13 unchanged
    assert [a["name"] for a in study.store.load_replacements()] == ["panel", "deck"]
    study.store.close()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        refit = pas.refit(db, target="panel")
    assert sorted(refit.history["hf"]) == pytest.approx([10.5, 11.0, 12.0, 13.0], rel=1e-12)
