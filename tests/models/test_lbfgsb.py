"""The setulb driver against scipy.optimize.minimize on the joint fits' own objectives."""

import numpy as np
import pytest
from scipy import optimize

from pas.models.joint import joint_objective, location_bounds
from pas.models.lbfgsb import minimise_one


@pytest.mark.parametrize("name, marginal", [("student", "weibull"), ("gumbel", "lognormal"),
                                            ("frank", "weibull")])
def test_one_problem_takes_scipys_iterates(name, marginal):
    # the loop's joint fits go through this driver: the same optimum to the last bit, the
    # same evaluations (same code path, same machine: that is the point)
    rng = np.random.default_rng(7)
    u = rng.uniform(0.02, 0.98, 60)
    h = 2.0 + rng.weibull(1.6, 60) * (1.0 + 2.5 * u)
    _, grad, _ = joint_objective(name, u, h, marginal=marginal)
    shape = (
        (np.log(0.02), np.log(10.0)) if marginal == "lognormal" else (np.log(0.05), np.log(50.0))
    )
    bounds = location_bounds(h, 0.0, True) + [(None, None), shape] + [(None, None)] * (
        2 if name == "student" else 1)
    x0 = np.r_[-1.0, 0.5 if marginal == "lognormal" else 1.0, 0.3, 0.5, [1.0] * (name == "student")]
    ours = minimise_one(grad, x0, bounds)
    theirs = optimize.minimize(grad, x0, jac=True, method="L-BFGS-B", bounds=bounds)
    assert ours.nfev == theirs.nfev and ours.nit == theirs.nit
    assert np.array_equal(ours.x, theirs.x) and ours.fun == theirs.fun
    assert ours.success == theirs.success and ours.message == theirs.message


def test_a_changed_private_routine_falls_back_to_scipy_with_a_warning(monkeypatch):
    # setulb is scipy's private routine; a release that calls it differently must cost
    # speed, not results: the driver finds out once and hands each problem to minimize
    import pas.models.lbfgsb as driver

    class Changed:
        @staticmethod
        def setulb(*args):
            raise TypeError("setulb() takes 18 positional arguments")

    monkeypatch.setattr(driver, "_lbfgsb", Changed)
    driver.driver_works.cache_clear()  # found out again, with the changed routine
    rng = np.random.default_rng(3)
    u = rng.uniform(0.02, 0.98, 50)
    h = 1.0 + rng.weibull(1.4, 50) * (1.0 + 2.0 * u)
    _, grad, _ = joint_objective("gumbel", u, h)
    bounds = location_bounds(h, 0.0, True) + [(None, None), (np.log(0.05), np.log(50.0)),
                                              (None, None)]
    x0 = np.r_[-1.0, 1.0, 0.3, 0.5]
    with pytest.warns(RuntimeWarning, match="scipy.optimize.minimize instead"):
        ours = driver.minimise_one(grad, x0, bounds)
    theirs = optimize.minimize(grad, x0, jac=True, method="L-BFGS-B", bounds=bounds)
    assert np.array_equal(ours.x, theirs.x) and ours.fun == theirs.fun
    assert driver.driver_works() is False  # remembered: asked once
    monkeypatch.undo()
    driver.driver_works.cache_clear()  # the real routine for the tests after this one


def test_the_driver_works_on_the_installed_scipy():
    # the fast path is the one CI's newest scipy takes; should this fail, the fallback
    # above keeps results right but the fits slow
    from pas.models.lbfgsb import driver_works

    assert driver_works()
