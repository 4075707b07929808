"""Study stores written by earlier pas versions still open, replay and continue.

``data/store_v1.sqlite`` was written by pas at commit 287a529 (schema 1, event
states stored as ``pending``/``done``/``false_positive``/``failed``) with::

    lf = np.random.default_rng(3).rayleigh(1.0, 300)
    oracle: call 3 raises RuntimeError("solver diverged"), call 7 returns 0.0,
            the others 2.0 * lf ** 1.2
    make_study(PAS, lf, n_waves=300, p_exp=0.01, eps1=0.01, seed=5, n_bootstrap=0,
               max_hf=12, store=path).optimize(oracle)
    make_study(..., max_hf=15, store=path).ask(2)  -> events 230 and 58 pending
    StudyStore(path).tell_by_key(230, 2.0 * lf[230] ** 1.2)   # stored, not yet consumed

The expected numbers below are what that version printed when it reopened
the file; they are not computed by the code under test.  They are fitted MPMs
from another machine, so they are compared to a relative ``REPLAY_RTOL``:
an optimiser amplifies last-bit libm/BLAS differences to about 1e-9.
"""

import json
import shutil
import sqlite3
from pathlib import Path

import pytest

from pas.strategies.estimators import ConditionalLikelihood
from pas.study import open_study

FIXTURE = Path(__file__).parents[1] / "data" / "store_v1.sqlite"
REPLAY_RTOL = 1e-7


@pytest.fixture()
def store_v1(tmp_path):
    path = tmp_path / "v1.sqlite"
    shutil.copy(FIXTURE, path)
    return path


def test_store_written_with_old_state_strings_replays(store_v1):
    with sqlite3.connect(store_v1) as c:
        states = dict(c.execute("SELECT idx, state FROM events").fetchall())
        stored_mpm = [r[0] for r in c.execute(
            "SELECT json_extract(data, '$.mpm') FROM history ORDER BY row")]
    assert sorted(set(states.values())) == ["done", "failed", "false_positive", "pending"]
    study = open_study(store_v1)
    try:
        assert (study.n_hf, study.n_failed, study.n_false_positive) == (13, 1, 1)
        assert len(study.rows) == 14                        # 13 stored + 1 consumed on open
        replayed = [r.get("mpm") for r in study.rows[:13]]
        assert [m is None for m in replayed] == [m is None for m in stored_mpm]
        assert [m for m in replayed if m is not None] == pytest.approx(
            [m for m in stored_mpm if m is not None], rel=REPLAY_RTOL)
        assert study.rows[-1]["mpm"] == pytest.approx(7.410337014024719, rel=REPLAY_RTOL)
        assert [ev.index for ev in study.pending] == [58]
        study.tell(58, 3.5)
        assert [ev.index for ev in study.ask(1)] == [46]
        assert study.rows[-1]["mpm"] == pytest.approx(7.07734006234522, rel=REPLAY_RTOL)
    finally:
        study.store.close()
    with sqlite3.connect(store_v1) as c:
        new = dict(c.execute("SELECT idx, state FROM events").fetchall())
    assert new[58] == "done" and new[230] == "done" and new[46] == "pending"


MAIN_FIXTURE = Path(__file__).parents[1] / "data" / "store_v0_1_main.sqlite"


def test_store_written_with_flat_settings_before_0_2_replays(tmp_path):
    """``data/store_v0_1_main.sqlite`` was written by pas at 0e65ed2 (the flat settings of
    every estimator, schema 2) with ``lf = default_rng(4).rayleigh(1.0, 400)``, call 3
    failing and call 6 a false positive, ``make_study(PAS, lf, n_waves=400, p_exp=0.01,
    eps1=0.01, seed=5, n_bootstrap=0, hf_marginal="both", max_hf=12, store=path)
    .optimize(oracle)``, then with ``max_hf=15`` two asks (14, 140) and the result of 14
    told to the store (the file copied then, by SQLite's backup).  The numbers are what
    that version printed on reopening the file, not computed by the code under test."""
    path = tmp_path / "main.sqlite"
    shutil.copy(MAIN_FIXTURE, path)
    study = open_study(path)
    try:
        assert study.strategy.estimator == ConditionalLikelihood(hf_marginal="both")
        assert study.strategy.band.n_bootstrap == 0 and study.max_hf == 15
        assert (study.n_hf, study.n_failed, study.n_false_positive, len(study.rows)) == \
            (13, 1, 1, 14)
        assert study.rows[-1]["mpm"] == pytest.approx(7.734405376587492, rel=REPLAY_RTOL)
        assert [ev.index for ev in study.pending] == [140]
        study.tell(140, 3.5)
        assert [ev.index for ev in study.ask(1)] == [2]
        assert study.rows[-1]["mpm"] == pytest.approx(7.753284251491003, rel=REPLAY_RTOL)
    finally:
        study.store.close()
    # the stored flat settings are read, not rewritten: the file still opens in 0.1
    with sqlite3.connect(path) as c:
        stored = json.loads(
            c.execute("SELECT value FROM meta WHERE key = 'settings'").fetchone()[0]
        )
    assert stored["strategy_settings"]["copula_fit"] == "mle"
