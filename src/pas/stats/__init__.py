"""Statistics primitives: peaks, exceedance probabilities, dependence, Weibull and log-normal fits,
and the fit check of the precision stop.

The record statistics of ``pas impacts`` are in :mod:`pas.records`.

The names below are imported from their modules on first use (PEP 562), so
``pas.stats.exceedance`` can be used without loading scipy.stats.
"""

from __future__ import annotations

from .._support.lazy import lazy_exports

_MODULES = {
    "exceedance": ("exceedance_probabilities", "value_at_exceedance", "quantile_exceedance",
        "p_exp_from_duration", "n_waves_from_duration", "mean_period_from_peak_period",
        "encounter_period"),
    "weibull": ("Weibull3", "fit_weibull3_ls", "upper_tail_fraction"),
    "lognormal": ("LogNormal3",),
    "weibull_mixture": ("WeibullMixture", "fit_weibull_mixture"),
    "peaks": ("zero_upcrossings", "upcrossing_times", "segment_max", "segment_min",
        "wave_crests", "wave_troughs", "matched_peaks", "rise_times", "rise_velocities",
        "peaks_over_threshold", "mask_near_joins"),
    "fit_check": ("FitCheck", "uniform_check"),
}
_EXPORTS = {name: module for module, names in _MODULES.items() for name in names}

__all__ = list(_EXPORTS)

__getattr__, __dir__ = lazy_exports(
    __name__, _EXPORTS, " (the record statistics of pas impacts moved to pas.records in pas 0.2)")
