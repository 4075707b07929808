"""Private helpers shared by the figure modules of :mod:`pas.plotting`.

Axes creation, unit labels, number formatting, access to a result's
history, the "line with U95 band" drawing used by several figures and the
legend placed under the Axes, where it covers no curve.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

LEGEND_FONTSIZE = 8.0
"""Legend text size in points: the smallest that reads at 100 % zoom."""
_LEGEND_GAP = 4.0
"""Points between the x axis label and a legend placed under it."""


def _new_axes(ax, figsize=(7.0, 4.5)):
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return fig, ax


def _with_unit(name: str, unit: str | None) -> str:
    return f"{name} [{unit}]" if unit else name


def _fmt(value: float, unit: str | None = None) -> str:
    return f"{value:.4g}{(' ' + unit) if unit else ''}"


def _history(result) -> pd.DataFrame:
    hist = getattr(result, "history", None)
    if not isinstance(hist, pd.DataFrame):
        raise ValueError("result: expected a ScreeningResult with a history DataFrame")
    missing = {"n_hf", "status", "mpm"} - set(hist.columns)
    if missing:
        raise ValueError(f"result.history lacks the column(s) {sorted(missing)}")
    return hist


def current_rows(hist: pd.DataFrame) -> pd.DataFrame:
    """The rows that still count: a result replaced later (``tell --replace``, a later row of
    the same event) is left out, so each evaluated event appears once, with its last value."""
    key = next((c for c in ("position", "event_id", "event_index") if c in hist.columns), None)
    if key is None or "replaced_hf" not in hist.columns:
        return hist
    ids = hist[key]
    return hist[~(ids.notna() & ids.duplicated(keep="last")).to_numpy()]


def _fitted(hist: pd.DataFrame) -> pd.DataFrame:
    """The fitted rows, one per HF count: a replacement's refit stands for the fit it redid."""
    hist = current_rows(hist)
    fitted = hist[pd.to_numeric(hist["mpm"], errors="coerce").notna()]
    return fitted[~fitted["n_hf"].duplicated(keep="last").to_numpy()]


def _is_design(result) -> bool:
    """A design-wave result (:func:`pas.run_rcw`): one HF episode per level, no band."""
    dist = getattr(result, "distribution", None)
    return isinstance(dist, pd.DataFrame) and {"linear", "f_nl"} <= set(dist.columns)


def _has_band(table, low, high) -> bool:
    return {low, high} <= set(table.columns) and bool(
        np.isfinite(table[[low, high]].to_numpy(dtype=float)).any())


def _strategy_name(result, label):
    if label:
        return label
    name = str(getattr(result, "strategy", "") or "").upper()
    family = getattr(result, "family", None)
    return f"{name} ({family})" if name and isinstance(family, str) and family else name or "result"


def _plot_with_band(ax, x, table, mean, low, high, fmt, *, name, label, color,
                    band_label="U95 band", **style):
    """Plot column ``mean`` of ``table`` over ``x`` and, when ``table`` has the columns
    ``low`` and ``high``, their band in the same colour (no legend entry when
    ``band_label`` is None); returns that colour."""
    (line,) = ax.plot(x, table[mean].to_numpy(dtype=float), fmt, color=color,
                      label=f"{name}: {label}", **style)
    c = line.get_color()
    if {low, high} <= set(table.columns):
        ax.fill_between(x, table[low].to_numpy(dtype=float), table[high].to_numpy(dtype=float),
                        color=c, alpha=0.2, lw=0,
                        label=f"{name}: {band_label}" if band_label else "_band")
    return c


def _p_exp_line(ax, p_exp) -> float:
    """The vertical ``P_exp`` line, labelled once per Axes; returns ``p_exp`` as a float."""
    p_exp = float(p_exp)
    label = f"$P_{{exp}}$ = {p_exp:.3g}"
    if label in ax.get_legend_handles_labels()[1]:
        label = "_" + label  # drawn by an earlier call on this Axes
    ax.axvline(p_exp, color="0.3", lw=0.8, ls=":", label=label)
    return p_exp


def _exceedance_axes(ax, quantity, unit, *, grow=False):
    """Log exceedance axis, reversed so rarer events lie to the right; labels, grid, legend."""
    ax.set_xscale("log")
    if not ax.xaxis_inverted():
        ax.invert_xaxis()
    ax.set_xlabel("exceedance probability per wave $d$ [-]")
    ax.set_ylabel(_with_unit(quantity, unit))
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    # one legend, also for the LF curve on its own axis (plot_distribution)
    handles, labels = ax.get_legend_handles_labels()
    twin = getattr(ax, "_pas_lf_axes", None)
    if twin is not None:
        more = twin.get_legend_handles_labels()
        handles, labels = handles + more[0], labels + more[1]
    _legend_below(ax, handles, labels, grow=grow)


def _legend_below(ax, handles=None, labels=None, *, ncol=1, grow=False):
    """The legend of ``ax`` under its x axis label, where it covers no curve.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    handles, labels : list, optional
        Default: every labelled artist of ``ax``.
    ncol : int, default 1
    grow : bool, default False
        Make the figure taller by the legend's height, so the Axes keep their
        size (for a figure the plotting function made itself).

    Notes
    -----
    A figure without a layout engine gets matplotlib's constrained layout,
    which makes room for the legend inside the figure.

    Returns
    -------
    matplotlib.legend.Legend
    """
    from matplotlib.transforms import offset_copy

    fig = ax.figure
    if fig.get_layout_engine() is None:
        # without a layout engine a legend under the Axes is cut off at the figure's edge
        fig.set_layout_engine("constrained")
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    # the x axis (ticks, tick labels, label) reaches this far under the Axes, in points
    depth = max(ax.get_window_extent().y0 - ax.xaxis.get_tightbbox().y0, 0.0) * 72.0 / fig.dpi
    old = ax.get_legend()
    if old is not None:
        old.remove()
    leg = ax.legend(handles, labels, fontsize=LEGEND_FONTSIZE, ncol=ncol, loc="upper center",
                    bbox_to_anchor=(0.5, 0.0), frameon=False,
                    bbox_transform=offset_copy(ax.transAxes, fig=fig, y=-(depth + _LEGEND_GAP),
                                               units="points"))
    if grow:
        fig.set_figheight(fig.get_figheight()
                          + leg.get_window_extent().height / fig.dpi + _LEGEND_GAP / 72.0)
    return leg


def _forecast_mark(ax, result, n_last, level, color, label, target):
    """The forecast of further HF from the last sample ``n_last`` at ``level``: a bar over its
    95 % interval, the expected count marked (nothing for a converged result or without one)."""
    ahead = getattr(result, "forecast_hf", None)
    if ahead is None or getattr(result, "converged", False) or not np.isfinite(ahead.expected):
        return
    high = ahead.high if np.isfinite(ahead.high) else 2.0 * ahead.expected + 1.0
    ax.plot([n_last + ahead.low, n_last + high], [level, level], lw=3, alpha=0.35, color=color,
            solid_capstyle="butt")
    ax.plot([n_last + ahead.expected], [level], marker=">", ms=7, color=color, ls="none",
            label=f"{label}, about {ahead.expected:.0f} more HF for ±{100 * target:g} % "
                  f"({ahead.low:.0f}–{'∞' if not np.isfinite(ahead.high) else f'{high:.0f}'})")
