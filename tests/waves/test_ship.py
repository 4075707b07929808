"""Closed-form ship responses and encounter-frequency bookkeeping."""

import numpy as np
import pytest

import pas.waves as W

SHIP = W.FERRY_190M
CONDITIONS = {"B": (5.1, 180.0), "Heavy": (np.hypot(2.4, 0.4), 150.0), "none": (0.0, 180.0)}


@pytest.mark.parametrize("speed,heading", list(CONDITIONS.values()))
def test_long_waves_heave_one_pitch_wave_slope(speed, heading):
    w = np.array([0.01, 0.02])
    r = W.ship_rao(SHIP, w, speed=speed, heading=heading)
    np.testing.assert_allclose(r.heave, 1.0, atol=2e-3)
    slope = -1j * (-(w**2) / W.GRAVITY * np.cos(np.deg2rad(heading)))  # -i q, bow down positive
    np.testing.assert_allclose(r.pitch / slope, 1.0, atol=2e-3)


@pytest.mark.parametrize("speed,heading", list(CONDITIONS.values()))
def test_vbm_vanishes_for_very_long_and_very_short_waves(speed, heading):
    w = np.linspace(0.005, 6.0, 3000)
    vbm = np.abs(W.ship_rao(SHIP, w, speed=speed, heading=heading).vbm)
    peak = vbm.max()
    assert peak > 1e7
    assert vbm[0] < 1e-4 * peak
    assert vbm[-1] < 1e-6 * peak


def test_zero_speed_vbm_matches_jensen_mansour_without_damping():
    # Where the damping terms A^2/(kB) are small (long waves, zero speed) the
    # model must reduce to the JM2002 closed form
    # rho g B L^2 kappa (1-kT) [1 - cos u - (kL/4) sin u] / (kL)^2, u = kL/2.
    w = np.array([0.12, 0.15])
    k = w**2 / W.GRAVITY
    L, T, B = SHIP.length, SHIP.draught, SHIP.block_coefficient * SHIP.beam
    u = k * L / 2
    jm = 1025 * W.GRAVITY * B * L**2 * np.exp(-k * T) * (1 - k * T) * (
        1 - np.cos(u) - k * L / 4 * np.sin(u)) / (k * L) ** 2
    vbm = W.ship_rao(SHIP, w, speed=0.0, heading=180.0).vbm
    np.testing.assert_allclose(np.abs(vbm), jm, rtol=0.02)


def test_relative_elevation_limits():
    x = SHIP.station_x(19)
    assert x == pytest.approx(0.45 * 190.0)
    r = W.relative_elevation_rao(SHIP, np.array([0.02, 5.0]), x, speed=5.0, heading=150.0)
    assert abs(r[0]) < 0.01       # ship contours very long waves
    assert abs(r[1]) == pytest.approx(1.0, abs=1e-6)  # ship does not move in short waves


def test_mean_encounter_period_table_values():
    # Paper Table 3 T_p,e (rounded to 0.1 s) and Table 2's T1 = Tp / 1.198.
    assert W.mean_encounter_period(10.0, 5.1, 180.0) == pytest.approx(7.5, abs=0.05)
    assert W.mean_encounter_period(9.4, 2.4, 150.0) == pytest.approx(8.2, abs=0.05)
    assert W.mean_encounter_period(10.0, 5.0, 150.0) == pytest.approx(7.8, abs=0.05)
    assert W.mean_encounter_period(11.0 / 1.198, 0.0, 180.0) == pytest.approx(9.18, abs=0.005)
    with pytest.raises(ValueError):
        W.mean_encounter_period(2.0, 10.0, 0.0)


def test_encounter_grid_maps_back_and_keeps_energy():
    spec = lambda w: W.jonswap(w, 13.2, 10.0, gamma=3.0)  # noqa: E731
    still = W.linear_sea(spec, 1800.0, seed=1, depth=1000.0)
    sea = W.linear_sea(spec, 1800.0, seed=1, depth=1000.0, speed=5.1, heading=180.0)
    np.testing.assert_allclose(
        W.encounter_frequency(sea.omega, 5.1, 180.0), sea.omega_e, rtol=1e-12
    )
    assert np.all(np.diff(sea.omega) > 0)
    assert sea.m0 == pytest.approx(still.m0, rel=2e-3)  # S_e d(w_e) = S dw
    # Counted up-crossing period vs Tz,e = 2 pi sqrt(m0 / m2e) with
    # m2e = integral w_e(w)^2 S(w) dw over the same 0-5 rad/s band.
    t, eta = sea.elevation(0.05)
    n_up = np.count_nonzero((eta[:-1] < 0) & (eta[1:] >= 0))
    w = np.linspace(0.01, 5.0, 20000)
    we = w + w**2 * 5.1 / W.GRAVITY
    tze = 2 * np.pi * np.sqrt(np.trapezoid(spec(w), w) / np.trapezoid(we**2 * spec(w), w))
    assert 1800.0 / n_up == pytest.approx(tze, rel=0.05)


def test_ship_responses_share_the_wave_event():
    spec = lambda w: W.jonswap(w, 8.1, 9.4)  # noqa: E731
    sea = W.linear_sea(spec, 600.0, seed=4, depth=179.9, speed=2.43, heading=150.0)
    out = W.ship_responses(sea, SHIP, 0.05)
    x = SHIP.station_x(19)
    eta_x = sea.elevation(0.05, x=x)[1]
    np.testing.assert_allclose(out["rwe_19"], eta_x - (out["heave"] - x * out["pitch"]), atol=1e-10)
    assert np.std(out["rwe_bow"]) > np.std(out["eta"])  # bow motions out of phase add to RWE
