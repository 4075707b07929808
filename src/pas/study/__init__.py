"""Running screening campaigns: the study loop, its results, oracles and store."""

from .oracles import CommandOracle, OracleError, OracleFailureLimit, TableOracle, check_hf_value
from .result import ScreeningResult
from .state import EventState
from .store import StoreError, StudyStore
from .study import Study, open_study

__all__ = ["Study", "ScreeningResult", "OracleFailureLimit", "check_hf_value", "StudyStore",
           "StoreError", "open_study", "TableOracle", "CommandOracle", "OracleError",
           "EventState"]
