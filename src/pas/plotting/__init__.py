"""Figures: ``plot_*(..., ax=None) -> (fig, ax)`` so users can compose them."""

from .design import plot_design_points, plot_nonlinear_factor
from .records import plot_convergence, plot_record_exceedance
from .figures import (
    conditional_quantile_curves,
    plot_aic,
    plot_distribution,
    plot_metrics,
    plot_mpm_convergence,
    plot_scatter,
)
