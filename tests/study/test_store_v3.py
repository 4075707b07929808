"""Schema 3: every study table scoped by a study key; stores of version 2 upgrade in place.

``data/store_v2.sqlite`` was written by pas at commit 0e65ed2 (schema 2) with::

    lf = np.random.default_rng(3).rayleigh(1.0, 300)
    oracle: call 3 raises RuntimeError("solver diverged"), the others answer
            {"hf": 2.0 * lf ** 1.2, "other": lf}
    make_study(PAS, lf, n_waves=300, p_exp=0.01, eps1=0.01, seed=5, n_bootstrap=0,
               max_hf=10, target="hf", store=path).optimize(oracle)
    StudyStore(path).tell_by_key(<first asked event>, 1.23, replace=True)
    make_study(..., max_hf=12, ...): retry_failed(), optimize(oracle), result()

so every table holds rows (a replacement, dropped asks, named loads, stored
results).  The history rows stored then are what the replay must reproduce.
"""

import json
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest

import pas
from pas.study import open_study
from pas.study.store import SCHEMA_VERSION, StudyStore

FIXTURE = Path(__file__).parents[1] / "data" / "store_v2.sqlite"
TABLES = ("meta", "lf_peaks", "events", "history", "replacements", "dropped", "event_loads",
          "results")
REPLAY_RTOL = 1e-7


def _counts(path):
    with sqlite3.connect(path) as c:
        return {t: c.execute(f"SELECT COUNT(*) FROM {t}").fetchone()[0] for t in TABLES}


@pytest.fixture()
def store_v2(tmp_path):
    path = tmp_path / "v2.sqlite"
    shutil.copy(FIXTURE, path)
    return path


def test_a_version_2_store_upgrades_keeping_every_row_and_replays(store_v2):
    before = _counts(store_v2)
    with sqlite3.connect(store_v2) as c:
        assert c.execute("PRAGMA user_version").fetchone()[0] == 2
        stored = [json.loads(r[0]).get("mpm") for r in
                  c.execute("SELECT data FROM history ORDER BY row")]
    study = open_study(store_v2)
    try:
        replayed = [r.get("mpm") for r in study.rows]
        assert [m is None for m in replayed] == [m is None for m in stored]
        assert [m for m in replayed if m is not None] == pytest.approx(
            [m for m in stored if m is not None], rel=REPLAY_RTOL)
        assert len(study.store.replacements()) == 1
        assert len(study.store.dropped()) == before["dropped"]
        assert "study" not in study.store.events().columns
    finally:
        study.store.close()
    after = _counts(store_v2)
    with sqlite3.connect(store_v2) as c:
        assert c.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION == 3
        scopes = {t: {r[0] for r in c.execute(f"SELECT DISTINCT study FROM {t}")}
                  for t in TABLES}
        assert c.execute("PRAGMA foreign_key_check").fetchall() == []
    assert after == before  # the replay consumed nothing new: only the scope was added
    assert all(s == {""} for s in scopes.values())


def test_studies_in_one_file_do_not_see_each_other(tmp_path):
    path = tmp_path / "two.sqlite"
    rng = np.random.default_rng(0)
    lfs = {"a": rng.rayleigh(1.0, 200), "b": rng.rayleigh(2.0, 300)}
    studies = {k: pas.Study(pas.LFSet(v, n_waves=v.size, p_exp=0.02, sea_state=k), pas.PAS(
        band=pas.ModelBand(n_bootstrap=0)), stopping=pas.Stopping(eps1=0.01), seed=1,
        store=StudyStore(path, scope=k))
        for k, v in lfs.items()}
    for k, st in studies.items():
        for ev in st.ask():
            assert ev.sea_state == k
            st.tell(ev, 2.0 * ev.lf)
    told = {k: [r["event_index"] for r in st.rows] for k, st in studies.items()}
    for st in studies.values():
        st.store.close()
    for k, v in lfs.items():
        with StudyStore(path, scope=k) as store:
            assert [r["event_index"] for r in store.history()] == told[k]
            assert store.settings()["n_waves"] == v.size
            assert store.lf_inputs().lf_peaks.size == v.size
    with StudyStore(path) as root:  # the single-study scope is empty
        assert root.is_new and root.history() == []
