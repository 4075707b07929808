"""Sharma-Dean second order: closed forms and FFT vs direct double summation."""

import numpy as np
import pytest

import pas.waves as W


def _mono_sea(omega_target, amplitude, depth, duration=200.0):
    """A LinearSea with a single component at the grid frequency nearest omega_target."""
    df = 1.0 / duration
    j = int(round(omega_target / (2 * np.pi * df)))
    n = 4 * j
    amp = np.zeros(n, dtype=complex)
    amp[j] = amplitude
    return W.LinearSea(df=df, amplitude=amp, omega=2 * np.pi * df * np.arange(n), depth=depth), j


def _stokes2(a, k, h):
    if np.isinf(h):
        return 0.5 * k * a**2
    return a**2 * k * np.cosh(k * h) * (2 + np.cosh(2 * k * h)) / (4 * np.sinh(k * h) ** 3)


@pytest.mark.parametrize("depth", [10.0, 30.0, 179.9, np.inf])
def test_monochromatic_wave_is_stokes_second_order(depth):
    a = 1.3 * np.exp(0.4j)
    sea, j = _mono_sea(0.6, a, depth)
    k = sea.wave_number[j]
    c = W.second_order_coefficients(sea, W.second_order_kernel(sea))
    expected = _stokes2(abs(a), k, depth) * np.exp(2 * 0.4j)
    assert c[2 * j] == pytest.approx(expected, rel=1e-10)
    assert np.count_nonzero(np.abs(c) > 1e-14) == 1
    t, eta2 = W.second_order_elevation(sea, 0.05)
    phase = sea.omega[j] * t + 0.4
    np.testing.assert_allclose(eta2, _stokes2(abs(a), k, depth) * np.cos(2 * phase), atol=1e-12)


def test_deep_water_kernels_are_longuet_higgins():
    wn, wm = np.meshgrid(np.linspace(0.2, 4.0, 40), np.linspace(0.25, 3.9, 37))
    lp, lm = W.sharma_dean_kernels(wn, wm, np.inf)
    kn, km = wn**2 / W.GRAVITY, wm**2 / W.GRAVITY
    np.testing.assert_allclose(lp, (kn + km) / 4, rtol=1e-12)
    np.testing.assert_allclose(lm, -np.abs(kn - km) / 4, rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize("depth,omega", [(30.0, 0.57), (30.0, 0.9), (10.0, 0.5)])
def test_group_set_down_tends_to_longuet_higgins_stewart(depth, omega):
    # Bichromatic pair a1, a2 with close frequencies: eta2_diff = 2 a1 a2 L- cos(dpsi)
    # and LHS (1964): mean level = -S_xx / (rho (g h - cg^2)), S_xx = E (2 cg/c - 1/2),
    # E = rho g A^2 / 2 with A^2 = a1^2 + a2^2 + 2 a1 a2 cos(dpsi).
    g = W.GRAVITY
    k = W.wave_number(omega, depth)
    c = omega / k
    cg = 0.5 * c * (1 + 2 * k * depth / np.sinh(2 * k * depth))
    lhs = -g * (2 * cg / c - 0.5) / (g * depth - cg**2)
    _, lm = W.sharma_dean_kernels(omega, omega * (1 + 1e-5), depth)
    assert 2 * lm < 0
    assert 2 * lm == pytest.approx(lhs, rel=1e-3)


def _case_a(duration=600.0, seed=11, **kw):
    return W.linear_sea(lambda w: W.jonswap(w, 10.0, 11.0), duration, seed=seed, depth=30.0, **kw)


@pytest.mark.parametrize("kw", [{}, {"speed": 5.1, "heading": 180.0},
                                {"speed": 2.4, "heading": 150.0}])
def test_fft_equals_direct_double_summation(kw):
    sea = _case_a(**kw)
    kern = W.second_order_kernel(sea)
    x = 40.0 if kw else 0.0
    t, eta2 = W.second_order_elevation(sea, 0.05, kernel=kern, x=x)
    band = slice(kern.j0, kern.j0 + kern.size)
    ref = W.direct_second_order(sea.omega[band], sea.amplitude_at(x)[band], t[:300],
                                depth=sea.depth, omega_e=sea.omega_e[band])
    err = np.max(np.abs(eta2[:300] - ref)) / np.max(np.abs(ref))
    assert err < 1e-8
    assert np.max(np.abs(ref)) > 0.1  # a non-trivial signal was compared


def test_interaction_band_limits_the_pairs():
    sea = _case_a()
    kern = W.second_order_kernel(sea, omega_max=2.0)
    assert sea.omega[kern.j0 + kern.size - 1] <= 2.0 < sea.omega[kern.j0 + kern.size]
    c = W.second_order_coefficients(sea, kern)
    assert c.size == 2 * (kern.j0 + kern.size) - 1


def test_second_order_raises_crests_of_a_steep_sea():
    sea = _case_a(duration=3600.0, seed=2)
    _, eta = sea.elevation(0.1)
    _, eta2 = W.second_order_elevation(sea, 0.1)
    assert abs(np.mean(eta2)) < 1e-12
    # Stokes-type asymmetry: higher crests, positive skewness. (In 30 m the
    # deepest troughs may still deepen: the group set-down lowers them.)
    total = eta + eta2
    assert total.max() > 1.1 * eta.max()
    skew = np.mean(total**3) / np.mean(total**2) ** 1.5
    assert 0.1 < skew < 0.5
