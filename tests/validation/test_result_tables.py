"""The writers of the validation tables, on a committed fixture of ``runs.csv`` rows.

The expected rows were worked out by hand from ``tests/data/spread_runs.csv``
(medians of one or two replications), not by the code under test.
"""

from pathlib import Path

import pandas as pd
import pytest
from harness.result_tables import (
    VALIDATION_HEADER,
    properties_seed_table,
    properties_spread_table,
    readme_summary,
    short_pct,
    validation_tables,
    write_between_markers,
)

ROOT = Path(__file__).resolve().parents[2]
RUNS = pd.read_csv(ROOT / "tests" / "data" / "spread_runs.csv")

PAPER_LIKE = """\
| 1a | PAS | 10.74 m | 22.5 | 0.15 % | +1.4 % | -0.4 … +3.2 % | 1.8 % | 3.2 % | +0.2 % | 2/2 |
| 1a | PAS paper preset | 10.7 m | 10 | 0.06 % | +0.3 % | +0.3 … +0.3 % | 0.3 % | 0.3 % | +1.5 % | 1/1 |
| 1a | AS | 10.7 m | 24 | 0.14 % | +0.4 % | +0.4 … +0.4 % | 0.4 % | 0.4 % | +2.0 % | 1/1 |
| 1a | RCW | 10.74 m | 5 | 0.03 % | -18.0 % | -18.4 … -17.6 % | 18.0 % | 18.4 % | -19.6 % | 2/2 |
| 1b | PAS | 10.74 m | 28 | 0.17 % | +1.4 % | +1.4 … +1.4 % | 1.4 % | 1.4 % | -0.2 % | 1/1 |
| 2b | PAS | 9.28e+08 N m | 31 | 0.22 % | -1.5 % | -1.5 … -1.5 % | 1.5 % | 1.5 % | -3.1 % | 0/1 |
| 3a | PAS | 1775 kN | 107 | 0.70 % | +67.3 % | +67.3 … +67.3 % | 67.3 % | 67.3 % | -12.7 % | 1/1 |
| 3a | PAS paper preset | 1775 kN | 96 | 0.63 % | +36.7 % | +36.7 … +36.7 % | 36.7 % | 36.7 % | +40.0 % | 1/1 |
| 3a | AS | 1775 kN | 87 | 0.58 % | +142.6 % | +142.6 … +142.6 % | 142.6 % | 142.6 % | +73.3 % | 1/1 |
| 4a | PAS | 1577 kN | 160 | 1.05 % | +4.9 % | -12.8 … +22.6 % | 17.7 % | 22.6 % | -16.5 % | 0/2 |"""  # noqa: E501

HARD = ("| 3a-hard | PAS | 2124 kN | 54 | 0.36 % | +18.2 % | +18.2 … +18.2 % | 18.2 % | "
        "18.2 % | +20.4 % | 1/1 |")

README = """\
| problems | HF runs (PAS, median) | PAS (defaults) | paper preset | AS |
|---|---|---|---|---|
| known truth, 3 runs | 104 | 5.0 % / 50 % | 20 % / 566 % | – |
| analogues 1a–2b (crests, bending moments) | 22.5–31 | 1.4–1.8 % / 3.2 % | 0.3 % / 0.3 % | 0.4 % / 0.4 % |
| green water 3a, 3b | 107 | 67 % / 67 % | 37 % / 37 % | 143 % / 143 % |
| bow-flare slamming 4a, 4b | 160 (budget) | 18 % / 23 % | – | – |

The reported U95 holds the truth in 67 % of the known-truth runs and 6 of 8 analogue data sets (nominal 95 %)."""  # noqa: E501


def test_validation_tables_give_the_hand_checked_rows():
    tables = validation_tables(RUNS)
    rule = "|---|---|---|---|---|---|---|---|---|---|---|"
    assert tables["paper-like"] == f"{VALIDATION_HEADER}\n{rule}\n{PAPER_LIKE}"
    assert tables["hard"] == f"{VALIDATION_HEADER}\n{rule}\n{HARD}"


def test_validation_tables_keep_the_usual_order_whatever_the_order_of_the_runs():
    shuffled = RUNS.sample(frac=1.0, random_state=3)
    assert validation_tables(shuffled) == validation_tables(RUNS)


def test_readme_summary_gives_the_hand_checked_table():
    defaults = pd.DataFrame({"error": [0.02, -0.05, 0.5], "covered": [True, True, False],
                             "n_hf": [100, 104, 120]})
    paper = pd.DataFrame({"error": [0.1, -0.2, 5.656], "covered": [False] * 3,
                          "n_hf": [90, 95, 99]})
    assert readme_summary(RUNS, defaults, paper) == README


@pytest.mark.parametrize("fraction, text", [(0.043, "4.3"), (0.0995, "10"), (0.146, "15"),
                                            (5.656, "566"), (0.04, "4.0")])
def test_short_pct_keeps_one_decimal_below_ten_percent(fraction, text):
    assert short_pct(fraction) == text


def test_write_between_markers_replaces_only_the_block_and_keeps_the_markers():
    page = "intro\n<!-- BEGIN t a -->\nold\nrows\n<!-- END t a -->\nafter\n"
    assert (write_between_markers(page, {"a": "new"}, "t")
            == "intro\n<!-- BEGIN t a -->\nnew\n<!-- END t a -->\nafter\n")


def test_write_between_markers_names_the_missing_markers():
    with pytest.raises(ValueError, match="<!-- BEGIN t b -->"):
        write_between_markers("no markers here", {"b": "x"}, "t")


def test_the_validation_page_holds_both_tables_between_markers_with_the_writers_header():
    page = (ROOT / "docs" / "results" / "validation.md").read_text(encoding="utf-8")
    for name in ("paper-like", "hard"):
        begin = f"<!-- BEGIN validation_spread.py {name} -->\n"
        assert begin in page and f"<!-- END validation_spread.py {name} -->" in page
        assert page.split(begin)[1].splitlines()[0] == VALIDATION_HEADER


def test_the_readme_summary_sits_between_markers():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = readme.split("<!-- BEGIN validation_spread.py readme-summary -->\n")[1]
    assert block.split("<!-- END validation_spread.py readme-summary -->")[0].startswith(
        "| problems | HF runs (PAS, median) |")


# The measured properties of the twelve analogues (case_properties.py 10, 2026-12-02),
# trimmed to the columns the tables read, six significant digits.
PROPERTIES = pd.read_csv(ROOT / "tests" / "data" / "analogue_properties.csv")


def _block(page: str, tag: str, name: str) -> str:
    return page.split(f"<!-- BEGIN {tag} {name} -->\n")[1].split(f"\n<!-- END {tag} {name} -->")[0]


def test_properties_rows_follow_the_page_formats():
    seed0 = PROPERTIES[PROPERTIES["seed"] == 0]
    rows = properties_seed_table(seed0[seed0["case"].isin(["2a", "3a"])]).splitlines()[2:]
    assert rows == [
        "| 2a | 0.90 | 0.87 / 0.87 | 0 % | 0 % | – | – | 1.093e9 N m | 1.10e9 | −0.6 % | "
        "Student (952) |",
        "| 3a | 0.55 | 0.29 / 0.42 | 43 % | 44 % [45 %] | 2.7 % [3 %] | 0.31 | 1851 kN | 1850 | "
        "+0.1 % | Frank (11) |"]


def test_the_properties_page_is_the_writers_output_on_the_measured_data():
    page = (ROOT / "docs" / "results" / "analogue-properties.md").read_text(encoding="utf-8")
    assert _block(page, "case_properties.py", "seed-0") == properties_seed_table(
        PROPERTIES[PROPERTIES["seed"] == 0])
    assert _block(page, "case_properties.py", "spread") == properties_spread_table(PROPERTIES)


def test_write_between_markers_indents_the_block_as_its_markers():
    page = "- item\n\n  <!-- BEGIN t a -->\n  old\n  <!-- END t a -->\n"
    assert (write_between_markers(page, {"a": "| x |\n\n|---|"}, "t")
            == "- item\n\n  <!-- BEGIN t a -->\n\n  | x |\n\n  |---|\n\n  <!-- END t a -->\n")

