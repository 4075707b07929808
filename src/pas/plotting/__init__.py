"""Figures: ``plot_*(..., ax=None) -> (fig, ax)`` so users can compose them."""

from .design import plot_design_points, plot_nonlinear_factor
from .figures import (
    conditional_quantile_curves,
    plot_aic,
    plot_distribution,
    plot_metrics,
    plot_mpm_convergence,
    plot_scatter,
)
from .impacts import plot_exposure, plot_inter_arrival, plot_occurrence, plot_qq
from .long_term import (
    plot_long_term_allocation,
    plot_long_term_convergence,
    plot_long_term_distribution,
)
from .records import (
    plot_convergence,
    plot_record_analysis,
    plot_record_convergence,
    plot_record_exceedance,
)

__all__ = [
    "conditional_quantile_curves",
    "plot_aic",
    "plot_convergence",
    "plot_design_points",
    "plot_distribution",
    "plot_exposure",
    "plot_inter_arrival",
    "plot_long_term_allocation",
    "plot_long_term_convergence",
    "plot_long_term_distribution",
    "plot_metrics",
    "plot_mpm_convergence",
    "plot_nonlinear_factor",
    "plot_occurrence",
    "plot_qq",
    "plot_record_analysis",
    "plot_record_convergence",
    "plot_record_exceedance",
    "plot_scatter",
]
