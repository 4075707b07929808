"""The conditional CDF C(v | u) of the long-record draws against pyvinecopulib and the inverse."""

import numpy as np
import pytest
import pyvinecopulib as pv

from pas.models.conditional_cdf import CLOSED_FORMS, conditional_cdf
from pas.models.copulas import conditional_quantile

CASES = [("gaussian", 0, [[0.7]]), ("gaussian", 0, [[-0.4]]), ("student", 0, [[0.6], [4.0]]),
         ("student", 0, [[0.9], [2.5]]), ("clayton", 0, [[2.0]]), ("clayton", 180, [[1.2]]),
         ("gumbel", 0, [[3.0]]), ("gumbel", 180, [[1.6]]), ("frank", 0, [[7.0]]),
         ("frank", 0, [[-5.0]]), ("joe", 0, [[2.0]]), ("joe", 180, [[1.5]]),
         ("bb1", 0, [[0.5], [1.5]]), ("bb1", 180, [[0.5], [1.5]])]


def _bicop(family, rotation, params):
    return pv.Bicop(family=getattr(pv.BicopFamily, family), rotation=rotation,
                    parameters=np.array(params, float))


def _points(n=3000, seed=0):
    rng = np.random.default_rng(seed)
    return rng.uniform(1e-6, 1 - 1e-6, n), rng.uniform(1e-6, 1 - 1e-6, n)


@pytest.mark.parametrize("family, rotation, params", CASES)
def test_conditional_cdf_is_pyvinecopulibs_hfunc1(family, rotation, params):
    b = _bicop(family, rotation, params)
    u, v = _points()
    np.testing.assert_allclose(conditional_cdf(b, v, u), b.hfunc1(np.column_stack([u, v])),
                               rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("family, rotation, params",
                         [c for c in CASES if c[0] in CLOSED_FORMS])
def test_conditional_cdf_undoes_the_draws_inverse_in_the_upper_tail(family, rotation, params):
    # the long-record draws choose candidates by C(v_L | u) and trust the inverse to put
    # every other uniform below v_L: the two must agree far inside tail_draws.MARGIN = 1e-3,
    # relative in 1 - r, where the top of a realisation lies
    b = _bicop(family, rotation, params)
    u, r = _points(seed=1)
    r = 1 - (1 - r) * 1e-3  # 1 - r from 1e-9 to 1e-3
    r = np.clip(r, None, 1 - 1e-6)
    back = conditional_cdf(b, conditional_quantile(b, u, r), u)
    np.testing.assert_allclose(1 - back, 1 - r, rtol=1e-9, atol=1e-15)


def test_joes_numerical_inverse_is_too_coarse_for_the_margin_so_it_draws_everything():
    # why CLOSED_FORMS leaves Joe out of the long-record draws: pyvinecopulib's hinv1
    # misses C(v | u) = r by more than tail_draws.MARGIN relative in 1 - r somewhere
    from pas.strategies.tail_draws import MARGIN

    b = _bicop("joe", 0, [[2.0]])
    u, r = _points(20000, seed=1)
    r = np.clip(1 - (1 - r) * 10 ** np.random.default_rng(2).uniform(-3, 0, r.size), None,
                1 - 1e-6)
    back = conditional_cdf(b, conditional_quantile(b, u, r), u)
    assert np.max(np.abs((1 - back) - (1 - r)) / (1 - r)) > MARGIN
    assert "joe" not in CLOSED_FORMS


@pytest.mark.parametrize("family, theta", [("gumbel", 1 + 1e-7), ("clayton", 1e-9),
                                           ("frank", -1e-9)])
def test_conditional_cdf_is_the_identity_where_the_inverse_draws_independence(family, theta):
    b = _bicop(family, 0, [[max(theta, 1.0) if family == "gumbel" else theta]])
    u, v = _points(50)
    np.testing.assert_array_equal(conditional_quantile(b, u, v), v)
    np.testing.assert_array_equal(conditional_cdf(b, v, u), v)


def test_conditional_cdf_broadcasts_one_level_against_many_peaks():
    b = _bicop("gumbel", 0, [[2.5]])
    u, _ = _points(40)
    v = np.array([0.99, 0.999])[:, None]
    got = conditional_cdf(b, v, u[None, :])
    assert got.shape == (2, 40)
    np.testing.assert_allclose(got[1], b.hfunc1(np.column_stack([u, np.full(40, 0.999)])),
                               rtol=1e-10)
