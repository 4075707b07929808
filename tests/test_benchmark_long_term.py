"""benchmarks/studies/long_term.py: the level and record-length options and the tables that
keep data sets of different record lengths apart.

The fixtures are tiny CSV files in the script's formats; the expected cells are worked out
by hand from them.
"""

import numpy as np
import pandas as pd
import pytest
from _snippets import load_script

SCRIPT = "benchmarks/studies/long_term.py"


def _run_row(seed, method, truth, value, *, p=5e-6, hours=400, n_hf=100, band=(np.nan, np.nan)):
    covered = (band[0] <= truth <= band[1]) if np.isfinite(band[0]) else None
    return {"analogue": 3, "data_seed": seed, "kept_hours": hours, "method": method,
            "p_exceed": p, "truth": truth, "value": value, "error": value / truth - 1.0,
            "band_low": band[0], "band_high": band[1], "covered": covered, "n_hf": n_hf,
            "seconds": 10.0, "note": ""}


def _truth_row(seed, t5, *, hours=400, halves=(1.0, 1.0)):
    row = {"analogue": 3, "data_seed": seed, "kept_hours": hours, "p_exceed": 5e-6,
           "generation_s": 1.0, "hf_events": 1000, "p_20y": 1.2e-8, "truth_20y": np.nan,
           "lf_only_20y": np.nan, "dropped_share": 0.001, "dropped_share_u95": 0.5}
    for p in ("5e-06", "2e-06", "1e-06"):
        row[f"truth_{p}"] = t5
        row[f"half0_{p}"], row[f"half1_{p}"] = t5 * halves[0], t5 * halves[1]
    return row


def _cells(p, hours):
    return pd.DataFrame({"name": ["a", "b"], "kept": [True, False],
                         "share_rayleigh": [0.9, 0.002], "l_min": 12.0, "p_exceed": p,
                         "kept_hours": hours})


@pytest.fixture
def folders(tmp_path):
    """An old folder (100 h at 2e-6, written before the kept_hours and p_exceed columns) and a
    new one (400 h at 5e-6, PAS long-term on data sets 1 and 2, uniform on 1 only)."""
    old, new = tmp_path / "old", tmp_path / "new"
    old.mkdir()
    new.mkdir()
    runs = pd.DataFrame([_run_row(1, "uniform", 100.0, 90.0, p=2e-6, hours=100)])
    runs.drop(columns="kept_hours").to_csv(old / "runs_3.csv", index=False)
    pd.DataFrame([_truth_row(1, 100.0, hours=100)]).drop(
        columns=["kept_hours", "p_exceed"]).to_csv(old / "truth_3.csv", index=False)
    _cells(2e-6, 100).drop(columns=["p_exceed", "kept_hours"]).to_csv(old / "cells_3.csv",
                                                                      index=False)
    pd.DataFrame([_run_row(1, "pas-long-term", 100.0, 110.0, band=(95.0, 130.0)),
                  _run_row(2, "pas-long-term", 200.0, 190.0, band=(180.0, 198.0)),
                  _run_row(1, "uniform", 100.0, 104.0, n_hf=300)]).to_csv(
        new / "runs_3.csv", index=False)
    pd.DataFrame([_truth_row(1, 100.0, halves=(0.9, 1.1)),
                  _truth_row(2, 120.0, halves=(1.0, 1.0))]).to_csv(new / "truth_3.csv",
                                                                   index=False)
    _cells(5e-6, 400).to_csv(new / "cells_3.csv", index=False)
    pd.DataFrame([{"analogue": 3, "kept_hours": 400, "p_exceed": 5e-6, "data_sets": 2,
                   "truth_5e-06": 110.0, "truth_2e-06": 130.0, "truth_1e-06": 150.0}]).to_csv(
        new / "pooled_3.csv", index=False)
    return old, new


def _rows(block):
    return [[c.strip() for c in line.strip("|").split("|")] for line in block.splitlines()[2:]]


def test_the_comparison_holds_the_level_of_the_pas_runs_on_their_common_data_sets(folders):
    blocks = load_script(SCRIPT).tables(list(folders))
    comparison = _rows(blocks["comparison"])
    assert [r[:5] for r in comparison] == [
        ["green water (kN)", "5e-06", "400 h", "pas-long-term", "1"],
        ["green water (kN)", "5e-06", "400 h", "uniform", "1"]]
    assert comparison[0][5] == "10.0 %"          # data set 1 only: 110 / 100 - 1
    every = _rows(blocks["every_run"])
    assert [r[:5] for r in every] == [
        ["green water (kN)", "2e-06", "100 h", "uniform", "1"],
        ["green water (kN)", "5e-06", "400 h", "pas-long-term", "2"],
        ["green water (kN)", "5e-06", "400 h", "uniform", "1"]]
    assert every[1][5:9] == ["7.5 %", "10.0 %", "+2.5 %", "1/2"]   # |+10 %|, |-5 %|; 1 covered


def test_the_record_length_table_uses_each_group_s_own_hours(folders):
    hours = _rows(load_script(SCRIPT).tables(list(folders))["truth_hours"])
    row = next(r for r in hours if r[1] == "400 h" and r[2] == "5e-06")
    # full sets 100 and 120: CV = 14.142 / 110; halves 90, 110, 120, 120: CV = 14.142 / 110
    cv = np.std([100.0, 120.0], ddof=1) / 110.0
    assert row[3] == "2"
    assert row[5] == f"{100 * cv:.1f} %"
    assert row[8] == f"{400 * (cv / 0.02) ** 2:.0f} h"
    assert row[7] == f"{200 * (cv / 0.02) ** 2:.0f} h"     # halves: half the record
    assert any(r[1] == "100 h" for r in hours)


def test_the_cell_plans_of_both_levels_are_listed(folders):
    cells = _rows(load_script(SCRIPT).tables(list(folders))["cells"])
    assert [r[:5] for r in cells] == [["green water (kN)", "2e-06", "100 h", "2", "1"],
                                      ["green water (kN)", "5e-06", "400 h", "2", "1"]]
    assert cells[1][5] == "0.20 %"


@pytest.mark.parametrize(("scale", "hours"), [(1.0, 100), (4.0, 400), (0.01, 4)])
def test_kept_hours_follow_the_scale_as_the_data_set_does(scale, hours):
    plan = pd.DataFrame()
    plan.attrs["pilot_hours"] = 4
    assert load_script(SCRIPT)._kept_hours(plan, scale) == hours


@pytest.mark.parametrize("bad", ["0", "-1e-6"])
def test_a_level_that_is_not_positive_is_refused(bad, capsys):
    with pytest.raises(SystemExit):
        load_script(SCRIPT).main(["run", "3", "--out", "x", f"--p-exceed={bad}"])
    assert "--p-exceed: must be a number > 0" in capsys.readouterr().err


def test_pending_runs_the_seeds_from_first_to_last_that_are_not_done():
    assert load_script(SCRIPT)._pending(3, 6, {1, 2, 4}) == [3, 5, 6]
    assert load_script(SCRIPT)._pending(1, 2, {1, 2}) == []


def test_the_pooled_table_measures_against_the_truth_of_the_data_sets_together(folders):
    rows = _rows(load_script(SCRIPT).tables(list(folders))["pooled"])
    assert [r[:6] for r in rows] == [
        ["green water (kN)", "5e-06", "400 h", "110 (2)", "each data set's own truth", "2"],
        ["green water (kN)", "5e-06", "400 h", "110 (2)", "pas-long-term", "2"],
        ["green water (kN)", "5e-06", "400 h", "110 (2)", "uniform", "1"]]
    assert rows[0][6:8] == ["9.1 %", "9.1 %"]                        # 100 and 120 against 110
    assert rows[0][8] in ("+0.0 %", "-0.0 %")
    assert rows[1][6:] == ["36.4 %", "72.7 %", "+36.4 %", "1/2"]     # 110 and 190; 95…130 holds it
    assert rows[2][6:] == ["5.5 %", "5.5 %", "-5.5 %", "–"]          # 104, no band


def test_without_a_pooled_file_there_is_no_pooled_block(folders):
    (folders[1] / "pooled_3.csv").unlink()
    assert "pooled" not in load_script(SCRIPT).tables(list(folders))
