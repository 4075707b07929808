"""Names of a package imported from their modules on first use (PEP 562)."""

from __future__ import annotations

import importlib
import sys
import types


def lazy_exports(package: str, exports: dict[str, str], hint: str = ""):
    """The ``__getattr__`` and ``__dir__`` of a package that imports its names on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : dict
        Public name -> the submodule (relative to ``package``) that defines it.
    hint : str, optional
        Added to the AttributeError of a name the package does not have
        (e.g. where names it once had went).

    Returns
    -------
    getattr_, dir_ : callable
        To assign to the package's ``__getattr__`` and ``__dir__``.
    """
    def getattr_(name):
        if name in exports:
            value = getattr(importlib.import_module(f".{exports[name]}", package), name)
            setattr(sys.modules[package], name, value)
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}{hint}")

    def dir_():
        # what a user may take: the public names, the dunders and the public sub-packages
        # imported so far; not the module's own imports or private helpers
        module = sys.modules[package]
        public = set(getattr(module, "__all__", ())) | set(exports)
        return sorted(public | {
            name for name, value in vars(module).items()
            if name.startswith("__") and name.endswith("__")
            or isinstance(value, types.ModuleType) and not name.startswith("_")
            and value.__name__ == f"{package}.{name}"})

    return getattr_, dir_
