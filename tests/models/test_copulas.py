import copulas.bivariate as cb
import numpy as np
import pytest
import pyvinecopulib as pv
from scipy import special

from pas.models.copulas import (
    PAPER_FAMILIES,
    CopulaFit,
    conditional_quantile,
    fit_candidates,
    fit_copula,
    pseudo_observations,
    select_family,
    t_cdf,
    t_quantile,
)
from pas.stats.dependence import empirical_tail_dependence

RNG = np.random.default_rng(11)
U = RNG.uniform(1e-4, 1 - 1e-4, (5000, 2))


def test_pseudo_observations_eq5():
    u, v = pseudo_observations([3.0, 1.0, 2.0], [10.0, 30.0, 20.0])
    np.testing.assert_allclose(u, [0.75, 0.25, 0.5])
    np.testing.assert_allclose(v, [0.25, 0.75, 0.5])


@pytest.mark.parametrize("family, rotation, params", [
    (pv.BicopFamily.gaussian, 0, [[0.7]]),
    (pv.BicopFamily.student, 0, [[0.6], [3.5]]),
    (pv.BicopFamily.student, 0, [[0.92], [2.0]]),
    (pv.BicopFamily.student, 0, [[-0.4], [37.0]]),
    (pv.BicopFamily.clayton, 0, [[2.5]]),
    (pv.BicopFamily.frank, 0, [[7.0]]),
    (pv.BicopFamily.gumbel, 0, [[2.2]]),
    (pv.BicopFamily.gumbel, 0, [[1.02]]),
    (pv.BicopFamily.gumbel, 0, [[12.0]]),
    (pv.BicopFamily.joe, 0, [[2.0]]),
    (pv.BicopFamily.clayton, 180, [[1.5]]),
    (pv.BicopFamily.gumbel, 180, [[1.5]]),
])
def test_conditional_inverse_matches_pyvinecopulib(family, rotation, params):
    b = pv.Bicop(family=family, rotation=rotation, parameters=np.array(params))
    np.testing.assert_allclose(conditional_quantile(b, U[:, 0], U[:, 1]), b.hinv1(U), atol=1e-8)
    # broadcasting one conditioning row against many draws gives the same numbers
    z = conditional_quantile(b, U[None, :50, 0], np.tile(U[:50, 1], (3, 1)))
    np.testing.assert_allclose(z, np.tile(b.hinv1(U[:50]), (3, 1)), atol=1e-8)


@pytest.mark.parametrize("name, family, theta", [
    ("clayton", pv.BicopFamily.clayton, 2.0),
    ("gumbel", pv.BicopFamily.gumbel, 2.0),
    ("frank", pv.BicopFamily.frank, 6.0),
])
def test_conditional_inverse_matches_copulas_package(name, family, theta):
    # the paper's own stack: copulas' percent_point(y, V) solves dC/dv(u, V) = y; the
    # families are exchangeable, so it equals our C^-1_{V|U}(y | u=V)
    ref = cb.Bivariate.from_dict({"copula_type": name.upper(), "theta": theta, "tau": None})
    cond, r = U[:300, 0], U[:300, 1]
    expected = ref.percent_point(r, cond)
    b = pv.Bicop(family=family, parameters=np.array([[theta]]))
    np.testing.assert_allclose(conditional_quantile(b, cond, r), expected, atol=1e-8)


def test_mle_fit_recovers_parameter_and_aic_definition():
    true = pv.Bicop(family=pv.BicopFamily.gumbel, parameters=np.array([[2.0]]))
    uv = true.sample(3000, seeds=[5])
    fits = fit_candidates(*pseudo_observations(uv[:, 0], uv[:, 1]))
    assert list(fits) == list(PAPER_FAMILIES)
    assert fits["gumbel"].parameters[0] == pytest.approx(2.0, rel=0.06)
    assert min(fits, key=lambda k: fits[k].aic) == "gumbel"
    f = fits["student"]
    assert f.npars == 2 and f.aic == pytest.approx(2 * 2 - 2 * f.loglik)


def _fake(name, aic, at_bound=False):
    return CopulaFit(name=name, bicop=None, loglik=-aic / 2, aic=aic, npars=1, at_bound=at_bound)


def test_aic_hysteresis_needs_four_points():
    fits = {"gaussian": _fake("gaussian", -10.0), "gumbel": _fake("gumbel", -13.9)}
    assert select_family(fits, None) == "gumbel"          # no current: plain minimum
    assert select_family(fits, "gaussian") == "gaussian"  # 3.9 better is not enough
    fits["gumbel"] = _fake("gumbel", -14.0)
    assert select_family(fits, "gaussian") == "gumbel"    # 4.0 better switches


def test_boundary_fits_excluded_only_when_asked():
    fits = {"gaussian": _fake("gaussian", -10.0),
            "student": _fake("student", -30.0, at_bound=True)}
    assert select_family(fits, "gaussian") == "student"  # the paper's exact rule
    assert select_family(fits, "gaussian", exclude_at_bound=True) == "gaussian"


def test_student_nu_at_lower_bound_is_flagged():
    # a Student-t sample with very heavy joint tails drives the nu MLE to its bound of 2
    true = pv.Bicop(family=pv.BicopFamily.student, parameters=np.array([[0.0], [2.0]]))
    uv = true.sample(4000, seeds=[2])
    uv = np.r_[uv, np.column_stack([np.r_[np.full(200, 0.999), np.full(200, 0.001)],
                                    np.r_[np.full(200, 0.001), np.full(200, 0.999)]])]
    fit = fit_copula("student", *pseudo_observations(uv[:, 0], uv[:, 1]))
    assert fit.parameters[1] == pytest.approx(2.0, abs=0.01)
    assert fit.at_bound
    assert not fit_copula("gaussian", *pseudo_observations(uv[:, 0], uv[:, 1])).at_bound


def test_empirical_tail_dependence_comonotone_and_independent():
    x = np.arange(100.0)
    assert empirical_tail_dependence(x, x) == (1.0, 1.0)
    rng = np.random.default_rng(0)
    lu, ll = empirical_tail_dependence(rng.normal(size=20000), rng.normal(size=20000))
    assert lu == pytest.approx(0.1, abs=0.03) and ll == pytest.approx(0.1, abs=0.03)


def test_unknown_family_rejected():
    with pytest.raises(ValueError, match="unknown copula family"):
        fit_copula("gumbal", [0.2, 0.5, 0.7], [0.3, 0.4, 0.8])


def test_frank_inverse_accurate_at_strong_dependence():
    # forward Frank h-function in 60-digit decimal arithmetic as the reference
    from decimal import Decimal, getcontext

    getcontext().prec = 60
    th = 34.0
    b = pv.Bicop(family=pv.BicopFamily.frank, parameters=np.array([[th]]))
    rng = np.random.default_rng(4)
    u = np.r_[rng.uniform(0.9, 1 - 1e-6, 30), rng.uniform(1e-6, 0.1, 10)]
    r = rng.uniform(1e-6, 1 - 1e-6, 40)
    v = conditional_quantile(b, u, r)
    T = Decimal(th)
    for ui, vi, ri in zip(u, v, r):
        a, bb = (-T * Decimal(ui)).exp(), (-T * Decimal(vi)).exp()
        h = a * (bb - 1) / ((-T).exp() - 1 + (a - 1) * (bb - 1))
        assert abs(float(h) - ri) < 1e-8


@pytest.mark.parametrize("nu", [2.0, 2.7, 5.0, 13.3, 50.0, 51.0])
def test_student_t_quantile_and_cdf_match_scipy(nu):
    # the interpolated t quantile and CDF behind the Student-t draws, against scipy over
    # the draws' range (1e-6 ... 1 - 1e-6), deep into the tails and beyond the grid
    rng = np.random.default_rng(3)
    tails = np.geomspace(1e-12, 0.5, 500)
    p = np.r_[rng.uniform(1e-6, 1 - 1e-6, 20000), tails, 1 - tails, 0.0, 1.0]
    ref = special.stdtrit(nu, p)
    np.testing.assert_allclose(t_quantile(nu, p), ref, rtol=1e-8, atol=1e-12)
    x = np.r_[ref[1:-1], rng.standard_t(nu, 20000) * 3, np.linspace(-5, 5, 1001),
              -1e6, 1e6, -np.inf, np.inf]
    ref = special.stdtr(nu, x)
    tail = np.minimum(ref, 1 - ref)
    err = np.abs(t_cdf(nu, x) - ref)
    assert np.all(err <= 1e-8 * tail + 1e-15), float(np.max(err / np.maximum(tail, 1e-300)))
    # shapes broadcast through, as the conditional draws use them
    assert t_quantile(nu, p[:6].reshape(2, 3)).shape == (2, 3)


def test_weighted_ranks_drawn_are_uniform_order_statistics():
    # With an rng the steps are Gamma(w) draws (Bayesian bootstrap): the order stays, the
    # mean is about Hazen's (i - 1/2)/m, and the k-th largest position's exceedance is
    # k - 1 unit exponentials and half of one over the sum of m: mean (k - 1/2)/m,
    # coefficient of variation sqrt(k - 3/4)/(k - 1/2)
    from pas.stats.dependence import weighted_ranks

    m = 400
    x = np.random.default_rng(3).permutation(m).astype(float)
    rng = np.random.default_rng(4)
    draws = np.array([weighted_ranks(x, np.ones(m), rng) for _ in range(3000)])
    assert np.all(np.argsort(draws, axis=1) == np.argsort(x))
    hazen = (x + 0.5) / m
    np.testing.assert_allclose(draws.mean(axis=0), hazen, atol=3e-3)
    for k in (1, 10):
        exceed = 1.0 - draws[:, x == m - k][:, 0]
        assert exceed.mean() == pytest.approx((k - 0.5) / m, rel=0.06)
        assert exceed.std() / exceed.mean() == pytest.approx(
            np.sqrt(k - 0.75) / (k - 0.5), rel=0.08
        )
    np.testing.assert_array_equal(weighted_ranks(x, np.ones(m)), hazen)


def test_gpd_tail_ranks_read_the_top_of_a_rayleigh_sample_closer_to_its_cdf():
    # The top 30 of 15 000 Rayleigh peaks: the exceedance probability of each against the
    # exact exp(-x²/2), from Hazen mid-ranks and from the GPD tail over the top 5 %
    from pas.stats.dependence import gpd_tail_ranks

    for seed in range(5):
        x = np.random.default_rng(seed).rayleigh(1.0, 15_000)
        u = (np.argsort(np.argsort(x)) + 0.5) / x.size
        v, (shape, scale) = gpd_tail_ranks(x, u)
        assert -0.3 < shape < 0.05          # a Rayleigh tail is light: ξ a little below 0
        top = np.argsort(x)[-30:]
        exact = np.exp(-x[top] ** 2 / 2)
        ranks_err = np.mean(np.abs(np.log((1 - u[top]) / exact)))
        gpd_err = np.mean(np.abs(np.log((1 - v[top]) / exact)))
        assert gpd_err < ranks_err
        assert np.all(np.argsort(v, kind="stable") == np.argsort(x, kind="stable"))
        below = x < np.sort(x)[-750]
        np.testing.assert_array_equal(v[below], u[below])
    small = np.arange(150.0)
    np.testing.assert_array_equal(gpd_tail_ranks(small, small / 150)[0], small / 150)
    # bootstrap refits: a resampled bounded tail may not end below the largest value
    rng = np.random.default_rng(0)
    for seed in range(40):
        x = np.random.default_rng(seed).rayleigh(1.0, 1000)
        u = (np.argsort(np.argsort(x)) + 0.5) / x.size
        assert gpd_tail_ranks(x, u, rng=rng)[0].max() < 1.0


def test_weighted_ranks_drawn_with_tiny_weights_stay_finite():
    from pas.stats.dependence import weighted_ranks

    x = np.arange(50.0)
    w = np.r_[np.full(45, 1e-6), np.ones(5)]
    rng = np.random.default_rng(1)
    for _ in range(200):
        u = weighted_ranks(x, w, rng)
        assert np.all(np.isfinite(u)) and np.all(np.diff(u) >= 0) and u[-1] < 1
    u = weighted_ranks(x, np.full(50, 1e-300), rng)
    assert np.all(np.isfinite(u))
