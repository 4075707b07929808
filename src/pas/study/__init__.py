"""Running screening campaigns: the study loop, its results, oracles and store.

The names are imported from their modules on first use (PEP 562): ``pas study
tell`` needs only :mod:`pas.study.store`, not the strategies behind
:class:`Study`.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "CommandOracle": "oracles", "OracleError": "oracles", "OracleFailureLimit": "oracles",
    "TableOracle": "oracles", "check_hf_value": "oracles", "ScreeningResult": "result",
    "EventState": "state", "StoreError": "store", "StudyStore": "store", "Study": "study",
    "open_study": "resume", "refit": "refit", "check_hf_answer": "answers",
}

__all__ = ["Study", "ScreeningResult", "OracleFailureLimit", "check_hf_value", "StudyStore",
           "StoreError", "open_study", "TableOracle", "CommandOracle", "OracleError",
           "EventState", "refit", "check_hf_answer"]


def __getattr__(name):
    if name in _EXPORTS:
        value = globals()[name] = getattr(
            importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
        return value
    raise AttributeError(f"module 'pas.study' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
