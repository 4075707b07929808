"""The model band's replicates: the same band on any number of processes, warm starts."""

import numpy as np
import pytest

from pas.strategies import band
from pas.strategies.pas import PAS
from test_estimator import _problem


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
    strategy = PAS(n_bootstrap=12, band_lf_ranks=lf_ranks)
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
    strategy = PAS(n_bootstrap=12, band_marginals="fitted")
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    warm = _band(strategy, pairs, s, 1)
    monkeypatch.setattr(band, "WARM_BAND", False)
    cold = _band(strategy, pairs, s, 1)
    np.testing.assert_allclose(warm[2], cold[2], rtol=1e-4)
