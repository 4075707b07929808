"""The package's face: what ``import pas`` offers is its public names, and the docs agree."""

import importlib
import re
import types
from pathlib import Path

import pas

ROOT = Path(__file__).resolve().parents[1]


def test_dir_holds_only_the_public_names_dunders_and_public_sub_packages():
    import pas.study  # noqa: F401  (a sub-package imported: it may show)

    extra = [n for n in dir(pas) if n not in pas.__all__
             and not (n.startswith("__") and n.endswith("__"))]
    assert "study" in extra
    for name in extra:
        value = getattr(pas, name)
        assert isinstance(value, types.ModuleType) and not name.startswith("_"), name
    for leaked in ("annotations", "lazy_exports", "_EXPORTS", "_support", "_version"):
        assert leaked not in dir(pas)


def test_every_name_of_the_face_page_is_importable_from_pas():
    # docs/reference/pas.md: "Each name is importable from `pas`"
    page = (ROOT / "docs" / "reference" / "pas.md").read_text(encoding="utf-8")
    targets = re.findall(r"^::: (pas\.[\w.]+)$", page, flags=re.MULTILINE)
    assert len(targets) >= 10
    for target in targets:
        module, _, name = target.rpartition(".")
        value = getattr(importlib.import_module(module), name)
        if isinstance(value, types.ModuleType):
            continue  # a module documented whole (its functions are the face's)
        assert name in pas.__all__, f"{target} is on the face page but not pas.{name}"
        assert getattr(pas, name) is value
