"""The twelve validation analogues: generation, consistency, physics, and the CLI.

Reduced sizes (``scale`` 0.05-0.1); the truths are compared to quantities
computed here independently of the generator (e.g. empirical counts).
"""

import hashlib

import numpy as np
import pytest

import pas
from pas.cli import main
from pas.validation import CASE_IDS, PAPER_CASE_IDS, CaseData, generate_case, get_case
from pas.validation.generate import build_case, cache_path


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("pas-cache")


@pytest.fixture(scope="module")
def small(cache):
    scales = {"1": 0.06, "2": 0.1, "3": 0.1, "4": 0.1}
    return {c: generate_case(c, scale=scales[c[0]], path=cache) for c in CASE_IDS}


def test_registry_matches_paper_table2():
    s = get_case("3A")
    assert (s.n_waves, s.p_exp, s.threshold, s.eps1) == (15198, 1.91e-3, 12.0, 200.0)
    assert get_case("1a").n_waves == 16364 and get_case("4b").paper_truth == 2.44e3
    with pytest.raises(ValueError, match="unknown case '5a'"):
        get_case("5a")


def test_registry_has_both_impact_sets():
    assert len(CASE_IDS) == 12
    assert PAPER_CASE_IDS == ("1a", "1b", "2a", "2b", "3a", "3b", "4a", "4b")
    for c in ("3a", "3b", "4a", "4b"):
        hard, paper = get_case(f"{c}-HARD"), get_case(c)
        assert (hard.variant, paper.variant) == ("hard", "paper-like")
        assert hard.paper_id == c and hard.family == c[0]
        assert (hard.n_waves, hard.p_exp, hard.threshold, hard.eps1, hard.paper_truth) == \
            (paper.n_waves, paper.p_exp, paper.threshold, paper.eps1, paper.paper_truth)


@pytest.mark.slow
@pytest.mark.parametrize("case", CASE_IDS)
def test_case_shapes_ids_and_truth(small, case):
    d = small[case]
    n = d.lf.size
    assert d.hf.shape == d.ids.shape == d.seed_no.shape == d.t_start.shape == (n,)
    assert len(set(d.ids)) == n and all(i.startswith(case) for i in d.ids[:5])
    assert np.all(d.t_end > d.t_start) and np.all(d.hf >= 0) and np.all(np.isfinite(d.lf))
    spec = get_case(case)
    assert d.p_exp == spec.p_exp and d.eps1 == spec.eps1
    assert np.all(np.diff(d.truth_d) > 0) and np.isfinite(d.truth_mpm) and d.truth_mpm > 0
    if spec.truth_method == "empirical":  # independent: k-th largest with d = k/n_w
        v = np.sort(d.hf)[::-1]
        k = d.p_exp * d.n_waves
        lo, hi = v[int(np.floor(k)) - 1], v[int(np.ceil(k)) - 1]
        assert min(lo, hi) - 1e-9 <= d.truth_mpm <= max(lo, hi) + 1e-9


@pytest.mark.slow
def test_oracle_reveals_the_table(small):
    d = small["2a"]
    oracle = d.oracle()
    ev = pas.Event(index=7, id=d.ids[7], lf=d.lf[7], d=0.5)
    assert oracle(ev) == d.hf[7] and oracle.calls == 1
    assert d.meta()[7]["seed"] == d.seed_no[7]


@pytest.mark.slow
def test_case1_physics(small):
    d = small["1a"]
    assert d.tau > 0.9  # paper Fig. 16 / SPEC §8: ~0.95
    assert small["1b"].tau < d.tau - 0.05  # the noise system degrades the indicator
    assert d.info["hs_max_rel_error"] < 0.01
    # second-order crests are higher than linear ones on average in the tail
    top = np.argsort(d.lf)[-50:]
    assert np.mean(d.hf[top] - d.lf[top]) > 0.3
    # same waves, noise only on the LF: HF tails of 1a and 1b are the same sea
    assert abs(small["1b"].truth_mpm - d.truth_mpm) < 0.05 * d.truth_mpm


@pytest.mark.slow
def test_case2_hog_sag_asymmetry(small):
    # VERSION 3: the midbody side-flare term outweighs the bow flare, so the
    # non-linear hogging peaks grow and the sagging peaks shrink: the paper's order hog > sag
    hog, sag = small["2a"], small["2b"]
    np.testing.assert_array_equal(hog.t_start, sag.t_start)  # same wave windows
    assert np.median(hog.hf - hog.lf) > 0 > np.median(sag.hf - sag.lf)
    assert hog.truth_mpm > sag.truth_mpm


@pytest.mark.slow
@pytest.mark.parametrize("case, rate", [("3a", 0.03), ("3b", 0.08), ("3a-hard", 0.03),
                                        ("3b-hard", 0.08)])
def test_green_water_false_positives_and_rate(small, case, rate):
    d = small[case]
    over = d.lf > d.threshold
    assert over.sum() >= d.p_exp * d.n_waves  # PAS's pool reaches P_exp
    assert np.any(d.hf[over] == 0)  # false positives above the LF threshold
    measured = np.count_nonzero(d.hf) / d.n_waves
    assert 0.5 * rate < measured < 2.0 * rate
    assert np.all((d.hf == 0) | (d.hf >= 100.0))  # 100 kN noise threshold


@pytest.mark.slow
def test_slamming_outliers(small):
    d = small["4a-hard"]
    pos = d.hf > 0
    assert 0.3 < d.tau < 0.8 and pos.mean() > 0.1
    # timing-driven outliers: events with the same (top-decile) RRV differ in load by > 3x,
    # and the largest load does not come from the largest RRV
    top = pos & (d.lf > np.quantile(d.lf[pos], 0.9))
    assert np.quantile(d.hf[top], 0.95) > 3 * np.quantile(d.hf[top], 0.25)
    assert np.argmax(d.hf) != np.argmax(d.lf)


@pytest.mark.slow
def test_cache_roundtrip(small, cache):
    d = small["3a"]
    file = cache_path("3a", 0, d.scale, cache)
    assert file.exists()
    e = CaseData.load(file)
    np.testing.assert_array_equal(e.hf, d.hf)
    assert e.info == d.info and e.threshold == 12.0


def test_generation_is_seeded():
    a = build_case("2b", scale=0.05)
    b = build_case("2b", scale=0.05)
    c = build_case("2b", seed=1, scale=0.05)
    np.testing.assert_array_equal(a.hf, b.hf)
    assert a.hf.size != c.hf.size or not np.array_equal(a.hf, c.hf)


def test_bad_scale():
    with pytest.raises(ValueError, match="scale"):
        build_case("1a", scale=0.0)
    with pytest.raises(ValueError, match="too few waves"):
        build_case("1a", scale=0.01)


@pytest.mark.slow
def test_cli_reproduce_writes_table_and_figures(tmp_path, monkeypatch, cache, capsys):
    monkeypatch.setenv("PAS_CACHE", str(cache))
    out = tmp_path / "out"
    assert main(["reproduce", "1a", "--scale", "0.1", "--out", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "1a" in text and "PAS" in text and "analogue" in text
    for f in ("table.csv", "runs.csv", "case_1a.png", "metrics.png"):
        assert (out / f).stat().st_size > 0
    import pandas as pd
    t = pd.read_csv(out / "table.csv")
    assert {"truth_mpm", "paper_truth", "predicted_mpm", "hf_samples", "M1", "M2", "M3"} <= set(t)
    assert abs(t.loc[t.strategy == "PAS", "M2"].iloc[0]) < 0.15
    assert main(["reproduce", "7c"]) == 2


# -- impact cases: the hard variants are the first release, bit for bit -----------------------

def _digest(a):
    """sha256 (16 hex) of an array; floats rounded to 9 significant digits first."""
    a = np.asarray(a)
    if a.dtype.kind == "f":
        a = np.array([float(f"{x:.9g}") for x in a])
    return hashlib.sha256(np.ascontiguousarray(a.astype(a.dtype.newbyteorder("<"))).tobytes()
                          ).hexdigest()[:16]


# Produced by the code of commit 287a529 (before the paper-like analogues existed, when these
# data sets had the ids 3a ... 4b): build_case(<id>, seed=0, scale=0.1), then _digest of
# lf, hf, t_start, t_end and of seed_no as int64, and repr(truth_mpm).  The float rounding
# to 9 digits keeps the check independent of last-bit FFT differences between platforms;
# on the machine that recorded them the raw arrays were also compared bit for bit
# (identical at scale 0.1 and 1.0).  The truth MPM is a fit, whose optimiser amplifies
# last-bit differences of libm/BLAS: 3b gave 5336.852321456016 on another machine, 1.6e-9
# relative off, so it is compared to TRUTH_RTOL.
HARD_REFERENCE = {
    "3a": (1824, "98571e8aa27ef7ff", "ee6a29d9b9d6eeb4", "02fdbeae46c56a23", "40ab1c8dabaca156",
           "422cd57ee7ce77c7", 1964.52241391635),
    "3b": (1314, "b1a753656abfcc9d", "54bfeed72c9f95f5", "ebb14fb3ebd84470", "1d4192b70a22c3e5",
           "766e9bb251b734f0", 5336.85231289556),
    "4a": (1869, "d3c5abc94e5c9b62", "3cab17d3303c2359", "18a92542e2a383a0", "9ad61e1d852bb5d3",
           "d2ac4ab1d1e38ca0", 1743.021046164625),
    "4b": (1342, "df0b1de5ad1c1398", "6d68b0e2263fa0cb", "a6108f967a500bb3", "34c2b2c0129724e1",
           "d87e85df92463923", 2126.075199606955),
}


TRUTH_RTOL = 1e-7


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(HARD_REFERENCE))
def test_hard_variants_reproduce_the_first_release(small, case):
    d = small[f"{case}-hard"]
    n, lf, hf, t0, t1, seeds, truth = HARD_REFERENCE[case]
    assert d.scale == 0.1 and d.seed == 0 and d.lf.size == n
    assert (_digest(d.lf), _digest(d.hf), _digest(d.t_start), _digest(d.t_end)) == (lf, hf, t0, t1)
    assert _digest(d.seed_no.astype(np.int64)) == seeds
    assert d.truth_mpm == pytest.approx(truth, rel=TRUTH_RTOL)
    assert d.ids[0].startswith(f"{case}-hard-s000-w")  # documented: the ids carry the new id


@pytest.mark.slow
@pytest.mark.parametrize("case", ["3a", "3b", "4a", "4b"])
def test_paper_like_and_hard_share_waves_and_lf(small, case):
    new, hard = small[case], small[f"{case}-hard"]
    np.testing.assert_array_equal(new.lf, hard.lf)
    np.testing.assert_array_equal(new.t_start, hard.t_start)
    assert not np.array_equal(new.hf, hard.hf)  # only the HF model differs


# -- paper-like impact cases -------------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("case", ["3a", "3b"])
def test_green_water_misses_spread_over_the_lf_range(small, case):
    # Misses (HF = 0 over the 12 m threshold) in every LF tercile, including the top one: a
    # large RWE does not guarantee a load.  Scale 0.1 leaves 40-70 pool events, 13-23 per
    # tercile; with a miss probability near 0.4 a tercile without misses has p < 1e-3.
    d = small[case]
    over = d.lf > d.threshold
    edges = np.quantile(d.lf[over], [0, 1 / 3, 2 / 3, 1])
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = over & (d.lf >= lo) & (d.lf <= hi)
        assert 0.1 < np.mean(d.hf[sel] == 0) < 0.9


def test_green_water_load_of_an_episode_follows_the_documented_formula():
    from pas.validation.case_impacts import COEFFICIENTS as C
    from pas.validation.case_impacts import green_water_load
    t = np.arange(0.0, 8.0, 0.1)
    r = 14.0 * np.sin(np.pi * t / 8.0)
    speed = 2.4
    # median realisation: not deflected (q < 0.5), no impulsive part (p_imp < 0.5), no scatter
    h = r.max() + C["bow_wave"] * speed**2 / (2 * 9.81) - C["freeboard"] - C["gw_margin"]
    expected = C["C_gw"] * 1025.0 * 9.81 * C["accommodation_width"] / 1000.0 * h**2
    assert green_water_load(r, speed=speed) == pytest.approx(expected, rel=1e-12)
    assert green_water_load(r - h - 0.01, speed=speed) == 0.0  # below freeboard + margin
    a = green_water_load(r, speed=speed, rng=np.random.default_rng(5))
    assert a == green_water_load(r, speed=speed, rng=np.random.default_rng(5))
    with pytest.raises(ValueError, match="r_bow"):
        green_water_load([np.nan], speed=speed)


def test_slamming_load_of_an_episode_uses_the_panel_level_speed():
    from pas.validation.case_impacts import COEFFICIENTS as C
    from pas.validation.case_impacts import slamming_load
    dt = 0.01
    t = np.arange(0.0, 8.0, dt)
    r = 9.0 * np.sin(2 * np.pi * (t - 1.0) / 8.0)  # up-crossing at 1 s, 9 m peak at 3 s
    v = 0.5 * np.pi * 9.0 / 2.0 * np.sqrt(1 - (C["panel_height"] / 9.0) ** 2)
    expected = 0.5 * 1025.0 * C["C0"] * np.pi * C["panel_area"] / 1000.0 * v**2 \
        / np.tan(np.deg2rad(C["beta_flare_deg"]))
    no_cut = {"noise_kN": 0.0}  # the median load of this episode is below the 100 kN threshold
    assert slamming_load(r, dt, coefficients=no_cut) == pytest.approx(expected, rel=1e-3)
    assert slamming_load(r, dt) == 0.0
    v_ochi = C["ochi_factor"] * np.sqrt(9.81 * 190.0)
    impulsive = {"u_impulse": 0.0, "e_impulse": 2.0, "z_scatter": 0.0}
    assert slamming_load(r, dt, rng=impulsive, coefficients=no_cut) == pytest.approx(
        expected * (1 + C["slam_impulse"] * v / v_ochi * 2.0), rel=1e-3)
    # the tested-and-rejected velocity gate (cases/README.md): below it, no impulsive part
    gated = dict(no_cut, slam_impulse_gate=1.01 * v / v_ochi)
    assert slamming_load(r, dt, rng=impulsive, coefficients=gated) == pytest.approx(expected,
                                                                                    rel=1e-3)
    assert slamming_load(r, dt, rng=impulsive, coefficients=dict(gated, slam_impulse_gate=(
        0.99 * v / v_ochi))) > 1.5 * expected
    assert slamming_load(np.minimum(r, 2.8), dt, coefficients=no_cut) == 0.0  # panels not reached
    assert slamming_load(r[int(1.5 / dt):], dt, coefficients=no_cut) == 0.0  # no up-crossing
    with pytest.raises(ValueError, match="dt"):
        slamming_load(r, 0.0)


@pytest.mark.slow
@pytest.mark.parametrize("case", ["3a", "4a"])
def test_episode_functions_reproduce_generated_events(small, case):
    # The per-episode HF functions (for design waves) give the generator's HF of an
    # event when fed that event's relative elevation and random inputs.
    from pas.validation import case_impacts as ci
    from pas.validation._common import DT, model_rng, seed_plan, windows
    from pas.validation._impact_signals import OMEGA_MAX_2, impact_sea
    from pas.waves import FERRY_190M, second_order_kernel

    d, spec = small[case], get_case(case)
    n, dur = seed_plan(spec.t_mcs, d.scale)
    sea = impact_sea(spec, 0, 0, dur)
    kern = second_order_kernel(sea, omega_max=OMEGA_MAX_2)
    green = case == "3a"
    x, y = (FERRY_190M.length / 2, 0.0) if green else (FERRY_190M.station_x(19), -9.0)
    lin, nl = ci.relative_elevation_coefficients(sea, kern, x=x, y=y)
    r_lf, r_hf = sea.synthesise(lin, DT)[1], sea.synthesise(nl, DT)[1]
    u = windows(r_lf)[0]
    names = ci._GW_DRAWS if green else ci._SLAM_DRAWS
    draws = ci._draws(model_rng(0, 0, ci._TAG_GW if green else ci._TAG_SLAM), u.size - 1, names)
    hf = d.hf[d.seed_no == 0]
    checked = 0
    for i in range(u.size - 1):
        one = {k: v[i] for k, v in draws.items()}
        if green:
            got = ci.green_water_load(r_hf[u[i]:u[i + 1]], speed=sea.speed, rng=one)
        else:  # the whole record: the rise may start before the event's window
            got = ci.slamming_load(r_hf, DT, window=(u[i], u[i + 1]), rng=one)
        assert got == pytest.approx(hf[i], rel=1e-9, abs=1e-9)
        checked += got > 0
    assert checked >= 3


def test_ln_uniform_sample_and_miss_shares():
    from pas.validation.properties import ln_uniform_sample, miss_shares
    lf = np.arange(1.0, 1001.0)
    s = ln_uniform_sample(lf, threshold=500.0, n=50)
    assert len(set(s)) == 50 and np.all(lf[s] > 500)
    ranks = 1000 - s  # rank 1 = largest
    assert sorted(ranks)[:10] == list(range(1, 11))  # dense at the top, like PAS (§2.5)
    assert ranks.max() == 500
    hf = np.where(lf > 990, 0.0, 1.0)  # the ten largest events are misses
    all_, lnu = miss_shares(lf, hf, threshold=500.0, n=50)
    assert all_ == pytest.approx(10 / 500) and lnu == pytest.approx(10 / 50)


def test_green_water_dependence_is_lower_tail_dominant_unlike_the_hard_variant():
    # λ at q = 0.9 on ~200 pairs has a standard error near 0.1 (about 20 pairs per tail), so
    # the robust check is the contrast on the same waves: the paper-like model has λ_L ≥ λ_U,
    # the hard one λ_U far above λ_L.  (Full scale, 3b had λ_L ≥ λ_U in 10 of 10 data seeds,
    # 3a in 8 of 10: benchmarks/studies/case_properties.py, cases/README.md.)
    new, hard = build_case("3b", scale=0.3), build_case("3b-hard", scale=0.3)
    assert new.lambda_l >= new.lambda_u
    assert (new.lambda_l - new.lambda_u) - (hard.lambda_l - hard.lambda_u) > 0.3


def test_reproduce_of_one_small_case_writes_a_table_that_agrees_with_its_runs(tmp_path):
    # the fast counterpart of the CLI test above: AS on 2b at scale 0.05 (about 1 s)
    from pas.validation.reproduce import format_table, parse_strategies, reproduce

    out = reproduce(["2b"], scale=0.05, strategies=["as"], out=tmp_path, cache=False)
    for name in ("table.csv", "runs.csv", "properties.csv", "case_2b.png", "metrics.png"):
        assert (tmp_path / name).stat().st_size > 0, name
    assert sorted(p.name for p in out["files"]) == sorted(p.name for p in tmp_path.iterdir())
    (run,), (row,) = out["runs"].to_dict("records"), out["table"].to_dict("records")
    data, spec = out["data"]["2b"], get_case("2b")
    assert (row["case"], row["strategy"], row["replications"]) == ("2b", "AS", 1)
    assert row["predicted_mpm"] == run["mpm"] and row["hf_samples"] == run["n_hf"]
    assert run["M1"] == pytest.approx(run["n_hf"] / data.n_waves, rel=1e-12)
    assert row["truth_vs_paper"] == pytest.approx(data.truth_mpm / spec.paper_truth - 1, rel=1e-12)
    assert row["paper_mpm"] == spec.paper_as and row["converged"] in ("0/1", "1/1")
    text = format_table(out["table"])
    assert "2b" in text and "AS" in text and f"{100 * row['M2']:+.2f}%" in text
    with pytest.raises(ValueError, match="strategies: unknown form"):
        parse_strategies("as,form")
