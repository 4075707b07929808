"""benchmarks/ as a documented set: listed in its README, independent, each answering --help.

Also the page writers of the two studies that write documented tables, run
in process on committed fixtures against copies of the pages.
"""

import ast
import importlib
import importlib.util
import re
import runpy
import shutil
import sys
from pathlib import Path

import pandas as pd
import pytest
from _snippets import load_script

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"
HARNESS = BENCHMARKS / "harness"  # what the scripts share (a package, not a script)
SCRIPTS = sorted(p for p in BENCHMARKS.rglob("*.py") if HARNESS not in p.parents)
NAMES = sorted(str(p.relative_to(BENCHMARKS)) for p in SCRIPTS)


def _imported_modules(path: Path):
    """Every module a script imports, at module level or inside functions."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from ((a.name, 0) for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            yield node.module or "", node.level


def _load(relative: str):
    return load_script(f"benchmarks/{relative}")


def test_the_benchmarks_are_grouped_and_found():
    assert len(SCRIPTS) >= 20
    assert {p.parent.name for p in SCRIPTS} >= {"timing", "studies", "investigations"}


@pytest.mark.parametrize("name", NAMES)
def test_every_script_is_listed_in_the_readme(name):
    readme = (BENCHMARKS / "README.md").read_text(encoding="utf-8")
    assert f"`{name}`" in readme, f"benchmarks/README.md does not list {name}"


@pytest.mark.parametrize("name", NAMES)
def test_no_script_imports_another(name):
    own = ({p.stem for p in SCRIPTS} | {p.name for p in BENCHMARKS.iterdir() if p.is_dir()}) - {
        HARNESS.name}
    imported = list(_imported_modules(BENCHMARKS / name))
    wrong = [m for m, level in imported if level or m.split(".")[0] in own]
    assert not wrong, f"{name} imports {wrong}: shared code belongs in the package or harness"


def test_the_harness_imports_no_script():
    scripts = {p.stem for p in SCRIPTS} | {p.name for p in BENCHMARKS.iterdir() if p.is_dir()}
    for path in HARNESS.glob("*.py"):
        imported = [m for m, level in _imported_modules(path) if not level]
        assert not [m for m in imported if m.split(".")[0] in scripts - {HARNESS.name}], path


@pytest.mark.parametrize("name", NAMES)
def test_every_name_a_script_takes_from_pas_exists(name):
    """Also the imports inside functions, which --help does not reach (and the harness's)."""
    tree = ast.parse((BENCHMARKS / name).read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] in (
                "pas", "harness"):
            module = importlib.import_module(node.module)
            for alias in node.names:
                assert hasattr(module, alias.name) or importlib.util.find_spec(
                    f"{node.module}.{alias.name}"), f"{name}: {node.module}.{alias.name}"


@pytest.mark.parametrize("name", NAMES)
def test_each_script_answers_help_in_process(name, monkeypatch, capsys):
    path = BENCHMARKS / name
    modules = {m.split(".")[0] for m, _ in _imported_modules(path)}
    # a script without argparse would take --help for work and start it
    assert "argparse" in modules, f"{name} does not parse its arguments with argparse"
    monkeypatch.setattr(sys, "argv", [str(path), "--help"])
    with pytest.raises(SystemExit) as stop:
        runpy.run_path(str(path), run_name="__main__")
    assert stop.value.code == 0
    assert "usage:" in capsys.readouterr().out


def _copy_pages(tmp_path):
    for relative in ("README.md", "docs/results/validation.md",
                     "docs/results/analogue-properties.md"):
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / relative, tmp_path / relative)


def _outside_markers(text: str, tag: str) -> str:
    return re.sub(rf"<!-- BEGIN {tag} (\S+) -->\n.*?<!-- END {tag} \1 -->", "", text,
                  flags=re.DOTALL)


def test_validation_spread_write_rewrites_the_tables_and_nothing_else(tmp_path, monkeypatch):
    _copy_pages(tmp_path)
    (tmp_path / "spread").mkdir()
    shutil.copy(ROOT / "tests" / "data" / "spread_runs.csv", tmp_path / "spread" / "runs.csv")
    defaults = pd.DataFrame({"error": [0.02, -0.05, 0.5], "covered": [True, True, False],
                             "n_hf": [100, 104, 120]})
    defaults.to_csv(tmp_path / "kt_defaults.csv", index=False)
    defaults.assign(error=[0.1, -0.2, 5.656]).to_csv(tmp_path / "kt_paper.csv", index=False)
    monkeypatch.chdir(tmp_path)
    _load("studies/validation_spread.py").main(
        ["--write", "--out", "spread", "--known-truth", "kt_defaults.csv", "kt_paper.csv"])
    tag = "validation_spread.py"
    for relative in ("docs/results/validation.md", "README.md"):
        old = (ROOT / relative).read_text(encoding="utf-8")
        new = (tmp_path / relative).read_text(encoding="utf-8")
        assert new != old
        assert _outside_markers(new, tag) == _outside_markers(old, tag)
    page = (tmp_path / "docs/results/validation.md").read_text(encoding="utf-8")
    assert "| 4a | PAS | 1577 kN | 160 | 1.05 % | +4.9 % |" in page  # the fixture's 4a rows
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "| known truth, 3 runs | 104 | 5.0 % / 50 % | 20 % / 566 % | – |" in readme


def test_validation_spread_write_names_the_missing_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit):
        _load("studies/validation_spread.py").main(["--write", "--out", "nowhere"])
    assert "nowhere/runs.csv" in capsys.readouterr().err


def test_case_properties_read_write_gives_the_page_as_it_stands(tmp_path, monkeypatch):
    _copy_pages(tmp_path)
    monkeypatch.chdir(tmp_path)
    _load("studies/case_properties.py").main(
        ["--read", str(ROOT / "tests" / "data" / "analogue_properties.csv"), "--write"])
    page = "docs/results/analogue-properties.md"
    assert (tmp_path / page).read_text(encoding="utf-8") == (ROOT / page).read_text(
        encoding="utf-8")
