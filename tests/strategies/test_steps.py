"""Unit tests of single PAS steps against hand-computed values."""

import numpy as np
import pytest

from pas.strategies.acquisition import md_select, nearest_available
from pas.strategies.base import Pairs
from pas.strategies.estimators import SelectedSample
from pas.strategies.pas import PAS, conditioning_set, hf_distribution, remove_outliers
from pas.strategies.screening import LFSet
from pas.strategies.stopping import StoppingRule, distribution_change, range_grid


def test_lfset_threshold_sort_and_exceedance():
    s = LFSet([1.0, 7.0, 3.0, 9.0, 5.0, 8.0], n_waves=10, p_exp=0.2, threshold=2.0)
    np.testing.assert_allclose(s.lf, [9.0, 8.0, 7.0, 5.0, 3.0])
    np.testing.assert_allclose(s.d, [0.1, 0.2, 0.3, 0.4, 0.5])
    ev = s.event(0)
    assert (ev.index, ev.id, ev.lf, ev.d) == (3, 3, 9.0, 0.1)


def test_initial_samples_uniform_on_log_d():
    s = LFSet(np.arange(1000.0, 0.0, -1.0), n_waves=1000, p_exp=0.01)
    pos = PAS().initial_positions(s)
    # ln d spans ln(1/1000)..ln(1); 4 uniform targets are d = 1e-3, 1e-2, 1e-1, 1
    np.testing.assert_allclose(s.d[pos], [1e-3, 1e-2, 1e-1, 1.0])


def test_md_targets_largest_gap_midpoint():
    ln_d = np.log(np.arange(1, 1001) / 1000.0)
    avail = np.ones(1000, dtype=bool)
    sel = np.log([1e-3, 1e-2, 1.0])
    # largest gap is [1e-2, 1] (4.6 on ln d): its midpoint is d = 0.1
    (p,) = md_select(ln_d, avail, sel, 1)
    assert np.exp(ln_d[p]) == pytest.approx(0.1)
    # batch of two: second target fills the next largest gap, [1e-3, 1e-2] or a half of
    # the split one (all 2.3 wide); the sequential fill never repeats a position
    batch = md_select(ln_d, avail, sel, 3)
    assert len(set(batch)) == 3 and batch[0] == p


def test_md_skips_gaps_no_peak_can_split():
    ln_d = np.log(np.arange(1, 101) / 100.0)
    avail = np.ones(100, dtype=bool)
    avail[[0, 1]] = False  # d = 0.01 and 0.02 already selected
    sel = np.log([0.01, 0.02, 0.05])  # gap [0.01, 0.02] = ln 2 is largest but has no peak inside
    (p,) = md_select(ln_d, avail, np.log([0.01, 0.02, 0.025]), 1, skip_unsplittable=False)
    assert p == 2  # paper's rule: nearest to the midpoint of [0.01, 0.02] is outside the gap
    avail[2] = False
    (p,) = md_select(ln_d, avail, sel, 1)
    assert 2 < p < 4  # the unsplittable gap is skipped: the pick splits [0.02, 0.05]


def test_nearest_available():
    ln_d = np.log([0.1, 0.2, 0.3, 0.4])
    assert nearest_available(ln_d, np.array([True, False, False, True]), np.log(0.15)) == 0
    assert nearest_available(ln_d, np.zeros(4, bool), 0.0) == -1


def test_temporary_outlier_removal():
    rng = np.random.default_rng(1)
    lf = np.linspace(1, 10, 30)
    hf = 2 * lf**2 + rng.normal(0, 1, 30)
    hf[17] += 80.0
    keep = remove_outliers(lf, hf)
    assert not keep[17] and keep.sum() == 29


def test_conditioning_set_and_hf_distribution():
    lf = np.array([9.0, 7.0, 5.0, 3.0])
    np.testing.assert_allclose(conditioning_set(lf, 5.0), [9.0, 7.0, 5.0])
    draws = np.array([[1.0, 3.0, 2.0], [2.0, 6.0, 4.0]])
    d, mean, low, high = hf_distribution(draws, n_waves=10)
    np.testing.assert_allclose(d, [0.1, 0.2, 0.3])
    np.testing.assert_allclose(mean, [4.5, 3.0, 1.5])
    sd = np.array([np.std([3, 6], ddof=1), np.std([2, 4], ddof=1), np.std([1, 2], ddof=1)])
    np.testing.assert_allclose(high - mean, 1.96 * sd)


def test_stopping_windows_and_cov():
    rule = StoppingRule(eps1=0.5, eps2=0.1, k1=3, k2=3, measure="step")
    assert rule.min_iterations == 1
    outs = [rule.update(np.full(5, h), m) for h, m in [(0, 10), (1, 10), (3, 12), (3.1, 12)]]
    e = [o[0] for o in outs]
    assert np.isnan(e[0]) and e[1:] == pytest.approx([1.0, 2.0, 0.1])
    # E_bar: mean of the available E's, then of the last k1
    assert [o[1] for o in outs[1:]] == pytest.approx([1.0, 1.5, (1 + 2 + 0.1) / 3])
    # COV over the last k2 MPMs with the population standard deviation
    last3 = np.array([10, 12, 12.0])
    assert outs[3][2] == pytest.approx(last3.std() / last3.mean())
    assert not any(o[3] for o in outs)  # E_bar never below 0.5


def test_window_measure_is_the_change_across_k1_iterations():
    # Eq. 28 averages per-step changes; the window measure compares with K1 steps back
    rule = StoppingRule(eps1=0.5, eps2=0.5, k1=2, k2=2)
    outs = [rule.update(np.full(5, h), 10.0) for h in (0.0, 0.2, 0.4, 0.6, 0.6, 0.6)]
    assert np.isnan(outs[0][1])
    # one step available: its change counts for the K1 = 2 of a window
    assert [o[1] for o in outs[1:]] == pytest.approx([0.4, 0.4, 0.4, 0.2, 0.0])
    # a steady drift of 0.2 a step passes Eq. 28 (mean step 0.2 < 0.5) ...
    step = StoppingRule(eps1=0.3, eps2=0.5, k1=4, k2=4, measure="step")
    window = StoppingRule(eps1=0.3, eps2=0.5, k1=4, k2=4)
    drift = [0.2 * k for k in range(8)]
    assert [step.update(np.full(5, h), 10.0)[3] for h in drift][-1]
    # ... but not the window measure: the distribution moved 0.8 over the window
    assert not any(window.update(np.full(5, h), 10.0)[3] for h in drift)
    with pytest.raises(ValueError, match="stop_measure"):
        StoppingRule(eps1=1.0, measure="steps")


def test_window_measure_sees_a_model_flipping_between_two_curves():
    # two curves 10 eps1 apart, alternating: an even lag back sees the same curve
    for measure in ("window", "step"):
        rule = StoppingRule(eps1=1.0, eps2=0.5, k1=20, k2=20, measure=measure)
        stops = [rule.update(np.full(5, 10.0 * (k % 2)), 10.0)[3] for k in range(60)]
        assert not any(stops), measure


def test_stopping_not_before_k1_over_3():
    rule = StoppingRule(eps1=1.0, eps2=0.5, k1=20, k2=20)
    stops = [rule.update(np.zeros(3), 5.0)[3] for _ in range(8)]
    assert rule.min_iterations == 7
    assert stops == [False] * 6 + [True, True]


def test_range_grid_and_change():
    g = range_grid(1e-3, 5)
    assert g[0] == pytest.approx(5e-4) and g[-1] == pytest.approx(2e-3)
    assert np.allclose(np.diff(np.log(g)), np.log(4) / 4)
    assert distribution_change([1, 2, 3], [2, 2, 1]) == pytest.approx(1.0)


def test_pas_predict_runs_on_minimal_pairs():
    s = LFSet(np.linspace(10, 0.1, 500), n_waves=600, p_exp=0.01)
    pos = np.array([0, 10, 100, 400])
    pairs = Pairs(pos, s.lf[pos], 2 * s.lf[pos] + 1, s.d[pos])
    pred = PAS().predict(pairs, s, np.random.default_rng(0))
    assert np.all(np.diff(pred.d) > 0) and np.all(np.diff(pred.h_mean) <= 1e-12)
    assert pred.mpm_band[0] <= pred.mpm <= pred.mpm_band[1]


def test_impact_probability_rises_with_lf():
    from pas.strategies.pas import impact_probability

    assert impact_probability([5.0, 6.0], []) is None
    rng = np.random.default_rng(0)
    lf = rng.uniform(10, 20, 400)
    hit = rng.uniform(size=400) < 1 / (1 + np.exp(-(lf - 14)))
    p = impact_probability(lf[hit], lf[~hit])
    low, mid, high = p(np.array([11.0, 14.0, 19.0]))
    assert low < 0.15 and 0.3 < mid < 0.7 and high > 0.9


def test_a_falling_impact_probability_is_kept_only_where_the_test_rejects_a_flat_one():
    from pas.strategies.selection import FALLING_P, impact_probability

    rng = np.random.default_rng(1)
    lf = rng.uniform(10, 20, 200)
    hit = rng.uniform(size=200) < np.where(lf > 17.5, 0.3, 0.95)  # misses high up: a step
    tested = impact_probability(lf[hit], lf[~hit], falling_p=FALLING_P)
    low, high = tested(np.array([11.0, 19.5]))
    assert low > 0.85 and high < 0.6            # the drop the evaluated events show
    rising = impact_probability(lf[hit], lf[~hit])
    assert np.ptp(rising(np.array([11.0, 19.5]))) == 0.0
    assert rising([11.0])[0] == pytest.approx(hit.mean(), rel=1e-12)
    flat = rng.uniform(size=200) < 0.7            # no trend: a falling fit is chance
    slope = [impact_probability(lf[f], lf[~f], falling_p=FALLING_P)(np.array([10.0, 20.0]))
             for f in (flat, ~(rng.uniform(size=200) < 0.3))]
    assert all(np.ptp(p) < 0.1 for p in slope)
    with pytest.raises(ValueError, match="impact_trend must be one of"):
        PAS(impact_trend="falling")


def test_the_impact_trend_acts_in_the_fit_and_the_paper_keeps_rising():
    s = LFSet(np.linspace(10, 0.1, 500), n_waves=600, p_exp=0.01)
    pos = np.arange(0, 120, 2)
    fp = np.arange(1, 16, 2)                     # misses among the largest peaks only
    pairs = Pairs(pos, s.lf[pos], 2 * s.lf[pos] + 1, s.d[pos], fp_position=fp, fp_lf=s.lf[fp])
    tested, rising = PAS(), PAS(impact_trend="rising")
    assert tested.impact_of(pairs)(s.lf[:1])[0] < 0.7 < rising.impact_of(pairs)(s.lf[:1])[0]
    assert PAS.paper().impact_trend == "rising" and PAS().impact_trend == "tested"
    assert PAS(impact_model=False).impact_of(pairs) is None


def test_outliers_leave_the_selected_space_marginals_by_default():
    s = LFSet(np.linspace(10, 0.1, 500), n_waves=600, p_exp=0.01)
    pos = np.arange(0, 500, 25)
    hf = 2 * s.lf[pos] + 1
    hf[1] += 60.0  # one genuine heavy load far off the trend
    pairs = Pairs(pos, s.lf[pos], hf, s.d[pos])
    all_ = PAS(estimator=SelectedSample(marginals_from="all")).predict(
        pairs, s, np.random.default_rng(0))
    kept = PAS(estimator=SelectedSample(marginals_from="kept")).predict(
        pairs, s, np.random.default_rng(0))
    assert all_.record["n_outliers"] == kept.record["n_outliers"] == 1
    assert all_.h_mean[0] > kept.h_mean[0]  # the HF tail keeps the heavy load


def test_hf_distribution_sorts_each_realisation_descending_with_ties_and_zeros():
    from pas.strategies.steps import hf_distribution

    rng = np.random.default_rng(3)
    h = np.where(rng.uniform(size=(5, 400)) < 0.3, 0.0, np.round(rng.weibull(1.2, (5, 400)), 2))
    d, mean, low, high = hf_distribution(h, 1000)
    expected = np.array([sorted(row, reverse=True) for row in h])
    np.testing.assert_allclose(mean, expected.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(high - mean, mean - low, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(d, np.arange(1, 401) / 1000, rtol=1e-12)


@pytest.mark.parametrize("family, params", [("gumbel", [[3.0]])])
def test_draws_hold_few_arrays_of_their_shape_at_a_time(family, params):
    # a long record's draws are z x n0 values (10 x 1.5 M: 120 MB an array); the Gumbel
    # inverse held five such arrays at once and the impact model's zeros one more
    import tracemalloc

    import pyvinecopulib as pv
    from scipy import special

    from pas.models.copulas import CopulaFit
    from pas.stats.weibull import Weibull3
    from pas.strategies.steps import FittedModel

    rng = np.random.default_rng(0)
    u, r = rng.uniform(1e-3, 1 - 1e-3, 20000), rng.uniform(1e-3, 1 - 1e-3, (10, 20000))
    q = rng.uniform(size=r.shape)
    cop = pv.Bicop(family=getattr(pv.BicopFamily, family), parameters=np.array(params))
    fit = CopulaFit(name=family, bicop=cop, loglik=0.0, aic=0.0, npars=1, at_bound=False)
    model = FittedModel(fit, Weibull3(0.1, 2.0, 1.3), None, u, np.full(u.size, 0.8), {}, 0)
    scores = special.ndtri(r)  # kept by the study (common random numbers)
    tracemalloc.start()
    try:
        h = model.draws(r, q, scores)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 3.5 * r.nbytes
    v = pv.Bicop(family=cop.family, parameters=cop.parameters).hinv1(
        np.column_stack([np.broadcast_to(u, r.shape).ravel(), r.ravel()])).reshape(r.shape)
    expected = np.where(q < 0.8, Weibull3(0.1, 2.0, 1.3).ppf(np.clip(v, 1e-6, 1 - 1e-6)), 0.0)
    np.testing.assert_allclose(h, expected, rtol=1e-5)
