"""Every Python code block of the docs pages and the README runs, or says why it does not.

A page's blocks run in order in one namespace (as a reader types them), in a
fresh folder holding the small input files the pages read (``lf_peaks.csv``,
``basin.csv``).  A block that needs what a test cannot have (a CFD program,
a cluster) carries ``<!-- not run: REASON -->`` just before it.
"""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest
from _snippets import ROOT, load_script, page_blocks

# The site's pages: docs/, the case pages it generates from cases/<id>/README.md, the README.
PAGES = sorted(p.relative_to(ROOT).as_posix()
               for p in [*(ROOT / "docs").rglob("*.md"), *(ROOT / "cases").glob("*/README.md")])
PAGES.append("README.md")
# Pages whose code runs a whole study (tens of seconds on two shared cores).
SLOW_PAGES = {"README.md", "docs/guide/quickstart.md", "docs/guide/hf-tool.md",
              "docs/guide/long-term-lf.md", "docs/guide/lf-events.md",
              "docs/guide/long-term.md"}


def runnable(page):
    return [b for b in page_blocks(page, "python") if b["not_run"] is None]


def write_inputs(folder):
    """The CSV files the pages read: an LF peak table and a basin result table.

    ``peak`` is a Rayleigh LF indicator (the README's quickstart); ``rwe`` a
    relative wave elevation with a 12 m threshold, and ``force_kN`` its HF
    load: none below 12.5 m, a growing, scattered load above.
    """
    rng = np.random.default_rng(7)
    n = 3000
    events = [f"s{i // 400:02d}-w{i % 400:03d}" for i in range(n)]
    rwe = rng.rayleigh(6.0, n)
    force = np.where(rwe < 12.5, 0.0, 60.0 * np.clip(rwe - 12.0, 0, None) ** 1.5
                     * rng.lognormal(0.0, 0.2, n))
    pd.DataFrame({"event": events, "peak": rng.rayleigh(2.0, n), "rwe": rwe}).to_csv(
        folder / "lf_peaks.csv", index=False)
    pd.DataFrame({"event": events, "force_kN": force}).to_csv(folder / "basin.csv", index=False)


def params():
    for page in PAGES:
        if runnable(page):
            marks = [pytest.mark.slow] if page in SLOW_PAGES else []
            yield pytest.param(page, id=page, marks=marks)


@pytest.mark.parametrize("page", list(params()))
def test_page_code_runs(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_inputs(tmp_path)
    namespace = {"__name__": "__docs__"}
    for block in runnable(page):
        try:
            exec(compile(block["code"], f"{page}:{block['line']}", "exec"), namespace)
        except Exception as exc:  # name the block, not only the line inside it
            raise AssertionError(f"{page}, code block at line {block['line']}: "
                                 f"{type(exc).__name__}: {exc}") from exc


def test_every_page_with_code_is_covered():
    """The pages are found by globbing, so a new page's code is run without listing it;
    the pages known to hold runnable code must be among those found."""
    covered = {p for p in PAGES if runnable(p)}
    assert {"README.md", "docs/guide/quickstart.md", "docs/guide/campaigns.md",
            "docs/guide/hf-tool.md"} <= covered
    assert SLOW_PAGES <= covered


def test_unrun_blocks_say_why():
    reasons = [b["not_run"] for p in PAGES for b in page_blocks(p, "python") if b["not_run"]]
    assert reasons and all(len(r) > 10 for r in reasons)


@pytest.mark.parametrize("text, message", [
    ("<!-- not run: -->\n```python\nx = 1\n```\n", "must say why"),
    ("<!-- not run: needs CFD -->\nSome prose.\n```python\nx = 1\n```\n", "just before"),
    ("text\n<!-- not run: needs CFD -->\n", "just before"),
], ids=["without a reason", "prose before the block", "no block after it"])
def test_a_bad_marker_is_an_error(tmp_path, text, message):
    page = tmp_path / "page.md"
    page.write_text(text, encoding="utf-8")
    with pytest.raises(ValueError, match=message):
        page_blocks(page, "python")


def test_a_marker_applies_to_the_next_block_only(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("<!-- not run: needs your CFD program -->\n\n```python\na = 1\n```\n\n"
                    "```python\nb = 2\n```\n", encoding="utf-8")
    blocks = page_blocks(page, "python")
    assert [b["not_run"] for b in blocks] == ["needs your CFD program", None]
    assert [b["code"] for b in blocks] == ["a = 1\n", "b = 2\n"]


def load_known_truth_table():
    return load_script("benchmarks/studies/known_truth_table.py")


def test_known_truth_table_writes_the_page_between_its_markers(tmp_path):
    """The script fills both tables of a copy of docs/explanation/known-truth.md from its runs
    and leaves every line outside its markers as it was."""
    runs = pd.DataFrame({"type": ["a", "a", "b"], "type_tau": [0.7, 0.7, 0.3],
                         "error": [0.1, -0.2, 0.3], "covered": [True, False, True],
                         "n_hf": [20, 40, 60], "converged": [True, True, False]})
    runs.to_csv(tmp_path / "defaults.csv", index=False)
    runs.assign(error=[0.5, 0.5, -1.0]).to_csv(tmp_path / "paper.csv", index=False)
    original = (ROOT / "docs" / "explanation" / "known-truth.md").read_text(encoding="utf-8")
    page = tmp_path / "known-truth.md"
    page.write_text(original, encoding="utf-8")
    load_known_truth_table().main([str(tmp_path / "defaults.csv"), str(tmp_path / "paper.csv"),
                                   "--write", str(page)])
    written = page.read_text(encoding="utf-8")
    # |error| 0.1, 0.2, 0.3: median 20 %, worst 30 %; coverage 2 of 3; HF median 40
    assert "| defaults, all 3 runs | 20.0 % | 28.0 % | 30.0 % | 67 % | 40 | 67 % |" in written
    assert "| b | 30.0 % | 30.0 % | +30.0 % | 100 % | 60 | 0 % | 100.0 % | 100 % | 60 |" in written
    inside = re.compile(r"<!-- BEGIN known_truth_table.py (\S+) -->\n.*?<!-- END", re.S)
    assert inside.sub("", written) == inside.sub("", original)


def test_known_truth_table_needs_the_markers(tmp_path):
    with pytest.raises(ValueError, match="markers"):
        load_known_truth_table().write_between_markers("no markers here", {"overall": "x"},
                                                       "known_truth_table.py")


def test_the_site_turns_sphinx_roles_into_cross_references():
    hook = load_script("docs/hooks/crossrefs.py")
    html = (":func:<code>pas.run_pas</code>, :class:<code>~pas.strategies.screening.Event</code>, "
            ":class:<code>Stopping</code>, not :notarole:<code>x</code>")
    assert hook.on_page_content(html) == (
        '<autoref identifier="pas.run_pas" optional><code>pas.run_pas</code></autoref>, '
        '<autoref identifier="pas.strategies.screening.Event" optional>'
        '<code>Event</code></autoref>, '
        '<autoref identifier="pas.Stopping" optional><code>Stopping</code></autoref>, '
        "not :notarole:<code>x</code>")
