"""Spectra, dispersion and linear realisations against closed forms."""

import numpy as np
import pytest

import pas.waves as W
from pas.stats import wave_crests

OMEGA = np.linspace(1e-3, 20.0, 400_001)


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 7.0])
def test_jonswap_integrates_to_hs_squared_over_16(gamma):
    s = W.jonswap(OMEGA, 10.0, 11.0, gamma=gamma)
    m0 = np.trapezoid(s, OMEGA)
    assert m0 == pytest.approx(10.0**2 / 16.0, rel=2e-6)


def test_jonswap_gamma_one_is_pierson_moskowitz():
    # PM is normalised analytically; JONSWAP numerically: they must agree.
    np.testing.assert_allclose(W.jonswap(OMEGA, 8.1, 9.4, gamma=1.0),
                               W.pierson_moskowitz(OMEGA, 8.1, 9.4), rtol=1e-10, atol=1e-14)


def test_periods_match_dnv_rp_c205_relations():
    # DNV-RP-C205 3.5.5: T1/Tp and Tz/Tp polynomials in gamma; gamma = 3.3 gives
    # T1 = Tp / 1.198 (the paper's Table 2 convention).
    g = 3.3
    s = W.jonswap(OMEGA, 10.0, 11.0, gamma=g)
    t1 = W.mean_period_t1(OMEGA, s)
    tz = W.zero_crossing_period_tz(OMEGA, s)
    assert t1 == pytest.approx(
        11.0 * (0.7303 + 0.04936 * g - 0.006556 * g**2 + 0.0003610 * g**3), rel=3e-3
    )
    assert tz == pytest.approx(
        11.0 * (0.6673 + 0.05037 * g - 0.006230 * g**2 + 0.0003341 * g**3), rel=3e-3
    )
    assert t1 == pytest.approx(9.18, abs=0.02)


@pytest.mark.parametrize("depth", [5.0, 30.0, 179.9, 1000.0])
def test_wave_number_inverts_the_dispersion_relation(depth):
    k = np.geomspace(1e-5, 50.0, 2001)
    omega = np.sqrt(W.GRAVITY * k * np.tanh(k * depth))
    np.testing.assert_allclose(W.wave_number(omega, depth), k, rtol=1e-10)


def test_wave_number_limits():
    w = np.array([0.0, 1e-3, 2.0])
    assert W.wave_number(w, np.inf)[2] == pytest.approx(4.0 / W.GRAVITY, rel=1e-15)
    assert W.wave_number(w, 30.0)[0] == 0.0
    assert W.wave_number(1e-3, 30.0) == pytest.approx(1e-3 / np.sqrt(W.GRAVITY * 30.0), rel=1e-6)
    assert W.wave_number(2.0, 1000.0) == pytest.approx(4.0 / W.GRAVITY, rel=1e-14)
    with pytest.raises(ValueError):
        W.wave_number(-1.0, 30.0)


def _spec(w):
    return W.jonswap(w, 10.0, 11.0)


def test_realised_hs_within_one_percent():
    sea = W.linear_sea(_spec, 3600.0, seed=3, depth=30.0)
    t, eta = sea.elevation(0.1)
    assert t[1] - t[0] == pytest.approx(0.1)
    assert np.var(eta) == pytest.approx(sea.m0, rel=1e-10)  # Parseval over one period
    assert 4.0 * np.sqrt(np.var(eta)) == pytest.approx(10.0, rel=0.01)


def test_phases_depend_on_seed_only():
    a = W.linear_sea(_spec, 600.0, seed=1).amplitude
    b = W.linear_sea(_spec, 600.0, seed=1).amplitude
    c = W.linear_sea(_spec, 600.0, seed=2).amplitude
    np.testing.assert_array_equal(a, b)
    np.testing.assert_allclose(np.abs(a), np.abs(c))
    assert not np.allclose(a, c)


def test_linear_crest_quantile_matches_rayleigh():
    # 20 h of sea: the crest exceeded once per hour on average vs sqrt(2 m0 ln n).
    crests, m0 = [], []
    for seed in range(20):
        sea = W.linear_sea(_spec, 3600.0, seed=seed, depth=30.0)
        crests.append(wave_crests(sea.elevation(0.25)[1])[0])
        m0.append(sea.m0)
    crests = np.concatenate(crests)
    n = crests.size / 20
    ratio = np.quantile(crests, 1.0 - 1.0 / n) / np.sqrt(2.0 * np.mean(m0) * np.log(n))
    assert abs(ratio - 1.0) < 0.03


def test_dt_too_coarse_is_refused():
    sea = W.linear_sea(_spec, 600.0, seed=0)
    with pytest.raises(ValueError, match="Nyquist"):
        sea.elevation(1.0)


def test_period_domain_discretisation():
    s = _spec(OMEGA)
    tz = W.zero_crossing_period_tz(OMEGA, s)
    sea = W.period_domain_sea(_spec, tz, seed=0, depth=30.0)
    periods = 2 * np.pi / sea.omega
    assert sea.omega.size == 100
    np.testing.assert_allclose(np.diff(periods), (2.5 - 0.2) * tz / 100, rtol=1e-9)
    assert periods.min() > 0.2 * tz and periods.max() < 2.5 * tz
    # Band energy = integral of S over [2 pi / 2.5 Tz, 2 pi / 0.2 Tz].
    band = (OMEGA >= 2 * np.pi / (2.5 * tz)) & (OMEGA <= 2 * np.pi / (0.2 * tz))
    assert sea.m0 == pytest.approx(np.trapezoid(s[band], OMEGA[band]), rel=1e-3)
    t = np.arange(0.0, 3600.0, 0.5)
    eta = sea.elevation(t)
    assert np.var(eta) == pytest.approx(sea.m0, rel=0.05)
