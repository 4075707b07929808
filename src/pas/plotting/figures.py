"""Figures of a screening result, like the paper's Fig. 6/7/8/16/17/18.

Every function follows pyextremes: it takes ``ax=None`` (a new figure is made
when omitted), draws on the given Axes otherwise, and returns ``(fig, ax)``, so
results of several strategies can be composed on one Axes (call twice with the
same ``ax`` and different ``label``).  Functions that draw more than one panel
accept ``axes=None`` as well and then return ``(fig, axes)``.

Axis labels carry units through ``unit=`` (the HF load unit) and
``lf_unit=`` (the LF indicator unit); legends say what every artist is.

No statistics are re-implemented here: the scatter figure refits the
strategy's copula and marginals from :attr:`ScreeningResult.pairs` with
:mod:`pas.models.copulas`, :func:`pas.models.marginals.fit_marginal` and
:func:`pas.strategies.pas.remove_outliers`.

This module re-exports the figure functions, which live in
:mod:`pas.plotting.convergence` (:func:`plot_mpm_convergence`), :mod:`pas.plotting.aic`
(:func:`plot_aic`),
:mod:`pas.plotting.distributions` (:func:`plot_distribution`, :func:`plot_scatter`,
:func:`conditional_quantile_curves`) and :mod:`pas.plotting.metrics`
(:func:`plot_metrics`).
"""

from __future__ import annotations

import numpy as np  # noqa: F401  (kept: was a module attribute)
import pandas as pd  # noqa: F401

from ._common import (  # noqa: F401  (private helpers, kept importable from here)
    _fitted,
    _fmt,
    _history,
    _new_axes,
    _plot_with_band,
    _strategy_name,
    _with_unit,
)
from .aic import plot_aic  # noqa: F401
from .convergence import (  # noqa: F401
    _FAIL_COLOR,
    _FP_COLOR,
    _convergence_row,
    plot_mpm_convergence,
)
from .distributions import (  # noqa: F401
    _lf_curve,
    _truth_curve,
    conditional_quantile_curves,
    plot_distribution,
    plot_scatter,
)
from .metrics import _METRIC_LABEL, _METRICS, plot_metrics  # noqa: F401

__all__ = [
    "plot_mpm_convergence",
    "plot_distribution",
    "plot_scatter",
    "plot_aic",
    "plot_metrics",
    "conditional_quantile_curves",
]
