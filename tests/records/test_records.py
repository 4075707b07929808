"""Record analysis: MPM from pooled peaks / seed maxima / fits, theory, convergence, figures."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from scipy import optimize, stats

import pas.waves as W
from pas.plotting import (
    plot_convergence,
    plot_record_analysis,
    plot_record_convergence,
    plot_record_exceedance,
)
from pas.records import (
    analyse_record,
    forristall_crest_exceedance,
    forristall_crest_mpm,
    forristall_parameters,
    mpm_convergence,
    mpm_pooled,
    mpm_seed_maxima,
    mpm_weibull,
    pooled_peaks_distribution,
    quantile_pooled,
    random_subsets,
    rayleigh_crest_exceedance,
    rayleigh_crest_mpm,
    rayleigh_crest_quantile,
    seed_maxima,
    seeds_needed,
)
from pas.stats import quantile_exceedance, value_at_exceedance, wave_crests

HS, TP = 10.0, 11.0


@pytest.fixture(scope="module")
def linear_record():
    """100 one-hour seeds of a linear JONSWAP sea (FFT random phase), crests per wave."""
    spec = lambda w: W.jonswap(w, HS, TP, gamma=3.3)  # noqa: E731
    crests, enc = [], []
    for s in range(100):
        sea = W.linear_sea(spec, 3600.0, seed=s, depth=30.0)
        _, eta = sea.elevation(0.25)
        c, _ = wave_crests(eta)
        crests.append(c)
        enc.append(c.size)
    return crests, np.array(enc), sea.m0


def test_linear_sea_pooled_mpm_matches_rayleigh(linear_record):
    crests, enc, m0 = linear_record
    n = enc.mean()  # encounters per exposure (one seed = one hour)
    theory = np.sqrt(2.0 * m0 * np.log(n))
    mpm = mpm_pooled(crests, enc)
    assert abs(mpm / theory - 1.0) < 0.03
    fit_mpm, fit = mpm_weibull(crests, enc, top_fraction=0.3)
    assert abs(fit_mpm / theory - 1.0) < 0.03
    assert 1.5 < fit.beta < 3.0


def test_linear_sea_seed_maxima_mpm_agrees(linear_record):
    crests, enc, m0 = linear_record
    n, big_n = enc.mean(), len(crests)
    theory = np.sqrt(2.0 * m0 * np.log(n))
    # Tolerance: three standard errors of the sample 0.368-quantile of N maxima,
    # sqrt(q(1-q)/N) / f(x_q), with the maximum's (Gumbel) density at its mode
    # f = 1/(e b), b = sigma / sqrt(2 ln n): 0.094 m = 1.1 % here, so 3.3 %.
    b = np.sqrt(m0) / np.sqrt(2.0 * np.log(n))
    se = np.sqrt(0.368 * 0.632 / big_n) * np.e * b
    tol = 3.0 * se
    smax = mpm_seed_maxima(seed_maxima(crests))
    assert abs(smax - theory) < tol
    assert abs(smax - mpm_pooled(crests, enc)) < tol
    a = analyse_record(crests, enc)
    assert a.mpm_seed_maxima == pytest.approx(smax)
    assert a.mpm_pooled == pytest.approx(mpm_pooled(crests, enc))
    assert a.n_seeds == big_n and a.n_encounters == enc.sum()


def test_quantile_exceedance_worked_example():
    # van Essen, Scharnke & Seyffert (2023): M = 35 one-hour seeds (exposure
    # durations) in a record of n_e = 16 113 encounters.
    p368 = quantile_exceedance(0.368, 35, 16113)
    p90 = quantile_exceedance(0.9, 35, 16113)
    # 2.169e-3 to its 4 printed digits; 2.29e-4 is printed with 3 digits, the
    # 4-digit value is 2.288e-4 (1 - 0.9^(35/16113) = 2.28833e-4).
    assert f"{p368:.3e}" == "2.169e-03"
    assert f"{p90:.2e}" == "2.29e-04" and f"{p90:.3e}" == "2.288e-04"
    # and the record read-out uses exactly that probability
    rng = np.random.default_rng(3)
    enc = np.full(35, 16113 // 35)
    enc[: 16113 - enc.sum()] += 1
    peaks = [rng.rayleigh(2.5, k) for k in enc]
    d, v = pooled_peaks_distribution(peaks, enc)
    assert quantile_pooled(peaks, enc, 0.9) == pytest.approx(float(value_at_exceedance(d, v, p90)))
    assert quantile_pooled(peaks, 16113, 0.368) == pytest.approx(
        float(value_at_exceedance(d, v, p368)))


def test_pooled_distribution_and_seed_maxima_conventions():
    # the paper's Eq. 3 on request ...
    d, v = pooled_peaks_distribution([[1.0, 3.0], [2.0], []], n_encounters=[5, 5, 10],
                                     positions="k/n")
    np.testing.assert_allclose(d, [0.05, 0.1, 0.15])
    np.testing.assert_allclose(v, [3.0, 2.0, 1.0])
    # ... Gringorten (k - 0.44) / (n + 0.12) by default (changed on purpose: k/n
    # reads high quantiles near the top of a record biased high)
    d, _ = pooled_peaks_distribution([[1.0, 3.0], [2.0], []], n_encounters=[5, 5, 10])
    np.testing.assert_allclose(d, [0.56 / 20.12, 1.56 / 20.12, 2.56 / 20.12])
    np.testing.assert_allclose(seed_maxima([[1.0, 3.0], [], [2.0]]), [3.0, 0.0, 2.0])
    # k/(N+1) by default: 0.632 * 6 = 3.792 -> 3rd largest (3) + 0.792 * (2 - 3);
    # the old k/N reading (0.632 * 5 = 3.16 -> 2.84) only on request
    assert mpm_seed_maxima([5.0, 1.0, 3.0, 2.0, 4.0]) == pytest.approx(2.208)
    assert mpm_seed_maxima([5.0, 1.0, 3.0, 2.0, 4.0], positions="k/n") == pytest.approx(2.84)


def test_impact_loads_fit_and_pooled_use_encounter_basis():
    # 3 % of 100 000 encounters give an impact with Weibull-distributed force.
    rng = np.random.default_rng(7)
    true = stats.weibull_min(1.3, loc=100.0, scale=400.0)
    n_seeds, enc_per_seed = 50, 2000
    peaks = [true.rvs(rng.binomial(enc_per_seed, 0.03), random_state=rng) for _ in range(n_seeds)]
    exact = true.isf((1.0 / enc_per_seed) / 0.03)  # per-peak exceedance of the MPM
    assert mpm_pooled(peaks, enc_per_seed * n_seeds) == pytest.approx(exact, rel=0.06)
    fit_mpm, _ = mpm_weibull(peaks, enc_per_seed * n_seeds, top_fraction=0.9)
    assert fit_mpm == pytest.approx(exact, rel=0.06)
    # exposure shorter than the rank of the smallest peak: "no impact" level
    assert mpm_pooled(peaks, enc_per_seed * n_seeds, exposure_encounters=10.0) == 0.0


def test_rms_difference_decreases_with_seeds():
    rng = np.random.default_rng(11)
    peaks = [rng.rayleigh(2.5, 400) for _ in range(30)]
    cv = mpm_convergence(peaks, 400 * 30, n_subsets=300, n_subsets_fit=10, n_boot=30, seed=1)
    r = cv.rms["pooled"]
    picks = np.array([1, 2, 4, 8, 16, 29]) - 1
    assert np.all(np.diff(r[picks]) < 0)
    # the raw subset RMS vanishes at N = M by construction; the fresh-campaign
    # R(N) (finite-population corrected) is not defined there (changed on purpose)
    assert cv.rms_subsets["pooled"][-1] == 0.0 and np.isnan(r[-1])
    assert cv.reference == pytest.approx(mpm_pooled(peaks, 12000))
    assert np.all(cv.rms_low["pooled"][:-1] < r[:-1]) and np.all(
        r[:-1] < cv.rms_high["pooled"][:-1]
    )
    assert np.isnan(cv.rms["seed maxima"][0]) and cv.rms["seed maxima"][-2] < r[0]
    assert cv.rms["fit"][0] > cv.rms["fit"][15]
    assert cv.seeds_needed(r[9] + 1e-9) <= 10
    assert cv.seeds_needed(0.0) is None   # a record of M seeds never shows zero error


def test_random_subsets_and_seeds_needed():
    idx = random_subsets(10, 4, 200, np.random.default_rng(0))
    assert idx.shape == (200, 4)
    assert all(len(set(row)) == 4 for row in idx)
    assert seeds_needed([1, 2, 3, 4], [0.5, 0.2, 0.3, 0.1], 0.25) == 4
    assert seeds_needed([1, 2, 3], [0.5, 0.2, 0.1], 0.25) == 2
    assert seeds_needed([1, 2], [0.5, 0.4], 0.25) is None


def test_rayleigh_by_hand():
    assert rayleigh_crest_exceedance(5.0, 10.0) == pytest.approx(np.exp(-2.0), rel=1e-12)
    assert rayleigh_crest_exceedance(5.0, 10.0) == pytest.approx(0.1353353, rel=1e-6)
    # MPM over 400 waves: 10 * sqrt(ln 400 / 8) = 10 * sqrt(5.99146 / 8) = 8.65409
    assert rayleigh_crest_mpm(10.0, 400) == pytest.approx(8.65409, rel=1e-5)
    # the 0.368 quantile of the maximum is the MPM to O(1/n)
    assert rayleigh_crest_quantile(10.0, 400, 0.368) == pytest.approx(8.65409, rel=2e-4)


def test_forristall_by_hand():
    # Deep water, Hs 10 m, T1 9 s: S1 = 2 pi 10 / (9.81 * 81) = 0.0790726,
    # alpha = 0.3536 + 0.2892 S1 = 0.3764678, beta = 2 - 2.1597 S1 = 1.829227.
    a, b, s1, ur = forristall_parameters(10.0, 9.0)
    assert (s1, ur) == (pytest.approx(0.0790726, rel=1e-6), 0.0)
    assert a == pytest.approx(0.3764678, rel=1e-6) and b == pytest.approx(1.829227, rel=1e-6)
    # P(C > 8 m) = exp(-(8 / 3.764678)^1.829227) = exp(-(2.125016)^1.829227)
    #            = exp(-exp(1.829227 * 0.753779)) = exp(-3.970274) = 0.018868
    assert forristall_crest_exceedance(8.0, 10.0, 9.0) == pytest.approx(0.018868, rel=1e-4)
    # 3D deep: alpha = 0.3536 + 0.2568 S1, beta = 2 - 1.7912 S1
    a3, b3, _, _ = forristall_parameters(10.0, 9.0, kind="3d")
    assert a3 == pytest.approx(0.3536 + 0.2568 * 0.0790726, rel=1e-6)
    assert b3 == pytest.approx(2 - 1.7912 * 0.0790726, rel=1e-6)
    # Finite depth 30 m (condition A, T1 = 11/1.198 s): k1 from w^2 = g k tanh(k d)
    t1, depth = 11.0 / 1.198, 30.0
    w = 2 * np.pi / t1
    k1 = optimize.brentq(lambda k: 9.81 * k * np.tanh(k * depth) - w**2, 1e-4, 1.0)
    ur_hand = 10.0 / (k1**2 * depth**3)
    a, b, s1, ur = forristall_parameters(10.0, t1, depth)
    assert ur == pytest.approx(ur_hand, rel=1e-8) and ur == pytest.approx(0.1364, abs=1e-4)
    assert a == pytest.approx(0.3536 + 0.2892 * s1 + 0.1060 * ur_hand, rel=1e-12)
    assert b == pytest.approx(2 - 2.1597 * s1 + 0.0968 * ur_hand**2, rel=1e-12)
    assert forristall_crest_mpm(10.0, t1, depth, 392) == pytest.approx(
        a * 10.0 * np.log(392) ** (1 / b), rel=1e-12)
    # Rayleigh is the S1 = Ur = 0 limit (alpha0 = 0.3536, 1/sqrt(8) = 0.353553)
    assert forristall_crest_mpm(10.0, 1e6, np.inf, 400) == pytest.approx(
        rayleigh_crest_mpm(10.0, 400), rel=2e-4)


def test_bad_input_raises():
    with pytest.warns(UserWarning, match="above 1"):
        pooled_peaks_distribution([1.0, 2.0, 3.0], 2)
    with pytest.raises(ValueError, match="n_encounters must be > 0"):
        mpm_pooled([1.0, 2.0], 0)
    with pytest.raises(ValueError, match="seed maxima cannot resolve"):
        mpm_seed_maxima([3.0])
    with pytest.raises(ValueError, match="kind"):
        forristall_parameters(10.0, 9.0, kind="4d")
    with pytest.raises(ValueError, match="one count per seed"):
        mpm_pooled([[1.0], [2.0]], [5, 5, 5])
    with pytest.raises(ValueError, match="n_values"):
        mpm_convergence([[1.0, 2.0], [2.0, 3.0]], 10, n_values=[3])
    with pytest.raises(ValueError, match="NaN"):
        mpm_pooled([1.0, np.nan], 10)
    # a target beyond the record is an error, not the largest peak (changed on purpose)
    with pytest.raises(ValueError, match="beyond the largest peak"):
        mpm_pooled([1.0, 2.0], 10, exposure_encounters=20.0)
    with pytest.raises(ValueError, match="named tail"):
        mpm_pooled([1.0, 2.0], 10, exposure_encounters=20.0, extrapolate="pareto")


def test_figures_write_png(tmp_path, linear_record):
    crests, enc, _ = linear_record
    a = analyse_record(crests[:20], enc[:20])
    fig, ax = plot_record_analysis(a, units="m")
    assert ax.get_yscale() == "log" and "[m]" in ax.get_xlabel()
    fig.savefig(tmp_path / "exceedance.png", dpi=80)
    cv = mpm_convergence(crests[:20], enc[:20], n_subsets=50, n_subsets_fit=5, n_boot=10)
    fig2, ax2 = plot_record_convergence(cv, criterion=0.3, units="m", variable="crest MPM")
    fig2.savefig(tmp_path / "convergence.png", dpi=80)
    # composing on given axes
    import matplotlib.pyplot as plt

    fig3, axes = plt.subplots(1, 2)
    f, ax_l = plot_record_exceedance(a.d, a.values, p_target=a.p_target, ax=axes[0])
    f2, ax_r = plot_convergence(cv.n, cv.rms["pooled"], criterion=0.3, ax=axes[1])
    assert f is fig3 and f2 is fig3 and ax_l is axes[0]
    fig3.savefig(tmp_path / "both.png", dpi=80)
    for name in ("exceedance.png", "convergence.png", "both.png"):
        data = (tmp_path / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    assert len(ax.get_legend().get_texts()) >= 5
    plt.close("all")


# ------------------------------------------------------------ input checks
N_WAVES = 400   # crests per seed (one exposure duration)


def _rayleigh_maxima(rng, shape, hs=HS, n=N_WAVES):
    """Maxima of n Rayleigh crests, exactly: F_max = (1 - exp(-8c²/Hs²))^n = u."""
    u = rng.random(shape)
    return hs * np.sqrt(-np.log(-np.expm1(np.log(u) / n)) / 8.0)


def test_seed_maxima_mpm_is_unbiased_with_k_over_n_plus_1():
    # 20 000 replications of N seed maxima; the exact MPM is the e^-1 quantile
    from pas.records import read_at_exceedance

    rng = np.random.default_rng(15)
    exact = rayleigh_crest_quantile(HS, N_WAVES, np.exp(-1.0))
    for n in (3, 10, 20):
        m = -np.sort(-_rayleigh_maxima(rng, (20000, n)), axis=1)
        est = read_at_exceedance(m, n, 1 - 0.368, positions="weibull", scale="linear")
        assert mpm_seed_maxima(m[0]) == pytest.approx(est[0])     # the same read-out
        bias, se = est.mean() - exact, est.std() / np.sqrt(est.size)
        assert abs(bias) < 0.03 and se < 0.01
        old = read_at_exceedance(m, n, 1 - 0.368, positions="k/n", scale="linear")
        assert old.mean() - exact > {3: 0.3, 10: 0.08, 20: 0.03}[n]   # the defect, kept measurable


def test_mpm_is_the_e1_quantile_not_the_mode():
    # mode of the maximum of 1000 Rayleigh crests (density n f F^(n-1)) by a bounded search
    n, hs = 1000, HS
    def neg_log_density(c):
        z = 8 * c**2 / hs**2
        return -(np.log(16 * c / hs**2) - z + (n - 1) * np.log(-np.expm1(-z)))
    mode = optimize.minimize_scalar(neg_log_density, bounds=(5, 15), method="bounded",
                                    options={"xatol": 1e-10}).x
    q = rayleigh_crest_quantile(hs, n, np.exp(-1.0))
    assert mode / q - 1 == pytest.approx(0.0053, abs=0.0002)
    assert rayleigh_crest_mpm(hs, n) == pytest.approx(q, rel=1e-4)


def test_pooled_high_quantile_gringorten_less_biased_than_k_over_n():
    # q = 0.9 of the hourly maximum from 10 one-hour seeds of Rayleigh crests
    rng = np.random.default_rng(16)
    n_rep, m = 600, 10
    exact = rayleigh_crest_quantile(HS, N_WAVES, 0.9)
    est = {"gringorten": [], "k/n": []}
    for _ in range(n_rep):
        crests = rng.rayleigh(HS / 4, (m, N_WAVES))
        for pos in est:
            est[pos].append(quantile_pooled(list(crests), m * N_WAVES, 0.9, positions=pos))
    bias = {k: np.mean(v) - exact for k, v in est.items()}
    se = {k: np.std(v) / np.sqrt(n_rep) for k, v in est.items()}
    assert bias["k/n"] > 0.1 + 3 * se["k/n"]
    assert abs(bias["gringorten"]) < abs(bias["k/n"]) / 2


def test_target_beyond_the_record_needs_a_named_model():
    rng = np.random.default_rng(17)
    crests = [rng.rayleigh(HS / 4, N_WAVES) for _ in range(10)]
    # q = 0.99 of the hourly maximum: 2.5e-5 per wave, 10x beyond 1/4000
    with pytest.raises(ValueError, match="beyond the largest peak"):
        quantile_pooled(crests, 10 * N_WAVES, 0.99)
    exact = rayleigh_crest_quantile(HS, N_WAVES, 0.99)   # 11.51 m
    for model in ("gpd", "weibull"):
        v = quantile_pooled(crests, 10 * N_WAVES, 0.99, extrapolate=model)
        # the spread over 8 seeded records was 10.3-11.4 (GPD), 10.9-12.1 m (Weibull)
        assert v > max(c.max() for c in crests) and abs(v / exact - 1) < 0.12
    with pytest.warns(UserWarning, match="beyond the largest peak"):
        a = analyse_record(crests, 10 * N_WAVES, exposure_encounters=20 * N_WAVES, n_boot=0)
    assert np.isnan(a.mpm_pooled)


@pytest.mark.slow
def test_r_n_matches_fresh_campaigns_up_to_three_quarters_of_the_record():
    # 16 records of M = 40 seeds (100 crests per seed = one exposure); R(N) of
    # fresh N-seed campaigns about the exact MPM from 2000 new campaigns each
    rng = np.random.default_rng(18)
    m, n_w, ns = 40, 100, [5, 10, 20, 30]
    exact = HS * np.sqrt(np.log(n_w) / 8.0)
    fresh = []
    for n in ns:
        est = [mpm_pooled(list(rng.rayleigh(HS / 4, (n, n_w))), n * n_w) for _ in range(2000)]
        fresh.append(np.sqrt(np.mean((np.array(est) - exact) ** 2)))
    r, raw, inside = [], [], []
    for _ in range(16):
        rec = list(rng.rayleigh(HS / 4, (m, n_w)))
        cv = mpm_convergence(rec, m * n_w, n_values=ns, n_subsets=400, n_subsets_fit=0,
                             n_boot=40, n_subsets_boot=60, seed=1)
        r.append(cv.rms["pooled"])
        raw.append(cv.rms_subsets["pooled"])
        inside.append((cv.rms_low["pooled"] <= fresh) & (np.array(fresh) <= cv.rms_high["pooled"]))
    r, raw = np.mean(r, axis=0), np.mean(raw, axis=0)
    np.testing.assert_allclose(r, fresh, rtol=0.10)
    assert raw[-1] < 0.7 * fresh[-1]          # the uncorrected subset RMS at N = 0.75 M
    assert np.mean(inside) >= 0.8             # bootstrap band: nominal 95 %, 93-97 % measured


def test_bootstrap_intervals_cover_the_exact_mpm():
    from pas.records import bootstrap_mpm

    rng = np.random.default_rng(19)
    exact = HS * np.sqrt(np.log(N_WAVES) / 8.0)
    hits = {"pooled peaks": 0, "seed maxima": 0}
    for _ in range(60):
        rec = list(rng.rayleigh(HS / 4, (20, N_WAVES)))
        for method in hits:
            ci = bootstrap_mpm(rec, 20 * N_WAVES, method=method, n_boot=300, seed=2)
            hits[method] += ci["low"] <= exact <= ci["high"]
    assert hits["pooled peaks"] >= 0.8 * 60 and hits["seed maxima"] >= 0.8 * 60
    a = analyse_record(rec, 20 * N_WAVES, n_boot=200)
    assert set(a.ci.index) == {"pooled peaks", "seed maxima"}
    assert a.ci.loc["pooled peaks", "low"] < a.mpm_pooled < a.ci.loc["pooled peaks", "high"]
