"""The fast path's marker list stays true: every doctest named slow still exists."""

import importlib

from conftest import SLOW_DOCTESTS


def test_every_doctest_marked_slow_is_an_example_in_the_package():
    for name in sorted(SLOW_DOCTESTS):
        module_name, _, attribute = name.rpartition(".")
        obj = getattr(importlib.import_module(module_name), attribute)
        assert ">>> " in (obj.__doc__ or ""), f"{name} has no example: drop it from SLOW_DOCTESTS"
