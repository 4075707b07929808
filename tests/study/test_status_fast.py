"""``pas study status`` reads the result stored for the current log and never shows a stale one."""

from __future__ import annotations

import json

import numpy as np
import pytest

import pas
from pas.cli import main as cli
from pas.study.store import StudyStore

RAYLEIGH_LF = np.random.default_rng(0).rayleigh(1.0, 2000)


def hf_of(lf):
    return 1.3 * lf ** 1.1


def fast_study(db, max_hf=16):
    strategy = pas.PAS(band=pas.ModelBand(n_bootstrap=12), families=("gaussian", "gumbel"))
    return pas.make_study(strategy, RAYLEIGH_LF, n_waves=2000, p_exp=0.01, eps1=1e-12, seed=1,
                          store=db, max_hf=max_hf)


def told(study, n):
    """Ask and tell events until ``n`` are told (the first ask is the initial batch)."""
    while study.n_told < n:
        for ev in study.ask(1):
            study.tell(ev.index, hf_of(ev.lf))
    assert study.n_told == n


def status_json(capsys, db, *flags):
    capsys.readouterr()
    assert cli(["study", "status", db, "--json", *flags]) == 0
    return json.loads(capsys.readouterr().out)


def no_replay(*args, **kwargs):
    raise AssertionError("status replayed the log")


@pytest.fixture
def stored_db(tmp_path):
    """A study of 12 told results whose result (with the model band) was computed."""
    db = str(tmp_path / "s.db")
    study = fast_study(db)
    told(study, 12)
    result = study.result()
    assert result.mpm_band_model is not None
    study.store.close()
    return db, result


def test_status_with_a_stored_result_does_not_replay_and_matches_the_replay(
        stored_db, capsys, monkeypatch):
    db, result = stored_db
    replayed = status_json(capsys, db, "--refresh")
    capsys.readouterr()
    assert cli(["study", "status", db, "--refresh"]) == 0
    replayed_text = capsys.readouterr().out
    monkeypatch.setattr("pas.study.resume.open_study", no_replay)
    fast = status_json(capsys, db)
    assert fast["result_stored"] is True and replayed["result_stored"] is False
    assert fast["result_n_told"] == 12 and fast["n_hf"] == 12
    assert fast["mpm"] == pytest.approx(result.mpm, rel=1e-7)
    assert fast["mpm_band"] == pytest.approx(list(result.mpm_band), rel=1e-7)
    assert fast["mpm_band_model"] == pytest.approx(list(result.mpm_band_model), rel=1e-7)
    for key in ("mpm", "mpm_band", "mpm_band_sampling", "mpm_band_model", "E_bar", "COV"):
        assert fast[key] == pytest.approx(replayed[key], rel=1e-7), key
    for key in ("family", "converged", "finished", "n_evaluated", "n_pending", "converged_at_n_hf"):
        assert fast[key] == replayed[key], key
    assert cli(["study", "status", db]) == 0
    text = capsys.readouterr().out
    assert text == replayed_text.replace(
        "(computed by replaying the log of 12 used results: --refresh)\n", "")


def test_a_result_told_after_the_stored_one_is_named_as_not_included(stored_db, capsys,
                                                                   monkeypatch):
    db, result = stored_db
    study = _reopened(db)
    (ev,) = study.ask(1)
    study.store.close()
    with StudyStore(db, create=False) as store:
        assert store.tell_by_key(ev.id, hf_of(ev.lf))
    with monkeypatch.context() as m:
        m.setattr("pas.study.resume.open_study", no_replay)
        fast = status_json(capsys, db)
        assert cli(["study", "status", db]) == 0
        text = capsys.readouterr().out
    assert fast["results_not_yet_used"] == 1 and fast["result_n_told"] == 12
    assert fast["n_hf"] == 12 and fast["converged"] is None and fast["finished"] is None
    assert fast["mpm"] == pytest.approx(result.mpm, rel=1e-7)
    assert ("1 result(s) told since the last ask are not included below: this is the stored "
            "result of the 12 results the study has used") in text
    assert "included below, not yet used" not in text
    # --refresh replays and includes it, as status did before results were stored
    full = status_json(capsys, db, "--refresh")
    assert full["n_hf"] == 13 and full["results_not_yet_used"] == 1
    assert full["result_stored"] is False


def _reopened(db):
    from pas.study.resume import open_study

    return open_study(db)


def test_a_store_without_a_stored_result_is_replayed_once_then_read(tmp_path, capsys,
                                                                    monkeypatch):
    db = str(tmp_path / "s.db")
    study = fast_study(db)
    told(study, 12)  # no result computed: nothing stored
    study.store.close()
    capsys.readouterr()
    assert cli(["study", "status", db]) == 0
    assert "(computed by replaying the log of 12 used results: no result stored for it)" in \
        capsys.readouterr().out
    replayed = status_json(capsys, db, "--refresh")
    monkeypatch.setattr("pas.study.resume.open_study", no_replay)
    fast = status_json(capsys, db)
    assert fast["result_stored"] is True
    assert fast["mpm"] == pytest.approx(replayed["mpm"], rel=1e-7)


def test_a_settings_change_makes_the_stored_result_not_current(stored_db, capsys):
    db, _ = stored_db
    assert status_json(capsys, db)["result_stored"] is True
    assert cli(["study", "set", db, "--eps2", "0.2"]) == 0
    after = status_json(capsys, db)
    assert after["result_stored"] is False and after["eps2"] == 0.2


def test_a_result_is_not_stored_under_a_log_that_changed_since_the_replay(tmp_path):
    from pas.study.stored_results import save_result, stored_result

    db = str(tmp_path / "s.db")
    study = fast_study(db)
    told(study, 12)
    result = study.result(model_band=False)  # not stored: no model band
    with StudyStore(db, create=False) as store:
        assert stored_result(store)[0] is None
        save_result(store, study, result, expected_key="a log read before another tell")
        assert stored_result(store)[0] is None
        save_result(store, study, result, expected_key=stored_result(store)[2])
        assert stored_result(store)[0]["n_hf"] == 12
    study.store.close()
