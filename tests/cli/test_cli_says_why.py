"""Small answers that say why: the first ask's size, a [settings] typo, a long-term resume."""

import pytest
from test_cli_long_term import _argv
from test_cli_long_term import problem as problem  # noqa: F401 (fixture)
from test_study_cli import TOML, cli, write_case


def test_first_ask_says_why_it_gives_more_events_than_asked(tmp_path, capsys):
    db = str(tmp_path / "s.db")
    assert cli("study", "create", db, "--config", write_case(tmp_path)) == 0
    capsys.readouterr()
    assert cli("study", "ask", db, "-n", "2", "--format", "csv") == 0
    out, err = capsys.readouterr()
    assert len(out.strip().splitlines()) - 1 == 4  # the initial design: 4 events
    assert "all 4 events of its initial design, more than -n 2" in err
    assert cli("study", "ask", db, "-n", "2", "--format", "csv") == 0
    out, err = capsys.readouterr()
    assert len(out.strip().splitlines()) - 1 <= 2 and "initial design" not in err


def test_a_settings_typo_lists_the_study_settings_too(tmp_path, capsys):
    cfg = write_case(tmp_path, toml=TOML.format(extra="").replace("n_bootstrap = 0", "k3 = 4"))
    assert cli("study", "create", str(tmp_path / "s.db"), "--config", cfg) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "unknown setting 'k3'" in err
    known = err.split("its settings are ", 1)[1].replace(";", ",").replace("and the study's:", "")
    names = {w.strip() for w in known.split(",")}
    assert {"k1", "k2", "n_bootstrap", "stop_measure"} <= names


@pytest.mark.slow
def test_a_long_term_resume_with_another_seed_says_to_use_another_out(problem, capsys):  # noqa: F811
    out = problem / "out"
    assert cli(*_argv(problem, "--p-exceed", "1e-4", "--max-hf", "16", "--seed", "1",
                      "--out", str(out), "--json")) == 0
    capsys.readouterr()
    assert cli(*_argv(problem, "--p-exceed", "1e-4", "--max-hf", "16", "--seed", "2",
                      "--out", str(out))) == 2
    err = capsys.readouterr().err.strip()
    assert "seed differs" in err and "use another --out or --no-store" in err


def test_a_study_past_its_out_of_reach_forecast_says_what_further_hf_are_for():
    import math

    from pas.cli._progress import precision_text
    from pas.study.stop_text import HFForecast, forecast_text

    inf = math.inf
    line = precision_text({"halfwidth": 0.3, "forecast_hf": inf, "forecast_hf_low": inf,
                           "forecast_hf_high": inf}, 0.15)
    assert "not expected to reach ±15 %" in line
    assert line.endswith("the run goes on to its budget: further HF still correct the MPM and "
                         "its band, and the forecast is revised with each band")
    status = forecast_text(HFForecast(inf, inf, inf), 0.1, 17)
    assert "the budget allows 17: further HF still correct the MPM and its band" in status
    assert "further HF" not in forecast_text(HFForecast(inf, inf, inf), 0.1, 0)
    assert "further HF" not in precision_text({"halfwidth": 0.3, "forecast_hf": 40.0,
                                               "forecast_hf_low": 30.0,
                                               "forecast_hf_high": 60.0}, 0.15)
