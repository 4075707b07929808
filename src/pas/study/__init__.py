"""Running screening campaigns: the study loop, its results, oracles and store."""

from .result import ScreeningResult
from .study import OracleFailureLimit, Study, check_hf_value

__all__ = ["Study", "ScreeningResult", "OracleFailureLimit", "check_hf_value"]
