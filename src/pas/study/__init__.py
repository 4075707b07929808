"""Running screening campaigns: the study loop, its results, oracles and store."""

from .result import ScreeningResult
from .oracles import CommandOracle, OracleError, TableOracle
from .store import StoreError, StudyStore, open_study
from .study import OracleFailureLimit, Study, check_hf_value

__all__ = ["Study", "ScreeningResult", "OracleFailureLimit", "check_hf_value", "StudyStore",
           "StoreError", "open_study", "TableOracle", "CommandOracle", "OracleError"]
