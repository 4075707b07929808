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
