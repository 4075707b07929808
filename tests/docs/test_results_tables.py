"""Every table of docs/results/ is written by a benchmark script, never by hand.

A table sits between ``<!-- BEGIN script.py NAME -->`` and ``<!-- END script.py
NAME -->`` markers; the script named exists under ``benchmarks/`` and has a
``--write`` option (or a ``write`` sub-command), as its ``--help`` says.
"""

import contextlib
import io
import re
import runpy
import sys
from pathlib import Path
from unittest import mock

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted((ROOT / "docs" / "results").glob("*.md"))
SCRIPTS = {p.name: p for p in (ROOT / "benchmarks").rglob("*.py")}
MARKER = re.compile(r"<!-- (BEGIN|END) (\S+) (\S+) -->")
FENCE = re.compile(r"^\s*```")


def is_table_line(line: str) -> bool:
    """A Markdown table row: starts and ends with ``|`` (a prose line may start with one)."""
    stripped = line.strip()
    return len(stripped) > 1 and stripped.startswith("|") and stripped.endswith("|")


def table_lines_outside_markers(text: str) -> list[str]:
    """The table lines (``| … |``) of a page that no pair of markers encloses."""
    outside, open_block, in_code = [], None, False
    for line in text.splitlines():
        if FENCE.match(line):
            in_code = not in_code
            continue
        marker = MARKER.search(line)
        if marker:
            kind, *block = marker.groups()
            open_block = tuple(block) if kind == "BEGIN" else None
        elif not in_code and open_block is None and is_table_line(line):
            outside.append(line)
    return outside


def marker_pairs(text: str) -> list[tuple[str, str]]:
    """``(script, name)`` of every BEGIN marker, checked to be closed by its END."""
    pairs, stack = [], []
    for kind, script, name in MARKER.findall(text):
        if kind == "BEGIN":
            assert not stack, f"BEGIN {script} {name} inside {stack[-1]}"
            stack.append((script, name))
            pairs.append((script, name))
        else:
            assert stack == [(script, name)], f"END {script} {name} closes {stack or 'nothing'}"
            stack.pop()
    assert not stack, f"BEGIN {stack} is never closed"
    return pairs


def has_write(path: Path) -> bool:
    """Whether a script's ``--help``, run in process, offers ``--write`` or a ``write``
    sub-command."""
    out = io.StringIO()
    with mock.patch.object(sys, "argv", [str(path), "--help"]), \
            contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        runpy.run_path(str(path), run_name="__main__")
    text = out.getvalue()
    return bool(re.search(r"--write\b", text) or re.search(r"\{[^}]*\bwrite\b[^}]*\}", text))


def test_the_results_pages_are_found():
    assert {p.name for p in PAGES} >= {"validation.md", "precision.md", "investigations.md"}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_table_sits_between_the_markers_of_a_script_that_writes_it(page):
    text = page.read_text(encoding="utf-8")
    loose = table_lines_outside_markers(text)
    assert not loose, f"{page.name}: table lines outside any markers, e.g. {loose[0]!r}"
    for script, name in marker_pairs(text):
        assert script in SCRIPTS, f"{page.name}: markers name {script}, not a benchmarks/ script"
        assert has_write(SCRIPTS[script]), f"{script} (writes {name}) has no --write option"


def test_the_check_finds_a_loose_table_and_an_unclosed_marker():
    page = ("<!-- BEGIN a.py t -->\n| a |\n|---|\n<!-- END a.py t -->\n\n"
            "```\n| in code |\n```\n  | loose |\n|error| in prose\n")
    assert table_lines_outside_markers(page) == ["  | loose |"]
    with pytest.raises(AssertionError, match="never closed"):
        marker_pairs("<!-- BEGIN a.py t -->\n| a |\n")


def test_has_write_reads_the_help(tmp_path):
    with_write = tmp_path / "w.py"
    with_write.write_text("import argparse\nap = argparse.ArgumentParser()\n"
                          "ap.add_argument('--write', action='store_true')\nap.parse_args()\n")
    without = tmp_path / "n.py"
    without.write_text("import argparse\nap = argparse.ArgumentParser(description='no --writer')"
                       "\nap.add_argument('--csv')\nap.parse_args()\n")
    assert has_write(with_write) and not has_write(without)


def rendered_tables(text: str) -> int:
    import markdown

    html = markdown.markdown(text, extensions=["tables", "admonition", "pymdownx.superfences"])
    return html.count("<table>")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_written_table_renders_as_a_table(page):
    """A marker line right above a table nested in a list item hides it from Markdown."""
    text = page.read_text(encoding="utf-8")
    assert rendered_tables(text) == len(re.findall(r"^\s*\|---", text, re.MULTILINE))


def test_the_render_check_sees_a_hidden_table():
    hidden = "- a\n  - b\n\n    <!-- BEGIN a.py t -->\n    | x |\n    |---|\n    | 1 |\n"
    assert rendered_tables(hidden) == 0
    assert rendered_tables(hidden.replace("-->\n", "-->\n\n")) == 1
