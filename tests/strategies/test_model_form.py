"""The model band's model-form term: the semi-empirical distribution (pas.strategies.model_form)."""

import numpy as np
import pytest
from test_estimator import _problem

from pas.strategies import model_form
from pas.strategies.band import ModelBand
from pas.strategies.base import Pairs
from pas.strategies.pas import PAS
from pas.strategies.screening import LFSet


def _pairs(position, hf, fp_position=()):
    position, fp_position = np.asarray(position), np.asarray(fp_position, dtype=int)
    return Pairs(position, np.zeros(position.size), np.asarray(hf, float),
                 np.zeros(position.size), np.zeros(fp_position.size), fp_position)


def test_evaluated_events_take_their_observed_values_in_every_realisation():
    draws = np.arange(12.0).reshape(2, 6)
    # true positives at positions 1 and 7 (7 lies below the 6 drawn events), a false
    # positive at 4; the other events keep their draws
    out = model_form.semi_empirical(draws, _pairs([1, 7], [50.0, 9.0], [4]))
    np.testing.assert_array_equal(out, [[0, 50, 2, 3, 0, 5, 9], [6, 50, 8, 9, 0, 11, 9]])
    np.testing.assert_array_equal(draws, np.arange(12.0).reshape(2, 6))  # not in place


def test_with_every_event_evaluated_the_mpm_is_the_record_s():
    # the semi-empirical distribution of a fully evaluated pool is the record itself: its
    # MPM is the observed loads' exceedance curve read at p_exp (on ln d, Eq. 12)
    rng = np.random.default_rng(2)
    hf = rng.weibull(1.2, 400) * 1000.0
    s = LFSet(rng.rayleigh(1.0, 400), n_waves=400, p_exp=0.02)
    pairs = _pairs(np.arange(400), hf[s.index])
    mpm = model_form.replicate_values(rng.uniform(size=(5, 400)), pairs, s, "semi-empirical")[1]
    top = np.sort(hf)[::-1][:10]
    expected = np.interp(np.log(0.02), np.log(np.arange(1, 11) / 400.0), top)
    assert mpm == pytest.approx(expected, rel=1e-9)


def test_the_band_spans_both_forms_replicates_and_needs_ten():
    model = np.arange(101.0)
    values = [(m, m + 200.0) for m in model] + [None]
    low, high, mpms = model_form.band_ends(values)
    # 2.5 and 97.5 % of 0..100 are 2.5 and 97.5; of 200..300, 202.5 and 297.5
    assert (low, high) == pytest.approx((2.5, 297.5), rel=1e-12)
    np.testing.assert_array_equal(mpms, model)
    assert model_form.band_ends([(1.0,)] * 9 + [None]) is None
    assert model_form.band_ends([(float(i),) for i in range(41)])[:2] == pytest.approx((1.0, 39.0))


def test_a_bad_model_form_is_named_with_its_choices():
    with pytest.raises(ValueError, match="model_form"):
        ModelBand(model_form="empirical")


@pytest.mark.slow
def test_the_semi_empirical_band_holds_the_default_band_of_the_same_replicates(monkeypatch):
    s, pairs, _ = _problem(3, tau=0.6, p_impact=0.8, m=30)
    bands, seen, band_ends = {}, [], model_form.band_ends
    monkeypatch.setattr(model_form, "band_ends", lambda v: seen.append(v) or band_ends(v))
    for form in model_form.MODEL_FORMS:
        strategy = PAS(band=ModelBand(n_bootstrap=12, model_form=form))
        strategy.reset(0)
        strategy.predict(pairs, s, np.random.default_rng(0))
        bands[form] = strategy.model_band(pairs, s, np.random.default_rng(1), n_jobs=1)
    default, mended = bands["none"], bands["semi-empirical"]
    np.testing.assert_allclose(mended[2], default[2], rtol=1e-7)  # the same fits
    assert mended[0] <= default[0] and mended[1] >= default[1]
    semi = np.array([v for v in seen[1] if v is not None])[:, 1]
    assert not np.allclose(semi, mended[2], rtol=1e-3)  # the evaluated events moved the MPMs
