"""Validation-metrics figure: grouped bars of M1, M2, M3 per case (paper Fig. 8)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ._common import LEGEND_FONTSIZE, _legend_below

__all__ = ["plot_metrics"]

# -- validation metrics (paper Fig. 8) --------------------------------------
_MAX_BAR = 0.28
"""Widest bar, in units of the case spacing: one case does not become one full-width block."""
_MAX_LABELLED = 24
"""Bars are labelled with their values up to this many per panel."""
_METRICS = ("M1", "M2", "M3")
_METRIC_LABEL = {
    "M1": "$M_1 = n_c/n_w$ [%] (HF cost)",
    "M2": "$M_2$ [%] (MPM error)",
    "M3": "$M_3$ [%] (distribution error)",
}


def plot_metrics(table, *, ax=None, axes=None, percent=True):
    """Grouped bars of the validation metrics M1, M2, M3 per case (paper Fig. 8).

    Parameters
    ----------
    table : pandas.DataFrame
        Columns ``case``, ``M1``, ``M2``, ``M3`` and optionally ``strategy``
        (one bar per strategy within each case).  Metrics are fractions
        (:func:`pas.metrics`); missing values are left blank.
    ax : matplotlib.axes.Axes, optional
        Draw all three metrics on one panel, grouped per case (bars per
        metric × strategy).
    axes : sequence of three Axes, optional
        One panel per metric.  When neither ``ax`` nor ``axes`` is given, a
        new three-panel figure is made (the metrics have different scales).
    percent : bool, default True
        Show the metrics in percent.

    Returns
    -------
    fig : matplotlib.figure.Figure
    ax : matplotlib.axes.Axes or ndarray of three Axes

    Notes
    -----
    The legend (one for the three panels) sits under the x axis label, so it
    covers no bar and no bar label.
    """
    if not isinstance(table, pd.DataFrame):
        table = pd.DataFrame(table)
    missing = {"case", *_METRICS} - set(table.columns)
    if missing:
        raise ValueError(f"table lacks the column(s) {sorted(missing)}")
    if table.empty:
        raise ValueError("table is empty")
    if ax is not None and axes is not None:
        raise ValueError("give ax (one panel) or axes (three panels), not both")
    tab = table.copy()
    if "strategy" not in tab:
        tab["strategy"] = ""
    tab["strategy"] = tab["strategy"].fillna("").astype(str)
    tab["case"] = tab["case"].astype(str)
    cases = list(dict.fromkeys(tab["case"]))
    strategies = list(dict.fromkeys(tab["strategy"]))
    scale = 100.0 if percent else 1.0
    x = np.arange(len(cases))

    def value(case, strat, metric):
        rows = tab[(tab["case"] == case) & (tab["strategy"] == strat)]
        return (
            float(pd.to_numeric(rows[metric], errors="coerce").mean()) * scale
            if len(rows)
            else np.nan
        )

    def label_of(strat, metric=None):
        parts = [p for p in (metric, strat.upper() if strat else "") if p]
        return " ".join(parts) or "value"

    unit = "%" if percent else ""
    if ax is not None:
        fig = ax.figure
        series = [(m, s) for m in _METRICS for s in strategies]
        width = min(0.8 / len(series), _MAX_BAR)
        for k, (m, s) in enumerate(series):
            vals = [value(c, s, m) for c in cases]
            bars = ax.bar(x + width * (k + 0.5 - len(series) / 2), vals, width,
                          label=label_of(s, m), color=f"C{_METRICS.index(m)}",
                          alpha=1.0 - 0.35 * strategies.index(s) / max(1, len(strategies)),
                          edgecolor="k", lw=0.4)
            _label_bars(ax, bars, vals, unit, len(cases) * len(series))
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xlim(-0.6, len(cases) - 0.4)
        ax.set_xticks(x, cases)
        ax.set_xlabel("validation case")
        ax.set_ylabel("metric [%]" if percent else "metric [-]")
        ax.grid(True, axis="y", lw=0.3, alpha=0.5)
        _legend_below(ax, ncol=len(strategies))
        return fig, ax
    own_figure = axes is None
    if axes is None:
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(3, 1, figsize=(min(7.0, 2.5 + 1.2 * len(cases)), 7.0),
                                 sharex=True, layout="constrained")
    else:
        axes = list(axes)
        if len(axes) != 3:
            raise ValueError(f"axes: expected three Axes (M1, M2, M3), got {len(axes)}")
        fig = axes[0].figure
    width = min(0.8 / len(strategies), _MAX_BAR)
    for panel, m in zip(axes, _METRICS):
        for k, s in enumerate(strategies):
            vals = [value(c, s, m) for c in cases]
            bars = panel.bar(x + width * (k + 0.5 - len(strategies) / 2), vals, width,
                             label=label_of(s) if s else m, color=f"C{k}", edgecolor="k", lw=0.4)
            _label_bars(panel, bars, vals, unit, len(cases) * len(strategies))
        panel.axhline(0.0, color="k", lw=0.6)
        panel.set_xlim(-0.6, len(cases) - 0.4)
        panel.margins(y=0.15)
        label = _METRIC_LABEL[m] if percent else _METRIC_LABEL[m].replace("[%]", "[-]")
        panel.set_ylabel(label, fontsize=8)
        panel.grid(True, axis="y", lw=0.3, alpha=0.5)
    axes[-1].set_xticks(x, cases)
    axes[-1].set_xlabel("validation case")
    if any(strategies):  # one legend for the three panels, under them, off the bars
        _legend_below(axes[-1], *axes[0].get_legend_handles_labels(), ncol=len(strategies),
                      grow=own_figure)
    return fig, np.asarray(axes)


def _label_bars(ax, bars, values, unit, n_bars):
    """Write each bar's value on it when the panel has few bars (a one-case figure)."""
    if n_bars <= _MAX_LABELLED:
        ax.bar_label(bars, labels=["" if not np.isfinite(v) else f"{v:.3g}{unit}"
                                   for v in values], fontsize=LEGEND_FONTSIZE, padding=2)
