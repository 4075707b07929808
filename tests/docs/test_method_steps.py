"""The method page and the code number the paper's steps alike.

docs/explanation/method.md has a table: a step (or a range of steps) of the
paper's §2.1 and the functions of the default path that carry it out.  The
first function named in each row must say, in its docstring, a step number
of that row: the docs and the docstrings cannot drift apart unnoticed.
"""

from __future__ import annotations

import importlib
import re

from _snippets import ROOT

ROW = re.compile(r"^\| Steps? (\d+)(?:–(\d+))? \|.*?\]\[([\w.]+)\]", re.M)
NUMBERS = re.compile(r"\bSteps? (\d+)(?:\s*[–-]\s*(\d+))?")


def resolve(path: str):
    """The object of a dotted name (module, then attributes)."""
    parts = path.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for name in parts[cut:]:
            obj = getattr(obj, name)
        return obj
    raise ImportError(path)


def steps_in(text: str) -> set[int]:
    out = set()
    for first, last in NUMBERS.findall(text or ""):
        out.update(range(int(first), int(last or first) + 1))
    return out


def rows(text: str) -> list[tuple[set[int], str]]:
    return [(set(range(int(a), int(b or a) + 1)), target) for a, b, target in ROW.findall(text)]


def test_rows_are_read_from_the_table():
    table = ("| Steps 1–4 | x | [`f`][pas.a.f], [`g`][pas.a.g] |\n"
             "| Step 5 | y | [`h`][pas.b.h] |\n| Eq. 16 | z | [`m`][pas.c.m] |\n")
    assert rows(table) == [({1, 2, 3, 4}, "pas.a.f"), ({5}, "pas.b.h")]
    assert steps_in("Steps 10–11: the draws; Step 9's marginals") == {9, 10, 11}


def test_each_step_of_the_method_page_is_the_step_of_its_function():
    page = (ROOT / "docs" / "explanation" / "method.md").read_text(encoding="utf-8")
    table = rows(page)
    assert {n for numbers, _ in table for n in numbers} == set(range(1, 13)), \
        "the table should cover the paper's steps 1–12"
    wrong = {target: (sorted(numbers), sorted(steps_in(resolve(target).__doc__)))
             for numbers, target in table if not numbers & steps_in(resolve(target).__doc__)}
    assert not wrong, f"page steps vs docstring steps: {wrong}"
