"""Statistics primitives: peaks, exceedance probabilities, Weibull fits, MPM."""

from .exceedance import (
    encounter_period,
    exceedance_probabilities,
    mean_period_from_peak_period,
    n_waves_from_duration,
    p_exp_from_duration,
    quantile_exceedance,
    value_at_exceedance,
)
from .weibull import Weibull3, fit_weibull3_ls, upper_tail_fraction

__all__ = [
    "exceedance_probabilities", "value_at_exceedance", "quantile_exceedance",
    "p_exp_from_duration", "n_waves_from_duration", "mean_period_from_peak_period",
    "encounter_period", "Weibull3", "fit_weibull3_ls", "upper_tail_fraction",
]
from .peaks import (
    mask_near_joins,
    matched_peaks,
    peaks_over_threshold,
    rise_times,
    rise_velocities,
    segment_max,
    segment_min,
    upcrossing_times,
    wave_crests,
    wave_troughs,
    zero_upcrossings,
)

__all__ += [
    "zero_upcrossings", "upcrossing_times", "segment_max", "segment_min", "wave_crests",
    "wave_troughs", "matched_peaks", "rise_times", "rise_velocities", "peaks_over_threshold",
    "mask_near_joins",
]
from .convergence import (
    MPMConvergence,
    fresh_campaign_rms,
    mpm_convergence,
    random_subsets,
    rms_difference,
    seeds_needed,
)
from .positions import POSITIONS, plotting_positions, read_at_exceedance
from .record_analysis import RecordAnalysis, analyse_record, bootstrap_mpm
from .records import (
    MPM_QUANTILE,
    mpm_pooled,
    mpm_seed_maxima,
    mpm_weibull,
    pooled_peaks_distribution,
    quantile_pooled,
    seed_maxima,
    seed_maxima_distribution,
    seed_peaks,
)
from .tails import TAIL_MODELS, TailModel, fit_tail
from .theory import (
    forristall_crest_exceedance,
    forristall_crest_mpm,
    forristall_crest_quantile,
    forristall_parameters,
    rayleigh_crest_exceedance,
    rayleigh_crest_mpm,
    rayleigh_crest_quantile,
)

__all__ += [
    "MPM_QUANTILE", "seed_peaks", "pooled_peaks_distribution", "seed_maxima",
    "seed_maxima_distribution", "mpm_pooled", "quantile_pooled", "mpm_seed_maxima", "mpm_weibull",
    "RecordAnalysis", "analyse_record", "random_subsets", "rms_difference", "seeds_needed",
    "MPMConvergence", "mpm_convergence", "rayleigh_crest_exceedance", "rayleigh_crest_quantile",
    "rayleigh_crest_mpm", "forristall_parameters", "forristall_crest_exceedance",
    "forristall_crest_quantile", "forristall_crest_mpm", "fresh_campaign_rms", "bootstrap_mpm",
    "POSITIONS", "plotting_positions", "read_at_exceedance", "TAIL_MODELS", "TailModel",
    "fit_tail",
]
from .impacts import (
    OccurrenceFit,
    clustering_test,
    decluster,
    exponential_test,
    exposure_load,
    exposure_probability,
    fit_occurrence,
    impact_rates,
    inter_arrival_times,
    occurrence_model,
    occurrence_probability,
)
from .load_fits import CANDIDATES, compare_load_distributions, fit_load_distribution, qq_points

__all__ += [
    "occurrence_probability", "impact_rates", "occurrence_model", "OccurrenceFit",
    "fit_occurrence", "inter_arrival_times", "exponential_test", "clustering_test", "decluster",
    "exposure_probability", "exposure_load", "CANDIDATES", "fit_load_distribution",
    "compare_load_distributions", "qq_points",
]
