"""Figures: ``plot_*(..., ax=None) -> (fig, ax)`` so users can compose them."""

from .records import plot_convergence, plot_record_exceedance
