"""The SQLite study store: resume after SIGKILL, pending policies, schema and settings checks."""

import multiprocessing as mp
import os
import signal
import sqlite3
import time
from collections import Counter

import _campaign
import numpy as np
import pytest

import pas
from pas import PAS, ModelBand, SelectedSample, Stopping
from pas.study.store import SCHEMA_VERSION, StoreConflict, StoreError, StudyStore

LF = np.random.default_rng(0).rayleigh(1.0, 2000)
KW = dict(n_waves=2000, p_exp=1e-2, eps1=1e-4, seed=5, max_hf=20)
NO_BAND = PAS(band=ModelBand(n_bootstrap=0))


def hf(ev):
    return float(_campaign.oracle_value(ev.lf, ev.index))


class Crash(BaseException):
    """Stands in for the process dying inside the oracle (not an oracle failure)."""


class CrashingOracle:
    def __init__(self, at):
        self.at, self.calls = at, []

    def __call__(self, ev):
        if len(self.calls) == self.at:
            raise Crash
        self.calls.append(ev.index)
        return hf(ev)


def _n_results(db):
    if not os.path.exists(db):
        return 0
    try:
        with sqlite3.connect(db, timeout=10) as c:
            return c.execute("SELECT COUNT(*) FROM events WHERE result_seq IS NOT NULL").fetchone()[
                0
            ]
    except sqlite3.OperationalError:
        return 0


@pytest.mark.slow
def test_store_records_everything_and_resume_is_a_no_op(tmp_path):
    db = str(tmp_path / "s.db")
    ref = pas.run_pas(LF, hf, strategy=NO_BAND, **KW)
    res = pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **KW)
    again = pas.run_pas(LF, lambda ev: pytest.fail("finished event re-run"), strategy=NO_BAND,
                        study=db, **KW)
    assert res.mpm == ref.mpm == again.mpm
    assert list(again.history["event_index"]) == list(ref.history["event_index"])
    with StudyStore(db, create=False) as store:
        ev = store.events()
        assert len(ev) == 20 and set(ev["state"]) == {"done"} and (ev["attempts"] == 1).all()
        assert ev["tell_seq"].notna().all() and ev["result_seq"].notna().all()
        rows = store.history()
        assert [r["event_index"] for r in rows] == list(ref.history["event_index"])
        assert rows[-1]["mpm"] == ref.mpm
        assert store.settings()["seed"] == 5 and store.settings()["strategy_settings"]["z"] == 10
        for table in ("meta", "lf_peaks", "events", "history"):  # JSON and numbers, no pickles
            for col in [r[1] for r in store._conn.execute(f"PRAGMA table_info({table})")]:
                assert not store._conn.execute(
                    f"SELECT COUNT(*) FROM {table} WHERE typeof({col}) = 'blob'").fetchone()[0]


@pytest.mark.parametrize("batch_size,crash_at", [(1, 9), (4, 9), (4, 6)])
def test_resubmit_after_crash_matches_uninterrupted(tmp_path, batch_size, crash_at):
    db = str(tmp_path / "s.db")
    ref = pas.run_pas(LF, hf, strategy=NO_BAND, batch_size=batch_size, **KW)
    first = CrashingOracle(crash_at)
    with pytest.raises(Crash):
        pas.run_pas(LF, first, strategy=NO_BAND, study=db, batch_size=batch_size, **KW)
    with StudyStore(db, create=False) as store:
        assert (store.events()["state"] == "pending").sum() >= 1
    second = CrashingOracle(10**6)
    res = pas.run_pas(LF, second, strategy=NO_BAND, study=db, batch_size=batch_size, **KW)
    assert not set(first.calls) & set(second.calls)  # nothing finished is run twice
    assert len(first.calls) + len(second.calls) == res.n_hf == 20
    assert res.mpm == ref.mpm
    assert list(res.history["event_index"]) == list(ref.history["event_index"])
    np.testing.assert_array_equal(res.history["mpm"], ref.history["mpm"])


def test_pending_wait_leaves_event_for_tell(tmp_path):
    db = str(tmp_path / "s.db")
    with pytest.raises(Crash):
        pas.run_pas(LF, CrashingOracle(8), strategy=NO_BAND, study=db, **KW)
    with StudyStore(db, create=False) as store:
        waiting = store.events().query("state == 'pending'")
    (idx,) = waiting["idx"]
    second = CrashingOracle(10**6)
    pas.make_study(NO_BAND, LF, store=db, **{**KW, "max_hf": 12}).optimize(second, pending="wait")
    assert idx not in second.calls
    with StudyStore(db, create=False) as store:
        ev = store.events().set_index("idx")
        assert ev.loc[idx, "state"] == "pending" and ev.loc[idx, "attempts"] == 1
        store.tell_by_key(ev.loc[idx, "key"], 1.5)
    res = pas.make_study(NO_BAND, LF, store=db, **{**KW, "max_hf": 14}).optimize(
        CrashingOracle(10**6), pending="wait")
    assert res.n_hf == 14
    assert 1.5 in set(res.history["hf"])


def test_settings_and_peaks_must_match(tmp_path):
    db = str(tmp_path / "s.db")
    pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **{**KW, "max_hf": 6})
    with pytest.raises(StoreError, match="p_exp"):
        pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **{**KW, "p_exp": 2e-2})
    with pytest.raises(StoreError, match="threshold"):
        pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **{**KW, "threshold": 0.1})
    with pytest.raises(StoreError, match="z differs"):
        pas.run_pas(LF, hf, strategy=PAS(z=20, band=ModelBand(n_bootstrap=0)), study=db, **KW)
    with pytest.raises(StoreError, match="seed"):
        pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **{**KW, "seed": 6})
    lf2 = LF.copy()
    lf2[3] += 1e-9
    with pytest.raises(StoreError, match="lf_peaks differ"):
        pas.run_pas(lf2, hf, strategy=NO_BAND, study=db, **KW)
    # a budget may grow; seed=None takes the stored seed
    res = pas.run_pas(LF, hf, strategy=NO_BAND, study=db, **{**KW, "max_hf": 8, "seed": None})
    assert res.n_hf == 8 and res.seed == 5


def test_newer_schema_is_refused(tmp_path):
    db = str(tmp_path / "s.db")
    StudyStore(db).close()
    with sqlite3.connect(db) as c:
        c.execute(f"PRAGMA user_version={SCHEMA_VERSION + 1}")
    with pytest.raises(StoreError, match=f"schema version {SCHEMA_VERSION + 1}.*upgrade pas"):
        StudyStore(db)
    (tmp_path / "junk.db").write_text("not a database at all" * 100)
    with pytest.raises(StoreError, match="junk.db"):
        StudyStore(tmp_path / "junk.db")


def test_two_drivers_conflict(tmp_path):
    db = str(tmp_path / "s.db")
    a = pas.make_study(NO_BAND, LF, store=db, **KW)
    b = pas.make_study(NO_BAND, LF, store=db, **KW)
    for ev in a.ask():
        a.tell(ev, hf(ev))
    with pytest.raises(StoreConflict, match="another process"):
        b.ask()


@pytest.mark.slow
def test_sigkill_resume_loses_nothing_and_reruns_nothing(tmp_path):
    """SIGKILL a command-oracle campaign 8 times at random points, then finish it."""
    script = _campaign.write_script(tmp_path)
    ref_log = str(tmp_path / "ref.log")
    ref = _campaign.campaign(str(tmp_path / "ref.db"), str(tmp_path / "ref"), ref_log, script)

    db, root, log = str(tmp_path / "k.db"), str(tmp_path / "runs"), str(tmp_path / "k.log")
    ctx = mp.get_context("forkserver")
    ctx.set_forkserver_preload(["pas", "_campaign"])
    rng = np.random.default_rng(2)
    kills = 0
    while kills < 8:
        p = ctx.Process(target=_campaign.campaign, args=(db, root, log, script))
        p.start()
        base, deadline = _n_results(db), time.monotonic() + 60
        while _n_results(db) <= base and p.is_alive() and time.monotonic() < deadline:
            time.sleep(0.005)
        time.sleep(rng.uniform(0.0, 0.1))
        if not p.is_alive():
            break
        os.kill(p.pid, signal.SIGKILL)
        p.join()
        kills += 1
    assert kills == 8, "the campaign finished before 8 kills; shorten the delays"
    res = _campaign.campaign(db, root, log, script)

    completed = Counter(open(log).read().split())
    assert max(completed.values()) == 1, (
        f"re-run events: {[k for k, v in completed.items() if v > 1]}"
    )
    with StudyStore(db, create=False) as store:
        ev = store.events()
    assert len(ev) == 25 and set(ev["state"]) == {"done"}
    assert set(completed) == set(ev["key"])  # every completed HF run is stored
    np.testing.assert_array_equal(ev["hf"], _campaign.oracle_value(ev["lf"], ev["idx"]))
    assert res.mpm == ref.mpm
    assert list(res.history["event_id"]) == list(ref.history["event_id"])
    np.testing.assert_array_equal(res.history["mpm"], ref.history["mpm"])
    assert sorted(open(ref_log).read().split()) == sorted(completed)


def test_resume_after_unusable_indicator_warning(tmp_path):
    # a fit with tau <= 0 during replay must not break the resume
    import warnings

    rng = np.random.default_rng(0)
    lf = rng.rayleigh(3.0, 3000)
    hf = 1.0 / lf + rng.uniform(0, 0.01, 3000)
    kw = dict(n_waves=3000, p_exp=1e-2, eps1=1e-9, seed=0, max_hf=12, strategy=NO_BAND,
              study=str(tmp_path / "s.db"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = pas.run_pas(lf, lambda ev: float(hf[ev.index]), **kw)
        again = pas.run_pas(lf, lambda ev: float(hf[ev.index]), **kw)
    assert again.mpm == first.mpm and again.n_hf == first.n_hf == 12


# eps1 = 0.05 converges after 12 HF evaluations on this problem, 0.03 after 15 (with the
# per-step measure and redrawn uniforms, whose noise makes eps1 matter here)
STOP = dict(n_waves=2000, p_exp=1e-2, seed=5, max_hf=60,
            strategy=PAS(estimator=SelectedSample(), common_random_numbers=False,
                         band=ModelBand(n_bootstrap=0)))


def step_rule(eps1, **given):
    """The stopping rule of these tests: the per-step measure (Eq. 28) over windows of 6."""
    return Stopping(**{"eps1": eps1, "k1": 6, "k2": 6, "measure": "step", **given})


@pytest.mark.parametrize("batch_size", [1, 2])
def test_resume_with_a_tighter_eps1_asks_what_an_uninterrupted_run_asks(tmp_path, batch_size):
    db = str(tmp_path / "s.db")
    loose = pas.run_pas(LF, hf, study=db, stopping=step_rule(0.05), batch_size=batch_size, **STOP)
    ref = pas.run_pas(LF, hf, stopping=step_rule(0.03), batch_size=batch_size, **STOP)
    assert loose.converged and ref.converged and ref.n_hf > loose.n_hf  # the test has teeth
    calls = []
    res = pas.run_pas(LF, lambda ev: calls.append(ev.index) or hf(ev), study=db,
                      stopping=step_rule(0.03), batch_size=batch_size, **STOP)
    assert list(res.history["event_index"]) == list(ref.history["event_index"])
    assert res.mpm == ref.mpm and res.converged
    assert len(calls) == ref.n_hf - loose.n_hf  # only the new events ran
    # the stopping columns are those of the new limit, from the first iteration on
    np.testing.assert_array_equal(res.history["stop"].eq(True), ref.history["stop"].eq(True))
    with StudyStore(db, create=False) as store:
        assert store.settings()["eps1"] == 0.03
        (change,) = store.get("settings_changes")
        assert (change["key"], change["old"], change["new"]) == ("eps1", 0.05, 0.03)
        assert change["n_told"] == loose.n_hf + loose.n_failed


def test_resume_with_looser_limits_or_smaller_budget_keeps_what_was_done(tmp_path):
    db = str(tmp_path / "s.db")
    tight = pas.run_pas(LF, hf, study=db, stopping=step_rule(0.03), **STOP)
    no_call = lambda ev: pytest.fail("a finished study asked for more")  # noqa: E731
    # the looser limit would have stopped earlier; the evaluated events stay, nothing new runs
    res = pas.run_pas(LF, no_call, study=db, stopping=step_rule(0.05, k1=5, eps2=0.2), **STOP)
    assert res.n_hf == tight.n_hf and res.converged
    assert list(res.history["event_index"]) == list(tight.history["event_index"])
    res = pas.run_pas(LF, no_call, study=db, stopping=step_rule(0.03), **{**STOP, "max_hf": 8})
    assert res.n_hf == tight.n_hf
    with StudyStore(db, create=False) as store:
        keys = [c["key"] for c in store.get("settings_changes")]
    assert keys == ["eps1", "eps2", "k1", "eps1", "eps2", "k1", "max_hf"]
