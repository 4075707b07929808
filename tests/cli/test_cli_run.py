"""``pas run`` and ``pas plot``: files in, result files and figures out, one-line errors."""

import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import pas  # noqa: E402
from pas.cli import main  # noqa: E402
from pas.cli.plot import load_result  # noqa: E402
from pas.study.oracles import TableOracle  # noqa: E402
from pas.study.result import OUTPUT_FILES  # noqa: E402

N, NW, P, EPS1 = 3000, 3200, 3e-3, 0.2
COMMON = ["--n-waves", str(NW), "--p-exp", str(P), "--eps1", str(EPS1), "--seed", "1"]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """LF peaks keyed by event id, HF results of every event in a separate table."""
    d = tmp_path_factory.mktemp("inputs")
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(2.0, N)
    hf = np.where(lf < 1.0, 0.0, 1.2 * lf**1.1 * rng.lognormal(0, 0.08, N))
    ids = [f"ev{i:05d}" for i in range(N)]
    pd.DataFrame({"id": ids, "rwe": lf, "seed": np.arange(N) % 97}).to_csv(
        d / "lf.csv", index=False
    )
    pd.DataFrame({"event": ids, "force": hf}).to_csv(d / "hf.csv", index=False)
    np.save(d / "lf.npy", lf)
    (d / "my_oracle.py").write_text(textwrap.dedent("""\
        import os

        def load(event):
            log = os.environ.get("PAS_TEST_ORACLE_LOG")
            if log:
                with open(log, "a") as f:
                    f.write(f"{event.id}\\n")
            return 1.2 * event.lf ** 1.1
        """))
    return d, lf, hf, ids


def _run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.slow
def test_run_with_table_oracle_writes_everything_and_matches_the_api(files, tmp_path, capsys):
    d, _, _, ids = files
    out = tmp_path / "r1"
    code, stdout, stderr = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe",
                                "--oracle", f"table:{d / 'hf.csv'}:event:force", *COMMON,
                                "--out", out, "--unit", "kN")
    assert code == 0, stderr
    for f in OUTPUT_FILES:
        assert (out / f).exists(), f
    summary = json.loads((out / "summary.json").read_text())
    # the same study through the Python API gives the same answer (the values as read
    # back from the CSV files, which pandas parses to within an ulp)
    lf = pd.read_csv(d / "lf.csv")["rwe"].to_numpy()
    ref = pas.run_pas(pd.DataFrame({"lf": lf}, index=ids),
                      TableOracle(d / "hf.csv", id_column="event", value_column="force"),
                      n_waves=NW, p_exp=P, eps1=EPS1, seed=1)
    assert summary["mpm"] == pytest.approx(ref.mpm, rel=1e-12)
    assert summary["n_hf"] == ref.n_hf and summary["family"] == ref.family
    assert summary["inputs"]["unit"] == "kN" and summary["inputs"]["seed"] == 1
    hist = pd.read_csv(out / "history.csv")
    assert len(hist) == ref.n_hf + ref.n_failed
    assert hist["event_id"].astype(str).tolist() == ref.history["event_id"].astype(str).tolist()
    # progress on stderr: one line per HF result with MPM, E_bar, COV once fitted
    lines = [ln for ln in stderr.splitlines() if ln.startswith("[pas]")]
    assert len(lines) == len(hist)
    assert "MPM" in lines[-1] and "E_bar" in lines[-1] and "COV" in lines[-1]
    assert any("false positive" in ln for ln in lines) == bool(ref.n_false_positive)
    assert ref.summary(unit="kN") in stdout  # --unit reaches the summary
    # the files rebuild the result
    res, s, lf_curve = load_result(out)
    assert res.mpm == pytest.approx(ref.mpm) and res.family == ref.family
    pd.testing.assert_frame_equal(res.distribution, ref.distribution, check_exact=False)
    assert lf_curve[0].size == N and np.all(np.diff(lf_curve[1]) <= 0)
    assert res.range_curves.shape == ref.range_curves.shape


@pytest.mark.slow
def test_run_json_quiet_npy_python_oracle(files, tmp_path, capsys, monkeypatch):
    d, *_ = files
    log = tmp_path / "calls.log"
    monkeypatch.setenv("PAS_TEST_ORACLE_LOG", str(log))
    out = tmp_path / "r2"
    argv = ["run", d / "lf.npy", "--oracle", f"python:{d / 'my_oracle.py'}:load", *COMMON,
            "--out", out, "--quiet", "--json", "--max-hf", "12"]
    code, stdout, stderr = _run(capsys, *argv)
    assert code == 0 and stderr == ""
    summary = json.loads(stdout)
    assert summary["n_hf"] <= 12 and np.isfinite(summary["mpm"])
    n_calls = len(log.read_text().splitlines())
    assert n_calls == summary["n_hf"]
    # run again into the same folder: the study store answers, the oracle is not called again
    code, stdout2, _ = _run(capsys, *argv)
    assert code == 0
    assert json.loads(stdout2)["mpm"] == pytest.approx(summary["mpm"], rel=1e-12)
    assert len(log.read_text().splitlines()) == n_calls
    # a different setting into the same folder is refused, naming the setting (the
    # stopping limits and the budget may change: tests/study/test_store.py)
    argv[argv.index("--p-exp") + 1] = "4e-3"
    code, _, err = _run(capsys, *argv)
    assert code == 2 and "p_exp" in err and "--out" in err and err.count("\n") == 1


def test_python_oracle_by_module_name(files, tmp_path, capsys, monkeypatch):
    d, *_ = files
    monkeypatch.syspath_prepend(str(d))
    code, stdout, stderr = _run(capsys, "run", d / "lf.npy", "--oracle", "python:my_oracle:load",
                                *COMMON, "--out", tmp_path / "r3", "--quiet", "--no-store",
                                "--strategy", "as", "--max-hf", "8")
    assert code == 0, stderr
    assert stdout.startswith("AS: MPM")
    assert not (tmp_path / "r3" / "study.sqlite").exists()


@pytest.mark.slow
def test_command_oracle(files, tmp_path, capsys):
    d, *_ = files
    script = tmp_path / "cfd.py"
    script.write_text(
        "import sys\nlf, seed, out = float(sys.argv[1]), int(sys.argv[2]), sys.argv[3]\n"
        "open(out, 'w').write(str(1.2 * lf ** 1.1))\n"
    )
    out = tmp_path / "r4"
    cmd = f"command:{sys.executable} {script} {{lf}} {{seed}} {{result}}"
    code, stdout, stderr = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe",
                                "--meta-columns", "seed", "--oracle", cmd, *COMMON, "--out", out,
                                "--max-hf", "6", "--quiet", "--no-store")
    assert code == 0, stderr
    hist = pd.read_csv(out / "history.csv")
    assert (hist["status"] == "true_positive").all()
    np.testing.assert_allclose(hist["hf"], 1.2 * hist["lf"] ** 1.1, rtol=1e-12)
    runs = sorted(p.name for p in (out / "hf-runs").iterdir())
    assert runs == sorted(hist["event_id"].astype(str))


@pytest.mark.parametrize("argv, field", [
    (["--lf-column", "nope"], "--lf-column"),
    (["--lf-column", "rwe", "--id-column", "nope"], "--id-column"),
    ([], "--lf-column"),  # lf.csv has several columns and none is called "lf"
])
def test_bad_lf_columns(files, tmp_path, capsys, argv, field):
    d, *_ = files
    code, _, err = _run(capsys, "run", d / "lf.csv", *argv, "--oracle",
                        f"table:{d / 'hf.csv'}:event:force", *COMMON, "--out", tmp_path / "x")
    assert code == 2
    assert err.count("\n") == 1 and err.startswith("pas run: error:") and field in err


@pytest.mark.parametrize("spec, needle", [
    ("nonsense", "--oracle"),
    ("table:{d}/hf.csv", "'id'"),               # default id column is missing
    ("table:{d}/hf.csv:event", "--oracle"),     # id without value column
    ("table:{d}/missing.csv", "missing.csv"),
    ("python:{d}/my_oracle.py:nope", "nope"),
    ("python:no_such_module_xyz:f", "no_such_module_xyz"),
    ("shell:ls", "unknown kind"),
])
def test_bad_oracle_specs(files, tmp_path, capsys, spec, needle):
    d, *_ = files
    code, _, err = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
                        spec.format(d=d), *COMMON, "--out", tmp_path / "x")
    assert code == 2
    assert err.count("\n") == 1 and needle in err


@pytest.mark.parametrize("opt, value, needle", [
    ("--p-exp", "1.5", "--p-exp"),
    ("--p-exp", "1e-9", "--p-exp"),     # below the rarest LF event
    ("--eps1", "-1", "--eps1"),
    ("--threshold", "100", "threshold"),
])
def test_bad_numbers(files, tmp_path, capsys, opt, value, needle):
    d, *_ = files
    opts = {"--n-waves": NW, "--p-exp": P, "--eps1": EPS1, opt: value}
    code, _, err = _run(capsys, "run", d / "lf.npy", "--oracle",
                        f"python:{d / 'my_oracle.py'}:load",
                        *[x for kv in opts.items() for x in kv], "--out", tmp_path / "x")
    assert code == 2 and needle in err and err.count("\n") == 1
    assert not (tmp_path / "x").exists()


def test_missing_lf_file(files, tmp_path, capsys):
    d, *_ = files
    code, _, err = _run(capsys, "run", tmp_path / "none.csv", "--oracle", "table:x.csv", *COMMON)
    assert code == 2 and "LF_FILE" in err


def test_help_has_examples(capsys):
    for cmd in ("run", "plot"):
        with pytest.raises(SystemExit) as exc:
            main([cmd, "--help"])
        assert exc.value.code == 0
        text = capsys.readouterr().out
        assert "examples:" in text and f"pas {cmd} " in text.split("examples:")[1]


@pytest.mark.slow
def test_plot_redraws_from_the_output_folder(files, tmp_path, capsys):
    d, *_ = files
    out = tmp_path / "r5"
    code, _, err = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
                        f"table:{d / 'hf.csv'}:event:force", *COMMON, "--out", out, "--quiet",
                        "--no-store", "--unit", "kN", "--lf-unit", "m")
    assert code == 0, err
    code, stdout, err = _run(capsys, "plot", out, "--kind", "all")
    assert code == 0, err
    written = stdout.split()
    assert sorted(os.path.basename(p) for p in written) == \
        ["aic.png", "distribution.png", "mpm.png", "scatter.png"]
    for p in written:
        assert os.path.getsize(p) > 20_000
    code, stdout, err = _run(capsys, "plot", out, "--kind", "distribution", "--out",
                             tmp_path / "dist.pdf")
    assert code == 0 and (tmp_path / "dist.pdf").stat().st_size > 5_000
    code, stdout, err = _run(capsys, "plot", out, "--kind", "mpm", "--truth", "10.5")
    assert code == 0 and (out / "mpm.png").exists()
    # errors: not a run folder, bad extension
    code, _, err = _run(capsys, "plot", tmp_path, "--kind", "mpm")
    assert code == 2 and "summary.json" in err and err.count("\n") == 1
    code, _, err = _run(capsys, "plot", out, "--out", tmp_path / "fig.txt")
    assert code == 2 and "--out" in err


@pytest.mark.slow
def test_one_u95_in_summary_json_status_and_figure(files, tmp_path, capsys):
    d, *_ = files
    out = tmp_path / "u95"
    code, stdout, stderr = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
                                f"table:{d / 'hf.csv'}:event:force", *COMMON, "--out", out,
                                "--unit", "kN", "--max-hf", "14")
    assert code == 0, stderr
    summary = json.loads((out / "summary.json").read_text())
    (lo, hi), (s_lo, s_hi) = summary["mpm_band"], summary["mpm_band_sampling"]
    m_lo, m_hi = summary["mpm_band_model"]
    assert (lo, hi) == (min(s_lo, m_lo), max(s_hi, m_hi))  # the union of the two parts
    text = (f"U95 {lo:.4g}–{hi:.4g} kN (sampling part {s_lo:.4g}–{s_hi:.4g}, "
            f"model part {m_lo:.4g}–{m_hi:.4g})")
    assert text in stdout and text in summary["summary"]
    # the progress lines show the sampling part per iteration and call it that
    progress = [ln for ln in stderr.splitlines() if ln.startswith("[pas]")]
    assert "U95" not in stderr
    assert f"(sampling band {s_lo:.4g}–{s_hi:.4g})" in [ln for ln in progress if "MPM" in ln][-1]
    # pas study status reports the same band, rebuilt from the store
    assert main(["study", "status", str(out / "study.sqlite"), "--json"]) == 0
    status = json.loads(capsys.readouterr().out)
    for key in ("mpm", "mpm_band", "mpm_band_sampling", "mpm_band_model"):
        assert status[key] == summary[key], key
    assert main(["study", "status", str(out / "study.sqlite")]) == 0
    assert text.replace(" kN", "") in capsys.readouterr().out
    # the distribution figure puts that U95 on the MPM marker
    assert main(["plot", str(out), "--kind", "distribution"]) == 0
    capsys.readouterr()
    import matplotlib.pyplot as plt

    from pas.plotting import plot_distribution

    fig, ax = plot_distribution(load_result(out)[0], unit="kN")
    assert any(f"U95 {lo:.4g}–{hi:.4g}" in t.get_text() for t in ax.get_legend().get_texts())
    plt.close(fig)


@pytest.mark.slow
def test_failed_evaluations_give_one_stderr_line_each_even_quiet(files, tmp_path, capsys):
    d, lf, hf, ids = files
    top = int(np.argmax(lf))
    table = pd.read_csv(d / "hf.csv")
    table[table["event"] != ids[top]].to_csv(tmp_path / "hf.csv", index=False)  # row missing
    argv = ["run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
            f"table:{tmp_path / 'hf.csv'}:event:force", *COMMON, "--max-hf", "10"]
    code, stdout, stderr = _run(capsys, *argv, "--out", tmp_path / "q", "--quiet")
    assert code == 3  # done, with a failed event left out of the fit (pas.cli.EXIT_CODES)
    n_failed = json.loads((tmp_path / "q" / "summary.json").read_text())["n_failed"]
    assert n_failed == 1 and "1 failed" in stdout
    lines = stderr.splitlines()
    assert len(lines) == 1, lines
    (line,) = lines
    assert line.startswith(f"pas run: HF evaluation failed for event {ids[top]}, LF rank 1 of ")
    assert "the largest LF peak" in line and "not in" in line
    # with progress on, the failure is in its progress line, still once
    code, _, stderr = _run(capsys, *argv, "--out", tmp_path / "p")
    assert [ln for ln in stderr.splitlines() if "fail" in ln.lower()] == \
        [ln for ln in stderr.splitlines() if "FAILED (LF rank 1 of" in ln]
    assert sum("FAILED" in ln for ln in stderr.splitlines()) == 1


@pytest.mark.slow
def test_n_waves_below_the_peaks_is_an_error_and_spectral_says_so(files, tmp_path, capsys):
    d, *_ = files
    argv = ["run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
            f"table:{d / 'hf.csv'}:event:force", "--p-exp", "3e-3", "--eps1", "0.2", "--seed", "1",
            "--max-hf", "6", "--quiet"]
    code, stdout, err = _run(capsys, *argv, "--n-waves", "1000", "--out", tmp_path / "a")
    assert code == 2 and stdout == "" and err.count("\n") == 1
    assert "--n-waves=1000 is below the 3000 LF peaks over the threshold" in err
    assert "--n-waves-convention spectral" in err and not (tmp_path / "a").exists()
    # over a threshold fewer peaks count: a one-line warning, and the run goes on
    code, _, err = _run(capsys, *argv, "--n-waves", "2900", "--threshold", "1.0",
                        "--out", tmp_path / "b")
    lines = err.splitlines()
    assert code == 0 and lines[0].startswith("pas run: warning: --n-waves=2900 is below the 3000 "
                                             "LF peaks given")
    assert all(ln.startswith("pas run: warning: ") for ln in lines)  # warnings are one line
    code, _, err = _run(capsys, *argv, "--n-waves", "1000", "--n-waves-convention", "spectral",
                        "--out", tmp_path / "c")
    assert code == 0 and "n-waves" not in err
    assert json.loads((tmp_path / "c" / "summary.json").read_text())["inputs"][
        "n_waves_convention"] == "spectral"


def test_run_with_the_paper_preset_and_no_budget(files, tmp_path, capsys):
    d, _, _, _ = files
    out = tmp_path / "paper"
    code, _, stderr = _run(capsys, "run", d / "lf.csv", "--lf-column", "rwe",
                           "--oracle", f"table:{d / 'hf.csv'}:event:force", *COMMON,
                           "--preset", "paper", "--max-hf", "none", "--out", out, "--quiet")
    assert code == 0, stderr
    summary = json.loads((out / "summary.json").read_text())
    settings = summary["settings"]
    assert settings["max_hf"] is None and settings["stop_measure"] == "step"
    assert (settings["strategy_settings"]["estimator"], settings["strategy_settings"]["copula_fit"],
            settings["strategy_settings"]["common_random_numbers"]) == ("selected", "itau", False)
    with pytest.raises(SystemExit) as stop:
        main([str(a) for a in ("run", d / "lf.csv", "--lf-column", "rwe", "--oracle",
                               f"table:{d / 'hf.csv'}:event:force", *COMMON, "--max-hf", "0",
                               "--out", tmp_path / "bad")])
    stderr = capsys.readouterr().err
    assert stop.value.code == 2 and "--max-hf" in stderr and "positive integer" in stderr
