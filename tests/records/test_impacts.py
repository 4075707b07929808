"""Impact statistics: rates and intervals, Eq. 3.4 fit, clustering, declustering, fits, exposure.

Every formula is checked against an independent route: scipy's own
implementations, a generic optimiser, pyextremes, or direct simulation.
"""

import numpy as np
import pandas as pd
import pytest
from scipy import optimize, stats

from pas.records import (
    clustering_test,
    compare_load_distributions,
    decluster,
    exponential_test,
    exposure_load,
    exposure_probability,
    fit_load_distribution,
    fit_occurrence,
    impact_rates,
    inter_arrival_times,
    occurrence_model,
    occurrence_probability,
    qq_points,
)


def test_clopper_pearson_matches_scipy_binomtest():
    for k, n in ((0, 50), (3, 50), (461, 15198), (50, 50)):
        ours = occurrence_probability(k, n, method="clopper-pearson")
        ci = stats.binomtest(k, n).proportion_ci(confidence_level=0.95, method="exact")
        assert ours["low"] == pytest.approx(ci.low, abs=1e-10)
        assert ours["high"] == pytest.approx(ci.high, abs=1e-10)
        assert ours["probability"] == k / n


def test_jeffreys_interval_covers_at_its_nominal_rate():
    # coverage by simulation: 4000 binomial records of 2000 encounters at p = 3 %
    rng = np.random.default_rng(0)
    k = rng.binomial(2000, 0.03, 4000)
    table = occurrence_probability(k, np.full(k.size, 2000))
    cover = np.mean((table["low"] <= 0.03) & (0.03 <= table["high"]))
    assert 0.94 - 3 * 0.0036 < cover < 0.96 + 3 * 0.0036   # s.e. sqrt(.95 .05 / 4000)
    # no impact: the interval starts at zero; Beta(1/2, n + 1/2) upper quantile
    r = occurrence_probability(0, 100)
    assert r["low"] == 0.0 and r["high"] == pytest.approx(stats.beta.ppf(0.975, 0.5, 100.5))


def test_impact_rates_from_a_per_encounter_table():
    ev = pd.DataFrame({"load": [0, 0, 150.0, 0, 1200.0, 300.0, 0, 0, 0, 0]})
    t = impact_rates(ev, levels=[1000.0], hours=0.5)
    assert t.loc["impact", "n_events"] == 3 and t.loc["impact", "n_encounters"] == 10
    assert t.loc["load > 1000", "probability"] == pytest.approx(0.1)
    assert t.loc["impact", "per_hour"] == pytest.approx(6.0)
    with pytest.raises(ValueError, match="column 'force' not found"):
        impact_rates(ev, value="force")


def _conditions(c, rng, n=15000):
    hm0 = np.array([5.0, 6.0, 7.0, 8.0, 9.0])
    fb = np.full(hm0.size, 10.5)
    k = rng.binomial(n, occurrence_model(hm0, fb, c))
    return pd.DataFrame({"hm0": hm0, "freeboard": fb, "n_events": k, "n_encounters": n})


def test_occurrence_fit_is_the_binomial_ml_and_its_interval_covers():
    rng = np.random.default_rng(1)
    table = _conditions(1.19, rng)
    fit = fit_occurrence(table)

    # independent route: scipy's binomial log-pmf, a different optimiser
    def nll(c):
        p = occurrence_model(table["hm0"], table["freeboard"], c)
        return -stats.binom.logpmf(table["n_events"], table["n_encounters"], p).sum()

    ref = optimize.minimize_scalar(nll, bounds=(0.5, 3.0), method="bounded",
                                   options={"xatol": 1e-10}).x
    assert fit.c == pytest.approx(ref, abs=1e-6)
    # the interval ends are where the deviance rises by chi2_1(0.95) = 3.841
    for end in (fit.low, fit.high):
        assert 2 * (nll(end) - nll(ref)) == pytest.approx(3.8415, abs=1e-3)
    band = fit.predict([6.0, 8.0], 10.5)
    assert np.all(band["low"] < band["probability"]) and np.all(band["probability"] < band["high"])
    # coverage over 200 seeded campaigns (nominal 95 %, s.e. 1.5 %)
    hits = [(f.low <= 1.19 <= f.high) for f in (fit_occurrence(_conditions(1.19, rng))
                                                  for _ in range(200))]
    assert np.mean(hits) >= 0.90


def _poisson_events(rng, rate, n_seeds=10, duration=3 * 3600.0):
    rows = []
    for s in range(n_seeds):
        t = np.cumsum(rng.exponential(1.0 / rate, int(3 * rate * duration) + 50))
        t = t[t < duration]
        rows.append(pd.DataFrame({"t": t, "seed": s, "load": rng.lognormal(6.0, 0.5, t.size)}))
    return pd.concat(rows, ignore_index=True)


def test_ks_does_not_reject_poisson_processes():
    rng = np.random.default_rng(2)
    not_rejected = 0
    for _ in range(100):
        gaps = inter_arrival_times(_poisson_events(rng, 1 / 120.0))
        res = exponential_test(gaps)
        ref = stats.kstest(gaps, "expon", args=(0.0, gaps.mean()))
        assert res["pvalue"] == pytest.approx(ref.pvalue, rel=1e-12)
        not_rejected += res["pvalue"] > 0.05
    assert not_rejected >= 90


def _clustered_events(rng, n_seeds=10, duration=3 * 3600.0):
    """Wave-group clusters: Poisson cluster starts (mean gap 600 s), each with
    1 + Poisson(1.5) impacts 6–10 s apart."""
    rows = []
    for s in range(n_seeds):
        starts = np.cumsum(rng.exponential(600.0, 60))
        starts = starts[starts < duration]
        size = 1 + rng.poisson(1.5, starts.size)
        offs = [np.cumsum(np.r_[0.0, rng.uniform(6.0, 10.0, k - 1)]) for k in size]
        t = np.concatenate([a + o for a, o in zip(starts, offs)])
        load = rng.lognormal(6.0, 0.5, t.size)
        rows.append(pd.DataFrame({"t": t, "seed": s, "load": load}).sort_values("t"))
    return pd.concat(rows, ignore_index=True)


def test_clusters_are_rejected_and_pass_after_declustering():
    rng = np.random.default_rng(3)
    after = []
    for _ in range(20):
        ev = _clustered_events(rng)
        gaps = inter_arrival_times(ev)
        assert exponential_test(gaps)["pvalue"] < 0.05
        z = clustering_test(gaps, 12.0)
        assert z["pvalue"] < 1e-3 and z["zero_inflation"] > 0.3
        dc = decluster(ev, 12.0)
        assert dc["cluster_size"].sum() == len(ev)
        after.append(exponential_test(inter_arrival_times(dc), loc=12.0)["pvalue"] > 0.05)
    assert np.mean(after) >= 0.9
    # and a Poisson record shows no zero-inflation
    assert clustering_test(inter_arrival_times(_poisson_events(rng, 1 / 120.0)), 12.0)[
        "pvalue"] > 0.01


def test_decluster_agrees_with_pyextremes_on_one_seed():
    pyextremes = pytest.importorskip("pyextremes")
    ev = _clustered_events(np.random.default_rng(4), n_seeds=1)
    ours = decluster(ev, 12.0, seed=None)
    series = pd.Series(ev["load"].to_numpy(),
                       index=pd.Timestamp("2000-01-01") + pd.to_timedelta(ev["t"], unit="s"))
    theirs = pyextremes.get_extremes(series, "POT", threshold=0.0, r=pd.Timedelta(seconds=12))
    np.testing.assert_allclose(ours["load"].to_numpy(), theirs.to_numpy())
    # seeds are never joined: the same times in two seeds give two clusters
    two = pd.DataFrame({"t": [5.0, 5.0], "seed": [0, 1], "load": [1.0, 2.0]})
    assert len(decluster(two, 12.0)) == 2 and len(decluster(two, 12.0, seed=None)) == 1


def test_ml_fits_are_scipys_and_match_pyextremes():
    x = stats.invweibull(3.0, loc=0.0, scale=800.0).rvs(600, random_state=5)
    r = fit_load_distribution(x, "frechet", loc=0.0)
    np.testing.assert_allclose(r["params"], stats.invweibull.fit(x, floc=0.0), rtol=1e-6)
    ll = stats.invweibull.logpdf(x, *r["params"]).sum()
    assert r["loglik"] == pytest.approx(ll, rel=1e-12) and r["aic"] == pytest.approx(4 - 2 * ll)
    # free location: at least as likely as scipy's own fit
    free = fit_load_distribution(x, "frechet")
    assert free["loglik"] >= stats.invweibull.logpdf(x, *stats.invweibull.fit(x)).sum() - 1e-9
    # GEV against pyextremes' MLE model (it reports AICc)
    pytest.importorskip("pyextremes")
    from pyextremes.models import get_model

    y = stats.genextreme(-0.1, loc=1000.0, scale=200.0).rvs(500, random_state=3)
    model = get_model("MLE", extremes=pd.Series(y, index=pd.date_range("2000", periods=500)),
                      distribution="genextreme")
    ours = fit_load_distribution(y, "gev")
    p = model.fit_parameters
    np.testing.assert_allclose(ours["params"], [p["c"], p["loc"], p["scale"]], rtol=1e-6)
    assert ours["loglik"] == pytest.approx(model.loglikelihood, rel=1e-9)
    assert ours["aic"] + 2 * 3 * 4 / (500 - 3 - 1) == pytest.approx(model.AIC, rel=1e-9)


def test_binned_least_squares_matches_curve_fit_and_ranking():
    x = stats.weibull_min(1.5, loc=0.0, scale=500.0).rvs(4000, random_state=6)
    ls = fit_load_distribution(x, "weibull", method="binned ls", loc=0.0, bins=40)
    density, edges = np.histogram(x, bins=40, density=True)
    mid = 0.5 * (edges[1:] + edges[:-1])
    ref, _ = optimize.curve_fit(lambda m, c, s: stats.weibull_min.pdf(m, c, 0.0, s), mid,
                                density, p0=(1.0, 300.0))
    np.testing.assert_allclose([ls["params"][0], ls["params"][2]], ref, rtol=1e-4)
    table = compare_load_distributions(x, loc=0.0)
    assert table.index[0] == "weibull" and table["delta_aic"].iloc[0] == 0.0
    assert list(table.columns[:2]) == ["distribution", "params"]
    qq = qq_points(x, table.loc["weibull", "dist"])
    assert np.corrcoef(qq["theoretical"], qq["empirical"])[0, 1] > 0.99


def test_exposure_probability_against_direct_simulation():
    rng = np.random.default_rng(7)
    pr, n_w, load = 0.03, 400, stats.invweibull(3.0, scale=500.0)
    n_rep = 20000
    k = rng.binomial(n_w, pr, n_rep)            # impacts per exposure
    draws = load.rvs(k.sum(), random_state=rng)
    start = np.r_[0, np.cumsum(k)[:-1]]
    peak = np.where(k > 0, np.maximum.reduceat(np.r_[draws, 0.0], start), 0.0)
    for lim in (800.0, 1500.0, 3000.0):
        sim = np.mean(peak > lim)
        se = np.sqrt(sim * (1 - sim) / n_rep)
        assert abs(exposure_probability(lim, pr, load, n_w) - sim) < 2 * se
    # the inverse: back to the limits, and the MPM is the 1 - 1/e level
    limits = np.array([800.0, 1500.0, 3000.0])
    probs = exposure_probability(limits, pr, load, n_w)
    assert isinstance(probs, pd.Series) and probs.index.name == "limit"
    np.testing.assert_allclose(exposure_load(probs.to_numpy(), pr, load, n_w), limits, rtol=1e-9)
    mpm = exposure_load(1 - np.exp(-1), pr, load, n_w)
    assert np.mean(peak > mpm) == pytest.approx(1 - np.exp(-1), abs=0.01)
    # a target above the chance of any impact at all has no load
    assert np.isnan(exposure_load(0.9999999, pr, load, 10))


def test_inter_arrival_and_bad_input():
    ev = pd.DataFrame({"t": [30.0, 10.0, 35.0, 5.0], "seed": [0, 0, 0, 1],
                       "load": [1.0, 0.0, 2.0, 3.0]})
    assert inter_arrival_times(ev, value="load").tolist() == [5.0]
    assert inter_arrival_times(ev).tolist() == [20.0, 5.0]
    with pytest.raises(ValueError, match="t_min"):
        decluster(ev, 0.0)
    with pytest.raises(ValueError, match="at least 3"):
        exponential_test([1.0, 2.0])
    with pytest.raises(ValueError, match="shorter than loc"):
        exponential_test([1.0, 2.0, 30.0], loc=12.0)
    with pytest.raises(ValueError, match="too few"):
        fit_load_distribution([1.0, 2.0, 3.0], "gev")
    with pytest.raises(ValueError, match="must be one of"):
        fit_load_distribution(np.arange(1.0, 20.0), "pareto")
    with pytest.raises(ValueError, match="n_events"):
        occurrence_probability(5, 3)
    with pytest.raises(ValueError, match="with and without"):
        fit_occurrence(pd.DataFrame({"hm0": [5.0], "freeboard": [10.0], "n_events": [0],
                                     "n_encounters": [100]}))


def test_impact_figures_compose_and_write_png(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pas.plotting import plot_exposure, plot_inter_arrival, plot_occurrence, plot_qq

    rng = np.random.default_rng(8)
    ev = _clustered_events(rng, n_seeds=4)
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    f1, a1 = plot_occurrence(fit_occurrence(_conditions(1.19, rng)), ax=axes[0, 0])
    f2, a2 = plot_inter_arrival(inter_arrival_times(ev),
                                declustered=inter_arrival_times(decluster(ev, 12.0)),
                                t_min=12.0, ax=axes[0, 1])
    table = compare_load_distributions(ev["load"], ["lognormal", "gamma"])
    f3, a3 = plot_qq(ev["load"], table, ax=axes[1, 0])
    f4, a4 = plot_exposure(np.linspace(300, 3000, 50), 0.03, table.iloc[0]["dist"], 500,
                           mpm={"truth": 1500.0}, ax=axes[1, 1])
    assert all(f is fig for f in (f1, f2, f3, f4))
    assert a2.get_yscale() == "log" and a4.get_yscale() == "log"
    assert len(a2.get_legend().get_texts()) == 4      # two histograms, two fits
    assert any("truth" in t.get_text() for t in a4.get_legend().get_texts())
    fig.savefig(tmp_path / "impacts.png", dpi=70)
    assert (tmp_path / "impacts.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    fig_alone, _ = plot_qq(ev["load"], table.iloc[0]["dist"])
    assert fig_alone is not fig
    plt.close("all")


def test_weibull_mixture_candidate_recovers_bore_impulse_loads_and_leaves_one_law_alone():
    from pas.stats.weibull_mixture import WeibullMixture, fit_weibull_mixture

    truth = WeibullMixture(100.0, 0.6, 150.0, 3.5, 550.0, 1.1)
    x = truth.isf(np.random.default_rng(3).uniform(size=3000))
    ref = 0.6 * stats.weibull_min(3.5, 100.0, 150.0).pdf(x) + 0.4 * stats.weibull_min(
        1.1, 100.0, 550.0).pdf(x)
    np.testing.assert_allclose(truth.pdf(x), ref, rtol=1e-12)
    m = fit_weibull_mixture(x - 100.0, loc=0.0)
    assert (m.p, m.alpha1, m.beta1, m.alpha2, m.beta2) == pytest.approx(
        (0.6, 150.0, 3.5, 550.0, 1.1), rel=0.12)
    table = compare_load_distributions(x)
    assert table.index[0] == "weibull_mixture"
    row = table.loc["weibull_mixture"]
    assert row["n_params"] == 6 and row["distribution"] == "weibull_mixture"
    q = 0.017
    assert abs(row["dist"].isf(q) / truth.isf(q) - 1) < 0.05
    # on one Weibull the three extra parameters do not pay
    w = stats.weibull_min(1.5, loc=0.0, scale=500.0).rvs(2000, random_state=6)
    assert compare_load_distributions(w, loc=0.0).index[0] == "weibull"
    with pytest.raises(ValueError, match="maximum likelihood only"):
        fit_load_distribution(x, "weibull_mixture", method="binned ls")
    # loads rounded to 100 (11 tied at the smallest): the location may not run into
    # the ties, where the likelihood has no upper bound once β₂ < 10/11
    y = np.round(truth.isf(np.random.default_rng(0).uniform(size=400)), -2)
    y = y[y > 0]
    assert np.sum(y == y.min()) > 5
    tied = fit_weibull_mixture(y)
    assert y.min() - tied.theta > 1.0
    assert abs(tied.isf(q) / truth.isf(q) - 1) < 0.15
