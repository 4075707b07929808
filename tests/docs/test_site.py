"""The built site links every ``pas.`` name that names a documented object.

Builds the site (``mkdocs build --strict``, a few seconds) and reads its HTML:
a code span such as ``pas.run_pas`` or ``pas.strategies.band.ModelBand``
outside a link, a heading or a code block, that names an object of the API
reference (its ``objects.inv``, or a public name of ``pas``), should have
been a link to it.
"""

from __future__ import annotations

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
