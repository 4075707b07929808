"""Scatter diagrams, joint models through virocon, the IFORM contour and its design sea state."""

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import pas.waves as W


@pytest.fixture(scope="module")
def rec34():
    return W.north_atlantic()


@pytest.fixture(scope="module")
def fitted(rec34):
    return W.fit_joint_model(rec34.sample(4000, seed=11))


def test_north_atlantic_is_the_iacs_table(rec34):
    # IACS Rec. 34: 100 000 observations; Hs 1.5 m / Tz 7.5 s holds 7738 of them.
    assert rec34.probability.shape == (17, 18)
    frame = rec34.to_frame()
    assert frame.loc[1.5, 7.5] == pytest.approx(7738 / 99999.8, rel=1e-9)
    assert rec34.coverage == 1.0


def test_tz_over_tp_against_dnv_and_pierson_moskowitz():
    # Pierson-Moskowitz: Tz = 0.7104 Tp (DNV-RP-C205 3.5.5.4); JONSWAP 3.3:
    # DNV's fit 0.6673 + 0.05037 g - 0.006230 g^2 + 0.0003341 g^3 = 0.7777.
    assert W.tz_over_tp(1.0) == pytest.approx(0.7104, abs=1e-4)
    g = 3.3
    dnv = 0.6673 + 0.05037 * g - 0.006230 * g**2 + 0.0003341 * g**3
    assert W.tz_over_tp(g) == pytest.approx(dnv, rel=2e-3)


def test_wide_and_long_tables_give_the_same_diagram():
    wide = pd.DataFrame([[1.0, 3.0], [0.0, 4.0]], index=[1.0, 2.0], columns=["6", "5"])
    long = pd.DataFrame({"hs": [1, 1, 2, 2], "tp": [5, 6, 5, 6], "count": [3, 1, 4, 0]})
    a = W.ScatterDiagram.from_table(wide, period="tp")
    b = W.ScatterDiagram.from_table(long, period="tp")
    np.testing.assert_allclose(a.probability, b.probability, rtol=1e-12)
    np.testing.assert_allclose(a.period, [5.0, 6.0])
    np.testing.assert_allclose(a.probability, np.array([[3, 1], [4, 0]]) / 8)
    with pytest.raises(ValueError, match="needs columns"):
        W.ScatterDiagram.from_table(long.drop(columns="count"), period="tp")
    with pytest.raises(ValueError, match="non-negative"):
        W.ScatterDiagram.from_table(-wide, period="tp")
    with pytest.raises(ValueError, match="period must be"):
        W.ScatterDiagram.from_table(wide, period="t02")


def test_sea_states_table(rec34):
    ss = rec34.sea_states(speed=5.0)
    assert list(ss.columns) == [
        "name",
        "probability",
        "hs",
        "tp",
        "tz",
        "gamma",
        "heading",
        "speed",
    ]
    assert ss["probability"].sum() == pytest.approx(1.0, rel=1e-12)
    assert ss["name"].is_unique
    np.testing.assert_allclose(ss["tz"] / ss["tp"], W.tz_over_tp(3.3), rtol=1e-12)
    spread = rec34.sea_states(heading={180.0: 3.0, 150.0: 1.0})
    assert len(spread) == 2 * len(ss)
    head = spread[spread["heading"] == 180.0]["probability"].sum()
    assert head == pytest.approx(0.75, rel=1e-12)
    few = rec34.sea_states(min_probability=1e-3)
    assert len(few) < len(ss) and few["probability"].sum() > 0.98


def test_fitted_dnv_model_binned_back_reproduces_the_table(rec34, fitted):
    edges_h = np.arange(0.0, 18.0)
    edges_t = np.arange(1.0, 20.0)
    binned = W.ScatterDiagram.from_joint_model(fitted, edges_h, edges_t)
    assert binned.coverage == pytest.approx(1.0, abs=2e-3)
    tv = 0.5 * np.abs(binned.probability - rec34.probability).sum()
    assert tv < 0.08  # measured 0.05 with 4000 draws
    mean_hs = lambda sd: float((sd.probability.sum(axis=1) * sd.hs).sum())  # noqa: E731
    assert mean_hs(binned) == pytest.approx(mean_hs(rec34), rel=0.03)


def test_binning_a_weibull_whose_location_lies_inside_the_first_bin():
    # DNV-RP-C205's North-Atlantic model (dnv_joint_model): Hs 3-p Weibull (location 0.661 m,
    # inside the first 2 m bin, where the density has a kink), ln Tz | Hs normal.  Reference:
    # adaptive quadrature of f_Hs(h) [F_T(t1 | h) - F_T(t0 | h)] from the location on.
    from scipy import integrate

    def mu(h):
        return 0.70 + 1.27 * h**0.131

    def sigma(h):
        return 0.1334 + 0.0264 * np.exp(-0.1906 * h)

    model = W.dnv_joint_model(hs_weibull=(3.041, 1.484, 0.661), mu=(0.70, 1.27, 0.131),
                              sigma=(0.1334, 0.0264, -0.1906))
    weibull = stats.weibull_min(1.484, loc=0.661, scale=3.041)
    edges_h, edges_t = np.array([0.0, 2.0, 4.0]), np.array([3.0, 5.0, 7.0, 9.0])
    binned = W.ScatterDiagram.from_joint_model(model, edges_h, edges_t)
    for i, (a, b) in enumerate(zip(edges_h[:-1], edges_h[1:])):
        for j, (t0, t1) in enumerate(zip(edges_t[:-1], edges_t[1:])):
            def f(h, t0=t0, t1=t1):
                z = (np.log([t0, t1]) - mu(h)) / sigma(h)
                return weibull.pdf(h) * np.diff(stats.norm.cdf(z))[0]
            exact = integrate.quad(f, max(a, 0.661), b, epsabs=0.0, epsrel=1e-10)[0]
            got = binned.probability[i, j] * binned.coverage
            assert got == pytest.approx(exact, rel=2e-3)


def test_iform_contour_hs_maximum_is_the_marginal_quantile(fitted):
    # On an IFORM contour the largest Hs is where u = (beta, 0): the Hs
    # marginal's quantile Phi(beta), and beta = Phi^-1(1 - alpha).
    contour = W.iform_contour(fitted, 20.0, state_duration=3.0, n_points=360)
    alpha = 3.0 / (20.0 * 365.25 * 24)
    beta = stats.norm.isf(alpha)
    assert contour["beta"].iloc[0] == pytest.approx(beta, rel=1e-9)
    dist = fitted.distributions[0]
    expected = dist.gamma + dist.alpha * (-np.log(stats.norm.sf(beta))) ** (1 / dist.beta)
    assert contour["hs"].max() == pytest.approx(expected, rel=1e-4)


def test_design_sea_state_is_the_contour_maximum():
    contour = pd.DataFrame(
        {"name": ["a", "b", "c"], "hs": [4.0, 9.0, 6.0], "tp": [8.0, 12.0, 15.0]}
    )
    design, table = W.design_sea_state(contour, lambda r: r["hs"] * 10 - r["tp"])
    assert design["name"] == "b"
    np.testing.assert_allclose(table["value"], [32.0, 78.0, 45.0])
    with pytest.raises(ValueError, match="non-finite"):
        W.design_sea_state(contour, lambda r: np.nan)


def test_linear_design_sea_state_on_the_contour(fitted):
    tf = W.TransferFunction.from_ship(W.FERRY_190M, np.linspace(0.05, 2.5, 120))
    contour = W.iform_contour(fitted, 20.0)
    design, table = W.linear_design_sea_state(contour, tf, "vbm", duration=3 * 3600.0)
    assert design["value"] == table["value"].max()
    # The 0.9 fractile of the 3-hour maximum lies above its MPM.
    d90, _ = W.linear_design_sea_state(contour, tf, "vbm", fractile=0.9)
    assert d90["value"] > design["value"]


@pytest.mark.slow
def test_omae2020_model_fits_and_bins_too(rec34):
    model = W.fit_joint_model(rec34.sample(4000, seed=2), model="OMAE2020")  # ~3 s
    binned = W.ScatterDiagram.from_joint_model(model, np.arange(0.0, 18.0), np.arange(1.0, 20.0))
    assert 0.5 * np.abs(binned.probability - rec34.probability).sum() < 0.1  # measured 0.068


def test_joint_model_input_errors(rec34):
    with pytest.raises(ValueError, match="model must be one of"):
        W.fit_joint_model(rec34.sample(100, seed=1), model="Weibull")
    with pytest.raises(ValueError, match="shape"):
        W.fit_joint_model(np.ones((10, 2)))
    with pytest.raises(ValueError, match="hs_edges"):
        W.ScatterDiagram.from_joint_model(None, [1.0], [1.0, 2.0])
    with pytest.raises(ValueError, match=r"^hs_weibull must be \(scale > 0"):
        W.dnv_joint_model(hs_weibull=(3.0, 0.0, 0.5))
