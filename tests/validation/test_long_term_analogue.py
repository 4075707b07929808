"""The long-term analogues: scatter binning, the brute-force truth's combination, the generator."""

import math

import numpy as np
import pandas as pd
import pytest
from harness.long_term_data_sets import p_exceed_of_return_period, pool_data_sets
from scipy.stats import norm

from pas.validation.long_term import (
    generate_cell,
    joint_model,
    long_term_exceedance,
    scatter_diagram,
    tz_over_tp,
    value_at_exceedance_long_term,
)
from pas.validation.long_term_compare import combine_curves
from pas.validation.long_term_data import LongTermData, generate_long_term
from pas.waves.contour import iform_contour


def _two_states():
    """State A: p 0.75, 4 events in 40 s; state B: p 0.25, 2 events in 10 s."""
    table = pd.DataFrame({"name": ["A", "B"], "probability": [0.75, 0.25], "n_waves": [4, 2],
                          "duration": [40.0, 10.0]})
    hf = {"A": np.array([1.0, 2.0, 3.0, 4.0]), "B": np.array([5.0, 10.0])}
    lf = {k: 0.5 * v for k, v in hf.items()}
    return LongTermData("3", table, lf, hf, {k: np.arange(v.size) for k, v in hf.items()},
                        {}, 0, "kN")


def test_two_sea_states_by_hand():
    # w_A = 0.75 * 0.1 = 0.075, w_B = 0.25 * 0.2 = 0.05, sum 0.125
    data = _two_states()
    q = data.exceedance([3.5, 4.5, 7.0, 11.0])
    assert q == pytest.approx([(0.075 * 1 / 4 + 0.05 * 2 / 2) / 0.125, 0.05 / 0.125,
                               0.05 / 2 / 0.125, 0.0], rel=1e-12)
    # sorted descending 10 (Q just below: 0.2), 5 (0.4): p = 0.3 log-linear between them
    f = math.log(0.3 / 0.2) / math.log(0.4 / 0.2)
    assert data.truth(0.3) == pytest.approx(10.0 + f * (5.0 - 10.0), rel=1e-12)
    assert data.truth(0.2) == pytest.approx(10.0, rel=1e-12)
    assert math.isnan(data.truth(0.1))          # beyond the largest event


def test_contributions_of_two_states():
    data = _two_states()
    c = data.contributions(0.55).set_index("sea_state")   # truth 4: A's 4 is not over it
    x = data.truth(0.55)
    assert x == pytest.approx(4.0, rel=1e-12)
    assert c.loc["B", "share"] == pytest.approx(0.05 / 0.125 / 0.55, rel=1e-12)
    assert c.loc["A", "n_exceed"] == 0 and c.loc["A", "share_u95"] > 0


def test_value_rejects_bad_probability():
    with pytest.raises(ValueError, match="p must be"):
        value_at_exceedance_long_term(1.5, {"A": 1.0}, {"A": np.ones(3)})


def test_long_term_exceedance_weights_do_not_need_normalising():
    hf = {"A": np.array([1.0, 3.0]), "B": np.array([2.0])}
    a = long_term_exceedance(1.5, {"A": 2.0, "B": 1.0}, hf)
    b = long_term_exceedance(1.5, {"A": 20.0, "B": 10.0}, hf)
    assert a == pytest.approx(b, rel=1e-12)
    assert a[0] == pytest.approx((2.0 * 0.5 + 1.0 * 1.0) / 3.0, rel=1e-12)


def test_tz_over_tp_dnv():
    # DNV-RP-C205 3.5.5: 0.6673 + 0.05037*3.3 - 0.006230*3.3^2 + 0.0003341*3.3^3
    assert tz_over_tp(3.3) == pytest.approx(0.777683, rel=1e-5)
    assert tz_over_tp(1.0) == pytest.approx(0.7111, rel=1e-3)   # Pierson-Moskowitz, Tz ~ 0.71 Tp


def test_scatter_rows_match_the_weibull_marginal():
    cells, dropped = scatter_diagram(hs_edges=[0.0, 2.0, 4.0], tz_edges=[0.5, 40.0])
    def cdf(h):  # 3-p Weibull of DNV-RP-C205, North Atlantic
        return 1.0 - math.exp(-((h - 0.661) / 3.041) ** 1.484) if h > 0.661 else 0.0
    assert cells["probability"].tolist() == pytest.approx([cdf(2.0), cdf(4.0) - cdf(2.0)],
                                                          rel=1e-6)
    assert dropped["steep"] == 0.0


def test_scatter_default_covers_the_model():
    cells, dropped = scatter_diagram()
    total = cells["probability"].sum() + sum(dropped.values())
    assert total == pytest.approx(1.0, rel=1e-3)
    assert cells["name"].is_unique and (cells["tp"] > cells["tz"]).all()
    assert dropped["steep"] < 0.01


def test_scatter_rejects_bad_edges():
    with pytest.raises(ValueError, match="hs_edges and tz_edges"):
        scatter_diagram(hs_edges=[2.0, 1.0])


def test_joint_model_is_the_dnv_model_on_its_iform_contour():
    # the first contour point (theta = 0) lies at u = (beta, 0): Hs = F^-1(Phi(beta)) of the
    # 3-p Weibull and ln Tz = mu(Hs), the closed forms of DNV-RP-C205 3.6.3
    pts = iform_contour(joint_model(), 100.0, state_duration=3.0, n_points=4)
    beta = pts["beta"][0]
    assert beta == pytest.approx(norm.isf(3.0 / (100.0 * 8766.0)), rel=1e-9)
    hs0 = 0.661 + 3.041 * (-math.log(norm.sf(beta))) ** (1 / 1.484)
    assert pts["hs"][0] == pytest.approx(hs0, rel=1e-9)
    assert pts["tz"][0] == pytest.approx(math.exp(0.70 + 1.27 * hs0 ** 0.131), rel=1e-9)
    # theta = 90 degrees: u = (0, beta), ln Tz = mu + sigma beta at the median Hs
    hs1 = 0.661 + 3.041 * math.log(2.0) ** (1 / 1.484)
    sigma = 0.1334 + 0.0264 * math.exp(-0.1906 * hs1)
    assert pts["tz"][1] == pytest.approx(math.exp(0.70 + 1.27 * hs1 ** 0.131 + sigma * beta),
                                         rel=1e-9)


def test_combine_curves_two_exponentials():
    # Q_s(x) = exp(-x / a_s) on a grid; the combination solved against the closed form
    x = np.linspace(0.0, 30.0, 301)
    curves = {"a": (np.exp(-x / 2.0)[::-1], x[::-1]), "b": (np.exp(-x / 4.0)[::-1], x[::-1])}
    v = combine_curves(1e-3, {"a": 1.0, "b": 3.0}, curves)
    assert (np.exp(-v / 2.0) + 3.0 * np.exp(-v / 4.0)) / 4.0 == pytest.approx(1e-3, rel=1e-4)


_ROW = {"name": "t", "hs": 6.0, "tz": 8.0, "tp": 8.0 / tz_over_tp(3.0)}


def test_cell_shapes_seeds_and_cache(tmp_path):
    a = generate_cell("2", _ROW, 0, 0, 1, path=tmp_path)
    n = a["lf"].size
    assert n > 300 and all(a[k].shape == (n,) for k in ("hf", "seed_no", "t_start", "t_end"))
    assert a["duration"] == pytest.approx(3600.0, rel=1e-12)
    assert len(list(tmp_path.glob("lt2_t_seed0_h1_*.npz"))) == 1
    again = generate_cell("2", _ROW, 0, 0, 1, path=tmp_path)
    assert np.array_equal(a["lf"], again["lf"])                   # read from the cache
    other = generate_cell("2", _ROW, 1, 0, 1, path=tmp_path)      # another data seed
    assert other["lf"].size != n or not np.allclose(other["lf"], a["lf"])
    cell = generate_cell("2", _ROW, 0, 1, 1, cache=False)          # another cell: own waves
    assert cell["lf"].size != n or not np.allclose(cell["lf"], a["lf"])


def test_cell_rejects_bad_arguments(tmp_path):
    with pytest.raises(ValueError, match="analogue"):
        generate_cell("5", _ROW, 0, 0, 1, path=tmp_path)
    with pytest.raises(ValueError, match="hours"):
        generate_cell("2", _ROW, 0, 0, 0, path=tmp_path)


def test_generate_long_term_tiny(tmp_path):
    cells = pd.DataFrame([dict(_ROW, name="lo", probability=0.9),
                          dict(_ROW, name="hi", hs=10.0, probability=0.1)])
    data = generate_long_term("2", seed=0, hours={"lo": 1, "hi": 2}, cells=cells, path=tmp_path)
    t = data.sea_states.set_index("name")
    assert t.loc["hi", "duration"] == pytest.approx(7200.0, rel=1e-12)
    assert t.loc["lo", "n_waves"] == data.lf["lo"].size == data.hf["lo"].size
    assert data.ids["hi"][0].startswith("hi-s000-e")
    class Event:
        sea_state, index = "hi", 3
    assert data.oracle()(Event()) == pytest.approx(data.hf["hi"][3], rel=1e-12)
    # the larger sea state holds the largest loads: the long-term tail comes from it
    c = data.contributions(2e-3).set_index("sea_state")
    assert c.loc["hi", "share"] > c.loc["lo", "share"]
    with pytest.raises(ValueError, match="analogue"):
        generate_long_term("x")


def test_pooled_data_sets_weigh_each_sea_state_by_its_summed_rate():
    # A: 2 events in 2 s per data set (rate 1), B: 2 events in 2/3 s (rate 3), p 0.5 each:
    # w_A = 0.5, w_B = 1.5; each of A's 4 pooled events carries 0.5 / (4 · 2) = 1/16, so
    # Q just below A's second largest (9) is 2/16 and the value at 1/8 is 9 (not 10, the
    # value with the rates left out: 1/8 per event)
    def one(seed, a):
        table = pd.DataFrame({"name": ["A", "B"], "probability": [0.5, 0.5], "n_waves": [2, 2],
                              "duration": [2.0, 2.0 / 3.0], "hours": [1, 1]})
        hf = {"A": np.array(a), "B": np.zeros(2)}
        meta = {k: pd.DataFrame({"seed_no": [0, 1]}) for k in hf}
        return LongTermData("3", table, hf, hf, {k: np.array(["e0", "e1"]) for k in hf}, meta,
                            seed, "kN")

    pooled = pool_data_sets([one(1, [10.0, 9.0]), one(2, [8.0, 7.0])])
    assert pooled.truth(1.0 / 8.0) == pytest.approx(9.0, rel=1e-9)
    assert pooled.sea_states["n_waves"].tolist() == [4, 4]
    assert pooled.sea_states["duration"].tolist() == pytest.approx([4.0, 4.0 / 3.0], rel=1e-9)
    assert list(pooled.ids["A"]) == ["d1-e0", "d1-e1", "d2-e0", "d2-e1"]
    assert len(pooled.meta["B"]) == 4


def test_return_period_exceedance_by_hand():
    # Σ p ν / Σ p = 0.75 · 4/40 + 0.25 · 2/10 = 0.125 encounters per second, 8766 h a year
    p20 = p_exceed_of_return_period(_two_states(), 20)
    assert p20 == pytest.approx(1.0 / (20 * 3600.0 * 8766.0 * 0.125), rel=1e-12)
