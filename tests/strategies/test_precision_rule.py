"""The precision stopping rule and the forecast of the HF it needs, on hand-made sequences."""

import math

import numpy as np
import pytest

from pas._support.checks import check_setting
from pas.strategies.forecast import forecast_pairs, relative_half_width
from pas.strategies.stopping import (
    BAND_EVERY,
    BAND_GROWTH,
    FIRST_BAND_PAIRS,
    StoppingRule,
)

CURVE = np.zeros(41)


def rule_with(mpms, precision=0.1, k2=4, eps1=None):
    rule = StoppingRule(eps1=eps1, eps2=0.5, k1=4, k2=k2, precision=precision)
    for m in mpms:
        rule.update(CURVE, m)
    return rule


def test_half_width_is_the_wider_side():
    assert relative_half_width(100.0, (98.0, 111.0)) == pytest.approx(0.11, rel=1e-12)
    assert relative_half_width(100.0, (88.0, 101.0)) == pytest.approx(0.12, rel=1e-12)
    assert relative_half_width(float("nan"), (1.0, 2.0)) == math.inf


@pytest.mark.parametrize("band, met", [
    ((91.0, 109.0), True),      # ±9 %
    ((90.0, 110.0), True),      # exactly ±10 %
    ((89.9, 105.0), False),     # the low side is wider than ±10 %
    ((95.0, 110.5), False),     # the high side
])
def test_precision_met_only_when_both_sides_are_within_the_target(band, met):
    rule = rule_with([100.0, 101.0, 99.0, 100.0])
    assert rule.precision_met(100.0, band) is met


def test_precision_needs_the_last_k2_mpms_inside_the_band():
    assert rule_with([100.0, 104.0, 96.0, 100.0]).precision_met(100.0, (95.0, 105.0))
    assert not rule_with([100.0, 106.0, 96.0, 100.0]).precision_met(100.0, (95.0, 105.0))
    # an MPM outside the band before the window does not count
    assert rule_with([150.0, 100.0, 104.0, 96.0, 100.0]).precision_met(100.0, (95.0, 105.0))
    # fewer than k2 MPMs: no window yet
    assert not rule_with([100.0, 100.0, 100.0]).precision_met(100.0, (95.0, 105.0))


def test_the_gate_is_necessary_for_the_rule():
    """Wherever the rule holds for a band holding the sampling part, the cheap gate holds."""
    rng = np.random.default_rng(3)
    for _ in range(300):
        mpms = 100.0 + rng.normal(0, 4, 6)
        rule = rule_with(mpms)
        mpm = mpms[-1]
        sampling = tuple(sorted(mpm + rng.normal(0, 6, 2)))
        model = tuple(sorted(mpm + rng.normal(0, 8, 2)))
        u95 = (min(sampling[0], model[0]), max(sampling[1], model[1]))
        if rule.precision_met(mpm, u95):
            assert rule.precision_gate(mpm, sampling)


def test_eps1_alone_is_the_papers_rule_and_neither_is_an_error():
    rule = rule_with([100.0] * 8, precision=None, eps1=1.0)
    assert rule.update(CURVE, 100.0)[3] is True
    assert not rule.precision_met(100.0, (99.0, 101.0))
    assert not rule.band_due(50, True, 0.0)
    from pas.study.settings import lacks_a_limit

    assert lacks_a_limit({"eps1": None, "precision": None}).startswith("give eps1 (")
    assert lacks_a_limit({"precision": 0.1}) is None


def test_without_eps1_the_paper_part_does_not_block():
    rule = rule_with([100.0, 130.0])
    assert rule.update(CURVE, 70.0)[3] is True  # the precision part decides alone


def test_band_schedule_grows_geometrically_and_then_follows_the_gate():
    rule = rule_with([100.0] * 30)
    assert not rule.band_due(FIRST_BAND_PAIRS - 1, True, 0.0)
    assert rule.band_due(FIRST_BAND_PAIRS, False, 0.0)
    rule.record_band(FIRST_BAND_PAIRS, 0.5)
    n_next = math.ceil(BAND_GROWTH * FIRST_BAND_PAIRS)
    assert not rule.band_due(n_next - 1, False, 0.0)
    assert rule.band_due(n_next, False, 0.0)
    rule.record_band(n_next, 0.4)
    # gate open, but fewer than BAND_EVERY fits since the last band
    for _ in range(BAND_EVERY - 1):
        rule.update(CURVE, 100.0)
    assert not rule.band_due(n_next + 1, True, 0.0)
    rule.update(CURVE, 100.0)
    # two widths and the prior on b forecast the target far off: no gated band yet
    assert rule.forecast(n_now=n_next + 1).n_pairs > BAND_GROWTH * (n_next + 1)
    assert not rule.band_due(n_next + 1, True, 0.0)
    assert not rule.band_due(n_next + 1, False, 0.0)


def test_gated_band_waits_for_the_forecast():
    rule = rule_with([100.0] * 40)
    for n, w in ((10, 0.8), (15, 0.8 * 1.5 ** -0.5), (22, 0.8 * 2.2 ** -0.5)):
        rule.record_band(n, w)
    for _ in range(BAND_EVERY):
        rule.update(CURVE, 100.0)
    ahead = rule.forecast()
    assert ahead.n_pairs == pytest.approx(640.0, rel=1e-6)  # 10 · (0.8 / 0.1)²
    assert not rule.band_due(30, True, 0.0)
    assert rule.band_due(int(ahead.n_pairs / BAND_GROWTH) + 1, True, 0.0)


def test_forecast_fit_alone_recovers_a_known_exponent():
    n = np.array([10, 15, 22, 33, 50, 75])
    w = 0.6 * (n / 10.0) ** -0.4
    f = forecast_pairs(n, w, 0.1, prior_sd=math.inf)
    assert f.exponent == pytest.approx(0.4, rel=1e-9)
    assert f.n_pairs == pytest.approx(10.0 * 6.0 ** (1 / 0.4), rel=1e-9)
    assert f.low == pytest.approx(f.n_pairs, rel=1e-6) == pytest.approx(f.high, rel=1e-6)
    assert f.further(75, per_pair=1.25)[0] == pytest.approx((f.n_pairs - 75) * 1.25, rel=1e-9)


def test_forecast_interval_covers_the_truth_of_noisy_widths():
    rng = np.random.default_rng(11)
    n = np.array([10, 15, 22, 33, 50, 75, 110])
    truth = 10.0 * (0.5 / 0.1) ** 2  # w = 0.5 (n/10)^-1/2 reaches 0.1 at 250 pairs
    hits = 0
    for _ in range(200):
        w = 0.5 * (n / 10.0) ** -0.5 * np.exp(rng.normal(0, 0.08, n.size))
        f = forecast_pairs(n, w, 0.1)
        assert f.low <= f.n_pairs <= f.high
        hits += f.low <= truth <= f.high
    assert hits >= 180  # a 95 % interval


def test_forecast_out_of_reach_and_too_few_points():
    n = [10, 15, 22]
    assert forecast_pairs(n, [0.3, 0.3, 0.31], 0.1, prior_sd=math.inf).n_pairs == math.inf
    # not narrowing over so few pairs is weak evidence against b = 1/2: finite, and vague
    flat = forecast_pairs(n, [0.3, 0.3, 0.31], 0.1)
    assert math.isfinite(flat.n_pairs) and flat.high > 100 * flat.low
    assert forecast_pairs(n, [0.3, 0.2, 0.15], 0.1, floor=0.12).n_pairs == math.inf
    assert forecast_pairs(n[:2], [0.3, 0.2], 0.1, prior_sd=math.inf) is None
    assert forecast_pairs([], [], 0.1) is None
    # only the last two doublings count: widths at n < n_last / 4 are left out
    assert forecast_pairs([2, 3, 4, 20, 30], [9, 9, 9, 0.3, 0.2], 0.1, prior_sd=math.inf) is None
    assert (forecast_pairs([2, 3, 4, 20, 30], [9, 9, 9, 0.3, 0.2], 0.1)
            == forecast_pairs([20, 30], [0.3, 0.2], 0.1))


@pytest.mark.parametrize("value", [0, 1, 10, -0.1, float("nan"), "10%", True])
def test_precision_setting_is_a_fraction(value):
    with pytest.raises(ValueError, match="precision must be"):
        check_setting("precision", value)
    assert check_setting("precision", None) is None
    assert check_setting("precision", 0.1) == 0.1
