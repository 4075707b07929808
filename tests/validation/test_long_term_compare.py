"""The long-term methods on tiny data sets: LF-only by hand, uniform allocation end to end."""

import numpy as np
import pandas as pd
import pytest

from pas.validation.long_term import tz_over_tp
from pas.validation.long_term_compare import (
    _lf_load,
    _with_thresholds,
    reproduce_long_term,
    run_method,
)
from pas.validation.long_term_data import LongTermData, generate_long_term


def _two_states():
    table = pd.DataFrame({"name": ["A", "B"], "probability": [0.75, 0.25], "n_waves": [4, 2],
                          "duration": [40.0, 10.0]})
    hf = {"A": np.array([1.0, 2.0, 3.0, 4.0]), "B": np.array([5.0, 10.0])}
    return LongTermData("2", table, dict(hf), hf, {k: np.arange(v.size) for k, v in hf.items()},
                        {}, 0, "N m")


def test_lf_only_is_the_truth_when_lf_equals_hf():
    row = run_method(_two_states(), "lf-only", 0.3)
    assert row["value"] == pytest.approx(row["truth"], rel=1e-12)
    assert row["error"] == pytest.approx(0.0, abs=1e-12) and row["n_hf"] == 0


def test_green_water_lf_load_is_the_dam_break_load():
    # 14 m bow RWE + bow wave 2.4^2/(2 g) over the 10.5 m freeboard: C rho g W h^2 (kN)
    h = 14.0 + 2.4**2 / (2 * 9.81) - 10.5
    assert _lf_load("3", [14.0, 5.0]) == pytest.approx([0.1306 * 1.025 * 9.81 * 14.4 * h**2, 0.0],
                                                       rel=1e-9)


def test_unknown_method_and_case():
    with pytest.raises(ValueError, match="method must be one of"):
        run_method(_two_states(), "guess", 0.3)
    with pytest.raises(ValueError, match="unknown long-term case"):
        reproduce_long_term("long-term-5")


@pytest.mark.slow
def test_uniform_allocation_on_two_cells(tmp_path):
    cells = pd.DataFrame([{"name": n, "hs": hs, "tz": 9.0, "tp": 9.0 / tz_over_tp(3.0),
                           "probability": p} for n, hs, p in (("lo", 7.0, 0.8), ("hi", 11.0, 0.2))])
    data = generate_long_term("2", seed=0, hours=3, cells=cells, path=tmp_path)
    p = 5e-4
    row = run_method(data, "uniform", p, max_hf=40)
    assert 0 < row["n_hf"] <= 80 and "studies=2" in row["note"].replace(": ", "=")
    # VBM: HF close to LF; the combined PAS value lies within 10 % of the brute force
    assert abs(row["error"]) < 0.1
    assert row["band_low"] <= row["value"] <= row["band_high"]


def test_pas_long_term_takes_the_case_threshold_where_enough_peaks_exceed_it():
    table = pd.DataFrame({"name": ["calm", "rough"], "probability": [0.5, 0.5],
                          "n_waves": [10, 10], "duration": [100.0, 100.0]})
    lf = {"calm": np.array([13.0, 12.5, 11.0, 3.0]),          # 2 peaks over case 3's 12 m
          "rough": np.array([20.0, 18.0, 15.0, 12.1, 6.0])}  # 4 over it
    data = LongTermData("3", table, lf, lf, {k: np.arange(v.size) for k, v in lf.items()},
                        {}, 0, "kN")
    out = _with_thresholds(data)
    assert np.isnan(out["threshold"].iloc[0]) and out["threshold"].iloc[1] == 12.0
    assert "threshold" not in data.sea_states.columns        # the data set's table unchanged
    assert "threshold" not in _with_thresholds(_two_states()).columns   # case 2: none
