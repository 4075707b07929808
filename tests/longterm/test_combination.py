"""The long-term sum over sea states and its extensions, on exact short-term distributions."""

import numpy as np
import pytest
from scipy.optimize import brentq

from pas.longterm.combination import (
    PASCurve,
    extension_bounds,
    level_at,
    long_term_exceedance,
    proxy_curve,
)
from pas.longterm.inputs import SeaState

SIGMA = np.array([1.0, 1.5, 2.0])
W = np.array([0.5, 0.3, 0.2])
N = 2000


def _state(sigma, seed=0, n=N):
    lf = np.random.default_rng(seed).rayleigh(sigma, n)
    return SeaState("s", 1.0, n, 8.0 * n, lf)


def _exact_curve(sigma, n=N, k_end=None):
    """The exact Rayleigh quantile curve at d = k/n (what a perfect PAS would predict)."""
    d = np.arange(1, (k_end or n) + 1) / n
    h = sigma * np.sqrt(-2 * np.log(d))
    state = _state(sigma)
    return PASCurve(d, h, state, lf_end=h[-1])


def test_inside_the_range_the_exceedance_is_the_distribution_read_back():
    c = _exact_curve(1.5)
    assert c.exceedance(c.h[[0, 9, 499]]) == pytest.approx(c.d[[0, 9, 499]], rel=1e-9)


def test_the_weibull_tail_above_the_record_is_exact_for_a_rayleigh_distribution():
    c = _exact_curve(1.5)
    x = np.array([1.1, 1.3, 1.6]) * c.h[0]
    assert (x > c.h[0]).all()
    assert c.exceedance(x) == pytest.approx(np.exp(-x ** 2 / (2 * 1.5 ** 2)), rel=1e-6)


def test_the_long_term_level_solves_the_weighted_sum_in_closed_form():
    curves = [_exact_curve(s) for s in SIGMA]
    for p in (1e-2, 1e-3, 1e-5):  # the last beyond every record: the tails
        truth = brentq(lambda x, p=p: np.sum(W * np.exp(-x ** 2 / (2 * SIGMA ** 2))) - p,
                       0.01, 50)
        # piecewise linear on ln d between the ranks: an interpolation error of ~1e-6
        assert level_at(curves, W, p, start=3.0) == pytest.approx(truth, rel=1e-5)
        assert long_term_exceedance(curves, W, truth)[0] == pytest.approx(p, rel=1e-4)


def test_no_level_reaches_a_probability_above_every_exceedance():
    curves = [_exact_curve(s, k_end=100) for s in SIGMA]  # each ends at d = 0.05
    # below the ranges the flat lower bound d_end: Q never exceeds 0.05 there
    assert np.isnan(level_at([c.with_below("low") for c in curves], W, 0.5, start=3.0))


def test_extension_bounds_coincide_inside_the_ranges_and_bracket_the_value_below_them():
    curves = [_exact_curve(s, k_end=200) for s in SIGMA]  # each down to d = 0.1
    value = level_at(curves, W, 1e-3, start=3.0)
    assert extension_bounds(curves, W, 1e-3, start=3.0) == pytest.approx((value, value),
                                                                            rel=1e-9)
    short = [_exact_curve(s, k_end=4) for s in SIGMA]  # each ends at d = 0.002
    value = level_at(short, W, 5e-3, start=3.0)
    low, high = extension_bounds(short, W, 5e-3, start=3.0)
    assert low <= value <= high and high > low


def test_the_lf_proxy_follows_its_record_and_scales_with_the_ratio():
    state = _state(1.5, seed=4, n=20000)
    proxy = proxy_curve(state, 1.0)
    x = np.array([2.0, 3.0, 4.0])
    assert proxy.exceedance(x) == pytest.approx(np.exp(-x ** 2 / (2 * 1.5 ** 2)), rel=0.1)
    assert proxy_curve(state, 2.0).exceedance(2 * x) == pytest.approx(proxy.exceedance(x),
                                                                       rel=1e-9)


def test_the_record_band_is_the_binomial_spread_of_an_exceedance_from_the_record():
    from pas.longterm.combination import RecordBand

    mean = _exact_curve(1.5)
    p, n = 1e-2, N
    for side in (+1, -1):
        band = RecordBand(mean, mean, n, side)  # the PAS band's end on the mean: the record decides
        # Q + side 1.96 sqrt(Q (1 - Q) / n) = p, solved for Q, then the Rayleigh level of Q
        q = brentq(lambda q, s=side: q + s * 1.96 * np.sqrt(q * (1 - q) / n) - p, 1e-6, 0.5)
        expected = 1.5 * np.sqrt(-2 * np.log(q))
        assert level_at([band], [1.0], p, start=3.0) == pytest.approx(expected, rel=1e-4)


def test_the_gain_is_share_times_width_times_the_narrowing_of_one_more_event():
    from pas.longterm.allocation import gains

    triples = [tuple(_exact_curve(s * f) for f in (0.9, 1.0, 1.1)) for s in SIGMA]
    x, n_hf = 4.0, [0, 6, 12]
    q = {f: np.exp(-x ** 2 / (2 * (SIGMA * f) ** 2)) for f in (0.9, 1.0, 1.1)}
    share = W * q[1.0] / np.sum(W * q[1.0])
    width = np.where([False, True, True], (q[1.1] - q[0.9]) / q[1.0], 1.0)
    expected = share * width * (1 - np.sqrt(np.array(n_hf) / (np.array(n_hf) + 1)))
    got = gains(triples, W, x, n_hf, fitted=[False, True, True])
    assert got == pytest.approx(expected, rel=1e-4)


def test_the_level_is_the_root_of_the_curves_own_sum_to_1e_10():
    # the curves' own sum, solved by scipy's brentq: level_at's narrowing must find its root
    curves = [proxy_curve(_state(s, seed=i), 1.0) for i, s in enumerate(SIGMA)]
    for p in (3e-2, 2e-3, 4e-4):
        root = brentq(lambda x, p=p: long_term_exceedance(curves, W, x)[0] - p, 0.1, 20.0,
                      xtol=1e-14, rtol=1e-14)
        assert level_at(curves, W, p, start=2.0) == pytest.approx(root, rel=1e-10)

