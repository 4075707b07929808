"""The model band's replicates: the same band on any number of processes, warm starts."""

import copy

import numpy as np
import pytest
from test_estimator import _problem

from pas.strategies import band
from pas.strategies.band import ModelBand
from pas.strategies.base import Pairs
from pas.strategies.estimators import ConditionalLikelihood
from pas.strategies.pas import PAS


def _band(strategy, pairs, s, n_jobs):
    return strategy.model_band(pairs, s, np.random.default_rng(1), n_jobs=n_jobs)


def _plan(pairs, n, marginals, seed=1):
    """A band's plan and LF-rank stream as :func:`band.bootstrap_band` draws them."""
    rng = np.random.default_rng(seed)
    lf_rng = rng.spawn(1)[0]
    return band.replicate_plan(pairs, rng, n, marginals), lf_rng


def _one_after_another(strategy, pairs, s, starts, plan, lf_rng):
    """The reference: each replicate fitted on its own by the strategy's fit (one joint fit
    per candidate, :func:`pas.models.joint.fit_joint`), in plan order, reading ``lf_rng``
    in turn; None where the replicate cannot be fitted."""
    out = []
    for tp, fp, marginal, draw_rng in plan:
        b = band._resampled(pairs, tp, fp)
        try:
            if b is None:
                raise ValueError("too few or all alike")
            own = None if starts is None else band.replicate_starts(strategy, b, s, starts,
                                                                    marginal)
            model = strategy.fit(b, s, update=False, hf_marginal=marginal,
                                 lf_ranks_rng=lf_rng, starts=own)
            out.append(strategy._replicate_mpm(model, s, draw_rng))
        except (ValueError, np.linalg.LinAlgError):
            out.append(None)
    return out


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


def test_warm_replicates_reach_the_cold_optima():
    # the band's replicates, started from the final fits (Student-t also from the data),
    # against the same replicates started from the study's last fits and from the data
    s, pairs, _ = _problem(1, tau=0.6, m=30)
    strategy = PAS(band=ModelBand(n_bootstrap=12, marginals="fitted"))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    plan, lf_rng = _plan(pairs, 12, (None,))
    warm = band.replicate_mpms(strategy, pairs, s, strategy.final_joint_fits(pairs, s, "both"),
                               plan, copy.deepcopy(lf_rng), n_jobs=1)
    cold = _one_after_another(strategy, pairs, s, None, plan, copy.deepcopy(lf_rng))
    assert None not in warm and None not in cold
    np.testing.assert_allclose(np.ravel(warm), np.ravel(cold), rtol=1e-4)


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


@pytest.mark.slow
def test_pruned_replicates_fit_only_the_families_that_can_win_them(monkeypatch):
    # a Gumbel problem with strong dependence: Clayton is far behind on every resample,
    # Gaussian and Frank on some, so their replicate fits are dropped there
    import pas.strategies.band_batch as band_batch

    s, pairs, _ = _problem(3, tau=0.7, gumbel=True, m=60)
    strategy = PAS(band=ModelBand(n_bootstrap=12))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    final = strategy.final_joint_fits(pairs, s, "both")
    assert {f for f, _ in final} == set(strategy.families)
    batched, fitted = band_batch.fit_joint_batch, []

    def counted_batch(name, samples, *args, **kwargs):  # a spy: a fit per replicate
        fitted.extend([name] * len(samples))
        return batched(name, samples, *args, **kwargs)

    monkeypatch.setattr(band_batch, "fit_joint_batch", counted_batch)
    low, high, replicates = _band(strategy, pairs, s, 1)
    assert len(replicates) == 12 and low <= high
    assert "clayton" not in fitted and fitted.count("gumbel") == 2 * 12
    assert len(fitted) < 0.8 * 12 * len(final)


def test_replicate_starts_keep_the_families_within_the_margin_of_the_best():
    s, pairs, _ = _problem(3, tau=0.7, gumbel=True, m=60)
    strategy = PAS(band=ModelBand(n_bootstrap=4))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    starts = strategy.final_joint_fits(pairs, s, "both")
    # the whole sample as the replicate: the AIC of the final fits themselves
    kept = band.replicate_starts(strategy, pairs, s, starts, "both")
    aic = {k: f.copula.aic for k, f in starts.items()}
    best = min(a for k, a in aic.items() if not starts[k].copula.at_bound)
    families = {f for (f, _), a in aic.items() if a <= best + band.PRUNE_AIC}
    assert set(kept) == {k for k in starts if k[0] in families}
    assert 0 < len(kept) < len(starts)
    weibull_only = band.replicate_starts(strategy, pairs, s, starts, "weibull")
    assert {m for _, m in weibull_only} == {"weibull"}


def test_the_default_forks_only_a_process_without_other_threads(monkeypatch):
    import threading

    forked = []
    real = band.multiprocessing.get_context

    def spy(method):
        forked.append(method)
        return real(method)

    monkeypatch.setattr(band.multiprocessing, "get_context", spy)
    monkeypatch.setattr(band, "default_jobs", lambda: 2)
    monkeypatch.setattr(band, "_replicate_mpm", lambda job, i: float(i))
    plan = [None] * 4
    release = threading.Event()
    other = threading.Thread(target=release.wait)
    other.start()
    try:
        assert band.replicate_mpms(None, None, None, None, plan) == [0.0, 1.0, 2.0, 3.0]
        assert forked == []
    finally:
        release.set()
        other.join()
    if threading.active_count() == 1:
        assert band.replicate_mpms(None, None, None, None, plan) == [0.0, 1.0, 2.0, 3.0]
        assert forked == ["fork"]


@pytest.mark.slow
@pytest.mark.parametrize("marginals", ["reselected", "alternate"])
def test_replicates_fitted_together_give_the_band_of_one_after_another(marginals):
    # false positives and redrawn LF ranks: each replicate's draw must read the stream where
    # it would one after another; every replicate's fits are the ones it reaches alone
    # (Student-t's ν derivative, from the t quantiles' here and by a difference in the
    # fit alone, moves the optima within the optimiser's tolerance)
    s, pairs, _ = _problem(2, tau=0.6, p_impact=0.7, m=24)
    choices = {"reselected": ("both",), "alternate": ("weibull", "lognormal")}[marginals]
    bands = {}
    for trend in ("rising", "tested"):
        strategy = PAS(band=ModelBand(n_bootstrap=12, marginals=marginals), impact_trend=trend)
        strategy.reset(0)
        strategy.predict(pairs, s, np.random.default_rng(0))
        starts = strategy.final_joint_fits(pairs, s, "both")
        plan, lf_rng = _plan(pairs, 12, choices)
        assert band._can_batch(strategy, starts, plan)
        together = band.replicate_mpms(strategy, pairs, s, starts, plan, copy.deepcopy(lf_rng),
                                       n_jobs=1)
        alone = _one_after_another(strategy, pairs, s, starts, plan, copy.deepcopy(lf_rng))
        assert [m is None for m in together] == [m is None for m in alone]
        kept = [i for i, m in enumerate(together) if m is not None]
        assert len(kept) >= 10
        bands[trend] = (np.array([together[i][0] for i in kept]),
                        np.array([alone[i][0] for i in kept]))
    together, alone = bands["rising"]
    np.testing.assert_allclose(together, alone, rtol=1e-4)
    together, alone = bands["tested"]
    if marginals == "reselected":
        np.testing.assert_allclose(together, alone, rtol=1e-4)
    else:
        # A known weakness, traced (scipy 1.17.1, numpy 2.4.6): with a falling impact
        # model, replicate 7's Gaussian/log-normal fit is chaotic.  The two paths'
        # objectives agree to 1e-15 and their gradients to 2.8e-14, yet the iterates part
        # at the third evaluation; the batched one then stops on L-BFGS-B's
        # relative-reduction test at -log L 154.14 with the gradient still -0.54 in log
        # sigma, the other goes on to 125.64.  That replicate selects Frank instead and its
        # MPM is 49 % higher; the other families agree to 1e-11.  The band ends still
        # agree; no other replicate may differ.
        assert np.sum(~np.isclose(together, alone, rtol=1e-4, atol=0)) <= 1
    lo, hi = np.quantile(together, [0.025, 0.975])
    np.testing.assert_allclose((lo, hi), np.quantile(alone, [0.025, 0.975]), rtol=1e-4)


def test_a_mixture_band_is_fitted_one_replicate_after_another():
    s, pairs, _ = _problem(1, tau=0.6, m=30)
    strategy = PAS(band=ModelBand(n_bootstrap=3),
                   estimator=ConditionalLikelihood(hf_marginal="weibull_mixture"))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    starts = strategy.final_joint_fits(pairs, s, "all")
    plan = band.replicate_plan(pairs, np.random.default_rng(0), 3, ("all",))
    assert not band._can_batch(strategy, starts, plan)


@pytest.mark.slow
def test_replicates_too_alike_to_fit_draw_no_lf_ranks_either_way():
    # three HF levels, two of them rare: about a quarter of the resamples hold two and
    # cannot be fitted; neither path may read the LF-rank stream for them, so the
    # replicates after them find it where they would one after another
    s, pairs, _ = _problem(2, tau=0.6, p_impact=0.7, m=24)
    hf = np.full(len(pairs), 1000.0)
    order = np.argsort(pairs.lf)
    hf[order[-2:]], hf[order[-4:-2]] = 3000.0, 2000.0
    pairs = Pairs(pairs.position, pairs.lf, hf, pairs.d, pairs.fp_lf, pairs.fp_position)
    strategy = PAS(band=ModelBand(n_bootstrap=12))
    strategy.reset(0)
    strategy.predict(pairs, s, np.random.default_rng(0))
    starts = strategy.final_joint_fits(pairs, s, "both")
    rng = np.random.default_rng(3)
    lf_rng = rng.spawn(1)[0]
    plan = band.replicate_plan(pairs, rng, 12, ("both",))
    alike = [np.unique(pairs.hf[tp]).size < 3 for tp, _, _, _ in plan]
    assert 0 < sum(alike) < 12
    together = band.replicate_mpms(strategy, pairs, s, starts, plan, copy.deepcopy(lf_rng),
                                   n_jobs=1)
    alone = _one_after_another(strategy, pairs, s, starts, plan, copy.deepcopy(lf_rng))
    assert [m is None for m in together] == [m is None for m in alone]
    assert all(m is None for m, a in zip(together, alike) if a)
    kept = [i for i, m in enumerate(together) if m is not None]
    # the optimiser's tolerance: the two paths sum the objectives in another order, and
    # with scipy 1.17.1 / numpy 2.4.6 one replicate ends 5.4e-6 apart
    np.testing.assert_allclose([together[i] for i in kept], [alone[i] for i in kept],
                               rtol=1e-4)
