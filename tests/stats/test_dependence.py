"""Kendall's τ-b counted pair by pair for small samples, scipy's merge sort for large ones."""

import numpy as np
import pytest
from scipy import stats

from pas.stats import dependence
from pas.stats.dependence import kendall_tau


@pytest.mark.parametrize("n", [2, 3, 10, 33, 80, 200])
def test_kendall_tau_is_scipys_tau_b_with_and_without_ties(n):
    rng = np.random.default_rng(n)
    for k in range(20):
        x = rng.normal(size=n)
        y = 0.6 * x + rng.normal(size=n)
        if k % 2:  # ties in both samples, and a block of equal loads
            x, y = np.round(x, 1), np.round(y, 1)
            y[: n // 3] = 0.0
        want = stats.kendalltau(x, y).statistic
        assert kendall_tau(x, y) == pytest.approx(want, rel=1e-12, abs=1e-15)


def test_kendall_tau_of_a_sample_all_alike_or_too_small_is_nan():
    assert np.isnan(kendall_tau([1.0, 1.0, 1.0], [1.0, 2.0, 3.0]))
    assert np.isnan(kendall_tau([1.0], [2.0]))


def test_kendall_tau_of_perfect_order_is_one_and_reversed_minus_one():
    x = np.arange(50.0)
    assert kendall_tau(x, x ** 3) == 1.0
    assert kendall_tau(x, -x) == -1.0
    assert dependence._PAIRWISE_UP_TO >= 50  # the pairwise count answered


def test_kendall_tau_with_nan_follows_scipy():
    x, y = np.array([1.0, 2.0, np.nan, 4.0]), np.array([1.0, 3.0, 2.0, 5.0])
    assert np.isnan(kendall_tau(x, y)) == np.isnan(stats.kendalltau(x, y).statistic)



def test_kendall_tau_of_integers_is_not_cast_to_float():
    # 10**17 and 10**17 + 1 are one float64
    assert kendall_tau([10**17, 10**17 + 1, 3], [1, 2, 3]) == pytest.approx(-1 / 3)
