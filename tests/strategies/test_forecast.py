"""The forecast's prior on the exponent, its robust level and the stopping rule's floor."""

import math

import numpy as np
import pytest

from pas.strategies.forecast import PRIOR_SD, SCATTER, SCATTER_DOF, forecast_pairs
from pas.strategies.stopping import StoppingRule

CURVE = np.zeros(41)


def test_one_band_forecasts_with_the_prior_exponent():
    f = forecast_pairs([10], [0.4], 0.1)
    assert f.exponent == pytest.approx(0.5, rel=1e-12)
    assert f.n_pairs == pytest.approx(10 * (0.4 / 0.1) ** 2, rel=1e-9)  # w ∝ n^-1/2
    assert f.low < f.n_pairs < f.high


def test_the_prior_shrinks_a_fitted_exponent_by_its_weight():
    n = np.array([10.0, 15, 22, 33])
    w = 0.6 * (n / 10) ** -0.3  # on the line: the scatter is the prior's alone
    assert forecast_pairs(n, w, 0.1, prior_sd=math.inf).exponent == pytest.approx(0.3, rel=1e-9)
    assert forecast_pairs(n, w, 0.1, prior_sd=1e-9).exponent == pytest.approx(0.5, rel=1e-6)
    x = np.log(n)
    s2 = SCATTER_DOF * SCATTER ** 2 / (n.size - 2 + SCATTER_DOF)
    data, prior = np.sum((x - x.mean()) ** 2) / s2, PRIOR_SD ** -2
    expected = (0.3 * data + 0.5 * prior) / (data + prior)
    assert 0.3 < expected < 0.5
    assert forecast_pairs(n, w, 0.1).exponent == pytest.approx(expected, rel=1e-9)


def test_the_median_level_ignores_one_wild_bootstrap_width():
    n = np.array([10.0, 15, 23, 35, 53])
    w = 0.4 * (n / 10) ** -0.5
    w[1] *= 4  # a bootstrap whose replicates fell apart once
    on_line = 10 * (0.4 / 0.1) ** 2
    assert forecast_pairs(n, w, 0.1, prior_sd=1e-9).n_pairs == pytest.approx(on_line, rel=1e-6)
    assert forecast_pairs(n, w, 0.1, prior_sd=1e-9, centre="mean").n_pairs > 1.5 * on_line
    with pytest.raises(ValueError, match="centre must be"):
        forecast_pairs(n, w, 0.1, centre="mode")


def rule_with(mpms, precision=0.1, k2=20):
    rule = StoppingRule(k2=k2, precision=precision)
    for m in mpms:
        rule.update(CURVE, m)
    return rule


def test_the_rule_floor_counts_the_k2_window():
    rule = rule_with([100.0] * 5)
    assert rule.fewest_more_fits() == 15  # 20 MPMs are needed
    # widths already at the target: the band alone would say "now"
    assert rule.forecast(n_now=8, extra=(8, 0.05)).n_pairs == pytest.approx(23, rel=1e-12)
    # an MPM 30 % off must leave the window first (±10 % spans at most 22 %)
    assert rule_with([100.0, 130.0, 100.0, 100.0], k2=4).fewest_more_fits() == 2
    settled = rule_with([100.0, 105.0, 100.0, 100.0], k2=4)
    assert settled.fewest_more_fits() == 0
    # a fit at which the rule did not hold needs one more, one at which it held none
    assert settled.forecast(n_now=30, extra=(30, 0.05)).n_pairs == pytest.approx(31, rel=1e-12)
    assert settled.forecast(n_now=30, extra=(30, 0.05), may_stop_now=True).n_pairs == pytest.approx(
        30, rel=1e-12)


def test_the_rule_floor_is_never_more_than_the_rule_needs():
    """Before the floor's count of fits, no band the target allows holds the window."""
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(200):
        walk = list(100 * np.exp(np.cumsum(rng.normal(0, 0.06, 30))))
        rule = rule_with(walk[:12], k2=8)
        fewest = rule.fewest_more_fits()
        for m in walk[12:12 + fewest]:
            rule.update(CURVE, m)
            if len(rule.mpms) - 12 < fewest:
                checked += 1
                assert not rule.precision_met(m, (0.9 * m, 1.1 * m))
    assert checked > 50


def test_a_gated_band_is_due_where_the_forecast_says_the_target_is_reached():
    """Between growth bands, a band is due once the forecast's pairs are reached: the floor of
    "one more fit" must not keep it waiting for a fit that never comes."""
    from pas.strategies.stopping import BAND_EVERY, BAND_GROWTH

    rule = rule_with([100.0] * 40, k2=4)
    for n, w in ((20, 0.2), (25, 0.15), (30, 0.105)):
        rule.record_band(n, w)
    for _ in range(BAND_EVERY):
        rule.update(CURVE, 100.0)
    ahead = rule.forecast(n_now=31, may_stop_now=True)
    assert ahead.low <= 31 and ahead.n_pairs / BAND_GROWTH <= 31 < BAND_GROWTH * 30
    assert rule.band_due(31, True, 0.0)
    assert not rule.band_due(31, False, 0.0)  # the cheap gate still decides first
