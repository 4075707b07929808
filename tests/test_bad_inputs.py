"""Bad inputs as a new user gives them: one line naming the argument, no traceback.

:data:`CASES` is the table: a CLI case runs ``pas`` in process through
:func:`pas.cli.main` and gives its exit code; a Python case calls the API and
gives its exception type.  Each must say what to fix in one line that names
the argument.  ``/work/scratch/.../bad_inputs_table.py`` prints the same list
as a markdown table (:func:`outcome` runs one case).

The files the cases read are made by :func:`make_workspace`; ``{NAME}`` in a
CLI argument is the path of workspace file ``NAME``.
"""

from __future__ import annotations

import contextlib
import io
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import pas
from pas.cli import main
from pas.study.flat import from_flat
from pas.study.result import ScreeningResult
from pas.study.store import StudyStore

N, NW, P = 400, 500, 0.01
"""LF peaks of the workspace, wave encounters and P_exp (inside the LF range)."""


@dataclass(frozen=True)
class Case:
    """One bad input: ``what`` the user did, the CLI ``argv`` or Python ``call``, what to get.

    ``expect`` is the exit code (CLI) or the exception type (Python);
    ``names`` the argument the message must name.
    """

    what: str
    expect: int | type
    names: str
    argv: tuple = ()
    call: object = None


RUN = ("run", "{lf.csv}", "--oracle", "table:{hf.csv}", "--n-waves", str(NW), "--p-exp", str(P),
       "--eps1", "0.1", "--out", "{out}")


def run_with(*change, lf="{lf.csv}", drop=()):
    """``pas run`` on the workspace with options replaced or added (``change``: flat pairs)."""
    argv = list(RUN)
    argv[1] = lf
    for opt in drop:
        i = argv.index(opt)
        del argv[i:i + 2]
    for opt, value in zip(change[::2], change[1::2]):
        if opt in argv:
            argv[argv.index(opt) + 1] = value
        else:
            argv += [opt, value]
    return tuple(argv)


def api(**change):
    """A ``pas.run_pas`` call on the workspace peaks with keyword arguments replaced (``eps1``
    and ``max_hf`` left out beside a ``stopping`` or ``budget`` object)."""
    def call(ws):
        lf = np.asarray(pd.read_csv(ws / "lf.csv")["lf"])
        kw = {"n_waves": NW, "p_exp": P, "eps1": 0.1, "seed": 1, "max_hf": 10, **change}
        for obj, arg in (("stopping", "eps1"), ("budget", "max_hf")):
            if obj in change and arg not in change:
                del kw[arg]
        oracle = kw.pop("oracle", lambda ev: 1.2 * ev.lf)
        return pas.run_pas(kw.pop("lf_peaks", lf), oracle, **kw)
    return call


def study(**change):
    """A ``pas.make_study(...).optimize(oracle)`` call with study keywords replaced."""
    def call(ws):
        lf = np.asarray(pd.read_csv(ws / "lf.csv")["lf"])
        pending = change.pop("pending", "resubmit")
        built = pas.make_study("pas", lf, n_waves=NW, p_exp=P, eps1=0.1, seed=1, max_hf=10,
                               **change)
        return built.optimize(lambda ev: 1.2 * ev.lf, pending=pending)
    return call


def toml_case(what, file, names):
    return Case(what, 2, names, ("study", "create", "{new.db}", "--config", "{" + file + "}"))


CASES = [
    # -- pas run: the LF file
    Case("LF_FILE does not exist", 2, "nope.csv", run_with(lf="{nope.csv}")),
    Case("LF_FILE is empty (0 bytes)", 2, "empty.csv", run_with(lf="{empty.csv}")),
    Case("LF_FILE has a header, no rows", 2, "LF_FILE", run_with(lf="{header_only.csv}")),
    Case("LF_FILE has one row", 2, "LF", run_with(lf="{one_row.csv}")),
    Case("LF column holds text", 2, "lf", run_with(lf="{text_lf.csv}")),
    Case("LF column holds NaN", 2, "--lf-column", run_with(lf="{nan_lf.csv}")),
    Case("LF_FILE of unsupported format (.xlsx)", 2, "LF_FILE", run_with(lf="{peaks.xlsx}")),
    Case("--lf-column not in the file", 2, "--lf-column", run_with("--lf-column", "rwe")),
    Case("--id-column not in the file", 2, "--id-column", run_with("--id-column", "event")),
    Case("duplicate event ids", 2, "ids", run_with(lf="{dup_ids.csv}")),
    Case("--meta-columns not in the file", 2, "--meta-columns", run_with("--meta-columns", "x")),
    # -- pas run: the oracle
    Case("--oracle without a kind", 2, "--oracle", run_with("--oracle", "basin.csv")),
    Case("--oracle of unknown kind", 2, "--oracle", run_with("--oracle", "sql:db")),
    Case("--oracle table file missing", 2, "--oracle", run_with("--oracle", "table:{nope.csv}")),
    Case(
        "--oracle table without its columns", 2, "--oracle", run_with("--oracle", "table:{lf.csv}")
    ),
    Case(
        "--oracle python module missing",
        2,
        "--oracle",
        run_with("--oracle", "python:no_such_module_xyz:f"),
    ),
    Case(
        "--oracle python function missing",
        2,
        "--oracle",
        run_with("--oracle", "python:{oracle.py}:nope"),
    ),
    Case("--oracle command empty", 2, "--oracle", run_with("--oracle", "command:")),
    Case("--oracle missing", 2, "--oracle", run_with(drop=("--oracle",))),
    # -- pas run: numbers
    Case("--n-waves 0", 2, "--n-waves", run_with("--n-waves", "0")),
    Case("--n-waves abc", 2, "--n-waves", run_with("--n-waves", "abc")),
    Case("--n-waves below the LF peaks", 2, "--n-waves", run_with("--n-waves", "100")),
    Case(
        "--n-waves-convention wrong",
        2,
        "--n-waves-convention",
        run_with("--n-waves-convention", "counted"),
    ),
    Case("--p-exp 2 (> 1)", 2, "--p-exp", run_with("--p-exp", "2")),
    Case("--p-exp 0", 2, "--p-exp", run_with("--p-exp", "0")),
    Case("--p-exp abc", 2, "--p-exp", run_with("--p-exp", "abc")),
    Case("--p-exp outside the LF range", 2, "--p-exp", run_with("--p-exp", "1e-9")),
    Case("--eps1 -1", 2, "--eps1", run_with("--eps1", "-1")),
    Case("--eps1 nan", 2, "--eps1", run_with("--eps1", "nan")),
    Case("--eps2 0", 2, "--eps2", run_with("--eps2", "0")),
    Case("--threshold high", 2, "--threshold", run_with("--threshold", "high")),
    Case("--threshold above every peak", 2, "--threshold", run_with("--threshold", "1e9")),
    Case("--threshold nan", 2, "--threshold", run_with("--threshold", "nan")),
    Case("--max-hf 0", 2, "--max-hf", run_with("--max-hf", "0")),
    Case("--max-hf 2 (below the initial samples)", 2, "--max-hf", run_with("--max-hf", "2")),
    Case("--batch-size 0", 2, "--batch-size", run_with("--batch-size", "0")),
    Case("--workers 0", 2, "--workers", run_with("--workers", "0")),
    Case("--timeout -5", 2, "--timeout", run_with("--timeout", "-5")),
    Case("--seed abc", 2, "--seed", run_with("--seed", "abc")),
    Case("--seed -1", 2, "--seed", run_with("--seed", "-1")),
    Case("--strategy unknown", 2, "--strategy", run_with("--strategy", "gpr")),
    Case("--preset unknown", 2, "--preset", run_with("--preset", "fast")),
    Case(
        "--preset paper with --strategy as",
        2,
        "preset",
        run_with("--preset", "paper", "--strategy", "as"),
    ),
    Case("ambiguous option --eps", 2, "--eps", run_with("--eps", "0.1")),
    Case("unknown option", 2, "--nosuch", run_with("--nosuch", "1")),
    Case("--out is a file", 2, "--out", run_with("--out", "{lf.csv}")),
    Case(
        "--out holds a corrupted study store", 2, "study.sqlite", run_with("--out", "{corrupt_out}")
    ),
    # -- pas study
    Case("unknown command", 2, "<command>", ("stdy", "status", "{s.db}")),
    toml_case("study file missing", "nope.toml", "nope.toml"),
    toml_case('study file: [settings] z = "ten"', "z_ten.toml", "settings.z"),
    toml_case("study file: [settings] k1 = -3", "k1_neg.toml", "settings.k1"),
    toml_case("study file: [settings] unknown name", "zz.toml", "zz"),
    toml_case("study file: p_exp = 2", "p_exp_2.toml", "p_exp"),
    toml_case('study file: n_waves = "16364"', "n_waves_text.toml", "n_waves"),
    toml_case("study file: unknown top-level key", "top_key.toml", "nwaves"),
    toml_case(
        "study file: [settings] eps1 (a top-level key)", "eps1_in_settings.toml", "settings.eps1"
    ),
    toml_case("study file: not TOML", "broken.toml", "broken.toml"),
    toml_case("study file: lf.file missing", "lf_missing.toml", "lf.file"),
    Case(
        "study create on an existing store",
        2,
        "s.db",
        ("study", "create", "{s.db}", "--config", "{ok.toml}"),
    ),
    Case("study status: no such store", 2, "nope.db", ("study", "status", "{nope.db}")),
    Case("study status: corrupted store", 2, "corrupt.db", ("study", "status", "{corrupt.db}")),
    Case("study ask: corrupted store", 2, "corrupt.db", ("study", "ask", "{corrupt.db}")),
    Case("study status: not a store", 2, "foreign.db", ("study", "status", "{foreign.db}")),
    Case("study set --k1 -3", 2, "--k1", ("study", "set", "{s.db}", "--k1", "-3")),
    Case("study set --eps1 nan", 2, "--eps1", ("study", "set", "{s.db}", "--eps1", "nan")),
    Case("study set without an option", 2, "--eps1", ("study", "set", "{s.db}")),
    Case("study tell VALUE abc", 2, "VALUE", ("study", "tell", "{s.db}", "e1", "abc")),
    Case("study tell VALUE -1", 2, "VALUE", ("study", "tell", "{s.db}", "e1", "-1")),
    Case("study tell unknown event", 2, "e99999", ("study", "tell", "{s.db}", "e99999", "1.0")),
    Case("study run without an [oracle]", 2, "oracle", ("study", "run", "{s.db}")),
    # -- pas impacts, pas plot
    Case("impacts: EVENTS missing", 2, "EVENTS", ("impacts", "{nope.csv}")),
    Case("impacts: EVENTS empty", 2, "EVENTS", ("impacts", "{empty.csv}")),
    Case(
        "impacts: --load column missing", 2, "--load", ("impacts", "{events.csv}", "--load", "hf")
    ),
    Case(
        "impacts: --time column missing", 2, "--time", ("impacts", "{events.csv}", "--time", "t0")
    ),
    Case(
        "impacts: --seed column missing", 2, "--seed", ("impacts", "{events.csv}", "--seed", "run")
    ),
    Case(
        "impacts: --exposure-hours without --encounter-period",
        2,
        "--encounter-period",
        ("impacts", "{events.csv}", "--exposure-hours", "3"),
    ),
    Case("events: SERIES missing", 2, "SERIES", ("events", "{nope.npy}")),
    Case("events: SERIES empty", 2, "SERIES", ("events", "{empty.csv}")),
    Case(
        "events: a record without a zero up-crossing (loads >= 0)",
        2,
        "SERIES",
        ("events", "{events.csv}", "--out", "{out}"),
    ),
    Case(
        "events: CSV without a time column, no --dt",
        2,
        "--dt",
        ("events", "{hf.csv}", "--column", "hf"),
    ),
    Case(
        "events: --column not in the CSV",
        2,
        "--column",
        ("events", "{events.csv}", "--column", "rwe"),
    ),
    Case("plot: not a run folder", 2, "pas run", ("plot", "{empty_dir}")),
    Case("plot: --kind unknown", 2, "--kind", ("plot", "{empty_dir}", "--kind", "pdf")),
    Case("reproduce: unknown case", 2, "case", ("reproduce", "9z")),
    Case("reproduce: --scale -1", 2, "--scale", ("reproduce", "1a", "--scale", "-1")),
    Case(
        "reproduce: --replications 0",
        2,
        "--replications",
        ("reproduce", "1a", "--replications", "0"),
    ),
    Case(
        "reproduce: unknown strategy", 2, "--strategies", ("reproduce", "1a", "--strategies", "gpr")
    ),
    Case("study ask -n 0", 2, "-n", ("study", "ask", "{s.db}", "-n", "0")),
    Case("study tell VALUE nan", 2, "VALUE", ("study", "tell", "{s.db}", "e1", "nan")),
    # -- Python API
    Case("threshold='high'", ValueError, "threshold", call=api(threshold="high")),
    Case("Stopping(k1=0)", ValueError, "k1", call=lambda ws: pas.Stopping(eps1=0.1, k1=0)),
    Case("Stopping(k2=-1)", ValueError, "k2", call=lambda ws: pas.Stopping(eps1=0.1, k2=-1)),
    Case(
        "eps1 beside stopping=",
        ValueError,
        "stopping",
        call=api(stopping=pas.Stopping(eps1=0.2), eps1=0.1),
    ),
    Case("max_hf beside budget=", ValueError, "budget", call=api(budget=pas.Budget(), max_hf=5)),
    Case("p_exp='2.55e-3'", ValueError, "p_exp", call=api(p_exp="2.55e-3")),
    Case("n_waves='16364'", ValueError, "n_waves", call=api(n_waves="16364")),
    Case("n_waves=2.5", ValueError, "n_waves", call=api(n_waves=2.5)),
    Case("p_exp=1.5", ValueError, "p_exp", call=api(p_exp=1.5)),
    Case("eps1=nan", ValueError, "eps1", call=api(eps1=float("nan"))),
    Case("eps2='0.1'", ValueError, "eps2", call=api(eps2="0.1")),
    Case("seed='a'", ValueError, "seed", call=api(seed="a")),
    Case("max_hf=0", ValueError, "max_hf", call=api(max_hf=0)),
    Case(
        "Budget(max_failures=-1)",
        ValueError,
        "max_failures",
        call=lambda ws: pas.Budget(max_failures=-1),
    ),
    Case("PAS(z='ten')", ValueError, "z", call=lambda ws: pas.PAS(z="ten")),
    Case(
        "lf_events of an array without dt",
        ValueError,
        "dt",
        call=lambda ws: pas.lf_events(np.sin(np.arange(100.0))),
    ),
    Case(
        "lf_events(threshold='3')",
        ValueError,
        "threshold",
        call=lambda ws: pas.lf_events(np.sin(np.arange(100.0)), dt=0.5, threshold="3"),
    ),
    Case("PAS(delta_aic='x')", ValueError, "delta_aic", call=lambda ws: pas.PAS(delta_aic="x")),
    Case(
        "ModelBand(n_bootstrap=-1)",
        ValueError,
        "n_bootstrap",
        call=lambda ws: pas.ModelBand(n_bootstrap=-1),
    ),
    Case("strategy='paper' in run_pas", TypeError, "strategy", call=api(strategy="paper")),
    Case(
        "stop_on_convergence='no'",
        ValueError,
        "stop_on_convergence",
        call=study(stop_on_convergence="no"),
    ),
    Case("batch_size=0", ValueError, "batch_size", call=api(batch_size=0)),
    Case("pending='later'", ValueError, "pending", call=study(pending="later")),
    Case(
        "n_waves_convention='counted'",
        ValueError,
        "n_waves_convention",
        call=study(n_waves_convention="counted"),
    ),
    Case(
        "preset='paper' (a keyword of pas 0.1)", TypeError, "PAS.paper()", call=api(preset="paper")
    ),
    Case("n_bootstrap=0 (a keyword of pas 0.1)", TypeError, "ModelBand", call=api(n_bootstrap=0)),
    Case("unknown keyword zz=1", TypeError, "zz", call=api(zz=1)),
    Case("oracle=3 (not callable)", TypeError, "oracle", call=api(oracle=3)),
    Case("lf_peaks with a NaN", ValueError, "lf_peaks", call=api(lf_peaks=[1.0, np.nan] * 200)),
    Case("lf_peaks of text", ValueError, "lf_peaks", call=api(lf_peaks=["a", "b"] * 200)),
    Case("lf_peaks 2-D", ValueError, "lf_peaks", call=api(lf_peaks=np.ones((20, 20)))),
    Case("lf_peaks empty", ValueError, "lf_peaks", call=api(lf_peaks=[])),
    Case("lf_peaks of one peak", ValueError, "lf_peaks", call=api(lf_peaks=[3.0])),
    Case(
        "lf_peaks table repeating an id",
        ValueError,
        "id",
        call=api(lf_peaks=pd.DataFrame({"lf": np.linspace(1, 5, N)}, index=["a"] * N)),
    ),
    Case(
        "lf_peaks table without an lf column",
        ValueError,
        "'lf'",
        call=api(lf_peaks=pd.DataFrame({"a": np.ones(N), "b": np.ones(N)})),
    ),
    Case(
        "strategy 'gpr' in make_study",
        ValueError,
        "strategy",
        call=lambda ws: pas.make_study("gpr", [1.0] * 10, n_waves=10, p_exp=0.5, eps1=1.0),
    ),
    Case(
        "AS(fidelity='triple')", ValueError, "fidelity", call=lambda ws: pas.AS(fidelity="triple")
    ),
    Case(
        "p_exp_from_duration with a negative exposure",
        ValueError,
        "exposure_s",
        call=lambda ws: pas.p_exp_from_duration(-3.0, 3 * 3600.0),
    ),
    Case(
        "ScreeningResult.load of a missing folder",
        FileNotFoundError,
        "nope",
        call=lambda ws: ScreeningResult.load(ws / "nope"),
    ),
    Case(
        "StudyStore of a corrupted file",
        ValueError,
        "corrupt.db",
        call=lambda ws: StudyStore(ws / "corrupt.db", create=False).events(),
    ),
]


# -- the workspace the cases read ---------------------------------------------
def make_workspace(folder) -> Path:
    """Write every file the cases name into ``folder``; returns it."""
    ws = Path(folder)
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(2.0, N)
    ids = [f"e{i}" for i in range(N)]
    table = pd.DataFrame({"id": ids, "lf": lf})
    table.to_csv(ws / "lf.csv", index=False)
    pd.DataFrame({"id": ids, "hf": 1.2 * lf}).to_csv(ws / "hf.csv", index=False)
    (ws / "empty.csv").write_text("")
    (ws / "header_only.csv").write_text("id,lf\n")
    table.head(1).to_csv(ws / "one_row.csv", index=False)
    table.assign(lf=[f"{v:.2f} m" for v in lf]).to_csv(ws / "text_lf.csv", index=False)
    table.assign(lf=np.where(np.arange(N) == 7, np.nan, lf)).to_csv(ws / "nan_lf.csv", index=False)
    table.assign(id=["e1"] * N).to_csv(ws / "dup_ids.csv", index=False)
    (ws / "peaks.xlsx").write_text("1.0\n2.0\n")
    (ws / "oracle.py").write_text("def load(event):\n    return 1.0\n")
    pd.DataFrame({"t": np.arange(N) * 6.8, "load": np.where(lf > 3, lf, 0.0)}).to_csv(
        ws / "events.csv", index=False)
    (ws / "empty_dir").mkdir(exist_ok=True)
    _write_study_files(ws)
    return ws


_TOML = (f"n_waves = {NW}\np_exp = {P}\neps1 = 0.1\nseed = 1\n{{top}}\n"
         "[lf]\nfile = \"lf.csv\"\ncolumn = \"lf\"\nid_column = \"id\"\n")


def _write_study_files(ws: Path) -> None:
    files = {"ok": "", "z_ten": '[settings]\nz = "ten"', "k1_neg": "[settings]\nk1 = -3",
             "zz": "[settings]\nzz = 1", "top_key": "nwaves = 3",
             "eps1_in_settings": "[settings]\neps1 = 0.2"}
    for name, extra in files.items():
        top, _, tables = extra.partition("[settings]")
        text = _TOML.format(top=top) + (f"[settings]{tables}\n" if tables else "")
        (ws / f"{name}.toml").write_text(text)
    (ws / "p_exp_2.toml").write_text(_TOML.format(top="").replace(f"p_exp = {P}", "p_exp = 2.0"))
    (ws / "n_waves_text.toml").write_text(
        _TOML.format(top="").replace(f"n_waves = {NW}", 'n_waves = "16364"'))
    (ws / "broken.toml").write_text("n_waves = \n")
    (ws / "lf_missing.toml").write_text(_TOML.format(top="").replace('file = "lf.csv"\n', ''))
    assert main(["study", "create", str(ws / "s.db"), "--config", str(ws / "ok.toml")]) == 0
    shutil.copy(ws / "s.db", ws / "corrupt.db")
    with open(ws / "corrupt.db", "r+b") as f:  # pages 4-23: the tables' pages
        f.seek(4096 * 3)
        f.write(b"\xff" * 4096 * 20)
    (ws / "corrupt_out").mkdir(exist_ok=True)
    shutil.copy(ws / "corrupt.db", ws / "corrupt_out" / "study.sqlite")
    (ws / "foreign.db").write_text("not a database\n")


# -- running a case -------------------------------------------------------------
def outcome(case: Case, ws: Path) -> tuple[object, str]:
    """``(exit code or exception type, message)`` of ``case`` on workspace ``ws``.

    A CLI case's message is its whole stderr; a Python case that raises
    nothing gives ``(None, "")``.
    """
    if case.call is not None:
        try:
            case.call(ws)
        except Exception as exc:  # noqa: BLE001 - the type is what is compared
            return type(exc), str(exc)
        return None, ""
    argv = [_filled(a, ws) for a in case.argv]
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse
            code = exc.code
    return code, err.getvalue().strip()


def _filled(arg: str, ws: Path) -> str:
    """``arg`` with ``{NAME}`` replaced by the path of workspace file NAME."""
    while "{" in arg and "}" in arg[arg.index("{"):]:
        i = arg.index("{")
        j = arg.index("}", i)
        arg = arg[:i] + str(ws / arg[i + 1:j]) + arg[j + 1:]
    return arg


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    return make_workspace(tmp_path_factory.mktemp("bad_inputs"))


def test_the_table_is_large_and_covers_cli_and_python():
    assert len(CASES) >= 40
    assert sum(c.call is None for c in CASES) >= 20 and sum(c.call is not None for c in CASES) >= 20
    assert len({c.what for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.what for c in CASES])
def test_bad_input_gives_one_line_naming_the_argument(case, workspace):
    got, message = outcome(case, workspace)
    if isinstance(case.expect, type):
        assert isinstance(got, type) and issubclass(got, case.expect), message
    else:
        assert got == case.expect, message
    assert message and "\n" not in message and "Traceback" not in message
    assert case.names in message
    if case.call is None:
        assert not (workspace / "out").exists()  # a refused run leaves no output folder


SAME_RULE = [("k1", -3), ("k1", 0), ("k1", 5), ("k2", 0), ("k2", 30), ("max_failures", -1),
             ("max_failures", 0), ("eps1", -1.0), ("eps1", 0.2), ("eps2", 0.0), ("eps2", 0.05),
             ("max_hf", 0), ("max_hf", 30)]
_TOP_LEVEL = ("eps1", "eps2", "max_hf", "max_failures")


@pytest.mark.parametrize("key, value", SAME_RULE)
def test_a_setting_has_one_rule_in_python_the_study_file_and_study_set(key, value, workspace,
                                                                       tmp_path):
    lf = np.asarray(pd.read_csv(workspace / "lf.csv")["lf"])
    try:
        objects = from_flat({"eps1": 0.1, key: value})  # the objects, as the study file does
        pas.make_study(objects.pop("strategy"), lf, n_waves=NW, p_exp=P, seed=1, **objects)
        python_ok = True
    except ValueError:
        python_ok = False
    line = f"{key} = {value}"
    top, table = (line, "") if key in _TOP_LEVEL else ("", f"[settings]\n{line}\n")
    text = _TOML.format(top=top) + table
    if key == "eps1":
        text = text.replace("eps1 = 0.1\n", "")
    (tmp_path / "lf.csv").write_bytes((workspace / "lf.csv").read_bytes())
    (tmp_path / "s.toml").write_text(text)
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        file_ok = main(["study", "create", str(tmp_path / "s.db"), "--config",
                        str(tmp_path / "s.toml")]) == 0
    shutil.copy(workspace / "s.db", tmp_path / "set.db")
    code, message = outcome(Case("set", 0, key, ("study", "set", str(tmp_path / "set.db"),
                                                 "--" + key.replace("_", "-"), str(value))),
                            workspace)
    assert python_ok == file_ok == (code == 0), message
    assert python_ok == (value not in (-3, 0, -1, -1.0, 0.0) or (key, value) == ("max_failures", 0))
