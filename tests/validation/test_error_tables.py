"""Error tables of the investigations page, on hand-worked fixtures."""

import pandas as pd
from harness.error_tables import grid_table, has_results, median_worst


def test_median_worst_of_the_absolute_errors():
    # |errors| 0.05, 0.12, 0.30: median 12 %, worst 30 %; one decimal below 10 %
    assert median_worst([0.05, -0.12, 0.30]) == "12 / 30 %"
    assert median_worst([0.031, -0.052, 0.08]) == "5.2 / 8.0 %"
    assert median_worst([0.05, -0.12, 0.30], decimals=1) == "12.0 / 30.0 %"
    assert median_worst([]) == "–"


def test_grid_table_takes_the_results_of_its_row_and_column():
    results = pd.DataFrame({"case": ["3a", "3a", "3a", "4a", "4a"],
                            "setting": ["x", "x", "y", "x", "x"],
                            "error": [0.10, -0.30, 0.02, 0.5, 0.7]})
    table = grid_table(results, "setting", [("x", {"setting": "x"}), ("y", {"setting": "y"})],
                       [("3a", {"case": "3a"}), ("4a", {"case": "4a"})])
    assert table.split("\n") == ["| setting | 3a | 4a |", "|---|---|---|",
                                 "| x | 20 / 30 % | 60 / 70 % |", "| y | 2.0 / 2.0 % | – |"]


def test_has_results_sees_a_value_beside_a_label():
    head = "| setting | 3a |\n|---|---|\n"
    assert has_results(head + "| x | – |\n| y | 2.0 / 2.0 % |")
    assert not has_results(head + "| x | – |\n| y | – |")
    assert not has_results(head.rstrip("\n"))
