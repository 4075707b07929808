"""pas — Probabilistic Adaptive Screening for extreme non-linear wave loads.

Predicts the most probable maximum (MPM) of a high-fidelity (HF) load from a
long low-fidelity (LF) simulation and a few adaptively chosen HF events
(van Essen & Seyffert 2026).  Start with :func:`run_pas`; :func:`run_as` and the
design-wave :func:`run_rcw` (Dermatis et al. 2025) solve the same problem.

The public names are imported on first use (PEP 562), so ``import pas`` and
the command line (``pas --help``, ``pas study tell``) do not pay for scipy,
scikit-learn, pyvinecopulib or matplotlib before they need them.
"""

from ._support.lazy import lazy_exports
from ._version import __version__
from .stats.metrics import (  # light (numpy); eager so pas.metrics is the function
    m1,
    m2,
    m3,
    metrics,
)

#: Public name -> the module that defines it (imported when the name is first used).
_EXPORTS = {
    "run_pas": "api", "run_as": "api", "make_study": "api", "run_rcw": "design_waves",
    "Event": "strategies.screening", "LFSet": "strategies.screening",
    "encounter_period": "stats.exceedance", "mean_period_from_peak_period": "stats.exceedance",
    "n_waves_from_duration": "stats.exceedance", "p_exp_from_duration": "stats.exceedance",
    "quantile_exceedance": "stats.exceedance",
    "AS": "strategies.as_", "PAS": "strategies.pas",
    "ConditionalLikelihood": "strategies.estimators", "SelectedSample": "strategies.estimators",
    "ModelBand": "strategies.band", "Stopping": "study.settings", "Budget": "study.settings",
    "CommandOracle": "study.command_oracle", "OracleFailureLimit": "study.oracles",
    "TableOracle": "study.oracles", "ScreeningResult": "study.result", "Study": "study.study",
    "StudyStore": "study.store", "open_study": "study.resume", "refit": "study.refit",
    "lf_events": "waves.lf_events", "LFEvents": "waves.lf_events",
    "run_long_term": "longterm.runner", "LongTermResult": "longterm.result",
}

__all__ = [
    "run_pas", "make_study", "open_study", "Study", "ScreeningResult", "OracleFailureLimit",
    "Event", "LFSet",
    "PAS", "m1", "m2", "m3", "metrics", "p_exp_from_duration", "n_waves_from_duration",
    "mean_period_from_peak_period", "encounter_period", "quantile_exceedance", "__version__",
    "run_as", "AS", "StudyStore", "TableOracle", "CommandOracle", "run_rcw", "refit",
    "run_long_term", "LongTermResult", "lf_events", "LFEvents",
    "ConditionalLikelihood", "SelectedSample", "ModelBand", "Stopping", "Budget",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
del lazy_exports
