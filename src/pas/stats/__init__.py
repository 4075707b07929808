"""Statistics primitives: peaks, exceedance probabilities, Weibull fits, MPM.

The names below are imported from their modules on first use (PEP 562), so
``pas.stats.exceedance`` can be used without loading scipy.stats.
"""

from __future__ import annotations

import importlib

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
    "records": ("MPM_QUANTILE", "seed_peaks", "pooled_peaks_distribution", "seed_maxima",
        "seed_maxima_distribution", "mpm_pooled", "quantile_pooled", "mpm_seed_maxima",
        "mpm_weibull"),
    "record_analysis": ("RecordAnalysis", "analyse_record", "bootstrap_mpm"),
    "convergence": ("random_subsets", "rms_difference", "seeds_needed", "MPMConvergence",
        "mpm_convergence", "fresh_campaign_rms"),
    "theory": ("rayleigh_crest_exceedance", "rayleigh_crest_quantile", "rayleigh_crest_mpm",
        "forristall_parameters", "forristall_crest_exceedance", "forristall_crest_quantile",
        "forristall_crest_mpm"),
    "positions": ("POSITIONS", "plotting_positions", "read_at_exceedance"),
    "tails": ("TAIL_MODELS", "TailModel", "fit_tail"),
    "impacts": ("occurrence_probability", "impact_rates", "occurrence_model", "OccurrenceFit",
        "fit_occurrence", "inter_arrival_times", "exponential_test", "clustering_test",
        "decluster", "exposure_probability", "exposure_load"),
    "load_fits": ("CANDIDATES", "fit_load_distribution", "compare_load_distributions",
        "qq_points"),
}
_EXPORTS = {name: module for module, names in _MODULES.items() for name in names}

__all__ = list(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'pas.stats' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
