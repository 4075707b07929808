"""Joint fits of many resamples at once against pas.models.joint's one at a time."""

import numpy as np
import pytest
from scipy import optimize

from pas.models.joint import fit_joint, joint_objective
from pas.models.joint_batch import (
    batch_objective,
    fit_joint_batch,
    minimise_together,
    weighted_pairs,
)


def _pairs(seed, n=40):
    rng = np.random.default_rng(seed)
    u = rng.uniform(0.02, 0.98, n)
    h = 2.0 + rng.weibull(1.6, n) * (1.0 + 2.5 * u)
    return u, h


def _resamples(u, h, k, seed):
    rng = np.random.default_rng(seed)
    return [(u[i], h[i]) for i in (rng.integers(0, u.size, u.size) for _ in range(k))]


@pytest.mark.parametrize("name", ["gaussian", "student", "clayton", "gumbel", "frank"])
@pytest.mark.parametrize("marginal, location, censor",
                         [("weibull", True, 0.0), ("lognormal", True, 0.2),
                          ("weibull", False, 0.0)])
def test_the_weighted_objective_is_the_resamples_own(name, marginal, location, censor):
    # a resample with repeats against its distinct pairs weighted by their counts, at points
    # away from the optimum, value and gradient (Student-t's ν by the same difference)
    u, h = _pairs(0)
    samples = _resamples(u, h, 3, 1)
    data = weighted_pairs(name, samples, location=location, censor=censor, width=u.size)
    assert np.all(data["w"].sum(axis=1) == u.size)
    objective = batch_objective(name, data, location=location, marginal=marginal)
    rng = np.random.default_rng(2)
    n_par = (3 if location else 2) + (2 if name == "student" else 1)
    x = rng.normal(0.0, 0.3, (3, n_par)) + np.r_[[-1.0] if location else [], 0.5, 0.3,
                                                  [0.6] * (n_par - (3 if location else 2))]
    f, g = objective(x, np.arange(3))
    for j, (uj, hj) in enumerate(samples):
        _, grad, _ = joint_objective(name, uj, hj, location=location, censor=censor,
                                     marginal=marginal)
        f_one, g_one = grad(x[j])
        assert f[j] == pytest.approx(f_one, rel=1e-10)
        np.testing.assert_allclose(g[j], g_one, rtol=1e-6, atol=1e-6 * np.abs(g_one).max())


def test_lockstep_iterates_are_those_of_scipy_minimize():
    # each problem's L-BFGS-B stops where scipy's own would: same evaluations, same point
    centres = np.array([[1.0, -2.0, 0.5], [3.0, 0.2, -1.0], [0.1, 0.1, 0.1]])

    def rosen_like(x, c):
        d = x - c
        return float(np.sum(d ** 2) + 0.5 * (d[0] * d[1]) ** 2 + np.exp(d[2]) - d[2]), \
            np.array([2 * d[0] + d[0] * d[1] ** 2, 2 * d[1] + d[1] * d[0] ** 2,
                      2 * d[2] + np.exp(d[2]) - 1.0])

    def together(X, rows):
        out = [rosen_like(x, centres[r]) for x, r in zip(X, rows)]
        return np.array([o[0] for o in out]), np.array([o[1] for o in out])

    bounds = [[(None, None), (-1.5, None), (None, 2.0)]] * 3
    starts = [np.zeros(3), np.ones(3), np.full(3, -2.0)]
    res = minimise_together(together, starts, bounds, np.arange(3))
    for j in range(3):
        alone = optimize.minimize(rosen_like, starts[j], args=(centres[j],), jac=True,
                                  method="L-BFGS-B", bounds=bounds[j])
        assert res[j].nfev == alone.nfev
        np.testing.assert_allclose(res[j].x, alone.x, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name, cold", [("gaussian", False), ("gumbel", False), ("student", True)])
@pytest.mark.parametrize("marginal", ["weibull", "lognormal"])
def test_batched_fits_reach_the_one_at_a_time_optima(name, cold, marginal):
    u, h = _pairs(3, n=50)
    final = fit_joint(name, u, h, marginal=marginal)
    samples = _resamples(u, h, 6, 4)
    batch = fit_joint_batch(name, samples, [final.x] * 6, cold=cold, marginal=marginal)
    for (uj, hj), fit in zip(samples, batch):
        alone = fit_joint(name, uj, hj, start=final.x, cold=cold, marginal=marginal)
        # Student-t's ν is flat near its optimum: the likelihood, not the parameters, agrees
        assert fit.copula.loglik == pytest.approx(alone.copula.loglik, abs=1e-5)
        assert fit.copula.name == name and fit.marginal == marginal
        if name != "student":
            np.testing.assert_allclose(fit.x, alone.x, rtol=1e-6, atol=1e-6)


def test_a_resample_that_cannot_be_fitted_gives_its_error_and_leaves_the_others():
    u, h = _pairs(5)
    final = fit_joint("gumbel", u, h)
    good = _resamples(u, h, 2, 6)
    alike = (u[:5], np.r_[h[:3], h[:2]])  # three different loads: fitted; two: not
    two = (u[:5], np.r_[h[:2], h[:2], h[:1]])
    out = fit_joint_batch("gumbel", [good[0], two, alike, good[1]], [final.x] * 4)
    assert isinstance(out[1], ValueError) and "at least 3 different HF loads" in str(out[1])
    assert not isinstance(out[2], Exception)
    for j, (uj, hj) in ((0, good[0]), (3, good[1])):
        alone = fit_joint("gumbel", uj, hj, start=final.x, cold=False)
        assert out[j].copula.loglik == pytest.approx(alone.copula.loglik, rel=1e-9)


@pytest.mark.parametrize("marginal, location, censor",
                         [("weibull", True, 0.0), ("lognormal", True, 0.2),
                          ("weibull", False, 0.0)])
def test_student_nu_derivative_is_the_objectives_own(marginal, location, censor):
    # the ν derivative from the t quantiles' (implicit function theorem) against a central
    # difference of the objective's value; at these points the second resample has a pair
    # with v = F_H(h) within 1.2e-9 of 1, where a CDF difference taken above the median
    # loses its digits (it was 2 % off)
    u, h = _pairs(0)
    samples = _resamples(u, h, 3, 1)
    data = weighted_pairs("student", samples, location=location, censor=censor,
                          width=u.size + 3)  # with padding
    objective = batch_objective("student", data, location=location, marginal=marginal)
    n_par = (3 if location else 2) + 2
    x = np.random.default_rng(2).normal(0.0, 0.3, (3, n_par)) + np.r_[
        [-1.0] if location else [], 0.5, 0.3, 0.6, 0.6]
    _, g = objective(x, np.arange(3))
    step = np.zeros(n_par)
    step[-1] = 1e-5
    central = (objective(x + step, np.arange(3))[0]
               - objective(x - step, np.arange(3))[0]) / 2e-5
    np.testing.assert_allclose(g[:, -1], central, rtol=1e-5, atol=1e-7)


def test_student_quantiles_skip_the_padding_with_the_same_values():
    # the t quantiles and their ν slopes of the pairs of weight above 0 alone, the padding
    # given its row's first pair's: the same numbers as computing them everywhere
    from pas.models.joint_batch import _t_quantile_and_slope

    u, h = _pairs(3)
    data = weighted_pairs("student", _resamples(u, h, 4, 5), width=u.size + 2)
    live = data["w"] > 0
    assert not live.all() and live[:, 0].all()
    nu = np.array([[2.3], [4.0], [11.0], [47.0]])
    for w in (data["u"], 1.0 - data["u"] ** 3):
        everywhere = _t_quantile_and_slope(nu, w)
        skipped = _t_quantile_and_slope(nu, w, live)
        for a, b in zip(skipped, everywhere):
            np.testing.assert_array_equal(a[live], b[live])
            np.testing.assert_array_equal(a, np.where(live, a, a[:, :1]))
            np.testing.assert_array_equal(a[~live], b[~live])  # padding = copy of pair 0


def _student_pairs(seed, n=60, rho=0.6, nu=4.0):
    """Pairs of a Student-t copula (ρ 0.6, ν 4) to a shifted log-normal load."""
    from scipy import stats

    rng = np.random.default_rng(seed)
    z = rng.multivariate_normal([0.0, 0.0], [[1.0, rho], [rho, 1.0]], n)
    t = z / np.sqrt(rng.chisquare(nu, n) / nu)[:, None]
    uv = stats.t.cdf(t, nu)
    return uv[:, 0], 2.0 + stats.lognorm(0.6).ppf(uv[:, 1])


@pytest.mark.parametrize("marginal", ["weibull", "lognormal"])
def test_a_warm_student_start_is_trapped_at_the_edges_and_a_start_from_the_data_too_frees_it(
        marginal):
    """A warm start with ν at its bound of 50 (optimiser value 10.5, where the logistic map
    is flat) and the location at the smallest load stays short of the optimum a start from
    the data finds; also started from the data (the band's COLD_FAMILIES) it reaches it."""
    short = []
    for seed in range(2, 6):
        u, h = _student_pairs(seed)
        cold = fit_joint("student", u, h, marginal=marginal)
        trapped = np.array(cold.x, float)
        trapped[-1], trapped[0] = 10.5, -8.4
        [warm] = fit_joint_batch("student", [(u, h)], [trapped], cold=False, marginal=marginal)
        [both] = fit_joint_batch("student", [(u, h)], [trapped], cold=True, marginal=marginal)
        assert both.copula.loglik == pytest.approx(cold.copula.loglik, abs=1e-3)
        short.append(cold.copula.loglik - warm.copula.loglik)
    assert max(short) > 1.0, short  # the trap is real
