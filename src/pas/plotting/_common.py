"""Private helpers shared by the figure modules of :mod:`pas.plotting`.

Axes creation, unit labels, number formatting, access to a result's
history and the "line with U95 band" drawing used by several figures.
"""

from __future__ import annotations

import pandas as pd


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


def _fitted(hist: pd.DataFrame) -> pd.DataFrame:
    return hist[pd.to_numeric(hist["mpm"], errors="coerce").notna()]


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


def _exceedance_axes(ax, quantity, unit):
    """Log exceedance axis, reversed so rarer events lie to the right; labels, grid, legend."""
    ax.set_xscale("log")
    if not ax.xaxis_inverted():
        ax.invert_xaxis()
    ax.set_xlabel("exceedance probability per wave $d$ [-]")
    ax.set_ylabel(_with_unit(quantity, unit))
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    # one legend, also for the LF curve on its own axis (plot_distribution), where it
    # covers the fewest points; see-through, as a long truth curve leaves no empty corner
    handles, labels = ax.get_legend_handles_labels()
    twin = getattr(ax, "_pas_lf_axes", None)
    if twin is not None:
        more = twin.get_legend_handles_labels()
        handles, labels = handles + more[0], labels + more[1]
    ax.legend(handles, labels, fontsize=7, loc="best", framealpha=0.6)
