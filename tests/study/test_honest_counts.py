"""Exit codes scripts can trust and counts that add up, the README's ``pas impacts``
example as written, plain ``--help`` text and a generated case's own run arguments."""

import json
import shlex

import numpy as np
import pandas as pd
import pytest
from _snippets import code_blocks

import pas
from pas.cli import EXIT_CODES, EXIT_FAILED_LEFT_OUT, main
from pas.validation import CaseData

N, NW, P = 400, 500, 0.01


@pytest.fixture(scope="module")
def table_with_gaps(tmp_path_factory):
    """LF peaks and an HF table that lacks the three largest LF events."""
    d = tmp_path_factory.mktemp("gaps")
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(2.0, N)
    ids = np.array([f"e{i}" for i in range(N)])
    pd.DataFrame({"id": ids, "lf": lf}).to_csv(d / "lf.csv", index=False)
    keep = np.argsort(lf)[:-3]
    pd.DataFrame({"id": ids[keep], "hf": 1.2 * lf[keep]}).to_csv(d / "hf.csv", index=False)
    return d


def _run(capsys, folder, *more):
    code = main(["run", str(folder / "lf.csv"), "--oracle", f"table:{folder / 'hf.csv'}",
                 "--n-waves", str(NW), "--p-exp", str(P), "--eps1", "0.1", "--seed", "1",
                 "--max-hf", "4", "--preset", "paper", "--quiet", "--no-store", *map(str, more)])
    return code, *capsys.readouterr()


def test_a_run_that_leaves_failed_events_out_exits_3_and_counts_them(table_with_gaps, tmp_path,
                                                                      capsys):
    code, out, err = _run(capsys, table_with_gaps, "--out", tmp_path / "r")
    s = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert code == EXIT_FAILED_LEFT_OUT == 3
    assert s["n_failed"] >= 1  # the largest LF event is asked first and is missing
    assert s["n_evaluated"] == s["n_loads"] + s["n_no_impact"] + s["n_failed"]
    assert s["n_hf"] == s["n_loads"] + s["n_no_impact"]  # the old keys stay as they were
    assert s["n_false_positive"] == s["n_no_impact"]
    hist = pd.read_csv(tmp_path / "r" / "history.csv")
    assert len(hist) == s["n_evaluated"]
    counts = (f"{s['n_evaluated']} evaluated: {s['n_loads']} loads, {s['n_no_impact']} no impact, "
              f"{s['n_failed']} failed (left out of the fit)")
    assert counts in out and counts in s["summary"]
    assert err.count("HF evaluation failed") == s["n_failed"]


def test_a_run_without_failures_exits_0(table_with_gaps, tmp_path, capsys):
    full = tmp_path / "full"
    full.mkdir()
    lf = pd.read_csv(table_with_gaps / "lf.csv")
    lf.to_csv(full / "lf.csv", index=False)
    lf.assign(hf=1.2 * lf["lf"]).to_csv(full / "hf.csv", index=False)
    code, out, _ = _run(capsys, full, "--out", tmp_path / "r", "--json")
    s = json.loads(out)
    assert code == 0 and s["n_failed"] == 0 and s["n_evaluated"] == s["n_hf"] == 4
    assert "4 evaluated: 4 loads, 0 no impact, 0 failed;" in s["summary"]


def test_exit_codes_are_documented_in_the_help(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    text = capsys.readouterr().out
    assert "exit codes:" in text
    for code in EXIT_CODES:
        assert f"  {code} " in text
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    assert "3 done, but failed HF evaluations were left out" in capsys.readouterr().out


@pytest.mark.parametrize("command", [["impacts"], ["study"], ["run"]])
def test_help_reads_as_plain_text(command, capsys):
    with pytest.raises(SystemExit):
        main([*command, "--help"])
    text = capsys.readouterr().out
    assert "``" not in text and ":mod:" not in text and ":func:" not in text


def test_guide_impacts_example_runs_as_written(tmp_path, monkeypatch, capsys):
    (block,) = code_blocks("docs/guide/records.md", "From the shell: `pas impacts`", "bash")
    rng = np.random.default_rng(3)
    n = 3000  # the table the page describes: t, load (0 = no impact), no seed column
    load = np.where(rng.random(n) < 0.08, 100.0 * rng.weibull(1.5, n), 0.0)
    pd.DataFrame({"t": np.arange(n) * 6.8, "load": load}).to_csv(tmp_path / "EVENTS.csv",
                                                                 index=False)
    monkeypatch.chdir(tmp_path)
    argv = shlex.split(block.strip())
    assert argv[0] == "pas"
    assert main(argv[1:]) == 0, capsys.readouterr().err
    assert (tmp_path / "report" / "fits.csv").exists()
    assert (tmp_path / "report" / "exposure.csv").exists()


def _small_case(n=300, n_waves=200):
    """A generated-case stand-in whose n_w = T_MCS/T_p,e lies below its number of peaks."""
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(2.0, n)
    z = np.zeros(n)
    return CaseData(case="x", lf=lf, hf=1.2 * lf, ids=np.array([f"x-{i}" for i in range(n)]),
                    seed_no=z.astype(int), t_start=z, t_end=z + 10.0, n_waves=n_waves,
                    p_exp=0.02, threshold=None, eps1=0.1, unit="kN", truth_mpm=np.nan,
                    truth_d=z, truth_h=z, tau=np.nan, lambda_u=np.nan, lambda_l=np.nan,
                    seed=0, scale=1.0)


def test_a_generated_case_gives_its_own_run_arguments():
    d = _small_case()
    with pytest.raises(ValueError, match="n_waves_convention='spectral'"):
        pas.run_pas(d.lf_table(), d.oracle(), n_waves=d.n_waves, p_exp=d.p_exp, eps1=d.eps1,
                    seed=1, max_hf=4)
    no_band = pas.PAS(band=pas.ModelBand(n_bootstrap=0))
    res = pas.make_study(no_band, d.lf_table(), **d.run_kwargs(), seed=1, max_hf=4).optimize(
        d.oracle())
    assert res.n_hf == 4 and res.n_waves == d.n_waves
    assert set(res.history["event_id"]) <= set(d.ids)
    table = d.lf_table(meta=True)
    assert len(table) == d.n_events and list(table.columns) == ["lf", "seed", "t_start", "t_end"]
