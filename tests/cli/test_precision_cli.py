"""``--precision 10%`` on the command line: parsing, the one-line errors, status and progress."""

import argparse
import json
import warnings

import numpy as np
import pandas as pd
import pytest

import pas
from pas import PAS, ModelBand, Stopping
from pas.cli import main
from pas.cli._progress import Progress, precision_text
from pas.cli._stopping_options import precision_option

N = 2000
LF = np.random.default_rng(0).rayleigh(2.0, N)
HF = 1.2 * LF ** 1.1 * np.random.default_rng(1).lognormal(0, 0.2, N)
FAST = PAS(z=5, families=("gaussian", "gumbel"),
           band=ModelBand(n_bootstrap=12, marginals="fitted"))


@pytest.mark.parametrize("text, value", [("10%", 0.1), ("0.1", 0.1), (" 10 % ", 0.1),
                                         ("2.5%", 0.025), ("0.05", 0.05)])
def test_precision_option_reads_fractions_and_percentages(text, value):
    assert precision_option(text) == pytest.approx(value, rel=1e-12)


@pytest.mark.parametrize("text", ["10", "0", "100%", "-5%", "ten", "%", ""])
def test_precision_option_refuses_what_is_not_a_fraction(text):
    with pytest.raises(argparse.ArgumentTypeError, match="such as 10% or 0.1"):
        precision_option(text)


def _cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def files(tmp_path):
    ids = [f"e{i}" for i in range(N)]
    pd.DataFrame({"id": ids, "lf": LF}).to_csv(tmp_path / "lf.csv", index=False)
    pd.DataFrame({"id": ids, "hf": HF}).to_csv(tmp_path / "hf.csv", index=False)
    return tmp_path


def test_run_needs_precision_or_eps1(files, capsys):
    code, _, err = _cli(capsys, "run", files / "lf.csv", "--oracle", f"table:{files / 'hf.csv'}",
                        "--n-waves", N, "--p-exp", 0.01, "--out", files / "out")
    assert code == 2
    line = err.strip().splitlines()[-1]
    assert "--precision" in line and "--eps1" in line and line.startswith("pas")
    assert not (files / "out").exists()
    with pytest.raises(SystemExit) as stop:
        main(["run", str(files / "lf.csv"), "--oracle", f"table:{files / 'hf.csv'}",
              "--n-waves", str(N), "--p-exp", "0.01", "--precision", "10"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "--precision" in err and "10% or 0.1" in err


def test_run_with_precision_prints_the_target_and_the_forecast(files, capsys):
    code, out, err = _cli(capsys, "run", files / "lf.csv", "--oracle",
                          f"table:{files / 'hf.csv'}", "--n-waves", N, "--p-exp", 0.01,
                          "--precision", "20%", "--strategy", "as", "--max-hf", 14, "--seed", 1,
                          "--out", files / "out")
    assert code == 0, err
    assert "(target ±20 %)" in err.splitlines()[-1]
    summary = json.loads((files / "out" / "summary.json").read_text())
    assert summary["settings"]["precision"] == 0.2 and summary["inputs"]["precision"] == 0.2
    assert ("converged: U95 within ±20 %" in out) == summary["converged"]
    if not summary["converged"]:
        assert "against the target ±20 %" in out


def test_progress_line_of_a_precision_study():
    study = pas.make_study(FAST, LF, n_waves=N, p_exp=0.01, seed=1,
                           stopping=Stopping(precision=0.1, k2=5))
    row = {"row": 11, "event_id": "e7", "lf": 5.0, "hf": 6.0, "status": "true_positive",
           "mpm": 9.7, "mpm_low": 9.5, "mpm_high": 9.9, "halfwidth": 0.142,
           "halfwidth_sampling": 0.02, "forecast_hf": 58.6, "forecast_hf_low": 40.2,
           "forecast_hf_high": 95.0, "E_bar": 0.3, "COV": 0.01}
    line = Progress.line(study, row)
    assert "U95 ±14.2 % (target ±10 %), about 59 more HF (40–95)" in line
    assert "eps1" not in line  # no eps1 rule to report
    assert precision_text({"halfwidth_sampling": 0.031}, 0.1) == \
        "sampling part ±3.1 % (target ±10 %)"
    # a failed event refits nothing: its line says the last fit stands, not "no fit yet"
    failed = {"row": 12, "event_id": "e8", "lf": 4.0, "status": "failed", "position": 3,
              "error": "mesh missing"}
    assert "no fit yet" in Progress.line(study, failed)
    study.rows.append(row)
    assert "no refit (the model of the last fit stands)" in Progress.line(study, failed)


def test_status_and_set_of_a_precision_study(tmp_path, capsys):
    db = tmp_path / "s.db"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pas.run_pas(LF, lambda ev: float(HF[ev.index]), n_waves=N, p_exp=0.01, seed=1,
                    max_hf=12, strategy=FAST, stopping=Stopping(precision=0.03, k2=5), study=db)
    code, out, _ = _cli(capsys, "study", "status", db)
    assert code == 0
    line = next(x for x in out.splitlines() if x.startswith("precision target ±3 %"))
    assert "not converged" in line and "against the target ±3 %" in line
    assert "the budget allows 0" in line and "E_bar" not in out
    code, out, _ = _cli(capsys, "study", "status", db, "--json")
    assert json.loads(out)["precision"] == 0.03
    code, out, _ = _cli(capsys, "study", "set", db, "--precision", "5%")
    assert code == 0 and f"{db}: precision 0.03 -> 0.05" in out
    with pytest.raises(SystemExit) as stop:
        main(["study", "set", str(db), "--precision", "1.5"])
    assert stop.value.code == 2 and "--precision" in capsys.readouterr().err


STUDY_TOML = """
n_waves = 2000
p_exp = 0.01
{stop}
[lf]
file = "lf.csv"
column = "lf"
"""


@pytest.mark.parametrize("stop, expected", [('precision = "10%"', 0.1), ("precision = 0.2", 0.2),
                                            ("eps1 = 0.5\nprecision = 0.05", 0.05)])
def test_study_file_takes_precision_as_text_or_number(files, capsys, stop, expected):
    (files / "s.toml").write_text(STUDY_TOML.format(stop=stop))
    code, _, err = _cli(capsys, "study", "create", files / "s.db", "--config", files / "s.toml")
    assert code == 0, err
    assert pas.study.open_study(files / "s.db").rule.precision == expected


@pytest.mark.parametrize("stop, needle", [("", "give eps1 ("),
                                          ('precision = "10"', "s.toml: precision"),
                                          ("precision = 1.5", "precision must be")])
def test_study_file_without_a_valid_stopping_rule_is_refused(files, capsys, stop, needle):
    (files / "s.toml").write_text(STUDY_TOML.format(stop=stop))
    code, _, err = _cli(capsys, "study", "create", files / "s.db", "--config", files / "s.toml")
    assert code == 2 and needle in err.strip().splitlines()[-1]
    assert not (files / "s.db").exists()
