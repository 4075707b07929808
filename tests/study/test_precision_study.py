"""A study with a precision target: it stops exactly when its reported band meets the target,
and says how far it is and how many HF it expects to need when it does not."""

import math
import warnings

import numpy as np
import pytest

import pas
from pas import PAS, ModelBand, Stopping
from pas.strategies.forecast import relative_half_width
from pas.study.result import ScreeningResult

N = 2000
LF = np.random.default_rng(0).rayleigh(2.0, N)
NOISE = np.random.default_rng(1).lognormal(0, 0.2, N)
K2 = 5


def oracle(ev):
    return 1.2 * ev.lf ** 1.1 * NOISE[ev.index]


def run(*, max_hf, n_bootstrap=12, study=None, **stopping):
    """A fast PAS study (``z=5``, two families, a 12-replicate band) stopped by ``stopping``."""
    strategy = PAS(z=5, families=("gaussian", "gumbel"),
                   band=ModelBand(n_bootstrap=n_bootstrap, marginals="fitted"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pas.run_pas(LF, oracle, n_waves=N, p_exp=1e-2, seed=1, max_hf=max_hf,
                           strategy=strategy, stopping=Stopping(k2=K2, **stopping), study=study)


@pytest.fixture(scope="module")
def reached():
    return run(precision=0.10, max_hf=40)


@pytest.fixture(scope="module")
def short():
    return run(precision=0.03, max_hf=16)


def test_stops_once_the_reported_band_is_within_the_target(reached):
    assert reached.converged
    lo, hi = reached.mpm_band
    assert relative_half_width(reached.mpm, (lo, hi)) <= 0.10
    window = reached.fitted["mpm"].to_numpy()[-5:]
    assert np.all((lo <= window) & (window <= hi))
    last = reached.fitted.iloc[-1]
    assert bool(last["stop"]) and last["halfwidth"] <= 0.10
    # the band the loop judged is the band reported: the model part is not refitted
    assert (last["model_low"], last["model_high"]) == pytest.approx(reached.mpm_band_model,
                                                                    rel=1e-12)
    assert "converged: U95 within ±10 % of the MPM" in reached.summary()


@pytest.mark.slow
def test_never_stops_on_a_band_it_did_not_compute_or_that_is_wider(reached, short):
    for res in (reached, short):
        rows = res.fitted
        stopped = rows[rows["stop"].astype(bool)]
        assert stopped["halfwidth"].notna().all()
        assert (stopped["halfwidth"] <= res.settings["precision"]).all()
        wide = rows[rows["halfwidth"] > res.settings["precision"]]
        assert not wide["stop"].astype(bool).any()


@pytest.mark.slow
def test_a_study_at_its_budget_says_how_far_it_is_from_the_target(short):
    assert not short.converged and short.n_hf == 16
    width = relative_half_width(short.mpm, short.mpm_band)
    assert width > 0.03
    text = short.summary()
    assert f"NOT converged: U95 ±{100 * width:.3g} % of the MPM against the target ±3 %" in text
    assert text.endswith("the budget allows 0")
    assert short.forecast_hf is not None


@pytest.mark.slow
def test_forecast_survives_save_and_load(short, tmp_path):
    short.save(tmp_path)
    again = ScreeningResult.load(tmp_path)
    assert again.summary() == short.summary()
    for a, b in zip(again.forecast_hf, short.forecast_hf):
        assert a == pytest.approx(b, rel=1e-12) or (math.isinf(a) and math.isinf(b))
    assert {"halfwidth", "halfwidth_sampling", "forecast_hf"} <= set(again.history)


def test_eps1_alone_keeps_its_rows_and_has_no_forecast():
    res = run(eps1=0.05, max_hf=12, n_bootstrap=0)
    assert res.forecast is None and res.forecast_hf is None
    assert "halfwidth" not in res.history and "forecast_hf" not in res.history
    assert res.settings.get("precision") is None  # (stored only when set: 0.1's shape)


def test_without_a_model_band_the_sampling_band_is_judged_at_every_fit():
    # ModelBand(n_bootstrap=0) (and PAS.paper()) computes no model band: the sampling
    # band is the U95 at every fit, its whole width the part that narrows
    res = run(precision=0.10, max_hf=20, n_bootstrap=0)
    rows = res.fitted
    assert rows["halfwidth"].notna().all() and rows["forecast_hf"].notna().all()
    assert rows["halfwidth"].to_numpy() == pytest.approx(rows["halfwidth_sampling"].to_numpy(),
                                                         rel=1e-12)
    assert res.mpm_band_model is None and res.forecast["sampling_halfwidth"] is None


def test_neither_eps1_nor_precision_is_an_error():
    with pytest.raises(ValueError, match="give eps1 .* or precision"):
        run(max_hf=12)


@pytest.mark.slow
def test_a_resumed_precision_study_reuses_its_bands_and_decides_the_same(tmp_path, monkeypatch):
    db = tmp_path / "s.db"
    first = run(precision=0.03, max_hf=14, study=db)
    calls = []
    real = pas.strategies.pas.PAS.model_band

    def counted(self, *args, **kwargs):
        calls.append(1)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(pas.strategies.pas.PAS, "model_band", counted)
    again = run(precision=0.03, max_hf=14, study=db)
    # the loop's band (at 10 pairs) is read from the store; only the final one is computed
    assert first.history["model_low"].notna().sum() == 1 and len(calls) == 1
    assert again.mpm_band == pytest.approx(first.mpm_band, rel=1e-12)
    assert again.summary() == first.summary()


def test_the_forecast_never_says_fewer_than_the_window_needs(reached, short):
    """Before k2 MPMs the forecast is at least the fits still missing (one pair each), and at a
    fit where the rule did not hold at least one more."""
    for res in (reached, short):
        rows = res.fitted[res.fitted["forecast_hf"].notna()]
        assert len(rows)
        fits = np.arange(1, len(res.fitted) + 1)[res.fitted["forecast_hf"].notna().to_numpy()]
        per_pair = rows["n_hf"].to_numpy() / rows["n_pairs"].to_numpy()
        still = np.maximum(K2 - fits, np.where(rows["stop"].astype(bool), 0, 1))
        assert np.all(rows["forecast_hf"].to_numpy() >= still * per_pair * (1 - 1e-9))
        assert np.all(rows["forecast_hf_low"].to_numpy() >= still * per_pair * (1 - 1e-9))
