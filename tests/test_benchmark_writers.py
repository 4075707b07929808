"""The ``--write`` paths of the scripts that write docs/results/precision.md and
investigations.md, run in process on small fixtures against copies of the pages.

Expected rows are worked out by hand from the fixtures; the precision page is
checked against the recorded runs it was written from
(``tests/data/precision_runs.csv``, ``precision_heldout_runs.csv`` and the ten-set runs
``precision_measured_runs.csv`` and ``precision_measured_5_20_runs.csv``, the runs of
2026-12-02).
"""

import re
import shutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from _snippets import load_script

ROOT = Path(__file__).resolve().parents[1]
INVESTIGATIONS = ROOT / "docs" / "results" / "investigations.md"
PRECISION = ROOT / "docs" / "results" / "precision.md"


def _outside(text: str, tag: str) -> str:
    return re.sub(rf"<!-- BEGIN {tag} (\S+) -->\n.*?<!-- END {tag} \1 -->", "", text,
                  flags=re.DOTALL)


def _copy(page: Path, tmp_path) -> Path:
    copy = tmp_path / page.name
    shutil.copy(page, copy)
    return copy


def _write_investigations(tmp_path, script: str, csv: str) -> str:
    """The investigations page as ``script --write`` rewrites a copy of it from the results
    ``csv``, checked to differ only between the script's markers."""
    copy = _copy(INVESTIGATIONS, tmp_path)
    load_script(script).main(["--write", str(copy), "--from-csv", csv])
    return _written(tmp_path, INVESTIGATIONS, Path(script).name)


def _written(tmp_path, page: Path, tag: str) -> str:
    """The copy's text, checked to differ from the page only between ``tag``'s markers."""
    new = (tmp_path / page.name).read_text(encoding="utf-8")
    assert _outside(new, tag) == _outside(page.read_text(encoding="utf-8"), tag)
    return new


@pytest.mark.parametrize("runs, section, pool", [
    ("precision_runs.csv", "summary", []), ("precision_heldout_runs.csv", "held-out", []),
    ("precision_measured_runs.csv", "measured-10", ["--pool-groups"]),
    ("precision_measured_5_20_runs.csv", "measured-5-20", ["--pool-groups"])])
def test_precision_write_from_the_recorded_runs_gives_the_page_as_it_stands(tmp_path, runs,
                                                                          section, pool):
    copy = _copy(PRECISION, tmp_path)
    begin = f"<!-- BEGIN precision_stop.py {section} -->\n"
    text = copy.read_text(encoding="utf-8")
    head, rest = text.split(begin)
    copy.write_text(head + begin + rest[rest.index("<!-- END"):], encoding="utf-8")  # emptied
    load_script("benchmarks/studies/precision_stop.py").main(
        ["--from-csv", str(ROOT / "tests" / "data" / runs), "--write", str(copy),
         "--section", section, *pool])
    assert copy.read_text(encoding="utf-8") == PRECISION.read_text(encoding="utf-8")


def test_precision_cost_table_rows():
    script = load_script("benchmarks/studies/precision_stop.py")
    cost = pd.DataFrame({"loop": ["eps1", "precision 0.5"], "cpu_s_per_hf": [0.2, 1.234],
                         "model_bands": [0, 15], "ratio": [1.0, 6.17]})
    assert script.cost_markdown(cost).split("\n")[2:] == ["| eps1 | 0.2 | 0 | 1 |",
                                                          "| precision 0.5 | 1.23 | 15 | 6.17 |"]


def _refits(rows):
    return pd.DataFrame([dict(zip(("case", "mode", "setting", "seed", "error"), r))
                         for r in rows])


def test_final_sample_refits_write_fills_the_three_tables(tmp_path, capsys):
    final = _refits(
        [
            ("3a", "final", "study", 0, 0.10),
            ("3a", "final", "study", 1, -0.50),
            ("3a", "final", "default", 0, 0.04),
            ("3a", "final", "default", 1, 0.06),
        ]
    )
    every = _refits([("4a", "every", "default", 0, -0.3), ("4a", "every", "default", 1, -0.2),
                     ("4a", "every", "hf_marginal=weibull_mixture", 0, 0.123),
                     ("4a", "every", "hf_marginal=weibull_mixture", 1, 0.2)])
    final.to_csv(tmp_path / "final.csv", index=False)
    every.to_csv(tmp_path / "every.csv", index=False)
    page = _write_investigations(tmp_path, "benchmarks/investigations/final_sample_refits.py",
                                 f"{tmp_path / 'final.csv'},{tmp_path / 'every.csv'}")
    # HF marginal: 4a every-event mixture |0.123|, |0.2| -> 16 / 20 (two digits)
    assert "| Weibull mixture, every event told | – | – | 16 / 20 % | – |" in page
    # settings: the studies |0.1|, |0.5| -> 30 / 50; the default refitted 0.04, 0.06 -> 5.0 / 6.0
    assert "| PAS's studies themselves (not refitted) | 30 / 50 % | – |" in page
    assert "| default, refitted | 5.0 / 6.0 % | – |" in page
    assert "| Weibull (default), every event told | – | – | 25 / 30 % | – |" in page


def test_final_sample_refits_write_needs_the_saved_runs(capsys):
    with pytest.raises(SystemExit):
        load_script("benchmarks/investigations/final_sample_refits.py").main(["--write"])
    assert "--from-csv" in capsys.readouterr().err


def test_stop_movement_write_fills_its_table(tmp_path):
    row = dict(case="4a", k=104, eps1_rel=0.0131, pas_move20=0.099, pas_move20_min=0.054,
               pas_move20_max=0.167, pas_stopped=0, pas_max_hf=160, law_move20=0.092,
               law_within_eps1=0.0, law_draws=1000, law_error=0.172, lf_move20=0.057,
               lf_within_eps1=0.684, lf_draws=250, lf_error=0.098)
    pd.DataFrame([row, {**row, "case": "3b", "pas_stopped": 3}]).to_csv(tmp_path / "m.csv",
                                                                       index=False)
    page = _write_investigations(tmp_path, "benchmarks/investigations/stop_movement.py",
                                 str(tmp_path / "m.csv"))
    assert ("| 4a (k 104) | 1.3 % | 9.9 % [5.4, 16.7] at 160 HF | 9.2 % | 5.7 % | "
            "0 % of 1000, 68 % of 250 | 17.2 / 9.8 % |") in page
    assert "| 3b (k 104) | 1.3 % | 9.9 % [5.4, 16.7] at its stop or 160 HF |" in page


def test_sampling_reference_write_fills_its_three_tables(tmp_path):
    rows = [dict(case="3a", k=60, reference="pas", tau=0.57, median=0.093, worst=0.673),
            dict(case="3a", k=50, reference="truth-estimator", tau=0.57, median=0.26, p90=0.94,
                 p_all10=0.0),
            dict(case="3a", k=60, reference="truth-estimator", tau=0.57, median=0.22, p90=0.64,
                 p_all10=0.004),
            dict(case="3a", k=50, reference="empirical", tau=0.57, median=0.26, p90=0.55),
            dict(case="3a", k=60, reference="empirical", tau=0.57, median=0.23, p90=0.49),
            dict(case="3a", k=107, reference="pas-random-events", tau=0.57, median=0.137,
                 p90=0.341, p_all10=0.11)]
    # the model references at k 50 (neither PAS's 60 nor the largest k) are left out
    for k, m in ((50, 0.3), (60, 0.213)):
        rows += [dict(case="3a", k=k, reference=ref, tau=0.57, median=m, p_targets=0.5)
                 for ref in ("known law", "gaussian", "gumbel")]
    pd.DataFrame(rows).to_csv(tmp_path / "s.csv", index=False)
    page = _write_investigations(tmp_path, "benchmarks/studies/sampling_reference.py",
                                 str(tmp_path / "s.csv"))
    assert ("| 3a | 50 / 60 | 26 / 22 % · 94 / 64 % | 0.00 / 0.00 | 26 / 23 % · 55 / 49 % | "
            "9.3 / 67 % (60 pairs) |") in page
    assert "| 3a | 13.7 / 34.1 % | 0.11 | 9.3 / 67 % |" in page
    assert ("| 3a | 0.57 | 60 | 21.3 % · 0.50 | 21.3 % · 0.50 | 21.3 % · 0.50 | "
            "9.3 / 67 % |") in page


def test_records_case1_mpm_table():
    script = load_script("benchmarks/investigations/records_case1.py")
    analyses = [SimpleNamespace(mpm_pooled=8.641, mpm_seed_maxima=8.7, mpm_fit=8.616),
                SimpleNamespace(mpm_pooled=10.6, mpm_seed_maxima=10.664, mpm_fit=10.53)]
    table = script.mpm_table(analyses, (("Rayleigh", 8.68), ("Forristall", 10.371)))
    assert table.split("\n")[2:] == ["| linear | 8.64 m | 8.70 m | 8.62 m | Rayleigh 8.68 m |",
                                     ("| second order | 10.60 m | 10.66 m | 10.53 m | "
                                      "Forristall 10.37 m |")]


def test_validation_summary_from_the_spread_fixture():
    """Worked by hand from tests/data/spread_runs.csv: 1a has two PAS runs (|M2| 0.004,
    0.032: median 1.8 %, one covered), 1b and 2b one each, 2a none; 4a two (|M2| 0.128,
    0.226); of the eight PAS runs six hold the truth."""
    from harness.result_tables import validation_summary

    runs = pd.read_csv(ROOT / "tests" / "data" / "spread_runs.csv")
    summary = load_script("benchmarks/studies/validation_spread.py").summarise(runs)
    lines = validation_summary(summary).split("\n")
    assert lines[2] == ("| 1a / 1b / 2a / 2b | 1.8 / 1.4 / – / 1.5 % | 3.2 / 1.4 / – / 1.5 % | "
                        "22.5 / 28 / – / 31 | 2/2 / 1/1 / – / 0/1 | 1/2 / 1/1 / – / 1/1 | "
                        "0.3 / – / – / – % | 0.4 / – / – / – % |")
    assert lines[4] == ("| 4a / 4b | 17.7 / – % | 22.6 / – % | 160 / – | 0 / – of 2 | "
                        "2 / – of 2 | – / – | – / – |")
    assert lines[-1] == ("The U95 of PAS holds the data set's truth in 6 of 8 runs "
                         "(75 %; nominal 95 %).")


def test_a_write_leaves_the_tables_it_has_no_results_for(tmp_path, capsys):
    """Results of one --every-event run fill the HF-marginal table; the estimator-settings
    table (final samples of 3a, 3b) keeps its rows."""
    _refits([("4a", "every", "default", 0, -0.3)]).to_csv(tmp_path / "e.csv", index=False)
    _write_investigations(tmp_path, "benchmarks/investigations/final_sample_refits.py",
                          str(tmp_path / "e.csv"))
    copy = tmp_path / INVESTIGATIONS.name
    tag = "final_sample_refits.py settings"
    block = re.compile(rf"<!-- BEGIN {tag} -->.*?<!-- END {tag} -->", re.DOTALL)
    assert (block.search(copy.read_text(encoding="utf-8")).group()
            == block.search(INVESTIGATIONS.read_text(encoding="utf-8")).group())
    assert "| Weibull (default), every event told | – | – | 30 / 30 % | – |" in copy.read_text(
        encoding="utf-8")
    assert "left as they were" in capsys.readouterr().out


def _history(path, n_hf: int, band_at: int, band, target: float):
    """A kept history: one fit per HF (a pair each), MPM 100, the model band at one fit only,
    the rule holding at the last fit."""
    rows = [{"n_hf": k, "n_pairs": k, "mpm": 100.0, "halfwidth_sampling": 0.01,
             "model_low": band[0] if k == band_at else None,
             "model_high": band[1] if k == band_at else None, "stop": k == n_hf}
            for k in range(1, n_hf + 1)]
    pd.DataFrame(rows).to_csv(path / f"p_1_{target:g}.csv", index=False)


def test_forecast_variants_write_fills_the_variants_table(tmp_path):
    histories = tmp_path / "histories"
    histories.mkdir()
    # stops at 8 HF; halfway (4 HF, 4 pairs) it knew one band, ±40 % at 2 pairs
    _history(histories, 8, 2, (60.0, 140.0), 0.2)
    copy = _copy(PRECISION, tmp_path)
    load_script("benchmarks/investigations/forecast_variants.py").main(
        [str(histories), "--write", str(copy)])
    page = _written(tmp_path, PRECISION, "forecast_variants.py")
    table = page.split("<!-- BEGIN forecast_variants.py variants -->")[1].split("<!-- END")[0]
    rows = {r.split(" | ")[0].strip("| "): r for r in table.strip().splitlines()[2:]}
    # the fit alone needs three bands: no forecast, a miss
    assert rows["fit alone (before)"].startswith("| fit alone (before) | 1 | 0 | 0 % |")
    # b = 1/2 through 0.4 at 2 pairs reaches 0.2 at 8 pairs: 4 more, as needed
    assert rows["b = 1/2, mean"] == ("| b = 1/2, mean | 1 | 1 | 100 % | 100 % | 1.00 | "
                                     "100 % |")
    # the rule needs 20 MPMs: 16 more fits after the 4th, four times what it took here
    assert "| 1 | 1 | 0 % | 0 % | 4.00 |" in rows["shrink 0.2, lowest (adopted) + k2 floor"]


def test_precision_table_counts_a_missing_halfway_forecast_and_pools_the_easy_types():
    script = load_script("benchmarks/studies/precision_stop.py")
    run = {"precision": 0.1, "max_hf": 400, "truth": 100.0, "covered": True, "error": 0.01,
           "halfwidth": 0.08, "seconds": 1.0}
    runs = pd.DataFrame([
        {**run, "problem": "core-a", "converged": True, "n_hf": 30, "forecast_halfway": 12.0,
         "needed_halfway": 10.0, "forecast_halfway_low": 5.0, "forecast_halfway_high": 20.0},
        {**run, "problem": "core-a", "converged": True, "n_hf": 40, "forecast_halfway": np.nan,
         "needed_halfway": np.nan, "forecast_halfway_low": np.nan,
         "forecast_halfway_high": np.nan},
        {**run, "problem": "core-b", "converged": False, "n_hf": 400, "halfwidth": 0.3,
         "forecast_halfway": np.nan, "needed_halfway": np.nan, "forecast_halfway_low": np.nan,
         "forecast_halfway_high": np.nan}])
    rows = script.markdown(script.table(runs, [400])).split("\n")[2:]
    # core-a: both reached, one forecast halfway (12 for 10: within ×1.5, its interval held)
    assert rows[0] == ("| core-a | ±10 % | 400 | 2 | 100 % | 100 % | 100 % | 35 | – | 1 | 50 % | "
                       "1.20 | 100 % |")
    assert rows[2] == ("| copula + Weibull types, pooled | ±10 % | 400 | 3 | 67 % | 100 % | "
                       "100 % | 35 | ±30 % | 1 | 50 % | 1.20 | 100 % |")


def test_long_term_precision_table_counts_by_hand():
    runs = pd.DataFrame({
        "analogue": [2, 2, 2], "p_exceed": 2e-6, "precision": 0.1, "max_hf": 400,
        "reached": [True, True, False], "covered": [True, False, True],
        "error": [0.02, -0.15, 0.01], "n_hf": [40, 60, 400], "halfwidth": [0.08, 0.09, 0.4],
        "floor": [0.05, 0.05, 0.12],
        # halfway: forecast 20 for 20 needed (within x1.5), 50 for 30 (not); none for the third
        "forecast_halfway": [20.0, 50.0, np.nan], "needed_halfway": [20.0, 30.0, np.nan],
        "interval_held": [True, False, None]})
    row = load_script("benchmarks/studies/long_term_precision.py").summary(runs).iloc[0]
    assert row["reached"] == "2/3" and row["U95 holds truth¹"] == "1/2"
    assert row["within ±10 %¹"] == "1/2" and row["median HF¹"] == "50"
    assert row["median \\|error\\|¹"] == "8.5 %"
    assert row["U95 of the others²"] == "±40 %" and row["of it, what HF cannot narrow²"] == "±12 %"
    assert row["halfway forecast within ×1.5¹"] == "1/2" and row["its interval held"] == "1/2"
    assert row["U95 holds truth (all runs)"] == "2/3"


def test_long_term_precision_page_is_written_from_the_recorded_runs(tmp_path):
    """docs/results/long-term.md's precision tables are what the script writes from
    tests/data/long_term_precision_runs.csv (the runs of 2026-12-02); no run that reached its
    target reports a band wider than it."""
    page = ROOT / "docs" / "results" / "long-term.md"
    copy = _copy(page, tmp_path)
    text = copy.read_text(encoding="utf-8")
    for name in ("summary", "at-budget"):  # empty both blocks first
        begin = f"<!-- BEGIN long_term_precision.py {name} -->\n"
        head, rest = text.split(begin)
        text = head + begin + rest[rest.index("<!-- END"):]
    copy.write_text(text, encoding="utf-8")
    runs = ROOT / "tests" / "data" / "long_term_precision_runs.csv"
    load_script("benchmarks/studies/long_term_precision.py").main(
        ["write", str(runs), "--page", str(copy)])
    assert copy.read_text(encoding="utf-8") == page.read_text(encoding="utf-8")
    r = pd.read_csv(runs)
    assert r["reached"].any() and not (r["reached"] & (r["halfwidth"] > r["precision"])).any()


def test_precision_table_pools_held_out_types_and_analogues_and_finds_wide_stops():
    script = load_script("benchmarks/studies/precision_stop.py")
    run = {"precision": 0.1, "max_hf": 400, "truth": 100.0, "covered": True, "error": 0.01,
           "seconds": 1.0, "forecast_halfway": np.nan, "needed_halfway": np.nan,
           "forecast_halfway_low": np.nan, "forecast_halfway_high": np.nan}
    runs = pd.DataFrame([
        {**run, "problem": "ho-a", "converged": True, "n_hf": 30, "halfwidth": 0.08},
        {**run, "problem": "ho2-b", "converged": False, "n_hf": 400, "halfwidth": 0.3},
        {**run, "problem": "analogue-1a", "converged": True, "n_hf": 50, "halfwidth": 0.12},
        {**run, "problem": "analogue-3a", "converged": True, "n_hf": 70, "halfwidth": 0.05,
         "error": -0.2, "covered": False}])
    assert "held-out types, pooled" not in set(script.table(runs, [400])["problem"])
    rows = script.markdown(script.table(runs, [400], pool_groups=True)).split("\n")[-2:]
    assert rows == [("| held-out types, pooled | ±10 % | 400 | 2 | 50 % | 100 % | 100 % | 30 | "
                     "±30 % | 0 | 0 % | – | – |"),
                    ("| analogues, pooled | ±10 % | 400 | 2 | 100 % | 50 % | 50 % | 60 | – | 0 | "
                     "0 % | – | – |")]
    # the 1a stop's band (±12 %) is wider than its target (±10 %); the others are not
    assert list(script.wide_stops(runs)["problem"]) == ["analogue-1a"]


def _fit_runs(rows):
    cols = ("problem", "data_set", "converged", "covered", "error", "misfit_checks")
    return pd.DataFrame([{**dict(zip(cols, r)), "precision": 0.1, "max_hf": 400} for r in rows])


def test_fit_check_paired_counts_by_hand():
    script = load_script("benchmarks/studies/fit_check_paired.py")
    on = _fit_runs([("ho-a", 1, False, False, 0.30, 4),   # held back: its stop is gone
                    ("ho-a", 2, True, True, 0.02, 0),
                    ("ho2-b", 1, True, False, -0.15, 0),
                    ("core-c", 1, True, True, 0.01, 1),   # held back, then stopped later
                    ("analogue-1a", 1, True, True, 0.00, 0)])
    off = on.copy()
    off["misfit_checks"] = 0
    off.loc[0, ["converged", "covered", "error"]] = [True, False, 0.30]
    off.loc[3, ["converged", "covered", "error"]] = [True, True, 0.12]
    table = script.paired(on, off).set_index("group")
    held = table.loc["held-out types"]
    assert (held["studies"], held["reached_off"], held["reached_on"]) == (3, 3, 2)
    assert (held["covered_off"], held["covered_on"], held["within_off"], held["within_on"]) \
        == (1, 1, 1, 1)
    assert (held["held_back"], held["lost_stops"], held["lost_covered"]) == (1, 1, 0)
    core = table.loc["copula + Weibull tuning types"]
    assert (core["reached_off"], core["reached_on"], core["within_off"], core["within_on"],
            core["lost_stops"]) == (1, 1, 0, 1, 0)
    assert list(table.index) == ["held-out types", "copula + Weibull tuning types", "analogues"]
    lines = script.markdown(table.reset_index()).split("\n")
    assert lines[2] == "| held-out types | ±10 % | 3 | 3 → 2 | 1 → 1 | 1 → 1 | 1 | 1 (0) |"


def test_fit_check_paired_copies_the_studies_the_check_never_held_back():
    script = load_script("benchmarks/studies/fit_check_paired.py")
    on = _fit_runs([("ho-a", 1, True, True, 0.02, 0), ("core-c", 3, False, True, 0.05, 0)])
    off = script.run_off(on)  # nothing to run again
    pd.testing.assert_frame_equal(off.drop(columns="fit_check"), on)
    with pytest.raises(ValueError, match="not the same studies"):
        script.paired(on, off.iloc[:1])


def test_fit_check_write_from_the_recorded_runs_gives_the_page_as_it_stands(tmp_path):
    copy = _copy(PRECISION, tmp_path)
    begin = "<!-- BEGIN fit_check_paired.py paired -->\n"
    head, rest = copy.read_text(encoding="utf-8").split(begin)
    copy.write_text(head + begin + rest[rest.index("<!-- END"):], encoding="utf-8")  # emptied
    data = ROOT / "tests" / "data"
    load_script("benchmarks/studies/fit_check_paired.py").main(
        [str(data / "precision_fit_check_on_runs.csv"), "--off",
         str(data / "precision_fit_check_off_runs.csv"), "--write", str(copy)])
    assert copy.read_text(encoding="utf-8") == PRECISION.read_text(encoding="utf-8")


def test_no_recorded_study_stopped_on_a_band_wider_than_its_target():
    data = ROOT / "tests" / "data"
    on = pd.read_csv(data / "precision_fit_check_on_runs.csv")
    off = pd.read_csv(data / "precision_fit_check_off_runs.csv")
    assert (off["misfit_checks"] == 0).all() and (on["misfit_checks"] > 0).sum() == 5
    for runs in (on, off):
        stop = runs[runs["converged"]]
        assert (stop["halfwidth"] <= stop["precision"] * (1 + 1e-12)).all()


def test_a_first_passage_comes_before_the_trend_reaches_the_target():
    script = load_script("benchmarks/investigations/forecast_variants.py")
    n, w = [10, 20, 40], [0.4 / (k / 10) ** 0.5 for k in (10, 20, 40)]  # 0.1 at 160 pairs
    median, low, high = script.first_passage_pairs(n, w, 0.1, 0.0, 40, every=3)
    assert 40 < low <= median < high and median < 160  # noise crosses first
    # a sparser schedule gives fewer chances to fall below: no earlier
    assert script.first_passage_pairs(n, w, 0.1, 0.0, 40, every=12)[0] >= median
    # a target below the part that does not narrow is out of reach
    assert script.first_passage_pairs(n, w, 0.1, 0.15, 40) == (float("inf"),) * 3
