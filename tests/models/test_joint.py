"""The joint fit of copula and HF marginal, its closed-form densities, τ inversion, presets."""

import copy

import numpy as np
import pytest
import pyvinecopulib as pv
from scipy import stats

import pas
from pas.models.copula_densities import (
    copula_loghfunc,
    copula_logpdf,
    logc_grad,
    logh_grad,
)
from pas.models.copulas import fit_copula, tau_inversion_parameter
from pas.models.joint import fit_joint
from pas.strategies.estimators import SelectedSample
from pas.strategies.pas import PAS

RNG = np.random.default_rng(0)
U, V = RNG.uniform(0.002, 0.998, 400), RNG.uniform(0.002, 0.998, 400)
CASES = [("gaussian", [0.6]), ("gaussian", [-0.3]), ("clayton", [2.5]), ("gumbel", [1.7]),
         ("gumbel", [6.0]), ("frank", [6.0]), ("frank", [34.9]), ("frank", [-2.0])]


def _frank_exact(th, u, v):
    """log c and log h of Frank in 60-digit decimals (a reference where floats cancel)."""
    from decimal import Decimal, getcontext

    getcontext().prec = 60
    th, u, v = Decimal(th), Decimal(float(u)), Decimal(float(v))
    e = lambda x: (-x).exp()  # noqa: E731
    den = e(th * u) + e(th * v) - e(th * (u + v)) - e(th)
    log_c = (th * (1 - e(th))).ln() - th * (u + v) - 2 * abs(den).ln()
    log_h = (e(th * u) * (1 - e(th * v)) / den).ln()
    return float(log_c), float(log_h)


def test_frank_near_its_bound_matches_exact_arithmetic():
    # pyvinecopulib's own Frank h-function is off by up to 1e-2 here (the form
    # (1 − e^{−θ}) − (1 − e^{−θu})(1 − e^{−θv}) cancels); ours is not
    for u, v in zip(U[:40], V[:40]):
        c, h = _frank_exact(34.9, u, v)
        assert copula_logpdf("frank", [34.9], np.array([u]), np.array([v]))[0] == pytest.approx(
            c, abs=1e-9)
        assert copula_loghfunc("frank", [34.9], np.array([u]), np.array([v]))[0] == pytest.approx(
            h, abs=1e-9)


@pytest.mark.parametrize("family, p", [c for c in CASES if c[1][0] < 30])
def test_closed_forms_match_pyvinecopulib(family, p):
    cop = pv.Bicop(family=getattr(pv.BicopFamily, family), parameters=np.array(p).reshape(-1, 1))
    uv = np.column_stack([U, V])
    np.testing.assert_allclose(copula_logpdf(family, p, U, V), np.log(cop.pdf(uv)),
                               atol=1e-9, rtol=1e-9)
    np.testing.assert_allclose(copula_loghfunc(family, p, U, V), np.log(cop.hfunc1(uv)),
                               atol=1e-8, rtol=1e-8)


def test_student_closed_forms_match_pyvinecopulib():
    cop = pv.Bicop(family=pv.BicopFamily.student, parameters=np.array([[0.6], [4.0]]))
    uv = np.column_stack([U, V])
    np.testing.assert_allclose(copula_logpdf("student", [0.6, 4.0], U, V), np.log(cop.pdf(uv)),
                               atol=1e-9)
    np.testing.assert_allclose(copula_loghfunc("student", [0.6, 4.0], U, V),
                               np.log(cop.hfunc1(uv)), atol=1e-9)


@pytest.mark.parametrize("family, p", [c for c in CASES if c[1][0] < 30])
@pytest.mark.parametrize("fn", [logc_grad, logh_grad])
def test_derivatives_match_finite_differences(family, p, fn):
    _, dv, dth = fn(family, p, U, V)
    e = 1e-6
    num_v = (fn(family, p, U, V + e, grad=False)[0] - fn(family, p, U, V - e, grad=False)[0]) / 2e-6
    num_t = (fn(family, [p[0] + e], U, V, grad=False)[0]
             - fn(family, [p[0] - e], U, V, grad=False)[0]) / 2e-6
    np.testing.assert_allclose(dv, num_v, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(dth, num_t, rtol=1e-5, atol=1e-5)


@pytest.mark.parametrize("family", ["clayton", "gumbel", "frank"])
def test_tau_inversion_is_the_copulas_package_estimate(family):
    from copulas.bivariate import Clayton, Frank, Gumbel

    cop = pv.Bicop(family=getattr(pv.BicopFamily, family), parameters=np.array(
        [[{"clayton": 3.0, "gumbel": 2.5, "frank": 9.0}[family]]]))
    uv = cop.simulate(300, seeds=[1, 2, 3])
    peer = {"clayton": Clayton, "gumbel": Gumbel, "frank": Frank}[family]()
    peer.fit(uv)
    ours = fit_copula(family, uv[:, 0], uv[:, 1], method="itau")
    assert ours.parameters[0] == pytest.approx(peer.theta, rel=1e-5)
    with pytest.raises(ValueError, match="cannot have tau"):
        tau_inversion_parameter("gumbel", -0.2)


def test_joint_fit_recovers_a_known_model():
    n = 3000
    rng = np.random.default_rng(4)
    u = rng.uniform(size=n)
    cop = pv.Bicop(family=pv.BicopFamily.gaussian, parameters=np.array([[0.7]]))
    v = cop.hinv1(np.column_stack([u, rng.uniform(size=n)]))
    h = stats.weibull_min(1.5, loc=0.5, scale=2.0).ppf(v)
    fit = fit_joint("gaussian", u, h)
    assert fit.copula.parameters[0] == pytest.approx(0.7, abs=0.03)
    w = fit.hf_marginal
    assert (w.theta, w.alpha, w.beta) == pytest.approx((0.5, 2.0, 1.5), rel=0.1)
    with pytest.raises(ValueError, match="at least 3 different HF loads"):
        fit_joint("gaussian", u[:10], np.full(10, 3.0))


def test_common_random_numbers_never_change_as_the_conditioning_set_grows():
    def numbers(history, seed=7):
        st = PAS()
        st.reset(seed)
        for n in history:
            r, q = st._random_numbers(n, None)
        return r, q

    r_big, q_big = numbers([300, 1500, 5000])
    for history in ([5000], [1200, 2500, 5000], [10, 1024, 1025, 5000]):
        r, q = numbers(history)
        np.testing.assert_array_equal(r, r_big)
        np.testing.assert_array_equal(q, q_big)
    r_small, q_small = numbers([300])
    np.testing.assert_array_equal(r_small, r_big[:, :300])
    assert not np.array_equal(numbers([300], seed=8)[0], r_small)


def test_paper_preset_through_the_api():
    lf = np.random.default_rng(0).rayleigh(2.0, 2000)
    study = pas.make_study(pas.PAS.paper(), lf, n_waves=2000, p_exp=1e-2, eps1=0.1, seed=0)
    s = study.settings()
    assert s["max_hf"] is None and s["stop_measure"] == "step"
    assert s["strategy_settings"]["estimator"] == "selected"
    assert s["strategy_settings"]["copula_fit"] == "itau"
    assert pas.make_study("paper", lf, n_waves=2000, p_exp=1e-2, eps1=0.1, seed=0).settings() == s
    own = pas.make_study(pas.PAS.paper(), lf, n_waves=2000, p_exp=1e-2, max_hf=40,
                         stopping=pas.Stopping(eps1=0.1, k1=9))
    assert own.max_hf == 40 and own.rule.measure == "window"     # given settings win
    assert pas.make_study("pas", lf, n_waves=2000, p_exp=1e-2, eps1=0.1).max_hf == 160
    from pas.study.flat import from_flat
    with pytest.raises(ValueError, match="preset must be one of"):
        from_flat({}, preset="papers")
    with pytest.raises(ValueError, match="set of PAS settings"):
        from_flat({}, strategy="as", preset="paper")


def test_the_conditional_fit_keeps_every_pair():
    # Step 7 selects pairs by their HF value; the conditional likelihood must not
    from pas.strategies.base import Pairs
    from pas.strategies.screening import LFSet

    s = LFSet(np.linspace(10, 0.1, 500), n_waves=600, p_exp=0.01)
    pos = np.arange(0, 500, 25)
    hf = 2 * s.lf[pos] + 1
    hf[1] += 60.0  # a genuine heavy load far off the trend
    pairs = Pairs(pos, s.lf[pos], hf, s.d[pos])
    cond = PAS().predict(pairs, s, np.random.default_rng(0))
    sel = PAS(estimator=SelectedSample()).predict(pairs, s, np.random.default_rng(0))
    assert cond.record["n_outliers"] == 0 and sel.record["n_outliers"] == 1


def _pairs(marginal, n=3000, seed=4):
    rng = np.random.default_rng(seed)
    u = rng.uniform(size=n)
    cop = pv.Bicop(family=pv.BicopFamily.gaussian, parameters=np.array([[0.7]]))
    v = cop.hinv1(np.column_stack([u, rng.uniform(size=n)]))
    return u, marginal.ppf(v)


def test_lognormal3_matches_scipy():
    from pas.stats import LogNormal3

    d = LogNormal3(theta=50.0, mu=6.0, sigma=0.7)
    ref = stats.lognorm(0.7, loc=50.0, scale=np.exp(6.0))
    x = np.array([10.0, 50.0, 120.0, 900.0, 2e4])
    np.testing.assert_allclose(d.cdf(x), ref.cdf(x), rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(d.sf(x), ref.sf(x), rtol=1e-10)
    p = np.array([1e-9, 0.3, 0.5, 0.999, 1 - 1e-12])
    np.testing.assert_allclose(d.ppf(p), ref.ppf(p), rtol=1e-10)
    np.testing.assert_allclose(d.isf(p), ref.isf(p), rtol=1e-10)


def test_joint_fit_recovers_a_lognormal_marginal():
    from pas.models.joint import best_per_family, fit_joint_all
    from pas.stats import LogNormal3

    u, h = _pairs(stats.lognorm(0.8, loc=100.0, scale=np.exp(6.0)))
    fit = fit_joint("gaussian", u, h, marginal="lognormal")
    assert isinstance(fit.hf_marginal, LogNormal3) and fit.marginal == "lognormal"
    assert fit.copula.parameters[0] == pytest.approx(0.7, abs=0.03)
    m = fit.hf_marginal
    assert (m.theta, m.mu, m.sigma) == pytest.approx((100.0, 6.0, 0.8), rel=0.1)
    # the likelihood tells the marginals apart, both ways
    for data, right in ((h, "lognormal"),
                        (_pairs(stats.weibull_min(1.5, loc=0.5, scale=2.0))[1], "weibull")):
        best = best_per_family(fit_joint_all(u, data, ["gaussian"],
                                             marginals=("weibull", "lognormal")))
        assert best["gaussian"].marginal == right


@pytest.mark.parametrize("marginal", ["weibull", "lognormal"])
@pytest.mark.parametrize("family", ["gaussian", "clayton", "gumbel", "frank"])
def test_objective_gradient_matches_finite_differences(family, marginal):
    from pas.models.joint import joint_objective

    u, h = _pairs(stats.lognorm(0.8, loc=100.0, scale=np.exp(6.0)), n=200, seed=1)
    negloglik, negloglik_grad, _ = joint_objective(family, u, h, marginal=marginal,
                                                   censor=0.1)
    x = np.array([np.log(0.3), 6.1 if marginal == "lognormal" else np.log(500.0),
                  np.log(0.7 if marginal == "lognormal" else 1.2), 0.4])
    value, grad = negloglik_grad(x)
    assert value == pytest.approx(negloglik(x), rel=1e-12)
    step = 1e-6
    fd = [(negloglik(x + step * e) - negloglik(x - step * e)) / (2 * step) for e in np.eye(4)]
    np.testing.assert_allclose(grad, fd, rtol=1e-5, atol=1e-4)


def _bore_impulse(n, seed):
    """Pairs whose HF is 60 % a narrow body and 40 % a wide tail, Gaussian copula ρ 0.7."""
    from pas.stats.weibull_mixture import WeibullMixture

    truth = WeibullMixture(theta=0.0, p=0.6, alpha1=150.0, beta1=3.5, alpha2=550.0, beta2=1.1)
    return (truth, *_pairs(truth, n=n, seed=seed))


def test_weibull_mixture_quantiles_invert_its_survival_function():
    from pas.stats.weibull_mixture import WeibullMixture

    d = WeibullMixture(theta=20.0, p=0.6, alpha1=150.0, beta1=3.5, alpha2=550.0, beta2=1.1)
    ref = [stats.weibull_min(3.5, loc=20.0, scale=150.0), stats.weibull_min(1.1, loc=20.0,
                                                                             scale=550.0)]
    x = np.array([10.0, 100.0, 400.0, 3000.0])
    np.testing.assert_allclose(d.sf(x), 0.6 * ref[0].sf(x) + 0.4 * ref[1].sf(x), rtol=1e-12)
    q = np.array([0.9, 0.5, 1e-2, 1e-6, 1e-12])
    np.testing.assert_allclose(d.sf(d.isf(q)), q, rtol=1e-9)
    np.testing.assert_allclose(d.cdf(d.ppf(1 - q)), 1 - q, rtol=1e-9)


@pytest.mark.parametrize(("family", "location", "censor"), [
    *[(f, loc, cen) for f in ("gaussian", "clayton", "gumbel", "frank")
      for loc, cen in [(True, 0.1), (True, 0.0), (False, 0.3)]],
    ("student", True, 0.1), ("student", False, 0.0)])
def test_mixture_objective_gradient_matches_finite_differences(family, location, censor):
    from pas.models.joint_mixture import mixture_objective

    _, u, h = _bore_impulse(200, seed=1)
    negloglik, negloglik_grad, _ = mixture_objective(family, u, h, location=location,
                                                     censor=censor)
    nu = [-1.0] if family == "student" else []   # Student-t's ν, as an optimiser value
    x = np.array(([np.log(0.1)] if location else []) + [
        0.3, np.log(140.0), np.log(3.0), np.log(600.0), np.log(1.2), 0.4] + nu)
    value, grad = negloglik_grad(x)
    assert value == pytest.approx(negloglik(x), rel=1e-12)
    step = 1e-6
    fd = [(negloglik(x + step * e) - negloglik(x - step * e)) / (2 * step)
          for e in np.eye(x.size)]
    np.testing.assert_allclose(grad, fd, rtol=1e-5, atol=1e-4)


def test_mixture_fit_recovers_a_bore_impulse_marginal_and_wins_on_aic():
    from pas.models.joint import best_per_family, fit_joint_all
    from pas.models.joint_mixture import MIXTURE, fit_joint_mixture_all

    truth, u, h = _bore_impulse(3000, seed=2)
    weibull = fit_joint_all(u, h, ["gaussian"], location=False)
    fits = weibull | fit_joint_mixture_all(u, h, weibull, location=False)
    best = best_per_family(fits, by="aic")["gaussian"]
    assert best.marginal == MIXTURE
    m = best.hf_marginal
    assert m.theta == 0.0  # no location: the two-parameter components
    assert (m.p, m.alpha1, m.beta1, m.alpha2, m.beta2) == pytest.approx(
        (truth.p, truth.alpha1, truth.beta1, truth.alpha2, truth.beta2), rel=0.12)
    assert best.copula.parameters[0] == pytest.approx(0.7, abs=0.03)
    # the tail a single Weibull bends towards the body; the mixture's does not
    q = 1e-3
    one = weibull["gaussian", "weibull"].hf_marginal.isf(q)
    assert abs(m.isf(q) / truth.isf(q) - 1) < 0.05 < abs(one / truth.isf(q) - 1)
    # on a single Weibull the three extra parameters do not pay
    uw, hw = _pairs(stats.weibull_min(1.5, loc=0.5, scale=2.0))
    w = fit_joint_all(uw, hw, ["gaussian"])
    assert best_per_family(w | fit_joint_mixture_all(uw, hw, w),
                           by="aic")["gaussian"].marginal == "weibull"


def test_a_failed_warm_mixture_start_goes_cold_as_the_weibull_fit_does():
    from pas.models.joint import fit_joint
    from pas.models.joint_mixture import fit_joint_mixture

    _, u, h = _bore_impulse(400, seed=3)
    weibull = fit_joint("gaussian", u, h, location=False)
    cold = fit_joint_mixture("gaussian", u, h, weibull, location=False)
    # a start whose objective is not finite (a scale of e^800 overflows every term)
    bad = np.array([0.0, 800.0, 0.0, 800.0, 0.0, 0.4])
    warm_only = fit_joint_mixture("gaussian", u, h, weibull, location=False, start=bad, cold=False)
    assert warm_only.copula.loglik == pytest.approx(cold.copula.loglik, rel=1e-9)
    # a good warm start alone is kept as it is (no cold start is needed)
    again = fit_joint_mixture("gaussian", u, h, weibull, location=False, start=cold.x, cold=False)
    assert again.copula.loglik >= cold.copula.loglik - 1e-6


def test_mixture_likelihood_keeps_its_digits_just_above_the_location():
    # loads a hair above θ, where F = 1 − S would keep only a few digits
    from pas.models.joint_mixture import mixture_objective
    from pas.stats.weibull_mixture import WeibullMixture

    h = np.array([1e-6, 3e-6, 1e-5, 50.0, 300.0])  # F ≈ 1e-10 … 1e-9 at the first three
    u = np.array([0.01, 0.02, 0.05, 0.5, 0.9])
    negloglik, _, unpack = mixture_objective("gaussian", u, h, location=False)
    x = np.array([0.3, np.log(150.0), np.log(3.5), np.log(550.0), np.log(1.1), 0.45])
    theta, p, a1, b1, a2, b2, c = unpack(x)
    m = WeibullMixture(theta=theta, p=p, alpha1=a1, beta1=b1, alpha2=a2, beta2=b2)
    rho = 0.999 * np.tanh(c[0])
    pdf = p * stats.weibull_min(b1, scale=a1).pdf(h) + (1 - p) * stats.weibull_min(
        b2, scale=a2).pdf(h)
    zl, zh = stats.norm.ppf(u), stats.norm.ppf(m.cdf(h))
    log_c = (stats.multivariate_normal([0, 0], [[1, rho], [rho, 1]]).logpdf(np.c_[zl, zh])
             - stats.norm.logpdf(zl) - stats.norm.logpdf(zh))
    assert negloglik(x) == pytest.approx(-np.sum(np.log(pdf) + log_c), rel=1e-10)


STUDENT_POINTS = [[0.6, 4.0], [-0.4, 2.3], [0.9, 30.0], [0.2, 12.0]]


@pytest.mark.parametrize("p", STUDENT_POINTS)
@pytest.mark.parametrize("fn", [logc_grad, logh_grad])
def test_student_derivatives_match_finite_differences(p, fn):
    _, dv, drho = fn("student", p, U, V)
    e = 1e-6
    num_v = (fn("student", p, U, V + e, grad=False)[0]
             - fn("student", p, U, V - e, grad=False)[0]) / 2e-6
    num_rho = (fn("student", [p[0] + e, p[1]], U, V, grad=False)[0]
               - fn("student", [p[0] - e, p[1]], U, V, grad=False)[0]) / 2e-6
    np.testing.assert_allclose(dv, num_v, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(drho, num_rho, rtol=1e-5, atol=1e-5)


def _student_x(marginal, rho, nu, location=True):
    """Optimiser values of a Student-t joint fit at ``(ρ, ν)`` (inverse of the joint's maps)."""
    marg = [6.1 if marginal == "lognormal" else np.log(500.0),
            np.log(0.7 if marginal == "lognormal" else 1.2)]
    cop = [np.arctanh(rho / 0.999), -np.log(48.0 / (nu - 2.0) - 1.0)]
    return np.array(([np.log(0.3)] if location else []) + marg + cop)


@pytest.mark.parametrize("marginal", ["weibull", "lognormal"])
@pytest.mark.parametrize("rho, nu", [(0.6, 4.0), (-0.3, 2.5), (0.85, 25.0), (0.3, 9.0)])
def test_student_objective_gradient_matches_finite_differences(marginal, rho, nu):
    from pas.models.joint import joint_objective

    u, h = _pairs(stats.lognorm(0.8, loc=100.0, scale=np.exp(6.0)), n=200, seed=1)
    negloglik, negloglik_grad, _ = joint_objective("student", u, h, marginal=marginal,
                                                   censor=0.1)
    assert negloglik_grad is not None
    x = _student_x(marginal, rho, nu)
    value, grad = negloglik_grad(x)
    assert value == pytest.approx(negloglik(x), rel=1e-12)
    step = 1e-6
    fd = [(negloglik(x + step * e) - negloglik(x - step * e)) / (2 * step) for e in np.eye(5)]
    np.testing.assert_allclose(grad, fd, rtol=1e-5, atol=1e-4)


def test_student_fit_with_its_gradient_finds_the_numerical_optimum():
    """The fit with the analytic gradient ends where an optimiser of the same objective with
    finite differences (scipy's L-BFGS-B, started from the same point) ends, or lower."""
    from scipy.optimize import minimize

    from pas.models.joint import joint_objective

    u, h = _pairs(stats.weibull_min(1.5, loc=0.5, scale=2.0), n=160, seed=3)
    analytic = fit_joint("student", u, h, censor=0.05)
    negloglik, _, _ = joint_objective("student", u, h, censor=0.05)
    start = np.asarray(analytic.x) + np.random.default_rng(0).normal(0.0, 0.05, analytic.x.size)
    numerical = minimize(negloglik, start, method="L-BFGS-B")
    assert negloglik(analytic.x) <= numerical.fun + 1e-6
    assert negloglik(analytic.x) == pytest.approx(numerical.fun, rel=1e-6)
    np.testing.assert_allclose(analytic.x[-2:], numerical.x[-2:], rtol=2e-2, atol=2e-2)


def test_a_deep_copy_of_a_joint_fit_shares_it_and_its_values_cannot_change():
    rng = np.random.default_rng(3)
    u = rng.uniform(size=40)
    fit = fit_joint("gaussian", u, 5.0 + 3.0 * u + rng.uniform(size=40))
    assert copy.deepcopy({"fit": fit})["fit"] is fit
    with pytest.raises(ValueError):
        fit.x[0] = 1.0



def test_copula_parameters_reach_their_bounds_without_overflow():
    """An optimiser value far past a bound gives the bound, with no overflow in exp()."""
    from pas.models.joint_likelihood import copula_parameters, parameter_slope

    c = np.array([800.0, 0.0, -800.0])
    with np.errstate(over="raise"):
        clayton = copula_parameters("clayton", [c])[0, 0]
        gumbel = copula_parameters("gumbel", [c])[0, 0]
        slopes = parameter_slope("clayton", [c]), parameter_slope("gumbel", [c])
    np.testing.assert_array_equal(clayton, [28.0, 1.0, 1e-6])
    np.testing.assert_array_equal(gumbel, [50.0, 2.0, 1.0])
    np.testing.assert_array_equal(slopes[0], [0.0, 1.0, 0.0])  # flat at both clips
    np.testing.assert_array_equal(slopes[1], [0.0, 1.0, 0.0])  # flat at 50; e^c at 1
