"""Design waves on the study machinery: the store, reruns, retries, corrections, refusals.

:func:`pas.run_rcw` runs the episodes of its ladder as the events of a study
(:class:`pas.design_waves.DesignWaveStudy`), so a study store keeps every HF
result, a rerun evaluates nothing twice and the corrections of PAS apply.
"""

import json
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import pas
from pas.study.resume import open_study
from pas.study.schema import StoreError
from pas.waves import jonswap, response_surrogate

LEVELS = [1e-2, 3e-3, 5e-4]
P_EXP = 1e-3


@pytest.fixture(scope="module")
def linear():
    return response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: np.ones_like(w),
                              duration=300.0, depth=30.0, omega_max=2.0, second_order=False)


class Counting:
    """``factor × target`` of every episode, remembering the levels it was called at."""

    def __init__(self, factor=1.3):
        self.factor, self.levels = factor, []

    def __call__(self, ep):
        self.levels.append(ep.level)
        return self.factor * ep.target


def test_a_rerun_on_the_study_store_takes_every_result_from_it(linear, tmp_path):
    path = tmp_path / "rcw.sqlite"
    first, seen = Counting(), []
    res = pas.run_rcw(linear, first, p_exp=P_EXP, levels=LEVELS, study=path,
                      callback=lambda ep, row: seen.append((ep.level, row["f_nl"], row["n_hf"])))
    assert first.levels == [1e-2, 3e-3, 1e-3, 5e-4] and res.n_hf == 4 and res.converged
    assert [s[0] for s in seen] == first.levels and [s[2] for s in seen] == [1, 2, 3, 4]
    assert np.allclose([s[1] for s in seen], 0.3)
    memory = pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS)
    assert res.mpm == pytest.approx(memory.mpm, rel=1e-12)
    events = pas.StudyStore(path).events()
    assert list(events["event_id"]) == list(res.history["episode_id"])
    assert events["meta"][2] == {"level": P_EXP, "target": pytest.approx(res.history["target"][2])}
    again = Counting(factor=99.0)  # would give other numbers, were it called
    back = pas.run_rcw(linear, again, p_exp=P_EXP, levels=LEVELS, study=path)
    assert again.levels == [] and back.mpm == res.mpm
    assert list(back.history.columns) == list(res.history.columns)
    assert list(back.history["hf"]) == list(res.history["hf"])


def test_other_episodes_or_method_are_refused_by_the_store(linear, tmp_path):
    path = tmp_path / "rcw.sqlite"
    pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS, study=path)
    with pytest.raises(StoreError, match="strategy differs.*rcw.*mler"):
        pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS, method="mler", study=path)
    with pytest.raises(StoreError, match="lf_peaks differ"):
        pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS[:2], study=path)
    with pytest.raises(StoreError, match=r"pas.run_rcw\(\.\.\., study="):
        open_study(path)  # the pas study commands cannot rebuild the episodes


def test_a_result_corrected_in_the_store_replaces_the_told_one(linear, tmp_path):
    path = tmp_path / "rcw.sqlite"
    res = pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS, study=path)
    episode = res.history["episode_id"][2]  # the P_exp episode
    with pas.StudyStore(path) as store:  # what 'pas study tell --replace' does
        assert store.tell_by_key(episode, 7.5, replace=True)
    oracle = Counting()
    fixed = pas.run_rcw(linear, oracle, p_exp=P_EXP, levels=LEVELS, study=path)
    assert oracle.levels == [] and fixed.mpm == 7.5 and fixed.n_hf == 4
    assert list(fixed.history["hf"])[:2] == list(res.history["hf"])[:2]
    assert fixed.distribution.set_index("exceedance_probability").at[P_EXP, "h_mean"] == 7.5


def test_failed_episodes_rerun_only_with_retry_failed(linear, tmp_path):
    path = tmp_path / "rcw.sqlite"

    def broken(ep):
        if ep.level == 3e-3:
            raise RuntimeError("mesh failed")
        return 2.0 * ep.target

    res = pas.run_rcw(linear, broken, p_exp=P_EXP, levels=LEVELS, study=path)
    assert res.n_failed == 1 and res.n_hf == 3 and not res.converged
    assert pas.run_rcw(linear, broken, p_exp=P_EXP, levels=LEVELS, study=path).n_failed == 1
    fixed = Counting(2.0)
    done = pas.run_rcw(linear, fixed, p_exp=P_EXP, levels=LEVELS, study=path, retry_failed=True)
    assert fixed.levels == [3e-3] and done.n_failed == 0 and done.n_hf == 4 and done.converged
    assert done.mpm == pytest.approx(res.mpm, rel=1e-12)


def test_a_record_file_of_pas_0_1_is_imported_into_the_study(linear, tmp_path):
    ids = pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS).history["episode_id"]
    record = tmp_path / "rcw.jsonl"
    # as 0.1 wrote it: one line per result, failures with their error
    lines = [{"episode_id": ids[0], "level": 1e-2, "target": 1.0, "hf": 11.0, "error": None},
             {"episode_id": ids[1], "level": 3e-3, "target": 1.0, "hf": None, "error": "boom"}]
    record.write_text("".join(json.dumps(rec) + "\n" for rec in lines))
    oracle = Counting()
    res = pas.run_rcw(linear, oracle, p_exp=P_EXP, levels=LEVELS, study=tmp_path / "s.sqlite",
                      record=record)
    assert oracle.levels == [3e-3, 1e-3, 5e-4]  # the failed one runs again
    assert res.history["hf"][0] == 11.0 and res.n_failed == 0
    stored = pas.StudyStore(tmp_path / "s.sqlite").events()
    assert stored["hf"][0] == 11.0
    record.write_text('{"level": 0.01}\n')
    with pytest.raises(ValueError, match="line 1 .* is not a pas 0.1 record"):
        pas.run_rcw(linear, oracle, p_exp=P_EXP, study=tmp_path / "t.sqlite", record=record)


def test_renamed_and_misplaced_options_give_one_line_errors(linear, tmp_path):
    for old in ("rayleigh", "lf", [1.0, 2.0]):
        with pytest.raises(ValueError, match="linear_target=") as err:
            pas.run_rcw(linear, Counting(), p_exp=P_EXP, target=old)
        assert "\n" not in str(err.value)
    with pytest.raises(ValueError, match="study='rcw.sqlite'"):
        pas.run_rcw(linear, Counting(), p_exp=P_EXP, record=tmp_path / "rcw.jsonl")
    with pytest.raises(ValueError, match="retry_failed=True needs study="):
        pas.run_rcw(linear, Counting(), p_exp=P_EXP, retry_failed=True)
    path = tmp_path / "rcw.sqlite"
    with pytest.raises(TypeError, match="oracle must be a callable"):
        pas.run_rcw(linear, 3.0, p_exp=P_EXP, study=path)
    assert not path.exists()  # refused before a store was written


def test_target_picks_the_load_of_a_multi_load_oracle(linear, tmp_path):
    def loads(ep):
        return {"panel": 2.0 * ep.target, "frame": 5.0 * ep.target}

    res = pas.run_rcw(linear, loads, p_exp=P_EXP, levels=LEVELS, target="frame",
                      study=tmp_path / "rcw.sqlite")
    assert np.allclose(res.distribution["f_nl"], 4.0)
    with pytest.raises(ValueError, match="target"):
        pas.run_rcw(linear, loads, p_exp=P_EXP)


def test_an_executor_runs_the_ladder_with_the_same_result(linear):
    oracle = Counting()
    with ThreadPoolExecutor(2) as pool:
        res = pas.run_rcw(linear, oracle, p_exp=P_EXP, levels=LEVELS, executor=pool)
    assert sorted(oracle.levels) == sorted([*LEVELS, P_EXP])
    serial = pas.run_rcw(linear, Counting(), p_exp=P_EXP, levels=LEVELS)
    assert list(res.history["hf"]) == pytest.approx(list(serial.history["hf"]), rel=1e-12)
