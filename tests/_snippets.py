"""Code blocks of the README and the docs pages, found by their section heading.

Tests that run a documented snippet verbatim locate it by heading, not by line
number, so the page can be reorganised without the test silently reading
another block.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*$")
_FENCE = re.compile(r"^```(\w*)\s*$")


def section(path, heading: str) -> str:
    """The text under the first heading whose title contains ``heading``, up to the next
    heading of the same or a higher level (fenced code is not scanned for headings)."""
    lines = (ROOT / path).read_text(encoding="utf-8").splitlines()
    level, out, in_code = None, [], False
    for line in lines:
        if _FENCE.match(line):
            in_code = not in_code
        m = None if in_code else _HEADING.match(line)
        if m and level is not None and len(m.group(1)) <= level:
            break
        if level is not None:
            out.append(line)
        elif m and heading in m.group(2):
            level = len(m.group(1))
    if level is None:
        raise LookupError(f"no heading containing {heading!r} in {path}")
    return "\n".join(out)


def code_blocks(path, heading: str, lang: str | None = None) -> list[str]:
    """The fenced code blocks of that section, in order (only ``lang`` ones if given)."""
    blocks, current, block_lang = [], None, ""
    for line in section(path, heading).splitlines():
        m = _FENCE.match(line)
        if m and current is None:
            current, block_lang = [], m.group(1)
        elif m:
            if lang is None or block_lang == lang:
                blocks.append("\n".join(current) + "\n")
            current = None
        elif current is not None:
            current.append(line)
    if not blocks:
        raise LookupError(f"no {lang or ''} code block under {heading!r} in {path}")
    return blocks


_NOT_RUN = re.compile(r"^<!--\s*not run:(.*?)-->\s*$")


def page_blocks(path, lang: str | None = None) -> list[dict]:
    """Every fenced code block of a page, in order (only ``lang`` ones if given).

    Each is a dict with ``code``, ``lang``, ``line`` (1-based line of the
    opening fence) and ``not_run``: the reason given in an HTML comment
    ``<!-- not run: REASON -->`` on the line just before the fence (blank
    lines between them allowed), else None.  A marker without a reason, or
    one that is not followed by a code block, is a ValueError.
    """
    lines = (ROOT / path).read_text(encoding="utf-8").splitlines()
    blocks, current, pending = [], None, None
    for number, line in enumerate(lines, start=1):
        fence = _FENCE.match(line)
        if current is not None:
            if fence:
                if lang is None or current["lang"] == lang:
                    current["code"] = "\n".join(current["code"]) + "\n"
                    blocks.append(current)
                current = None
            else:
                current["code"].append(line)
            continue
        marker = _NOT_RUN.match(line.strip())
        if marker:
            if not marker.group(1).strip():
                raise ValueError(f"{path}:{number}: a 'not run' marker must say why")
            pending = (number, marker.group(1).strip())
        elif fence:
            current = {"code": [], "lang": fence.group(1), "line": number,
                       "not_run": pending[1] if pending else None}
            pending = None
        elif line.strip() and pending:
            raise ValueError(f"{path}:{pending[0]}: a 'not run' marker must stand just "
                             "before a code block")
    if pending:
        raise ValueError(f"{path}:{pending[0]}: a 'not run' marker must stand just "
                         "before a code block")
    return blocks


def load_script(relative_path):
    """The module of a script of the repository (``benchmarks/...``), by its path from the root."""
    path = ROOT / relative_path
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
