"""pas.run_long_term on a user-supplied problem whose long-term truth is known in closed form."""

from concurrent.futures import ThreadPoolExecutor
from types import SimpleNamespace

import _longterm_problem as problem
import numpy as np
import pandas as pd
import pytest

import pas
from pas.longterm.allocation import REACH_SHARE
from pas.longterm.inputs import SeaState
from pas.longterm.runner import _Run
from pas.study import open_study
from pas.study.store import StoreError

P = 1e-3
N_CACHE = 2000
FAST = dict(
    p_exceed=P, seed=4, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)), model_band=False
)


def _small(seed=1):
    return problem.table(n_waves=2000), problem.lf_peaks(seed, n_waves=2000)


@pytest.mark.slow
@pytest.mark.parametrize("g, tolerance", [(problem.hf_smooth, 0.05), (problem.hf_impact, 0.10)])
def test_value_and_band_against_the_closed_form_truth(g, tolerance):
    truth = problem.true_value(P, g)
    res = pas.run_long_term(problem.table(), problem.lf_peaks(3), problem.Oracle(g), p_exceed=P,
                            max_hf=30, seed=5, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=20)))
    assert res.value == pytest.approx(truth, rel=tolerance)
    assert res.band[0] <= truth <= res.band[1]
    assert res.n_hf == res.contributions["n_hf"].sum() <= 30
    d = res.distribution
    assert d["exceedance_probability"].is_monotonic_increasing
    assert (d["h_low"] <= d["h_mean"]).all() and (d["h_mean"] <= d["h_high"]).all()
    at_p = d.loc[np.isclose(d["exceedance_probability"], P, rtol=1e-12), "h_mean"]
    assert at_p.iloc[0] == pytest.approx(res.value, rel=1e-9)


def test_sea_states_that_cannot_reach_the_level_get_no_hf_event():
    table, lf = _small()
    oracle = problem.Oracle()
    res = pas.run_long_term(table, lf, oracle, max_hf=8, **FAST)
    c = res.contributions.set_index("sea_state")
    x = problem.true_lf_level(P)
    lf_share = problem.weights() * np.exp(-x ** 2 / (2 * problem.SIGMA ** 2)) / P
    # H0 and H1 lie orders of magnitude below the reach share: no study, no HF event
    assert (lf_share[:2] < REACH_SHARE / 100).all()
    assert (c.loc[["H0", "H1"], "n_hf"] == 0).all()
    assert c.loc[["H0", "H1"], "p_exp"].isna().all()
    assert {s for s, _ in oracle.calls} <= {"H2", "H3", "H4"}
    assert len(oracle.calls) == res.n_hf == c["n_hf"].sum() <= 8
    assert c["share"].sum() == pytest.approx(1.0, rel=1e-9)
    assert "long-term value" in res.summary()
    # the studies screen down below the design level: the proxy below their ranges is not read
    assert set(c.loc[c["n_hf"] > 0, "read_off"]) <= {"pas", "tail"}
    assert res.extension_bounds == pytest.approx((res.value, res.value), rel=1e-9)


def test_a_table_oracle_keys_on_sea_state_and_event_id():
    table, lf = _small()
    rows = [{"sea_state": name, "id": i, "hf": float(problem.hf_smooth(v))}
            for name, values in lf.items() for i, v in enumerate(values)]
    oracle = pas.TableOracle(pd.DataFrame(rows))  # ids 0..1999 repeat in every sea state
    by_table = pas.run_long_term(table, lf, oracle, max_hf=8, **FAST)
    by_function = pas.run_long_term(table, lf, problem.Oracle(), max_hf=8, **FAST)
    assert by_table.value == pytest.approx(by_function.value, rel=1e-9)
    for r in by_table.results.values():
        assert r.pairs["hf"].to_numpy() == pytest.approx(
            problem.hf_smooth(r.pairs["lf"].to_numpy()), rel=1e-12)


@pytest.mark.slow
def test_resumed_analysis_asks_nothing_twice_and_ends_as_an_uninterrupted_one(tmp_path):
    table, lf = _small()
    db = tmp_path / "long.sqlite"
    oracle = problem.Oracle()
    pas.run_long_term(table, lf, oracle, max_hf=8, study=db, **FAST)
    first = list(oracle.calls)
    resumed = pas.run_long_term(table, lf, oracle, max_hf=12, study=db, **FAST)
    assert len(oracle.calls) == len(set(oracle.calls)) == 12
    assert oracle.calls[:8] == first
    fresh = pas.run_long_term(table, lf, problem.Oracle(), max_hf=12, **FAST)
    assert resumed.value == pytest.approx(fresh.value, rel=1e-9)  # same code, same machine
    again = problem.Oracle()
    pas.run_long_term(table, lf, again, max_hf=12, study=db, **FAST)
    assert again.calls == []
    with pytest.raises(StoreError, match="p_exceed differs from the long-term store"):
        pas.run_long_term(table, lf, again, max_hf=12, study=db, **{**FAST, "p_exceed": 2e-3})
    with pytest.raises(StoreError, match="seed differs"):
        pas.run_long_term(table, lf, again, max_hf=12, study=db, **{**FAST, "seed": 5})
    with pytest.raises(StoreError, match="holds no single study but a long-term analysis"):
        open_study(db)
    one = open_study(pas.StudyStore(db, scope="H4"))  # one sea state's study on its own
    assert one.n_hf == resumed.contributions.set_index("sea_state").loc["H4", "n_hf"]
    assert one.lfset.event(0).sea_state == "H4"
    one.store.close()
    single = tmp_path / "single.sqlite"
    pas.make_study(
        pas.PAS, lf["H4"], n_waves=2000, p_exp=0.01, eps1=0.1, store=single
    ).store.close()
    with pytest.raises(StoreError, match="holds a single study, not a long-term analysis"):
        pas.run_long_term(table, lf, again, max_hf=12, study=single, **FAST)


def test_sea_states_run_in_parallel_on_an_executor():
    table, lf = _small()
    oracle = problem.Oracle()
    with ThreadPoolExecutor(2) as pool:
        res = pas.run_long_term(table, lf, oracle, max_hf=8, batch_size=2, executor=pool, **FAST)
    assert len({s for s, _ in oracle.calls[:8]}) == 2  # the first round serves two sea states
    serial = pas.run_long_term(table, lf, problem.Oracle(), max_hf=8, batch_size=2, **FAST)
    assert res.value == pytest.approx(serial.value, rel=1e-9)


KILLED_RUN = """
import os, sys, time
sys.path.insert(0, {tests!r})
import pas
import _longterm_problem as problem

class SlowAfter(problem.Oracle):
    def __call__(self, event):
        if os.path.exists({log!r}) and len(open({log!r}).read().split("\\n")) > {n_before}:
            time.sleep(120)  # killed here
        value = super().__call__(event)
        with open({log!r}, "a") as f:
            f.write(f"{{event.sea_state}} {{event.index}}\\n")
        return value

pas.run_long_term(problem.table(n_waves=2000), problem.lf_peaks(1, n_waves=2000), SlowAfter(),
                  p_exceed={p}, seed=4, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                  model_band=False,
                  max_hf=12, study={db!r})
"""


@pytest.mark.slow
def test_kill_9_mid_campaign_then_resume_loses_nothing_and_asks_nothing_twice(tmp_path):
    import os
    import subprocess
    import sys
    import time
    from pathlib import Path

    log, db, n_before = tmp_path / "done.log", tmp_path / "long.sqlite", 6
    script = tmp_path / "run.py"
    script.write_text(KILLED_RUN.format(tests=str(Path(__file__).parents[1]), log=str(log),
                                        n_before=n_before, p=P, db=str(db)))
    env = {**os.environ, "PYTHONPATH": str(Path(pas.__file__).resolve().parents[1])}
    proc = subprocess.Popen([sys.executable, str(script)], env=env)
    deadline = time.monotonic() + 300
    while not (log.exists() and len(log.read_text().split()) >= 2 * n_before):
        assert proc.poll() is None and time.monotonic() < deadline
        time.sleep(0.2)
    time.sleep(1.0)  # the next HF run is in flight now
    proc.kill()
    proc.wait(timeout=30)
    done = [tuple(line.split()) for line in log.read_text().splitlines()]
    done = [(s, int(i)) for s, i in done]
    assert len(done) == n_before
    table, lf = _small()
    oracle = problem.Oracle()
    resumed = pas.run_long_term(table, lf, oracle, max_hf=12, study=db, **FAST)
    assert not set(oracle.calls) & set(done)  # no stored result computed again
    assert len(set(oracle.calls) | set(done)) == len(oracle.calls) + len(done) == 12
    fresh = pas.run_long_term(table, lf, problem.Oracle(), max_hf=12, **FAST)
    assert resumed.value == pytest.approx(fresh.value, rel=1e-9)
    assert resumed.contributions["n_hf"].tolist() == fresh.contributions["n_hf"].tolist()


@pytest.mark.slow
def test_sea_states_in_parallel_on_a_dask_cluster_with_a_store(tmp_path):
    distributed = pytest.importorskip("distributed")
    table, lf = _small()
    serial = pas.run_long_term(table, lf, problem.Oracle(), max_hf=8, batch_size=2, **FAST)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = pas.run_long_term(table, lf, problem.Oracle(), max_hf=8, batch_size=2,
                                executor=client.get_executor(), study=tmp_path / "d.sqlite",
                                **FAST)
    assert res.value == pytest.approx(serial.value, rel=1e-9)
    assert res.contributions["n_hf"].tolist() == serial.contributions["n_hf"].tolist()


class _FailsOnce(problem.Oracle):
    def __call__(self, event):
        if not self.calls:  # the first HF run diverges
            self.calls.append(("failed", -1))
            raise RuntimeError("solver diverged")
        return super().__call__(event)


@pytest.mark.slow
def test_a_failure_limit_names_the_sea_state_and_a_retry_runs_the_failed_event(tmp_path):
    table, lf = _small()
    db = tmp_path / "long.sqlite"
    kw = {**FAST, "study_settings": {"max_failures": 0}, "study": db}
    with pytest.raises(pas.OracleFailureLimit, match=r"sea state H\d: the HF oracle failed 1"):
        pas.run_long_term(table, lf, _FailsOnce(), max_hf=8, **kw)
    oracle = problem.Oracle()
    res = pas.run_long_term(table, lf, oracle, max_hf=8, retry_failed=True, **kw)
    assert res.contributions["n_failed"].sum() == 0 and res.n_hf == 8
    assert len(oracle.calls) == len(set(oracle.calls))
    with pytest.raises(ValueError, match="retry_failed=True needs study"):
        pas.run_long_term(table, lf, oracle, max_hf=8, retry_failed=True, **FAST)


def test_a_sea_states_curves_are_rebuilt_only_when_its_fit_or_the_proxy_ratios_change():
    d = np.arange(1, 51) / N_CACHE
    h = 1.5 * np.sqrt(-2 * np.log(d))

    def fit():
        return SimpleNamespace(d=d, h_mean=h, h_low=0.9 * h, h_high=1.1 * h, mpm=h[5],
                               columns={"lf": h})

    states = [SeaState(name, 0.5, N_CACHE, 8.0 * N_CACHE,
                       np.random.default_rng(i).rayleigh(sigma, N_CACHE))
              for i, (name, sigma) in enumerate((("a", 1.0), ("b", 1.5)))]
    fitted, unfitted = SimpleNamespace(last=fit()), SimpleNamespace(last=None)
    run = _Run(states, [0.5, 0.5], [fitted, unfitted], None, None, None, 10)
    first = [run.curves(i, (1.0, 1.0, 1.0)) for i in (0, 1)]
    assert all(run.curves(i, (1.0, 1.0, 1.0)) is first[i] for i in (0, 1))
    assert run.curves(0, (0.5, 2.0, 3.0)) is first[0]        # a fit does not read the ratios
    again = run.curves(1, (0.5, 2.0, 3.0))                  # the proxy does
    assert again is not first[1] and again[1].h[0] == pytest.approx(2.0 * states[1].lf.max())
    fitted.last = fit()                                       # a new fit: new curves
    assert run.curves(0, (0.5, 2.0, 3.0)) is not first[0]


def test_the_summary_gives_the_loads_unit():
    from pas.longterm.result import LongTermResult

    contributions = pd.DataFrame({"sea_state": ["H3", "H4"], "share": [0.4, 0.6], "n_hf": [8, 12],
                                  "read_off": ["pas", "tail"]})
    res = LongTermResult(value=123.4, band=(110.0, 150.0), p_exceed=1e-5, n_hf=20,
                         distribution=pd.DataFrame(), contributions=contributions, lf_value=4.2,
                         extension_bounds=(100.0, 160.0), seed=1)
    lines = res.summary(unit="kN").splitlines()
    assert lines[0] == ("long-term value at p_exceed = 1e-05 per wave encounter: 123.4 kN "
                        "(U95 110 – 150 kN)")
    assert lines[-1].endswith("the value is 100 – 160 kN")
    assert "kN" not in res.summary()


def test_results_still_running_are_stored_when_a_tell_raises(tmp_path):
    """A callback that raises during a round: every HF result the round's calls return is in
    the store (a resumed analysis takes them instead of running the events again)."""
    import sqlite3
    from concurrent.futures import ThreadPoolExecutor

    table, lf = _small()
    oracle = problem.Oracle()

    def callback(name, study, row):
        raise RuntimeError("the user's callback broke")

    db = tmp_path / "lt.sqlite"
    with ThreadPoolExecutor(4) as pool, pytest.raises(RuntimeError, match="callback broke"):
        pas.run_long_term(table, lf, oracle, max_hf=12, study=db, batch_size=3, executor=pool,
                          callback=callback, **FAST)
    with sqlite3.connect(db) as c:
        stored = c.execute("SELECT COUNT(*) FROM events WHERE result_at IS NOT NULL").fetchone()[0]
    assert len(oracle.calls) >= 2 and stored == len(oracle.calls)


@pytest.mark.parametrize("key", ["seed", "eps1", "max_hf", "stop_on_convergence"])
def test_study_settings_may_not_set_what_run_long_term_sets(tmp_path, key):
    table, lf = _small()
    with pytest.raises(ValueError, match=f"^study_settings: run_long_term sets {key} itself"):
        pas.run_long_term(table, lf, problem.Oracle(), max_hf=8, study=tmp_path / "lt.sqlite",
                          study_settings={key: 1}, **FAST)
    assert not (tmp_path / "lt.sqlite").exists()
