"""``pas long-term``: sea-state table and per-sea-state LF files in, one-line errors."""

import json
import textwrap

import numpy as np
import pandas as pd
import pytest

from pas.cli import main
from pas.cli.long_term import lf_files


@pytest.fixture
def problem(tmp_path):
    """Two sea states, LF peaks per state in lf/<name>.csv, HF = 2 LF + state offset."""
    rng = np.random.default_rng(3)
    rows = []
    (tmp_path / "lf").mkdir()
    for name, p, scale in (("calm", 0.8, 1.0), ("storm", 0.2, 2.0)):
        lf = rng.rayleigh(scale, 3000)
        pd.DataFrame({"id": [f"{name}-{i}" for i in range(lf.size)], "lf": lf,
                      "t0": np.arange(lf.size) * 8.0}).to_csv(tmp_path / "lf" / f"{name}.csv",
                                                              index=False)
        rows.append({"name": name, "probability": p, "n_waves": lf.size,
                     "duration": 8.0 * lf.size, "hs": 2.0 * scale})
    pd.DataFrame(rows).to_csv(tmp_path / "sea_states.csv", index=False)
    (tmp_path / "oracle.py").write_text(textwrap.dedent("""
        def hf(event):
            return 2.0 * event.lf + (1.0 if event.sea_state == "storm" else 0.0)
    """))
    return tmp_path


def _argv(d, *extra):
    return ["long-term", str(d / "sea_states.csv"), "--lf", str(d / "lf"),
            "--oracle", f"python:{d / 'oracle.py'}:hf", *extra]


def test_lf_files_from_folder_and_pattern(problem):
    by_folder = lf_files(problem / "lf", ["calm", "storm"])
    by_pattern = lf_files(str(problem / "lf" / "{name}.csv"), ["calm", "storm"])
    assert by_folder == by_pattern
    assert by_folder["storm"].name == "storm.csv"


def test_missing_lf_file_names_the_option(problem):
    with pytest.raises(ValueError, match=r"--lf .*no LF peak file for sea state\(s\) swell"):
        lf_files(problem / "lf", ["calm", "swell"])
    with pytest.raises(ValueError, match="pattern containing"):
        lf_files(problem / "nowhere", ["calm"])


@pytest.mark.parametrize("extra, message", [
    (["--p-exceed", "2"], "--p-exceed must lie in (0, 1)"),
    (["--return-period", "-1"], "--return-period must be a positive number"),
    (["--p-exceed", "1e-4", "--return-period", "20"], "not allowed with argument"),
    ([], "one of the arguments --p-exceed --return-period is required"),
    (["--p-exceed", "1e-4", "--max-hf", "0"], "expected a positive integer"),
])
def test_bad_options_exit_2_with_one_line(problem, capsys, extra, message):
    try:
        code = main(_argv(problem, *extra))
    except SystemExit as stop:   # argparse's own errors leave through the parser
        code = stop.code
    assert code == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_sea_state_table_without_columns(problem, capsys):
    pd.DataFrame({"name": ["calm"], "probability": [1.0]}).to_csv(problem / "bad.csv",
                                                                   index=False)
    argv = _argv(problem, "--p-exceed", "1e-4")
    argv[1] = str(problem / "bad.csv")
    assert main(argv) == 2
    assert "missing column(s) n_waves, duration" in capsys.readouterr().err


def test_inputs_read_with_ids_and_meta(problem):
    from pas.cli import build_parser
    from pas.cli.long_term import read_inputs

    args = build_parser().parse_args(_argv(problem, "--p-exceed", "1e-4", "--meta-columns", "t0"))
    table, peaks = read_inputs(args)
    assert list(table["name"]) == ["calm", "storm"]
    assert list(peaks["storm"].columns) == ["lf", "id", "t0"]
    assert peaks["storm"]["id"].iloc[2] == "storm-2"


@pytest.mark.slow
def test_end_to_end_writes_summary(problem, capsys):
    out = problem / "out"
    argv = _argv(problem, "--p-exceed", "1e-4", "--max-hf", "60", "--seed", "1",
                 "--out", str(out), "--json")
    assert main(argv) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert (
        summary["study"] == str(out / "long-term.sqlite") and (out / "long-term.sqlite").is_file()
    )
    assert main(argv) == 0   # the same command again: resumed from the store, nothing re-run
    again = json.loads((out / "summary.json").read_text())
    assert again["n_hf"] == summary["n_hf"]
    assert again["value"] == pytest.approx(summary["value"], rel=1e-9)
    assert summary["n_hf"] <= 60 and np.isfinite(summary["value"])
    assert (out / "contributions.csv").is_file()
    # the truth by brute force over the same files: HF = 2 LF (+1 in the storm)
    from pas.validation.long_term import value_at_exceedance_long_term
    table = pd.read_csv(problem / "sea_states.csv")
    hf = {n: 2.0 * pd.read_csv(problem / "lf" / f"{n}.csv")["lf"].to_numpy() + (n == "storm")
          for n in table["name"]}
    w = dict(zip(table["name"], table["probability"] * table["n_waves"] / table["duration"]))
    truth = value_at_exceedance_long_term(1e-4, w, hf)
    assert abs(summary["value"] / truth - 1) < 0.1, (summary, truth)


@pytest.mark.parametrize("cases, message", [
    (["long-term-9"], "unknown long-term case 'long-term-9'; choose from long-term-3, long-term-2"),
    (["long-term-3", "1a"], "give the long-term cases (long-term-3, long-term-2) on their own"),
])
def test_reproduce_long_term_names(capsys, cases, message):
    assert main(["reproduce", *cases]) == 2
    assert message in capsys.readouterr().err


def test_precision_and_figures_reach_the_output(problem):
    out = problem / "out"
    argv = _argv(problem, "--p-exceed", "1e-4", "--max-hf", "16", "--seed", "1", "--no-store",
                 "--precision", "1%", "--figures", "--out", str(out))
    assert main(argv) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["precision"] == 0.01 and summary["converged"] is False
    assert set(summary["forecast"]) >= {"forecast_hf", "out_of_reach", "sampling_halfwidth"}
    history = pd.read_csv(out / "history.csv")
    assert history["n_hf"].iloc[-1] == summary["n_hf"]
    names = sorted(p.name for p in (out / "figures").iterdir())
    # one descriptive column (hs): no allocation plane to draw
    assert names == ["long_term_convergence.png", "long_term_distribution.png"]


def test_unit_reaches_the_figures(problem, monkeypatch):
    from matplotlib.figure import Figure

    labels, save = [], Figure.savefig

    def record(fig, *args, **kwargs):
        labels.extend(ax.get_ylabel() for ax in fig.axes if ax.get_ylabel())
        return save(fig, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", record)
    out = problem / "out"
    argv = _argv(problem, "--p-exceed", "1e-4", "--max-hf", "8", "--seed", "1", "--no-store",
                 "--precision", "10%", "--figures", "--unit", "kN", "--out", str(out))
    assert main(argv) == 0
    assert len(labels) == 2 and all(label.endswith("[kN]") for label in labels)


def test_a_bad_precision_exits_2(problem, capsys):
    with pytest.raises(SystemExit) as stop:
        main(_argv(problem, "--p-exceed", "1e-4", "--precision", "150%"))
    assert stop.value.code == 2
    assert "expected a fraction" in capsys.readouterr().err


def test_a_fresh_output_folder_gives_no_store_warning(problem, capsys):
    """Every sea state opens the analysis's one store after the run created it: that file
    is not 'an existing file that holds no study' (the warning for a copied .sqlite)."""
    out = problem / "fresh"
    assert main(_argv(problem, "--p-exceed", "1e-3", "--max-hf", "12", "--seed", "1",
                      "--out", str(out))) == 0
    assert "holds no study" not in capsys.readouterr().err
