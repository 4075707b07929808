"""pas — Probabilistic Adaptive Screening for extreme non-linear wave loads.

Predicts the most probable maximum (MPM) of a high-fidelity (HF) load from a
long low-fidelity (LF) simulation and a few adaptively chosen HF events
(van Essen & Seyffert 2026).  Start with :func:`run_pas`; :func:`run_as` and the
design-wave :func:`run_rcw` (Dermatis et al. 2025) solve the same problem.
"""

from ._version import __version__
from .api import make_study, run_as, run_pas
from .design_waves import run_rcw
from .metrics import m1, m2, m3, metrics
from .screening import Event, LFSet
from .stats.exceedance import (
    encounter_period,
    mean_period_from_peak_period,
    n_waves_from_duration,
    p_exp_from_duration,
    quantile_exceedance,
)
from .strategies import AS, PAS
from .study import (
    CommandOracle,
    OracleFailureLimit,
    ScreeningResult,
    Study,
    StudyStore,
    TableOracle,
)

__all__ = [
    "run_pas", "make_study", "Study", "ScreeningResult", "OracleFailureLimit", "Event", "LFSet",
    "PAS", "m1", "m2", "m3", "metrics", "p_exp_from_duration", "n_waves_from_duration",
    "mean_period_from_peak_period", "encounter_period", "quantile_exceedance", "__version__",
    "run_as", "AS", "StudyStore", "TableOracle", "CommandOracle", "run_rcw",
]
