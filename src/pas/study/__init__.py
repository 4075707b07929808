"""Running screening campaigns: the study loop, its results, oracles and store.

The names are imported from their modules on first use (PEP 562): ``pas study
tell`` needs only :mod:`pas.study.store`, not the strategies behind
:class:`Study`.
"""

from __future__ import annotations

from .._support.lazy import lazy_exports

_EXPORTS = {
    "CommandOracle": "command_oracle", "OracleError": "oracles", "OracleFailureLimit": "oracles",
    "TableOracle": "oracles", "check_hf_value": "oracles", "ScreeningResult": "result",
    "EventState": "state", "StoreError": "store", "StudyStore": "store", "Study": "study",
    "open_study": "resume", "refit": "refit", "check_hf_answer": "answers",
}

__all__ = ["Study", "ScreeningResult", "OracleFailureLimit", "check_hf_value", "StudyStore",
           "StoreError", "open_study", "TableOracle", "CommandOracle", "OracleError",
           "EventState", "refit", "check_hf_answer"]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
