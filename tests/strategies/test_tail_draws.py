"""Long records: the top of each realisation drawn alone is the full draw's top."""

import contextlib

import numpy as np
import pytest
import pyvinecopulib as pv

from pas.models.conditional_cdf import conditional_cdf
from pas.models.copulas import CopulaFit
from pas.models.marginals import fit_marginal
from pas.stats.exceedance import mpm_of_realisations
from pas.strategies import tail_draws
from pas.strategies.band import ModelBand
from pas.strategies.base import Pairs
from pas.strategies.estimators import SelectedSample
from pas.strategies.pas import PAS
from pas.strategies.random_numbers import PeakUniforms
from pas.strategies.screening import LFSet
from pas.strategies.steps import FittedModel, hf_distribution
from pas.strategies.stopping import range_grid

FAMILIES = [("gaussian", 0, [[0.7]]), ("student", 0, [[0.6], [4.0]]), ("clayton", 0, [[2.0]]),
            ("clayton", 180, [[1.5]]), ("gumbel", 0, [[3.0]]), ("gumbel", 180, [[2.0]]),
            ("frank", 0, [[8.0]]), ("frank", 0, [[-3.0]]), ("gaussian", 0, [[-0.3]])]


def _model(family, rotation, params, n0, impact=None, seed=0):
    name = family + ("_180" if rotation else "")
    bicop = pv.Bicop(family=getattr(pv.BicopFamily, family), rotation=rotation,
                     parameters=np.array(params, float))
    hf = np.random.default_rng(seed).weibull(1.5, 60) * 5.0 - 0.5  # location below 0: zeros
    u = (n0 - np.arange(n0) - 0.5) / n0  # the ranks of an LF set, descending
    return FittedModel(CopulaFit(name, bicop, 0.0, 0.0, float(bicop.npars), False),
                       fit_marginal(hf, upper_tail=True), None, u, impact, {}, 0)


def _stream_q(z, seed, n0):
    """The impact uniforms of the common streams in float64 (PeakUniforms keeps float32)."""
    blocks = []
    for k in range(-(-n0 // 1024)):
        crn = np.random.default_rng([seed, 0x43524E, k])
        crn.uniform(1e-6, 1 - 1e-6, size=(z, 1024))
        blocks.append(crn.uniform(size=(z, 1024)))
    return np.concatenate(blocks, axis=1)[:, :n0]


def _full_top(model, r, q, k):
    return np.sort(model.draws(r, q), axis=1)[:, ::-1][:, :k]


def _uniforms(seed, n0, z=10):
    crn = PeakUniforms(z, seed=seed)
    r, q, r_max, _ = crn.replayable(n0, None)
    return crn, r, q, r_max, _stream_q(z, seed, n0)


@pytest.mark.parametrize("family, rotation, params", FAMILIES)
@pytest.mark.parametrize("n0", [3000, 60000])
def test_top_draws_are_the_full_draws_top(family, rotation, params, n0):
    model = _model(family, rotation, params, n0)
    crn, r, q, r_max, q64 = _uniforms(3, n0)
    k = 40 if n0 == 3000 else 500
    top = tail_draws.top_draws(model, r, q, r_max, k, crn)
    assert top is not None and top.shape == (10, k)
    np.testing.assert_allclose(np.sort(top, axis=1)[:, ::-1], _full_top(model, r, q64, k),
                               rtol=1e-12)


@pytest.mark.parametrize("family, rotation, params", FAMILIES[:5])
def test_top_draws_with_the_impact_model_zeroing_most_draws(family, rotation, params):
    n0 = 20000
    impact = np.linspace(0.6, 0.02, n0)  # impacts likely at the top, rare below
    model = _model(family, rotation, params, n0, impact=impact)
    crn, r, q, r_max, q64 = _uniforms(5, n0)
    top = tail_draws.top_draws(model, r, q, r_max, 120, crn)
    np.testing.assert_allclose(np.sort(top, axis=1)[:, ::-1], _full_top(model, r, q64, 120),
                               rtol=1e-12)


def test_impact_uniforms_kept_as_float32_decide_as_the_float64_stream_does():
    # impact probabilities set right at some uniforms (within float32 rounding of them):
    # the kept float32 values would decide those wrongly, q_for draws them again
    crn, _, q, _, q64 = _uniforms(7, 3000, z=4)
    assert q.dtype == np.float32
    impact = q64[1].copy()
    impact[::2] = np.nextafter(impact[::2], 2.0)  # just above: an impact
    exact = crn.q_for(q, impact, np.arange(3000))
    np.testing.assert_array_equal(exact < impact, q64 < impact)
    assert np.any((q.astype(float) < impact) != (q64 < impact))  # float32 alone would not


def test_too_few_impacts_to_fill_the_rows_draws_everything():
    n0 = 5000
    model = _model("gumbel", 0, [[2.0]], n0, impact=np.full(n0, 0.004))  # ~20 a row
    crn, r, q, r_max, _ = _uniforms(5, n0)
    assert tail_draws.top_draws(model, r, q, r_max, 100, crn) is None


def test_a_level_set_too_high_is_lowered_until_every_row_is_full(monkeypatch):
    # the subsample's level is an estimate: set far too high, the rows fall short and the
    # level comes down until every row's k-th largest is certain
    model = _model("gumbel", 0, [[3.0]], 30000)
    crn, r, q, r_max, _ = _uniforms(2, 30000)
    tries = []
    original = tail_draws._top_above

    def counted(*args):
        out = original(*args)
        tries.append(out[0] is not None)
        return out

    monkeypatch.setattr(tail_draws, "_stratified_tail", lambda *a: 1e-5)
    monkeypatch.setattr(tail_draws, "_top_above", counted)
    top = tail_draws.top_draws(model, r, q, r_max, 300, crn)
    assert tries[0] is False and tries[-1] is True
    np.testing.assert_allclose(np.sort(top, axis=1)[:, ::-1], _full_top(model, r, q, 300),
                               rtol=1e-12)


@pytest.mark.parametrize("family, rotation, params",
                         FAMILIES + [("student", 0, [[0.95], [2.2]]),
                                     ("student", 0, [[-0.5], [6.0]])])
def test_blocks_left_out_hold_no_uniform_above_their_conditional_cdf(family, rotation, params):
    # the bound from a block's ends (single-peaked C(v | u) in u) never leaves out a peak
    # whose largest uniform exceeds its own C(v | u), at levels above and below the median
    n0 = 50000
    model = _model(family, rotation, params, n0)
    _, _, r_max, _ = PeakUniforms(10, seed=4).replayable(n0, None)
    for v in (0.4, 0.9, 0.999, 1 - 1e-5):
        t = tail_draws._cdf_where_reached(model.copula, v, model.u_cond, r_max)
        exact = conditional_cdf(model.copula, np.array([v]), model.u_cond)
        out = t == 2.0
        assert not np.any(r_max[out] > exact[out])
        np.testing.assert_array_equal(t[~out], exact[~out])


def test_families_without_a_closed_form_inverse_draw_everything():
    model = _model("joe", 0, [[2.0]], 20000)
    crn, r, q, r_max, _ = _uniforms(1, 20000)
    assert tail_draws.top_draws(model, r, q, r_max, 50, crn) is None


def test_the_whole_distribution_drawn_row_by_row_is_the_full_draws(monkeypatch):
    model = _model("student", 0, [[0.6], [4.0]], 4000, impact=np.linspace(0.9, 0.3, 4000))
    crn, r, q, _, q64 = _uniforms(6, 4000)
    whole = hf_distribution(model.draws(r, q64), 5000)
    for got, want in zip(tail_draws.full_distribution(model, r, q, 5000, crn, rowwise_above=100),
                         whole):
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14)


def test_replayed_uniforms_are_the_drawn_ones_common_or_not():
    crn = PeakUniforms(4, seed=9)
    r, q, r_max, again = crn.replayable(1500, None)
    r2, q2 = again()
    np.testing.assert_array_equal(r2, r)
    np.testing.assert_array_equal(q2, q)
    np.testing.assert_array_equal(r_max, r.max(axis=0))
    grown = crn.replayable(5000, None)  # the set grows: the first peaks keep theirs
    np.testing.assert_array_equal(grown[0][:, :1500], r)
    np.testing.assert_array_equal(grown[2], grown[0].max(axis=0))
    rng = np.random.default_rng(1)
    r, q, r_max, again = PeakUniforms(4, seed=None, common=False).replayable(300, rng)
    r2, q2 = again()
    np.testing.assert_array_equal(r2, r)
    np.testing.assert_array_equal(q2, q)
    after = np.random.default_rng(1)
    after.uniform(size=(2, 4, 300))
    assert rng.uniform() == after.uniform()  # the rng moved on as the draw moves it


def _problem(n, seed=1, fp=False):
    from harness.timing_problem import scenario

    lf, hf = scenario(n, seed=seed)
    lfset = LFSet(lf, n_waves=int(round(n * 16364 / 15000)), p_exp=2.55e-3)
    pos = np.unique(np.round(np.geomspace(1, lfset.n, 40)).astype(int) - 1)
    fp_pos = pos[3::7] if fp else np.empty(0, dtype=int)  # a few evaluated misses
    tp = np.setdiff1d(pos, fp_pos)
    return lfset, Pairs(tp, lfset.lf[tp], hf[lfset.index[tp]], lfset.d[tp],
                        lfset.lf[fp_pos], fp_pos)


def _predictions(strategy, lfset, pairs):
    """Two iterations' predictions from the top of each realisation, and the same read
    from every draw of the iteration's model and uniforms (the reference)."""
    from pas.strategies.base import Prediction
    from pas.strategies.steps import hf_distribution

    strategy.reset(0)
    out = []
    for k in range(2):
        top = strategy.predict(pairs, lfset, np.random.default_rng(k))
        every = tail_draws.whole_draws(strategy.model_, strategy._uniforms,
                                       np.random.default_rng(k))
        out.append((top, Prediction.read_at(lfset.p_exp, *hf_distribution(every, lfset.n_waves))))
    return out


@pytest.mark.parametrize("strategy, n, fp", [
    (lambda: PAS(band=ModelBand(n_bootstrap=0)), 20000, False),
    (lambda: PAS(band=ModelBand(n_bootstrap=0)), 20000, True),
    (lambda: PAS(families=("gumbel_180", "clayton_180", "frank"), estimator=SelectedSample(),
                 band=ModelBand(n_bootstrap=0)), 20000, True),
    (PAS.paper, 20000, False),
    pytest.param(lambda: PAS(band=ModelBand(n_bootstrap=0)), 400000, True,
                 marks=pytest.mark.slow),
])
def test_predictions_from_the_top_are_the_full_draws(strategy, n, fp):
    lfset, pairs = _problem(n, fp=fp)
    grid = range_grid(lfset.p_exp)
    for a, b in _predictions(strategy(), lfset, pairs):
        assert isinstance(a, tail_draws.TailPrediction)
        np.testing.assert_allclose([a.mpm, *a.mpm_band], [b.mpm, *b.mpm_band], rtol=1e-12)
        np.testing.assert_allclose(a.at(grid), b.at(grid), rtol=1e-12)
        assert a.d.size == b.d.size and a._full is None  # nothing drawn in full yet
        for name in ("h_mean", "h_low", "h_high"):
            np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=1e-12,
                                       atol=1e-12)
        np.testing.assert_allclose(a.at([0.9 * lfset.d[-1]]), b.at([0.9 * lfset.d[-1]]),
                                   rtol=1e-12)


def test_a_band_replicates_mpm_from_the_top_is_the_full_draws():
    lfset, pairs = _problem(20000, fp=True)
    strategy = PAS(band=ModelBand(n_bootstrap=0))
    strategy.reset(0)
    strategy.predict(pairs, lfset, np.random.default_rng(0))
    model = strategy.model_
    r, _ = strategy._random_numbers(model.n0, None)
    q64 = _stream_q(10, 0, model.n0)
    np.testing.assert_allclose(strategy._replicate_mpm(model, lfset, None)[0],
                               mpm_of_realisations(model.draws(r, q64), lfset.n_waves,
                                                   lfset.p_exp), rtol=1e-12)


def test_a_candidate_level_that_differs_between_peaks_within_the_margin_keeps_the_top_exact(
        monkeypatch):
    # rounding may set a peak's candidate level anywhere up to the checked level v_L; here
    # every other peak's sits halfway, with a wide margin and a first v_L that leaves the
    # rows short above it, so the check on the k-th largest (not only the count) must
    # send the level down
    model = _model("gaussian", 0, [[0.7]], 20000)
    crn, r, q, r_max, _ = _uniforms(8, 20000)
    k, margin = 200, 1.0

    def above(tail):
        return np.sum(1 - conditional_cdf(model.copula, np.array([1 - tail]), model.u_cond))

    lo, hi = 1e-6, 1.0
    for _ in range(60):  # the tail with 0.7 k draws per row expected above v_L
        mid = np.sqrt(lo * hi)
        lo, hi = (mid, hi) if above(mid) < 0.7 * k else (lo, mid)

    def skewed(copula, v, u, r_max, margin):
        t = conditional_cdf(copula, np.array([v]), u)
        tail = (1 - v) / (1 + margin)
        t[::2] = conditional_cdf(copula, np.array([1 - tail * (1 + margin / 2)]), u)[::2]
        return t

    monkeypatch.setattr(tail_draws, "_stratified_tail", lambda *a: hi)
    monkeypatch.setattr(tail_draws, "_cdf_where_reached", skewed)
    top = tail_draws.top_draws(model, r, q, r_max, k, crn, margin=margin)
    np.testing.assert_allclose(np.sort(top, axis=1)[:, ::-1], _full_top(model, r, q, k),
                               rtol=1e-12)


def test_a_copy_of_the_common_uniforms_shares_them_read_only():
    import copy

    crn = PeakUniforms(3, seed=2)
    r, _ = crn.draw(2000, None)
    twin = copy.deepcopy(crn)
    assert twin.draw(2000, None)[0] is not None and np.shares_memory(twin.draw(2000, None)[0], r)
    assert not r.flags.writeable
    grown = twin.draw(3000, None)[0]  # a copy grows on its own, the numbers stay the same
    np.testing.assert_array_equal(grown[:, :2000], r)
    assert crn._r.shape[1] == 2048


def test_the_impact_uniforms_kept_only_once_asked_for_are_the_streams():
    crn = PeakUniforms(3, seed=4)
    r, q = crn.draw(2500, None, impacts=False)
    assert q is None and crn._q is None
    r2, q2 = crn.draw(2500, None)
    np.testing.assert_array_equal(r2, r)
    both = PeakUniforms(3, seed=4)  # r and q drawn together from the start
    np.testing.assert_array_equal(both.draw(4000, None)[1][:, :2500], q2)


def test_the_results_table_shares_the_predictions_arrays_read_only():
    from pas.study.result import distribution_frame

    lfset, pairs = _problem(20000)
    strategy = PAS(band=ModelBand(n_bootstrap=0))
    strategy.reset(0)
    pred = strategy.predict(pairs, lfset, np.random.default_rng(0))
    assert isinstance(pred, tail_draws.TailPrediction)
    frame = distribution_frame(pred.d, pred.h_mean, pred.h_low, pred.h_high, **pred.columns)
    kept = pred.h_mean.copy()
    for column, values in (("h_mean", pred.h_mean), ("h_high", pred.h_high), ("lf", lfset.lf)):
        assert np.shares_memory(frame[column].to_numpy(), values)  # not a copy
    lf_kept = lfset.lf[:10].copy()
    # pandas 2 refuses the write (read-only); with copy-on-write it would copy: either
    # way the prediction and the LF set stay as they were
    with contextlib.suppress(ValueError):
        frame.loc[0, "h_mean"] = -1.0
    with contextlib.suppress(ValueError):
        frame["lf"] *= 2.0
    np.testing.assert_array_equal(pred.h_mean, kept)
    np.testing.assert_array_equal(lfset.lf[:10], lf_kept)
    assert lfset.lf.flags.writeable  # only the view handed to the table is read-only
    writeable = np.arange(5.0)  # an array the caller may still write into is copied
    table = distribution_frame(writeable, writeable, writeable, writeable)
    writeable[0] = 9.0
    assert table["h_mean"].iloc[0] == 0.0
    copied = frame.copy()  # a copy of the table is the caller's to write into
    copied.loc[0, "h_mean"] = -1.0
    assert copied["h_mean"].iloc[0] == -1.0 and pred.h_mean[0] == kept[0]
