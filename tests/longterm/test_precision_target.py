"""The precision target of a long-term analysis: the stop, its schedule of bands, the forecast."""

import _longterm_problem as problem
import numpy as np
import pytest

import pas
from pas.longterm.target import BANDS_KEY, LongTermTarget
from pas.strategies.forecast import relative_half_width
from pas.strategies.stopping import FIRST_BAND_PAIRS
from pas.study.store import StoreError, StudyStore

P = 1e-3


def _run(precision, max_hf, **kw):
    kw = {"seed": 4, "strategy": pas.PAS(band=pas.ModelBand(n_bootstrap=10)), **kw}
    return pas.run_long_term(problem.table(n_waves=2000), problem.lf_peaks(1, n_waves=2000),
                             problem.Oracle(), p_exceed=P, max_hf=max_hf, precision=precision,
                             **kw)


@pytest.fixture(scope="module")
def reached():
    return _run(0.10, 80)


def test_a_reached_target_holds_its_band_and_the_window(reached):
    r = reached
    assert r.converged and r.n_hf < 80
    width = relative_half_width(r.value, r.band)
    assert width <= 0.10
    assert "precision reached" in r.summary() and f"±{100 * width:.3g} %" in r.summary()
    last = r.history.tail(20)["value"]
    assert ((r.band[0] <= last) & (last <= r.band[1])).all()
    # the closed-form truth (independent of pas.longterm) lies inside the band it stopped on
    truth = problem.true_value(P)
    assert r.band[0] <= truth <= r.band[1]
    assert r.forecast_hf.expected == 0.0
    # the cost, in all and per sea state (the oracle's time is the caller's)
    fit = r.contributions["fit_seconds"]
    assert (fit >= 0).all() and (fit[r.contributions["n_hf"] == 0] == 0).all()
    assert 0 < fit.sum() <= r.seconds
    assert f"wall time {r.seconds:.1f} s" in r.summary()


def test_the_full_band_is_computed_on_a_schedule_not_every_round(reached):
    h = reached.history
    computed = h[h["halfwidth"].notna()]
    assert 1 <= len(computed) <= len(h) / 3
    assert computed["n_hf"].iloc[0] >= FIRST_BAND_PAIRS
    # the full band holds the band without the model bands, the value inside both
    assert (computed["low"] <= computed["low_sampling"] + 1e-12).all()
    assert (computed["high"] >= computed["high_sampling"] - 1e-12).all()
    assert ((h["low_sampling"] <= h["value"]) & (h["value"] <= h["high_sampling"])).all()
    # the last computed band is the result's band
    assert (computed["low"].iloc[-1], computed["high"].iloc[-1]) == pytest.approx(reached.band)


def test_a_target_below_the_part_hf_cannot_narrow_says_so():
    r = _run(0.02, 30)
    assert not r.converged and r.n_hf == 30
    floor = r.forecast["sampling_halfwidth"]
    assert floor > 0.02                      # the records' spread alone is wider than ±2 %
    assert r.forecast["out_of_reach"] and r.forecast_hf.expected == np.inf
    text = r.summary()
    assert "precision NOT reached" in text and "more HF will not reach ±2 %" in text
    assert "the budget allows 0" in text


def test_without_a_target_the_history_is_kept_and_nothing_is_forecast():
    r = pas.run_long_term(problem.table(n_waves=2000), problem.lf_peaks(1, n_waves=2000),
                          problem.Oracle(), p_exceed=P, max_hf=12, seed=4, model_band=False,
                          strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    assert r.precision is None and not r.converged and r.forecast is None
    assert r.forecast_hf is None and "precision" not in r.summary()
    assert len(r.history) >= 2 and r.history["halfwidth"].isna().all()
    assert r.history["n_hf"].iloc[-1] == r.n_hf
    assert r.history["value"].iloc[-1] == pytest.approx(r.value, rel=1e-12)
    # the table's descriptive column reaches the contributions
    assert r.contributions.set_index("sea_state")["sigma"].to_dict() == pytest.approx(
        dict(zip(problem.table()["name"], problem.SIGMA)))


@pytest.mark.parametrize("bad", [0.0, 1.0, -0.1, float("nan")])
def test_a_bad_precision_names_the_argument(bad):
    with pytest.raises(ValueError, match=r"precision must lie in \(0, 1\)"):
        LongTermTarget(bad)


def test_a_continued_analysis_may_change_its_target_and_keeps_its_band_widths(tmp_path):
    db = tmp_path / "lt.sqlite"
    first = _run(0.02, 24, study=db)
    root = StudyStore(db, scope="")
    stored = root.get(BANDS_KEY)
    root.close()
    assert stored["n_hf"] and len(stored["n_hf"]) == len(stored["halfwidth"])
    again = _run(0.05, 30, study=db)       # a new target and budget: allowed
    assert again.n_hf == 30 and again.n_hf >= first.n_hf
    target = LongTermTarget(0.05)
    target.restore(stored)
    assert target.rule.band_pairs == stored["n_hf"]
    with pytest.raises(StoreError, match="p_exceed differs"):
        pas.run_long_term(problem.table(n_waves=2000), problem.lf_peaks(1, n_waves=2000),
                          problem.Oracle(), p_exceed=2 * P, max_hf=30, study=db)
