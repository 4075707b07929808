"""The store's narrow interface: named records out, each result written once.

The views hand out named records read by field (``Outstanding``,
``StoredResult``, the log's ``Ask`` / ``Tell`` / ``Replace``); a result is
written by ``record_result`` / ``tell_by_key`` alone, ``record_tell`` only
marks a stored result used and refuses one that differs from its row.
"""

from __future__ import annotations

import numpy as np
import pytest

import pas
from pas.study import open_study
from pas.study.refit import refit_study
from pas.study.store import Ask, Outstanding, Replace, StoredResult, StoreError, StudyStore, Tell

N = 300
LF = np.random.default_rng(3).rayleigh(1.0, N)


def hf_of(ev) -> float:
    return round(2.0 * ev.lf ** 1.2, 6)


def new_study(path) -> pas.Study:
    return pas.Study(
        pas.LFSet(LF, n_waves=N, p_exp=1e-2),
        pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
        stopping=pas.Stopping(eps1=1e-3),
        seed=2,
        store=StudyStore(path),
    )


def told_study(path):
    """A study whose first ask is told, and that ask's events."""
    study = new_study(path)
    first = study.ask()
    for ev in first:
        study.tell(ev, hf_of(ev))
    return study, first


def test_the_log_is_named_asks_tells_and_replacements(tmp_path):
    study, first = told_study(tmp_path / "s.db")
    second = study.ask(1)
    study.tell(first[0], 7.25, replace=True)
    with StudyStore(tmp_path / "s.db", create=False) as store:
        ops = store.ops()
        waiting = store.outstanding()
    study.store.close()
    n = len(first)
    assert [type(op) for op in ops] == [Ask] + [Tell] * n + [Ask, Replace]
    assert ops[0].indices == tuple(ev.index for ev in first)
    assert ops[n + 1].indices == (second[0].index,)
    assert [(op.idx, op.hf, op.error) for op in ops[1:n + 1]] == [(ev.index, hf_of(ev), None)
                                                                 for ev in first]
    assert ops[-1] == Replace(idx=first[0].index, hf=7.25, error=None)
    assert waiting == [Outstanding(idx=second[0].index, hf=None, error=None, has_result=False)]


def test_record_tell_refuses_a_row_whose_result_is_not_the_stored_one(tmp_path):
    study = new_study(tmp_path / "s.db")
    a, b = study.ask()[:2]
    study.store.close()
    with StudyStore(tmp_path / "s.db", create=False) as store:
        store.ops()  # as a driver does before it writes
        row = {"row": 0, "hf": 3.0, "error": None}
        with pytest.raises(StoreError, match="holds no result; store the result first") as never:
            store.record_tell(a, row)          # pas 0.2.0 wrote the result here instead
        store.record_result(b, 4.0)
        with pytest.raises(StoreError, match=r"holds hf=4\.0.*never overwritten") as differs:
            store.record_tell(b, row)
        assert store.history() == [] and store.unconsumed() == [StoredResult(b.index, 4.0, None)]
    for exc in (never, differs):
        assert "\n" not in str(exc.value)


def test_a_python_replacement_is_on_disk_before_the_refit(tmp_path, monkeypatch):
    db = tmp_path / "s.db"
    study, first = told_study(db)

    def refit_dies(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(study, "_iterate", refit_dies)
    with pytest.raises(KeyboardInterrupt):
        study.tell(first[-1], 9.5, replace=True)
    study.store.close()
    with StudyStore(db, create=False) as store:
        assert store.unconsumed() == [StoredResult(first[-1].index, 9.5, None)]
    reopened = open_study(db)  # the next driver applies it
    assert reopened.rows[-1]["hf"] == 9.5 and reopened.rows[-1]["replaced_hf"] == hf_of(first[-1])
    reopened.store.close()
    with StudyStore(db, create=False) as store:
        assert store.unconsumed() == [] and len(store.replacements()) == 1


def test_a_replacement_by_the_stored_value_is_refused_before_the_study_changes(tmp_path):
    study, first = told_study(tmp_path / "s.db")
    n_rows = len(study.rows)
    with pytest.raises(StoreError, match="already holds this result"):
        study.tell(first[0], hf_of(first[0]), replace=True)
    assert len(study.rows) == n_rows
    study.store.close()


def test_waiting_replacements_are_applied_in_order_without_new_ones(tmp_path):
    db = tmp_path / "s.db"
    study, first = told_study(db)
    study.store.close()
    with StudyStore(db, create=False) as store:
        assert store.tell_by_key(first[0].id, 8.0, replace=True, source="basin")
        assert store.tell_by_key(first[0].id, 9.0, replace=True, source="basin")
    reopened = open_study(db)
    assert [r["hf"] for r in reopened.rows[-2:]] == [8.0, 9.0]
    reopened.store.close()
    with StudyStore(db, create=False) as store:
        trail = store.replacements()
        assert [(r["new_hf"], r["source"]) for r in trail] == [(8.0, "basin"), (9.0, "basin")]
        assert all(r["consumed_seq"] for r in trail) and store.unconsumed() == []


def test_refit_reads_replacements_in_the_log(tmp_path):
    """Reproduction: refit of a store holding a replacement raised "already told"."""
    db = tmp_path / "s.db"
    study = pas.Study(pas.LFSet(LF, n_waves=N, p_exp=1e-2),
                      pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                      stopping=pas.Stopping(eps1=1e-3), seed=2,
                      store=StudyStore(db), target="a")
    first = study.ask()
    for ev in first:
        study.tell(ev, {"a": 2.0 * ev.lf, "b": 3.0 * ev.lf})
    study.tell(first[0], 9.0, replace=True)            # applied: a Replace in the log
    study.store.close()
    with StudyStore(db, create=False) as store:
        store.tell_by_key(first[1].id, 7.0, replace=True)   # waiting for the next driver
    own, info = refit_study(db, "a")
    reopened = open_study(db)
    reopened.store.close()
    assert [r["hf"] for r in own.rows] == [r["hf"] for r in reopened.rows]
    assert [r["hf"] for r in own.rows][-2:] == [9.0, 7.0] and info["n_missing"] == 0
    other, _ = refit_study(db, "b")  # the replacements corrected load "a" alone
    assert [r["hf"] for r in other.rows] == pytest.approx([3.0 * ev.lf for ev in first], rel=1e-12)
