"""The model band's replicates: the same band on any number of processes, warm starts."""

import numpy as np
import pytest
from test_estimator import _problem

from pas.strategies import band
from pas.strategies.band import ModelBand
from pas.strategies.estimators import ConditionalLikelihood
from pas.strategies.pas import PAS


def _band(strategy, pairs, s, n_jobs):
    return strategy.model_band(pairs, s, np.random.default_rng(1), n_jobs=n_jobs)


@pytest.mark.slow
@pytest.mark.parametrize("lf_ranks", ["redrawn", "fixed"])
def test_the_band_is_the_same_on_one_and_on_two_processes(lf_ranks):
    # false positives: every replicate fits its own impact model, so its draw of the LF
    # ranks reads a different length of their stream; on two processes each replicate
    # must still find the stream where it would find it in turn
    s, pairs, _ = _problem(2, tau=0.6, p_impact=0.7, m=24)
    assert len(pairs.fp_position) > 0
    strategy = PAS(band=ModelBand(n_bootstrap=12, lf_ranks=lf_ranks))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    one = _band(strategy, pairs, s, 1)
    two = _band(strategy, pairs, s, 2)
    np.testing.assert_array_equal(one[2], two[2])
    assert one[:2] == two[:2]
    with pytest.raises(ValueError, match="n_jobs must be at least 1"):
        _band(strategy, pairs, s, 0)


def test_warm_replicates_reach_the_cold_optima(monkeypatch):
    # the warm-started band (Student-t also cold) against every replicate started from the
    # study's fits and from the data, as before
    s, pairs, _ = _problem(1, tau=0.6, m=30)
    strategy = PAS(band=ModelBand(n_bootstrap=12, marginals="fitted"))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    warm = _band(strategy, pairs, s, 1)
    monkeypatch.setattr(band, "WARM_BAND", False)
    cold = _band(strategy, pairs, s, 1)
    np.testing.assert_allclose(warm[2], cold[2], rtol=1e-4)


@pytest.mark.parametrize("family, params", [("gaussian", [[0.7]]), ("student", [[0.6], [4.0]])])
def test_kept_normal_scores_draw_what_the_uniforms_draw(family, params):
    import pyvinecopulib as pv
    from scipy import special

    from pas.models.copulas import conditional_quantile

    cop = pv.Bicop(family=getattr(pv.BicopFamily, family), parameters=np.array(params, float))
    rng = np.random.default_rng(5)
    u, r = rng.uniform(1e-6, 1 - 1e-6, (1, 300)), rng.uniform(1e-6, 1 - 1e-6, (4, 300))
    np.testing.assert_allclose(conditional_quantile(cop, u, r, r_scores=special.ndtri(r)),
                               conditional_quantile(cop, u, r), rtol=1e-12)


def test_peak_uniforms_keep_the_normal_scores_of_their_uniforms_as_the_set_grows():
    from scipy import special

    from pas.strategies.random_numbers import PeakUniforms

    crn = PeakUniforms(3, seed=7)
    first = crn.scores(1500).copy()
    grown = crn.scores(4000)
    r, _ = crn.draw(4000, None)
    np.testing.assert_allclose(grown, special.ndtri(r), rtol=1e-14)
    np.testing.assert_array_equal(grown[:, :1500], first)
    assert PeakUniforms(3, seed=7, common=False).scores(10) is None


def test_kept_lf_ranks_are_those_of_the_lf_set_fitted():
    # the ranks are kept per LF set and n0: a second set of as many peaks in the same order
    # (the cube of the first) has the same mid-ranks but another GPD tail, so its own ranks
    from pas.strategies.base import Pairs
    from pas.strategies.screening import LFSet

    s_a, pairs_a, _ = _problem(0, tau=0.6, m=20)
    s_b = LFSet(s_a.lf ** 3, n_waves=s_a.n_waves, p_exp=s_a.p_exp)
    pos = pairs_a.position
    pairs_b = Pairs(pos, s_b.lf[pos], pairs_a.hf, s_b.d[pos])
    gpd = ConditionalLikelihood(lf_tail="gpd")
    strategy, fresh = (PAS(impact_model=False, estimator=gpd, band=ModelBand(n_bootstrap=0))
                       for _ in range(2))
    strategy.reset(0)
    fresh.reset(0)
    first = strategy.fit(pairs_a, s_a)
    again = strategy.fit(pairs_b, s_b)
    assert first.n0 == again.n0
    expected = fresh.fit(pairs_b, s_b).u_cond
    assert np.max(np.abs(first.u_cond - expected)) > 1e-6
    np.testing.assert_allclose(again.u_cond, expected, rtol=1e-12)
