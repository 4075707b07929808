"""Record statistics of a long record (``pas impacts``): MPMs, convergence, impacts, load fits.

Built on :mod:`pas.stats`; PAS itself does not use them.

The names below are imported from their modules on first use (PEP 562), so
``import pas.records`` does not load scipy.stats.
"""

from __future__ import annotations

from .._support.lazy import lazy_exports

_MODULES = {
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

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
