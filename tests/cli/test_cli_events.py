"""``pas events SERIES...``: the written events table, the printed n_waves/p_exp, errors."""

import numpy as np
import pandas as pd

from pas.cli import main


def _sine_cycles(amplitudes, steps):
    """One full sine cycle per wave (``steps`` samples each) after a short trough and before
    half a cycle: up-crossings at the cycle starts, crests ``amplitudes``."""
    lead = -np.sin(np.pi * np.arange(1, 10) / 10)
    waves = [a * np.sin(2 * np.pi * np.arange(n) / n) for a, n in zip(amplitudes, steps)]
    return np.concatenate([lead, *waves, 0.5 * np.sin(np.pi * np.arange(10) / 10)])


def test_pas_events_writes_the_table_and_prints_n_waves_and_p_exp(tmp_path, capsys):
    # seed1: 3 waves of 8, 16, 24 samples at 0.5 s (4, 8, 12 s); seed2 (CSV, time column):
    # 2 waves of 12 and 20 samples (6, 10 s) -> n_waves 5, mean period 8 s, p_exp 8 / 3600
    x1 = _sine_cycles([1.0, 2.0, 3.0], [8, 16, 24])
    x2 = _sine_cycles([0.4, 2.5], [12, 20])
    np.save(tmp_path / "seed1.npy", x1)
    pd.DataFrame({"t": 0.5 * np.arange(x2.size), "rwe": x2}).to_csv(tmp_path / "seed2.csv",
                                                                      index=False)
    out = tmp_path / "events.csv"
    code = main(["events", str(tmp_path / "seed1.npy"), str(tmp_path / "seed2.csv"),
                 "--dt", "0.5", "--threshold", "1.5", "--exposure-hours", "1", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 0
    assert "n_waves 5 " in text and "mean_period 8 s" in text
    assert f"p_exp {8 / 3600:.6g}" in text
    table = pd.read_csv(out)
    assert table["record"].tolist() == ["seed1", "seed1", "seed2"]      # 1.0 and 0.4 cut
    np.testing.assert_allclose(table["lf"], [2.0, 3.0, 2.5])
    np.testing.assert_allclose(table["t_start"], [4.5 + 4.0, 4.5 + 4.0 + 8.0, 4.5 + 6.0])
    assert table["id"].is_unique


def test_pas_events_bad_input_is_one_line_with_exit_code_2(tmp_path, capsys):
    np.save(tmp_path / "a.npy", _sine_cycles([1.0], [8]))
    pd.DataFrame({"t": [0.0, 1.0], "x": [1.0, 2.0], "y": [0.0, 1.0]}).to_csv(
        tmp_path / "b.csv", index=False)
    cases = [([str(tmp_path / "a.npy")], "--dt is missing"),
             ([str(tmp_path / "missing.npy"), "--dt", "1"], "does not exist"),
             ([str(tmp_path / "b.csv")], "--column"),
             ([str(tmp_path / "a.npy"), "--dt", "1", "--exposure-hours", "0"],
              "--exposure-hours must be > 0")]
    for argv, words in cases:
        assert main(["events", *argv, "--out", str(tmp_path / "e.csv")]) == 2
        err = capsys.readouterr().err.strip()
        assert err.startswith("pas events: error:") and words in err and "\n" not in err
