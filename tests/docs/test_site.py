"""The built site: its API reference and its cross-references.

Builds the site (``mkdocs build --strict``, a few seconds) and reads its HTML.

- A code span such as ``pas.run_pas`` or ``pas.strategies.band.ModelBand``
  outside a link, a heading or a code block, that names an object of the API
  reference (its ``objects.inv``, or a public name of ``pas``), should have
  been a link to it.
- Each parameter of the entry points has a row of its own text and the
  default the function really has.
"""

from __future__ import annotations

import ast
import inspect
import os
import re
import shutil
import subprocess
import sys
import zlib
from html.parser import HTMLParser
from pathlib import Path

import pytest
from _snippets import ROOT

import pas
from pas._support import DOCS_URL
from pas.study.settings import UNSET

# The pages whose pas. names must link: the guide, the explanation and the reference.
SECTIONS = ("guide", "explanation", "reference")
NAME = re.compile(r"pas(?:\.\w+)+")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if shutil.which("mkdocs") is None and not _has_mkdocs():
        pytest.fail("mkdocs is not installed (pip install -e .[docs])")
    out = tmp_path_factory.mktemp("site")
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "NO_MKDOCS_2_WARNING": "1"}
    run = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir",
                          str(out)], cwd=ROOT, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-3000:]
    return out


def _has_mkdocs():
    try:
        import mkdocs  # noqa: F401
    except ImportError:
        return False
    return True


def inventory(site: Path) -> set[str]:
    """The object names of the site's ``objects.inv`` (Sphinx inventory, version 2)."""
    raw = (site / "objects.inv").read_bytes()
    body = raw.split(b"\n", 4)[4]
    return {line.split(" ", 1)[0] for line in zlib.decompress(body).decode().splitlines()}


class _Spans(HTMLParser):
    """The text of every code span outside links, headings, signatures and code blocks."""

    SKIP = {"a", "pre", "h1", "h2", "h3", "h4", "h5", "h6"}

    def __init__(self):
        super().__init__()
        self.stack, self.spans, self.text = [], [], None

    def handle_starttag(self, tag, attrs):
        classes = (dict(attrs).get("class") or "").split()
        self.stack.append(tag in self.SKIP or "doc-signature" in classes)
        if tag == "code" and not any(self.stack[:-1]):
            self.text = ""

    def handle_endtag(self, tag):
        if tag == "code" and self.text is not None:
            self.spans.append(self.text)
            self.text = None
        if self.stack:
            self.stack.pop()

    def handle_data(self, data):
        if self.text is not None:
            self.text += data


def unlinked(html: str, known: set[str]) -> list[str]:
    parser = _Spans()
    parser.feed(html)
    return [s for s in parser.spans
            if NAME.fullmatch(s.removesuffix("()")) and s.removesuffix("()") in known]


def public(known: set[str]) -> set[str]:
    return known | {f"pas.{name}" for name in pas.__all__}


def test_unlinked_finds_a_plain_name_and_skips_links_and_code_blocks():
    html = ("<p><code>pas.run_pas</code> <a href='x'><code>pas.run_pas</code></a> "
            "<code>pas.nothing</code></p><pre><code>pas.run_pas</code></pre>"
            "<h2><code>pas.run_pas</code></h2>")
    assert unlinked(html, {"pas.run_pas"}) == ["pas.run_pas"]


def test_every_public_pas_name_on_the_guide_and_reference_pages_links(site):
    known = public(inventory(site))
    found = {}
    for section in SECTIONS:
        for page in sorted((site / section).rglob("index.html")):
            names = unlinked(page.read_text(encoding="utf-8"), known)
            if names:
                found[page.relative_to(site).as_posix()] = sorted(set(names))
    assert not found, found


def test_the_short_public_names_link_to_their_reference_entry(site):
    html = (site / "guide" / "long-term" / "index.html").read_text(encoding="utf-8")
    page = (site / "reference" / "pas" / "index.html").read_text(encoding="utf-8")
    assert 'id="pas.api.run_pas"' in page
    assert re.search(r'href="\.\./\.\./reference/pas/#pas\.api\.run_pas"', html + page)


# The entry points whose reference entries are checked row by row.
ENTRY_POINTS = {"reference/pas": ["pas.api.run_pas", "pas.api.run_as", "pas.api.make_study",
                                  "pas.longterm.runner.run_long_term"]}


class _Rows(HTMLParser):
    """The cells of the first parameter table: ``[(name, description, default), ...]``."""

    def __init__(self):
        super().__init__()
        self.rows, self.cells, self.cell, self.tables = [], None, None, 0

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables += 1
        if self.tables != 1:
            return
        if tag == "tr" and "doc-section-item" in (dict(attrs).get("class") or ""):
            self.cells = []
        elif tag == "td" and self.cells is not None:
            self.cell = ""

    def handle_endtag(self, tag):
        if self.tables != 1:
            return
        if tag == "td" and self.cell is not None:
            self.cells.append(" ".join(self.cell.split()))
            self.cell = None
        elif tag == "tr" and self.cells is not None:
            self.rows.append(tuple(self.cells))
            self.cells = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data


def entry(html: str, path: str) -> str:
    """The HTML of the reference entry of ``path``, up to the next entry of its level."""
    start = html.index(f'<h2 id="{path}"')
    end = html.find("<h2 id=", start + 1)
    return html[start:end if end > 0 else None]


def shown_default(value) -> str:
    """The default the reference should show for a parameter whose default is ``value``."""
    if value is inspect.Parameter.empty:
        return "required"
    if value is UNSET:  # the budget's default (none with the paper's preset, says the text)
        return str(pas.Budget().max_hf)
    return repr(value)


def same_default(rendered: str, expected: str) -> bool:
    if rendered == expected:
        return True
    try:
        return ast.literal_eval(rendered) == ast.literal_eval(expected)
    except (ValueError, SyntaxError):
        return False


def test_rows_read_a_parameter_table():
    html = ("<table><tr class='doc-section-item'><td><code>a</code></td><td>int</td>"
            "<td><p>The a.</p></td><td><code>1</code></td></tr></table><table><tr "
            "class='doc-section-item'><td>x</td></tr></table>")
    rows = _Rows()
    rows.feed(html)
    assert rows.rows == [("a", "int", "The a.", "1")]


@pytest.mark.parametrize("page, path", [(page, path) for page, paths in ENTRY_POINTS.items()
                                        for path in paths])
def test_each_parameter_has_its_own_row_and_its_true_default(site, page, path):
    html = entry((site / page / "index.html").read_text(encoding="utf-8"), path)
    text = re.sub(r"<[^>]+>", " ", html)
    assert "UNSET" not in text
    assert "As for" not in text
    rows = _Rows()
    rows.feed(html)
    module, name = path.rsplit(".", 1)
    func = getattr(__import__(module, fromlist=[name]), name)
    params = inspect.signature(inspect.unwrap(func)).parameters
    assert sorted(r[0] for r in rows.rows) == sorted(params)
    texts = [r[2] for r in rows.rows]
    shared = {t for t in texts if texts.count(t) > 1}
    assert not shared, f"{path}: parameters share the text {shared}"
    wrong = {r[0]: (r[3], shown_default(params[r[0]].default)) for r in rows.rows
             if not same_default(r[3], shown_default(params[r[0]].default))}
    assert not wrong, f"{path}: rendered vs true default {wrong}"


def test_the_site_url_is_the_one_messages_name():
    config = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    assert f"site_url: {DOCS_URL}\n" in config


def test_every_docs_page_a_message_names_exists():
    """``docs_page("x.md")`` in src names docs/x.md, which must exist."""
    named = set()
    for source in (ROOT / "src" / "pas").rglob("*.py"):
        named.update(re.findall(r'docs_page\("([^"]+)"\)', source.read_text(encoding="utf-8")))
    assert named, "no docs_page(...) found"
    missing = sorted(p for p in named if not (ROOT / "docs" / p).is_file())
    assert not missing, missing
