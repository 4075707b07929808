import numpy as np
import pytest

from pas.stats.exceedance import (
    encounter_period,
    exceedance_probabilities,
    mean_period_from_peak_period,
    n_waves_from_duration,
    p_exp_from_duration,
    quantile_exceedance,
    value_at_exceedance,
)


def test_exceedance_normalised_by_encounters():
    d, v = exceedance_probabilities([2.0, 5.0, 1.0, 4.0], n_waves=20)
    np.testing.assert_allclose(d, [0.05, 0.10, 0.15, 0.20])
    np.testing.assert_allclose(v, [5.0, 4.0, 2.0, 1.0])


def test_value_at_exceedance_interpolates_on_log_d():
    d = np.array([0.01, 0.1])
    h = np.array([10.0, 0.0])
    # halfway on ln d between 0.01 and 0.1 is sqrt(0.001)
    assert value_at_exceedance(d, h, np.sqrt(0.001)) == pytest.approx(5.0)


def test_paper_table2_case1_numbers():
    # Table 2: n_w = 50 h / Tp = 16 364 and P_exp = T1 / 1 h with T1 = Tp / 1.198
    assert n_waves_from_duration(50 * 3600, 11.0) == 16364
    t1 = mean_period_from_peak_period(11.0, 3.3)
    assert t1 == pytest.approx(11.0 / 1.198, rel=2e-3)
    assert p_exp_from_duration(3600, t1) == pytest.approx(2.55e-3, rel=3e-3)


def test_encounter_period_eq1_head_seas_shorter():
    # head seas at 5.1 m/s, T = 10 s: Te = T / (1 + 2 pi V / (T g))
    te = encounter_period(10.0, 5.1, 180.0)
    assert te == pytest.approx(10.0 / (1 + 2 * np.pi * 5.1 / (10.0 * 9.81)))
    with pytest.raises(ValueError, match="overtakes"):
        encounter_period(3.0, 20.0, 0.0)


def test_quantile_exceedance_worked_example():
    # van Essen, Scharnke & Seyffert (2023): q = 0.368, M = 35, n_e = 16 113
    assert quantile_exceedance(0.368, 35, 16113) == pytest.approx(2.169e-3, abs=5e-7)
    assert quantile_exceedance(0.9, 35, 16113) == pytest.approx(2.29e-4, abs=5e-7)


@pytest.mark.parametrize("bad", [0, -3, 2.5, "x", None, True])
def test_bad_n_waves(bad):
    with pytest.raises(ValueError, match="n_waves"):
        exceedance_probabilities([1.0, 2.0], n_waves=bad)


def test_the_mpm_from_the_top_order_statistics_is_that_of_the_whole_distribution():
    from pas.stats.exceedance import mean_top_order_statistics, mpm_of_realisations
    from pas.strategies.steps import hf_distribution

    rng = np.random.default_rng(3)
    draws = rng.weibull(1.3, size=(10, 5000)) * np.where(rng.uniform(size=(10, 5000)) < 0.1, 0, 1)
    for n_waves, p in ((6000, 2.55e-3), (6000, 1e-5), (5200, 0.9), (5000, 1.0)):
        d, mean, _, _ = hf_distribution(draws, n_waves)
        whole = value_at_exceedance(d, mean, p)
        assert mpm_of_realisations(draws, n_waves, p) == pytest.approx(whole, rel=1e-12)
    np.testing.assert_allclose(mean_top_order_statistics(draws, 40),
                               hf_distribution(draws, 6000)[1][:40], rtol=1e-12)
