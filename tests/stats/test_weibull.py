import numpy as np
import pytest
from scipy import stats

from pas.models.marginals import fit_marginal
from pas.stats.weibull import fit_weibull3_ls, upper_tail_fraction


def test_ls_fit_recovers_known_weibull():
    true = stats.weibull_min(1.7, loc=2.0, scale=5.0)
    x = true.rvs(20000, random_state=np.random.default_rng(3))
    w = fit_weibull3_ls(x)
    assert w.beta == pytest.approx(1.7, rel=0.05)
    assert w.alpha == pytest.approx(5.0, rel=0.05)
    assert w.theta == pytest.approx(2.0, abs=0.15)
    # the fitted tail quantile matches the true one
    assert w.isf(1e-3) == pytest.approx(true.isf(1e-3), rel=0.03)


def test_tail_fit_keeps_full_sample_plotting_positions():
    true = stats.weibull_min(2.0, loc=0.0, scale=3.0)
    x = true.rvs(5000, random_state=np.random.default_rng(4))
    w = fit_weibull3_ls(x, top_fraction=0.3)
    assert w.isf(1e-3) == pytest.approx(true.isf(1e-3), rel=0.03)


def test_location_stays_inside_its_bounds():
    x = np.array([10.0, 10.5, 10.7, 10.8, 11.0, 11.05, 11.1, 11.12])
    w = fit_weibull3_ls(x, theta_span=3.0)
    assert x.min() - 3.0 * np.ptp(x) - 1e-9 <= w.theta < x.min()
    u = w.cdf(x)
    assert np.all((u > 0) & (u < 1)) and np.all(np.diff(u) > 0)


def test_upper_tail_mode_fractions():
    assert [upper_tail_fraction(n) for n in (4, 9, 10, 20, 30, 31, 200)] == [
        1.0, 1.0, 1.0, 0.9, 0.8, 0.8, 0.8]


def test_fit_marginal_tail_mode_uses_upper_part():
    x = np.r_[np.full(20, 1.0) + np.linspace(0, 0.01, 20), np.linspace(5, 9, 30)]
    full = fit_marginal(x, upper_tail=False)
    tail = fit_marginal(x, upper_tail=True)
    assert tail.theta != full.theta


@pytest.mark.parametrize("bad", [[1.0, 2.0], [3.0, 3.0, 3.0], [1.0, np.nan, 2.0]])
def test_bad_samples(bad):
    with pytest.raises(ValueError):
        fit_weibull3_ls(bad)


def test_direct_formulas_match_scipy():
    w = fit_weibull3_ls(stats.weibull_min(1.3, loc=1.0, scale=2.0).rvs(500, random_state=1))
    x = np.linspace(w.theta - 1, w.theta + 10, 50)
    p = np.linspace(1e-6, 1 - 1e-6, 50)
    np.testing.assert_allclose(w.cdf(x), w.frozen.cdf(x), atol=1e-14)
    np.testing.assert_allclose(w.sf(x), w.frozen.sf(x), rtol=1e-12)
    np.testing.assert_allclose(w.ppf(p), w.frozen.ppf(p), rtol=1e-12)
    np.testing.assert_allclose(w.isf(p), w.frozen.isf(p), rtol=1e-12)
