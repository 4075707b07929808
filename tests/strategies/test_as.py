"""Adaptive Screening (AS, paper App. A / Eq. 20) as the GPR comparison strategy.

Truths are computed here from the full synthetic HF set with plain numpy
(sort descending, ``d = k / n_w``, interpolate on ``ln d`` at ``P_exp``),
never from the code under test.
"""

import numpy as np
import pytest

import pas
from pas.strategies.as_ import (
    AS,
    mvpd_score,
    mvpd_select,
    prediction_grid,
    thin_lf_curve,
)

N_W, N, P_EXP = 16_000, 15_000, 2.5e-3


def value_at_p(values, n_waves=N_W, p=P_EXP):
    """Empirical value of a peak set at exceedance probability ``p`` (Eq. 3, 12)."""
    v = np.sort(np.asarray(values, float))[::-1]
    d = np.arange(1, v.size + 1) / n_waves
    return float(np.interp(np.log(p), np.log(d), v))


def g(lf):
    return 1.2 * lf**1.1


@pytest.fixture(scope="module")
def rayleigh():
    return np.random.default_rng(0).rayleigh(1.0, N)


# -- MVPD (Eq. 20) -------------------------------------------------------------

def test_mvpd_score_hand_computed():
    # ln d* − ln P = −2..2: f1 = [−3, 0, 1, 0, −3], f2 = [0, 3, 4, 3, 0] → /4;
    # h = [10, 9, 6, 5, 2] → h̄ = (h − 2)/8 = [1, .875, .5, .375, 0].
    p = 1e-3
    d = p * np.exp([-2.0, -1.0, 0.0, 1.0, 2.0])
    score = mvpd_score(d, [10.0, 9.0, 6.0, 5.0, 2.0], p)
    np.testing.assert_allclose(score, [0.0, 0.65625, 0.5, 0.28125, 0.0])


def test_mvpd_select_picks_nearest_pool_peak_of_best_targets():
    p = 1e-3
    d = p * np.exp([-2.0, -1.0, 0.0, 1.0, 2.0])
    h = [10.0, 9.0, 6.0, 5.0, 2.0]
    # Best target ln P − 1, then ln P, then ln P + 1 (scores above).
    ln_d = np.log(p) + np.array([-3.0, -1.2, -0.9, -0.1, 0.8, 1.5])
    avail = np.ones(ln_d.size, bool)
    assert mvpd_select(ln_d, avail, d, h, p, q=1) == [2]          # |−0.9 − (−1)| = 0.1
    # then target ln P → −0.1 and ln P + 1 → 0.8
    assert mvpd_select(ln_d, avail, d, h, p, q=3) == [2, 3, 4]
    avail[2] = False
    assert mvpd_select(ln_d, avail, d, h, p, q=1) == [1]          # −1.2 is next closest to −1
    assert mvpd_select(ln_d, np.zeros(ln_d.size, bool), d, h, p, q=2) == []


def test_propose_falls_back_to_md_without_prediction(rayleigh):
    lfset = pas.LFSet(rayleigh, n_waves=N_W, p_exp=P_EXP)
    avail = np.ones(lfset.n, bool)
    avail[[0, lfset.n - 1]] = False
    got = AS().propose(lfset.d[[0, lfset.n - 1]], lfset, avail, None, q=1)
    mid = 0.5 * (lfset.ln_d[0] + lfset.ln_d[-1])
    want = int(np.argmin(np.abs(lfset.ln_d - mid)))
    assert got == [want]


# -- building blocks -----------------------------------------------------------

def test_thin_lf_curve_bins_means_on_ln_d():
    x, y = thin_lf_curve([-4.0, -3.0, -1.0, 0.0], [4.0, 3.0, 2.0, 1.0], n_bins=2)
    np.testing.assert_allclose(x, [-3.5, -0.5])
    np.testing.assert_allclose(y, [3.5, 1.5])


def test_prediction_grid_covers_decade_either_side_clipped(rayleigh):
    lfset = pas.LFSet(rayleigh, n_waves=N_W, p_exp=P_EXP)
    grid = prediction_grid(lfset)
    assert grid[0] == pytest.approx(P_EXP / 10) and grid[-1] == pytest.approx(P_EXP * 10)
    assert np.all(np.diff(grid) > 0)
    # P_exp = 4 / n_w: the rare side is clipped at the largest peak's d = 1 / n_w.
    rare = pas.LFSet(rayleigh, n_waves=N_W, p_exp=4 / N_W)
    assert prediction_grid(rare)[0] == pytest.approx(1 / N_W)


@pytest.mark.parametrize("bad", [dict(fidelity="dual"), dict(range_factor=1.5),
                                 dict(n_grid=2), dict(n_lf_bins=0), dict(n_restarts=-1)])
def test_bad_settings_raise(bad):
    with pytest.raises(ValueError):
        AS(**bad)


def test_run_as_names_the_new_place_of_an_as_setting(rayleigh):
    with pytest.raises(TypeError, match=r"fidelity is now strategy=AS\(fidelity=...\)"):
        pas.run_as(rayleigh, lambda ev: ev.lf, n_waves=N_W, p_exp=P_EXP, eps1=0.05,
                   fidelity="single")
    with pytest.raises(TypeError, match=r"strategy must be AS\(...\)"):
        pas.run_as(rayleigh, lambda ev: ev.lf, n_waves=N_W, p_exp=P_EXP, eps1=0.05,
                   strategy=pas.PAS())


# -- end to end ----------------------------------------------------------------

@pytest.mark.parametrize("fidelity", ["multi", "single"])
def test_perfect_indicator_recovers_mapped_mpm(rayleigh, fidelity):
    """HF a strictly increasing function of LF: LF and HF order statistics agree,
    so the order-statistics assumption is exact and the truth is ``g`` of the LF
    distribution at ``P_exp``."""
    truth = value_at_p(g(rayleigh))
    res = pas.run_as(rayleigh, lambda ev: g(ev.lf), n_waves=N_W, p_exp=P_EXP,
                     eps1=0.005 * truth, seed=0, max_hf=60, strategy=AS(fidelity=fidelity))
    assert res.strategy == "as"
    assert res.converged
    assert abs(res.mpm / truth - 1) < 0.03
    assert res.mpm_band[0] <= res.mpm <= res.mpm_band[1]
    assert len(res.pairs) == res.n_hf and res.n_false_positive == 0
    hist = res.history
    assert {"rho", "tau", "kernel"} <= set(hist.columns)
    tp = hist.dropna(subset=["mpm"])
    assert np.all(tp["tau"] > 0.99)  # a monotone map has Kendall τ = 1
    if fidelity == "multi":
        assert np.isfinite(tp["rho"]).all()
    else:
        assert tp["rho"].isna().all()


def test_noisy_indicator_is_biased_non_conservative(rayleigh):
    """HF = g(LF) · lognormal(0, 0.25): the indicator ranks events only roughly.

    The true MPM is the empirical HF value at ``P_exp`` of the full HF set.
    AS gives each HF sample its event's *LF* rank (App. A step 7), so the GPR
    learns ``E[h | LF rank]`` ≈ ``g(l_P) · exp(σ²/2)`` at ``P_exp``: a typical
    HF value of the events with that LF level.  The HF tail is wider than that
    because noise spreads it (the rare HF values come from events the LF ranks
    lower), so AS under-predicts — the non-conservative bias the paper reports
    for AS on weak indicators.  Measured with these seeds: truth 5.80, AS 5.04
    (−13 %, 29 HF), the order-statistics limit 4.91 (−15 %).  We assert the
    sign (< −5 %) and that AS is closer to that limit than to the truth.
    """
    rng = np.random.default_rng(1)
    sigma = 0.25
    hf = g(rayleigh) * rng.lognormal(0.0, sigma, rayleigh.size)
    truth = value_at_p(hf)
    os_limit = value_at_p(g(rayleigh)) * np.exp(sigma**2 / 2)
    res = pas.run_as(rayleigh, lambda ev: hf[ev.index], n_waves=N_W, p_exp=P_EXP,
                     eps1=0.01 * truth, seed=0, max_hf=80)
    err = res.mpm / truth - 1
    assert err < -0.05
    assert abs(res.mpm - os_limit) < 0.5 * abs(truth - os_limit)


def test_false_positives_are_counted_and_dropped(rayleigh):
    """Oracle 0 below LF = 2 (no impact): the lowest initial sample is a false
    positive; it is counted, kept out of the GPR pairs, MD bridges the missing
    prediction, and the MPM (an HF value well above the cut) is still the mapped
    one."""
    truth = value_at_p(g(rayleigh))
    res = pas.run_as(rayleigh, lambda ev: g(ev.lf) if ev.lf > 2.0 else 0.0, n_waves=N_W,
                     p_exp=P_EXP, eps1=0.005 * truth, seed=0, max_hf=60)
    assert res.n_false_positive >= 1
    assert res.n_hf == len(res.pairs) + res.n_false_positive
    assert np.all(res.pairs["hf"] > 0) and np.all(res.pairs["lf"] > 2.0)
    assert abs(res.mpm / truth - 1) < 0.03


def test_batches_are_distinct_and_reproducible(rayleigh):
    def run():
        study = pas.make_study("as", rayleigh, n_waves=N_W, p_exp=P_EXP, eps1=1e-9, seed=3,
                               max_hf=12, stop_on_convergence=False)
        return study.optimize(lambda ev: g(ev.lf), batch_size=3)

    a, b = run(), run()
    ids = a.history["event_index"].tolist()
    assert len(ids) == len(set(ids)) == 12
    assert ids == b.history["event_index"].tolist()
    assert a.mpm == b.mpm
