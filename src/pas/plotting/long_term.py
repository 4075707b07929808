"""Figures of a long-term analysis (:func:`pas.run_long_term`): ``plot_*(..., ax=None)``.

* :func:`plot_long_term_distribution` — the long-term exceedance per wave
  encounter with its U95 band where the level is a PAS estimate (the part
  read off the LF-only proxy drawn apart, with the range down to the level without it),
  the design value at ``p_exceed`` and, when given, the truth;
* :func:`plot_long_term_allocation` — the sea states over two descriptive
  columns of their table (Hs–Tp by default): colour the share of the
  exceedance at the value, the number the HF evaluations each was given;
* :func:`plot_long_term_convergence` — the value against the HF spent, with
  its band without the model bands every round, the full U95 where it was
  computed, the precision target and the forecast of the HF it still needs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._common import _fmt, _forecast_mark, _legend_below, _new_axes, _with_unit

__all__ = ["plot_long_term_distribution", "plot_long_term_allocation",
           "plot_long_term_convergence", "save_long_term_figures"]


def plot_long_term_distribution(result, *, truth=None, unit=None, ax=None):
    """The long-term exceedance per encounter: level against probability, U95 shaded.

    The band is drawn only where the level is a PAS estimate.  Where the level
    leans on the LF-only proxy below a sea state's PAS range (``from_proxy`` in
    ``result.distribution``, mostly at probabilities well above ``p_exceed``),
    the curve is dashed grey and the range down to the level without the proxy's
    part is hatched instead: a U95 there would look tight and mean nothing.

    Parameters
    ----------
    result : LongTermResult
    truth : float or (array, array), optional
        The true value at ``result.p_exceed``, or a true curve ``(levels, exceedance)``.
    unit : str, optional
        Unit of the HF load.
    ax : matplotlib.axes.Axes, optional
    """
    fig, ax = _new_axes(ax)
    d = result.distribution
    q = d["exceedance_probability"].to_numpy(dtype=float)
    mean = d["h_mean"].to_numpy(dtype=float)
    proxy = (d["from_proxy"].to_numpy(dtype=bool) if "from_proxy" in d.columns
             else np.zeros(len(d), dtype=bool))
    pas_part = ~proxy
    ax.fill_between(q, d["h_low"].to_numpy(dtype=float), d["h_high"].to_numpy(dtype=float),
                    where=pas_part, color="C0", alpha=0.2, lw=0, label="U95 band")
    ax.plot(q, np.where(pas_part, mean, np.nan), "-", color="C0", label="PAS long-term")
    if proxy.any():
        # the proxy part joins the PAS part at their common ends
        joined = proxy | np.convolve(proxy, [1, 1, 1], mode="same").astype(bool)
        ax.fill_between(q, d["proxy_low"].to_numpy(dtype=float), mean, where=proxy,
                        color="0.6", alpha=0.25, lw=0, hatch="//",
                        label="LF-proxy part: as low as without the proxy")
        ax.plot(q, np.where(joined, mean, np.nan), "--", color="0.35",
                label="LF-proxy part: read off the LF-only proxy (no U95)")
    lo, hi = result.band
    ax.errorbar([result.p_exceed], [result.value], yerr=[[result.value - lo], [hi - result.value]],
                fmt="o", color="C0", mec="k", capsize=3,
                label=f"value {_fmt(result.value, unit)} at {result.p_exceed:.3g} "
                      f"(U95 {_fmt(lo)} – {_fmt(hi)})")
    if truth is not None:
        if np.ndim(truth) == 0:
            ax.plot([result.p_exceed], [float(truth)], "*", ms=11, color="C3", mec="k",
                    ls="none", label=f"truth {_fmt(float(truth), unit)}")
        else:
            levels, exceedance = (np.asarray(a, dtype=float) for a in truth)
            ax.plot(exceedance, levels, "--", color="C3", label="truth")
    ax.set_xscale("log")
    if not ax.xaxis_inverted():
        ax.invert_xaxis()
    ax.set_xlabel("long-term exceedance probability per wave encounter [-]")
    ax.set_ylabel(_with_unit("HF load", unit))
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    _legend_below(ax)
    return fig, ax


def plot_long_term_allocation(result, *, x="hs", y="tp", ax=None):
    """The sea states over ``x``–``y``: colour their share of the exceedance at the value,
    marker size and label the HF evaluations each was given (a ring: none).

    ``x`` and ``y`` name descriptive columns of the sea-state table (they are in
    ``result.contributions``).
    """
    c = result.contributions
    missing = [k for k in (x, y) if k not in c.columns]
    if missing:
        raise ValueError(f"the sea-state table has no column {missing[0]!r} (give x= and y= "
                         f"from its descriptive columns: "
                         f"{', '.join(_descriptive(c)) or 'none — add hs and tp'})")
    fig, ax = _new_axes(ax, figsize=(6.5, 5.0))
    px, py = c[x].to_numpy(dtype=float), c[y].to_numpy(dtype=float)
    share, n_hf = c["share"].to_numpy(dtype=float), c["n_hf"].to_numpy(dtype=int)
    size = 30.0 + 220.0 * np.sqrt(n_hf / max(n_hf.max(), 1))
    given = n_hf > 0
    ax.scatter(px[~given], py[~given], s=30, facecolors="none", edgecolors="0.5", lw=0.8,
               label="no HF event")
    points = ax.scatter(px[given], py[given], s=size[given], c=share[given], cmap="viridis",
                        vmin=0.0, vmax=max(float(share.max()), 1e-12), edgecolors="k", lw=0.5,
                        label="HF events (size: how many)")
    for xi, yi, n in zip(px[given], py[given], n_hf[given]):
        ax.annotate(str(n), (xi, yi), textcoords="offset points", xytext=(6, 6), fontsize=7)
    fig.colorbar(points, ax=ax, label="share of the exceedance at the value")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.set_title(f"{int(n_hf.sum())} HF over {int(given.sum())} of {len(c)} sea states",
                 fontsize=9)
    _legend_below(ax)
    return fig, ax


def plot_long_term_convergence(result, *, truth=None, unit=None, ax=None):
    """The long-term value against the HF spent (one point per allocation round).

    The band without the model bands is shaded every round; the full U95 is
    drawn where it was computed; with a precision target, ``value × (1 ±
    precision)`` dotted and the forecast of the further HF it needs.  Early
    rounds whose value is 0 (no PAS model reaches the level yet) are marked on
    the lower edge, and the axis is scaled on the rounds that have a value.
    """
    h = result.history
    if h is None or len(h) == 0:
        raise ValueError("result.history is empty: the analysis ran no allocation round "
                         "(nothing to draw)")
    fig, ax = _new_axes(ax)
    n, value = h["n_hf"].to_numpy(dtype=float), h["value"].to_numpy(dtype=float)
    lf_only = (h["lf_only"].astype("boolean").fillna(False).to_numpy(dtype=bool)
               if "lf_only" in h else np.zeros(len(h), dtype=bool))
    shown_value = np.where(lf_only, np.nan, value)
    ax.fill_between(n, np.where(lf_only, np.nan, h["low_sampling"].to_numpy(dtype=float)),
                    np.where(lf_only, np.nan, h["high_sampling"].to_numpy(dtype=float)),
                    step="post", color="C0", alpha=0.2, lw=0,
                    label="band without the model bands")
    ax.plot(n, shown_value, "-", drawstyle="steps-post", color="C0", label="long-term value")
    full = h["halfwidth"].notna().to_numpy()
    if full.any():
        ax.errorbar(n[full], value[full], yerr=[value[full] - h["low"].to_numpy(float)[full],
                                                h["high"].to_numpy(float)[full] - value[full]],
                    fmt="none", ecolor="0.3", elinewidth=0.8, capsize=2,
                    label="U95 where it was computed")
    if result.precision is not None:
        for sign in (-1.0, 1.0):
            ax.plot(n, value * (1.0 + sign * result.precision), ":", lw=0.9, color="C1",
                    drawstyle="steps-post",
                    label=f"target ±{100 * result.precision:g} %" if sign > 0 else None)
        _forecast_mark(ax, result, n[-1], result.value, "C1", "forecast", result.precision)
    if truth is not None:
        ax.axhline(float(truth), color="C3", ls="--", lw=1.0,
                   label=f"truth {_fmt(float(truth), unit)}")
    nothing = ~(value > 0) | lf_only
    if nothing.any() and not nothing.all():
        # rounds before any PAS model reached the level read 0 or the LF-only proxy (in the
        # LF's unit): drawn on the lower edge, the axis scaled on the rounds with a value
        shown = ~nothing
        ends = np.concatenate([value[shown], h["low_sampling"].to_numpy(float)[shown],
                               h["high_sampling"].to_numpy(float)[shown]])
        ends = ends[np.isfinite(ends)]
        pad = 0.08 * (ends.max() - ends.min() or abs(ends.max()) or 1.0)
        bottom = ends.min() - pad
        ax.set_ylim(bottom, ends.max() + pad)
        ax.plot(n[nothing], np.full(int(nothing.sum()), bottom), "v", ms=6, mfc="none",
                color="0.4", clip_on=False, ls="none",
                label="no PAS model reaches the level yet (value 0 or the LF-only proxy)")
    ax.set_xlabel("HF evaluations spent (all sea states)")
    ax.set_ylabel(_with_unit(f"value at p_exceed = {result.p_exceed:.3g}", unit))
    ax.grid(True, lw=0.3, alpha=0.5)
    state = ("precision reached" if result.converged else
             "precision NOT reached" if result.precision is not None else "no precision target")
    ax.set_title(f"{int(result.n_hf)} HF: {state}", fontsize=9)
    _legend_below(ax)
    return fig, ax


def _descriptive(contributions):
    from ..longterm.result import CONTRIBUTION_COLUMNS

    return [c for c in contributions.columns if c not in CONTRIBUTION_COLUMNS]


def save_long_term_figures(result, folder, *, x=None, y=None, unit=None, fmt="png") -> list:
    """The three figures into ``folder`` (created): ``long_term_distribution``,
    ``long_term_allocation`` (over ``x``–``y``, default ``hs``–``tp`` or the first two
    descriptive columns; left out when the table has fewer) and ``long_term_convergence``.

    Returns the paths written.
    """
    import matplotlib.pyplot as plt

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    columns = _descriptive(result.contributions)
    if x is None or y is None:
        x, y = ("hs", "tp") if {"hs", "tp"} <= set(columns) else (columns + [None, None])[:2]
    figures = [("long_term_distribution", lambda: plot_long_term_distribution(result, unit=unit))]
    if x is not None and y is not None:
        figures.append(("long_term_allocation",
                        lambda: plot_long_term_allocation(result, x=x, y=y)))
    if len(result.history):
        figures.append(("long_term_convergence",
                        lambda: plot_long_term_convergence(result, unit=unit)))
    written = []
    for name, draw in figures:
        fig, _ = draw()
        path = folder / f"{name}.{fmt}"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        written.append(path)
    return written
