"""Waves and linear ship responses: spectra, realisations, second order, RAOs, design waves,
scatter diagrams, contours and the linear long-term value."""

from .contour import design_sea_state, iform_contour, linear_design_sea_state
from .design import FormResult, form_rcw, mler, mler_amplitudes, rayleigh_target
from .encounter import encounter_frequency, mean_encounter_period, wave_frequency_from_encounter
from .episode import Episode, design_episode
from .event_wave import EventWave, event_wave
from .lf_events import LFEvents, lf_events
from .lf_records import LFRecord, events_frame, lf_record, lf_records, sea_state_seed
from .linear_longterm import (
    HOURS_PER_YEAR,
    LinearLongTerm,
    linear_long_term,
    rayleigh_extreme,
    response_spectrum,
    short_term_linear,
)
from .realisation import ComponentSea, LinearSea, linear_sea, period_domain_sea, synthesise
from .scatter import (
    ScatterDiagram,
    dnv_joint_model,
    fit_joint_model,
    north_atlantic,
    tz_over_tp,
)
from .second_order import (
    SecondOrderKernel,
    direct_second_order,
    second_order_coefficients,
    second_order_elevation,
    second_order_kernel,
    sharma_dean_kernels,
)
from .ship import FERRY_190M, Ship, ShipRAO, relative_elevation_rao, ship_rao, ship_responses
from .spectra import (
    GRAVITY,
    jonswap,
    mean_period_t1,
    pierson_moskowitz,
    spectral_moments,
    wave_number,
    zero_crossing_period_tz,
)
from .surrogate import ResponseSurrogate, response_surrogate
from .transfer import TransferFunction

__all__ = [
    "EventWave",
    "event_wave",
    "GRAVITY", "jonswap", "pierson_moskowitz", "spectral_moments", "mean_period_t1",
    "zero_crossing_period_tz", "wave_number",
    "LinearSea", "ComponentSea", "linear_sea", "period_domain_sea", "synthesise",
    "encounter_frequency", "wave_frequency_from_encounter", "mean_encounter_period",
    "SecondOrderKernel", "sharma_dean_kernels", "second_order_kernel",
    "second_order_coefficients", "second_order_elevation", "direct_second_order",
    "Ship", "FERRY_190M", "ShipRAO", "ship_rao", "relative_elevation_rao", "ship_responses",
    "ResponseSurrogate", "response_surrogate", "mler_amplitudes", "mler", "FormResult",
    "form_rcw", "rayleigh_target", "Episode", "design_episode",
    "TransferFunction", "ScatterDiagram", "north_atlantic", "fit_joint_model", "dnv_joint_model",
    "tz_over_tp",
    "iform_contour", "design_sea_state", "linear_design_sea_state", "HOURS_PER_YEAR",
    "short_term_linear", "LinearLongTerm", "linear_long_term", "rayleigh_extreme",
    "response_spectrum",
    "LFEvents", "lf_events",
    "LFRecord", "lf_record", "lf_records", "sea_state_seed", "events_frame",
]
