"""End-to-end PAS on problems with a known answer, and the public API contract."""

import warnings

import numpy as np
import pandas as pd
import pytest
from conftest import gumbel_problem, monotone_problem, no_band, threshold_problem

import pas


@pytest.mark.slow
def test_monotone_indicator_reproduces_mapped_mpm(table_oracle):
    lf, hf, n_w, p_exp, truth = monotone_problem()
    oracle = table_oracle(hf)
    res = pas.run_pas(lf, oracle, n_waves=n_w, p_exp=p_exp, eps1=0.01 * truth, seed=3)
    assert res.converged
    assert res.mpm == pytest.approx(truth, rel=0.03)
    assert res.mpm_band[0] <= res.mpm <= res.mpm_band[1]
    assert len(set(oracle.calls)) == len(oracle.calls) == res.n_hf  # no event run twice
    assert res.n_hf < 60


@pytest.mark.slow
def test_known_copula_and_marginals(table_oracle):
    lf, hf, n_w, p_exp, truth = gumbel_problem()
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.01 * truth, seed=5)
    assert res.converged
    assert res.mpm == pytest.approx(truth, rel=0.10)


@pytest.mark.slow
def test_threshold_problem_with_false_positives(table_oracle):
    lf, hf, n_w, p_exp, truth = threshold_problem()
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.015 * truth,
                      threshold=3.0, seed=2)
    assert res.n_false_positive > 0
    h = res.history
    fp = h[h.status == "false_positive"]
    assert (fp.hf == 0).all() and fp.mpm.isna().all()  # counted, not fitted
    assert len(res.pairs) == res.n_hf - res.n_false_positive
    assert res.mpm == pytest.approx(truth, rel=0.10)


@pytest.mark.slow
@pytest.mark.parametrize("make, kwargs", [
    (monotone_problem, {}),
    (gumbel_problem, {}),
    (gumbel_problem, {"exclude_at_bound": False}),
])
def test_mpm_stays_put_to_160_samples(make, kwargs, table_oracle):
    """Stability: past the stopping point the MPM stays within ±15 % after the 30th sample."""
    lf, hf, n_w, p_exp, truth = make()
    study = pas.make_study(no_band(**kwargs), lf, n_waves=n_w, p_exp=p_exp, eps1=1.0, seed=0,
                           max_hf=160, stop_on_convergence=False)
    res = study.optimize(table_oracle(hf))
    assert res.n_hf == 160
    f = res.fitted
    err = f.mpm.to_numpy()[f.n_hf.to_numpy() > 30] / truth - 1
    assert np.abs(err).max() <= 0.15, f"worst deviation {err[np.argmax(np.abs(err))]:+.3f}"


@pytest.mark.slow
def test_result_api_shape(table_oracle):
    lf, hf, n_w, p_exp, truth = monotone_problem(n=3000, n_waves=3200)
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.05, seed=1,
                      max_hf=12)
    assert isinstance(res.mpm, float) and len(res.mpm_band) == 2
    assert res.n_hf == 12 and res.n_false_positive == 0 and isinstance(res.converged, bool)
    for col in ["event_index", "event_id", "lf", "hf", "family", "aic_gaussian", "aic_student",
                "aic_clayton", "aic_gumbel", "aic_frank", "mpm", "E", "COV", "threshold", "tau"]:
        assert col in res.history, col
    # the predicted distribution and, per rank, the LF peak conditioned on
    assert list(res.distribution.columns) == ["exceedance_probability", "h_mean", "h_low", "h_high",
                                              "lf"]
    assert isinstance(res.history, pd.DataFrame) and len(res.history) == 12
    assert res.mpm_band_model is not None


@pytest.mark.slow
def test_same_seed_same_answer(table_oracle):
    lf, hf, n_w, p_exp, _ = monotone_problem(n=3000, n_waves=3200)
    a = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.05, seed=9, max_hf=15)
    b = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.05, seed=9, max_hf=15)
    assert a.mpm == b.mpm and a.history.event_index.tolist() == b.history.event_index.tolist()


@pytest.mark.slow
def test_event_carries_index_lf_and_user_id():
    lf = np.random.default_rng(0).rayleigh(1.0, 500)
    seen = []

    def oracle(ev):
        seen.append(ev)
        assert ev.lf == lf[ev.index] and ev.id == f"ev{ev.index}" and ev.meta == {"seed": ev.index}
        return 2 * ev.lf

    table = pd.DataFrame({"lf": lf, "seed": range(500)}, index=[f"ev{i}" for i in range(500)])
    pas.run_pas(table, oracle, n_waves=500, p_exp=0.01, eps1=0.01, seed=0, max_hf=8)
    assert len(seen) == 8


@pytest.mark.slow
@pytest.mark.parametrize("bad", [
    lambda ev: float("nan"), lambda ev: float("inf"), lambda ev: -1.0, lambda ev: "abc",
    lambda ev: 1 / 0,
])
def test_oracle_failures_are_not_zero_loads(bad):
    lf = np.random.default_rng(0).rayleigh(1.0, 500)
    calls = {"n": 0}

    def oracle(ev):
        calls["n"] += 1
        return bad(ev) if calls["n"] in (2, 6) else 3.0 * ev.lf

    res = pas.run_pas(lf, oracle, n_waves=500, p_exp=0.01, eps1=0.01, seed=0, max_hf=10)
    failed = res.history[res.history.status == "failed"]
    assert len(failed) == 2 and failed.error.str.len().gt(0).all()
    assert res.n_failed == 2 and res.n_false_positive == 0 and res.n_hf == 10


def test_too_many_failures_stop_with_partial_result():
    lf = np.random.default_rng(0).rayleigh(1.0, 500)
    with pytest.raises(pas.OracleFailureLimit, match="max_failures=3") as info:
        pas.run_pas(lf, lambda ev: float("nan"), n_waves=500, p_exp=0.01, eps1=0.01,
                    budget=pas.Budget(max_failures=3))
    assert info.value.result.n_failed == 4


@pytest.mark.parametrize("kwargs, name", [
    ({"lf_peaks": []}, "lf_peaks"),
    ({"lf_peaks": [1.0, np.nan, 2.0, 3.0, 4.0]}, "lf_peaks"),
    ({"n_waves": 0}, "n_waves"),
    ({"n_waves": 10.5}, "n_waves"),
    ({"p_exp": 1.0}, "p_exp"),
    ({"p_exp": -0.1}, "p_exp"),
    ({"eps1": 0.0}, "eps1"),
    ({"threshold": 100.0}, "threshold"),
])
def test_bad_inputs_name_the_argument(kwargs, name):
    args = dict(lf_peaks=np.linspace(1, 5, 50), n_waves=100, p_exp=0.05, eps1=0.1)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        pas.run_pas(args.pop("lf_peaks"), lambda ev: 1.0, **args)


def test_unknown_setting_rejected():
    with pytest.raises(TypeError, match="unknown keyword argument 'zz'"):
        pas.run_pas(np.linspace(1, 5, 50), lambda ev: 1.0, n_waves=100, p_exp=0.05, eps1=0.1,
                    zz=3)
    with pytest.raises(ValueError, match="unknown setting 'zz'"):
        pas.PAS.from_flat({"zz": 3})


def test_fewer_waves_than_peaks_over_threshold_is_an_error_naming_both_numbers():
    # 50 peaks, all over the threshold, 40 waves: d would run to 50/40 = 1.25
    with pytest.raises(ValueError, match=r"n_waves=40 is below the 50 LF peaks over the "
                                         r"threshold.*1\.25.*n_waves_convention='spectral'"):
        pas.make_study(pas.PAS, np.linspace(1, 5, 50), n_waves=40, p_exp=0.05, eps1=0.1)
    with pytest.raises(ValueError, match="n_waves=40"):
        pas.run_pas(np.linspace(1, 5, 50), lambda ev: 1.0, n_waves=40, p_exp=0.05, eps1=0.1)


def test_fewer_waves_than_all_peaks_warns_in_one_line():
    # 30 of 50 peaks over the threshold: d stays below 1, but 40 waves for 50 peaks is odd
    lf = np.linspace(1, 5, 50)
    with pytest.warns(UserWarning, match=r"n_waves=40 is below the 50 LF peaks given \(30 over") \
            as caught:
        pas.make_study(pas.PAS, lf, n_waves=40, p_exp=0.05, eps1=0.1, threshold=lf[19])
    assert "\n" not in str(caught[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pas.make_study(pas.PAS, lf, n_waves=50, p_exp=0.05, eps1=0.1, threshold=lf[19])


def test_spectral_n_waves_convention_allows_exceedance_above_one():
    # the paper's Table 2 (and pas.validation): n_w = T_MCS / T_p,e, stated on purpose
    lf = np.linspace(1, 5, 50)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        study = pas.make_study(pas.PAS, lf, n_waves=40, p_exp=0.05, eps1=0.1,
                               n_waves_convention="spectral")
    assert study.lfset.d[-1] == pytest.approx(50 / 40)
    with pytest.raises(ValueError, match="n_waves_convention"):
        pas.make_study(pas.PAS, lf, n_waves=60, p_exp=0.05, eps1=0.1, n_waves_convention="guess")


@pytest.mark.slow
def test_unusable_indicator_warns():
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(1.0, 2000)
    hf = rng.permutation(2.0 * lf)  # LF carries no information on the HF ranks
    with pytest.warns(UserWarning, match="Kendall's tau"):
        pas.run_pas(lf, lambda ev: hf[ev.index] if hf[ev.index] > 0 else 1.0, n_waves=2000,
                    p_exp=0.01, eps1=1e-6, seed=0, max_hf=40, strategy=no_band())


def test_quantiles_of_the_exposure_maximum(table_oracle):
    lf, hf, n_w, p_exp, truth = monotone_problem(n=3000, n_waves=3200)
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.05, seed=1,
                      max_hf=15, strategy=no_band())
    # q = 1/e is the MPM level: 1 - exp(-P_exp) ~ P_exp
    assert res.quantile(np.exp(-1)) == pytest.approx(res.mpm, rel=2e-3)
    assert res.quantile(0.9) > res.mpm


@pytest.mark.parametrize("families", [
    ("gaussian", "gumbel_180", "clayton_180", "joe", "bb1", "bb1_180", "tll"),
])
def test_extra_copula_families(families, table_oracle):
    lf, hf, n_w, p_exp, truth = gumbel_problem(n=3000, n_waves=3300)
    # beyond the paper's five (and their rotations) only the selected-space fit applies
    with pytest.raises(ValueError, match=r"estimator=SelectedSample\(\)"):
        pas.PAS(families=families)
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=1.0, seed=1,
                      max_hf=20, strategy=no_band(families=families,
                                                  estimator=pas.SelectedSample()))
    assert set(res.fitted.family) <= set(families)
    assert all(f"aic_{f}" in res.history for f in families)
    assert res.mpm == pytest.approx(truth, rel=0.25)


def test_degenerate_pairs_do_not_stop_the_campaign():
    # the first HF answers are all equal: no Weibull fit is possible until spread arrives
    lf = np.random.default_rng(0).rayleigh(1.0, 800)
    calls = {"n": 0}

    def oracle(ev):
        calls["n"] += 1
        return 5.0 if calls["n"] <= 5 else 2.0 * ev.lf

    with pytest.warns(UserWarning, match="no model fit"):
        res = pas.run_pas(lf, oracle, n_waves=800, p_exp=0.01, eps1=0.01, seed=0, max_hf=14,
                          strategy=no_band())
    assert res.n_hf == 14 and res.history.fit_error.notna().any()
    assert np.isfinite(res.mpm)


@pytest.mark.slow
def test_impact_model_on_threshold_problem(table_oracle):
    lf, hf, n_w, p_exp, truth = threshold_problem()
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.015 * truth,
                      threshold=3.0, seed=2, strategy=pas.PAS(impact_model=True))
    assert res.n_false_positive > 0
    assert (res.distribution.h_mean == 0).any()  # some conditioning peaks give no impact
    assert res.mpm == pytest.approx(truth, rel=0.10)


def test_failed_initial_samples_are_replaced():
    lf = np.random.default_rng(0).rayleigh(1.0, 500)
    calls = {"n": 0}

    def oracle(ev):
        calls["n"] += 1
        if calls["n"] <= 4:
            raise RuntimeError("solver crashed")
        return 2.0 * ev.lf

    res = pas.run_pas(lf, oracle, n_waves=500, p_exp=0.01, eps1=0.01, seed=0, max_hf=8,
                      strategy=no_band())
    assert res.n_failed == 4 and res.n_hf == 8 and np.isfinite(res.mpm)


def _fp_band_problem():
    """Impacts only for the top 40 LF peaks and the 5 lowest pool peaks: a band of
    false positives in between that MD keeps probing."""
    n_w = 5000
    lf = np.sort(np.random.default_rng(0).rayleigh(3.0, n_w))[::-1]
    pool = np.flatnonzero(lf > 5.0)
    hf = np.zeros(n_w)
    hf[:40] = 10 * lf[:40]
    hf[pool[-5:]] = 1.0 + np.linspace(0, 0.1, 5)
    return lf, hf, n_w


def test_false_positives_between_true_positives_do_not_raise_the_threshold():
    # the §2.4 rule as written: only misses below every true positive raise l0, so a
    # band of misses with real (small) impacts beneath it keeps the threshold where
    # it is and those impacts stay reachable; the misses inform the impact model
    lf, hf, n_w = _fp_band_problem()
    res = pas.run_pas(lf, lambda ev: float(hf[ev.index]), n_waves=n_w, p_exp=2e-3, eps1=0.01,
                      threshold=5.0, seed=0, max_hf=60, strategy=no_band())
    assert (res.history.threshold.dropna() == 5.0).all()
    assert res.n_false_positive >= 10
    low = res.history[res.history.status == "true_positive"].lf.min()
    assert low < lf[lf > 5.0][-1] + 1.0  # an impact near the bottom of the pool was found
    assert res.distribution["p_impact"].min() < 0.5 < res.distribution["p_impact"].max()


def test_all_false_positives_do_not_exhaust_the_pool():
    lf = np.random.default_rng(1).rayleigh(3.0, 5000)
    pool = int((lf > 6.0).sum())
    res = pas.run_pas(lf, lambda ev: 0.0, n_waves=5000, p_exp=5e-3, eps1=0.01, threshold=6.0,
                      seed=0, strategy=no_band())
    assert res.n_false_positive == res.n_hf < pool / 2
    assert not res.converged and np.isnan(res.mpm)


def test_short_range_warns_and_cannot_converge():
    n_w = 10000
    lf = np.random.default_rng(0).rayleigh(3.0, n_w)
    order = np.argsort(-lf)
    hf = np.zeros(n_w)
    hf[order[:120]] = 10 * lf[order[:120]]  # impacts end at d = 0.012 < 2 P_exp
    with pytest.warns(UserWarning, match="short of"):
        res = pas.run_pas(lf, lambda ev: float(hf[ev.index]), n_waves=n_w, p_exp=0.01,
                          eps1=1e3, threshold=6.0, seed=0, max_hf=40, strategy=no_band())
    assert not res.converged and res.history.range_short.any()


@pytest.mark.slow
def test_a_study_stopped_by_its_budget_says_how_far_it_was_from_stopping(table_oracle):
    lf, hf, n_w, p_exp, truth = monotone_problem()
    res = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=1e-6 * truth,
                      seed=3, max_hf=15, strategy=no_band())
    assert not res.converged
    last = res.fitted.iloc[-1]
    assert np.isfinite(last["E_bar"]) and last["E_bar"] > 1e-6 * truth
    assert last["COV"] < 0.1  # only the measure over its limit is named
    assert res.summary().endswith(
        f"NOT converged (last Ē {last['E_bar']:.3g} against ε1 {1e-6 * truth:.3g}); the "
        "budget of 15 HF is spent")
    # stopped by its budget before the rule could stop, both measures within their limits
    early = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=10.0 * truth,
                        seed=3, max_hf=5, strategy=no_band())
    assert not early.converged
    assert "NOT converged (Ē and COV within ε1 and ε2: too few fitted iterations" in (
        early.summary())
    # a converged study keeps the short word
    done = pas.run_pas(lf, table_oracle(hf), n_waves=n_w, p_exp=p_exp, eps1=0.01 * truth,
                       seed=3, strategy=no_band())
    assert done.converged and done.summary().endswith("; converged")
