"""Figures for impact records (:mod:`pas.records.impacts`, :mod:`pas.records.load_fits`).

Occurrence probability against Hm0 with its interval, inter-arrival
histogram with the exponential fit before and after declustering, Q–Q plots
of fitted peak-load distributions, and the exposure probability against the
load limit. Each takes ``ax=None`` and returns ``(fig, ax)``; the legend sits
under the x axis label, where it covers no curve (compose panels with
``layout="constrained"`` to keep the legends clear of each other).
"""

from __future__ import annotations

import numpy as np

from ._common import _legend_below, _new_axes, _with_unit

__all__ = ["plot_occurrence", "plot_inter_arrival", "plot_qq", "plot_exposure"]


def plot_occurrence(fit, *, hm0=None, ax=None):
    """``Pr(GW)`` per condition (Jeffreys intervals) and the Eq. 3.4 fit with its band.

    Parameters
    ----------
    fit : pas.records.OccurrenceFit
        From :func:`pas.records.fit_occurrence`.
    hm0 : array_like, optional
        Wave heights of the curves; default spanning the data.
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    data = fit.data
    h = np.linspace(0.6 * data["hm0"].min(), 1.3 * data["hm0"].max(), 200) if hm0 is None \
        else np.asarray(hm0, dtype=float)
    for i, fb in enumerate(np.unique(data["freeboard"])):
        sel = data[data["freeboard"] == fb]
        p = sel["probability"].to_numpy()
        err = [p - sel["low"].to_numpy(), sel["high"].to_numpy() - p]
        ax.errorbar(sel["hm0"], p, yerr=err, fmt="o", ms=4, capsize=3, color=f"C{i}",
                    label=f"measured, f = {fb:g} m (95 % Jeffreys)")
        band = fit.predict(h, fb)
        ax.plot(h, band["probability"], "-", color=f"C{i}",
                label=f"exp(−(C f/Hm0)²), C = {fit.c:.3g}")
        ax.fill_between(h, band["low"], band["high"], color=f"C{i}", alpha=0.2, lw=0,
                        label=f"C in [{fit.low:.3g}, {fit.high:.3g}] ({fit.confidence:.0%})")
    ax.set_xlabel("Hm0 [m]")
    ax.set_ylabel("impact probability per encounter")
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax


def _gaps_with_fit(ax, gaps, bins, color, label, loc=0.0):
    from ..records.impacts import exponential_test

    g = np.asarray(gaps, dtype=float)
    res = exponential_test(g, loc=loc)
    ax.hist(g, bins=bins, density=True, histtype="step", color=color, lw=1.2,
            label=f"{label}: {g.size} gaps")
    x = np.linspace(loc, bins[-1], 300)
    shift = f"{loc:.3g} s + " if loc else ""
    ax.plot(x, np.exp(-(x - loc) / res["mean"]) / res["mean"], "--", color=color,
            label=f"{shift}exponential, mean {res['mean']:.3g} s (KS p = {res['pvalue']:.2g})")


def plot_inter_arrival(gaps, *, declustered=None, t_min=0.0, bins=40, log=True, ax=None):
    """Histogram of times between impacts with the exponential of their mean.

    Parameters
    ----------
    gaps : array_like
        Inter-arrival times (:func:`pas.records.inter_arrival_times`).
    declustered : array_like, optional
        The same after :func:`pas.records.decluster`, drawn beside them.
    t_min : float, default 0
        The declustering separation: the declustered gaps are compared with
        ``t_min`` plus an exponential (:func:`pas.records.exponential_test`).
    bins : int, default 40
    log : bool, default True
        Logarithmic density axis (the exponential is a straight line; an
        excess of short gaps, clustering, stands out at the left).
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    g = np.asarray(gaps, dtype=float)
    top = max(g.max(), np.max(declustered) if declustered is not None else 0.0)
    edges = np.linspace(0.0, top, int(bins) + 1)
    _gaps_with_fit(ax, g, edges, "C0", "all impacts")
    if declustered is not None:
        _gaps_with_fit(ax, declustered, edges, "C1", "declustered", loc=t_min)
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("time between impacts [s]")
    ax.set_ylabel("probability density [1/s]")
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax


def plot_qq(loads, fits, *, unit="kN", ax=None):
    """Q–Q plot of peak loads against one or more fitted distributions.

    Parameters
    ----------
    loads : array_like
        Peak loads.
    fits : frozen distribution, dict of str -> frozen distribution, or DataFrame
        A table from :func:`pas.records.compare_load_distributions` (its
        ``dist`` column, labelled with the AIC rank) also works.
    unit : str, default "kN"
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    from ..records.load_fits import qq_points

    own_figure = ax is None
    fig, ax = _new_axes(ax)
    if hasattr(fits, "columns"):
        fits = {f"{name} (ΔAIC {row['delta_aic']:.3g})": row["dist"]
                for name, row in fits.iterrows() if np.isfinite(row["aic"])}
    elif not isinstance(fits, dict):
        fits = {"fit": fits}
    x = np.asarray(loads, dtype=float)
    for i, (label, dist) in enumerate(fits.items()):
        qq = qq_points(x, dist)
        ax.plot(qq["theoretical"], qq["empirical"], ".", ms=3, color=f"C{i}", label=label)
    lim = [np.min(x), np.max(x)]
    ax.plot(lim, lim, "k-", lw=0.8, label="1:1")
    ax.set_xlabel(_with_unit("fitted quantile", unit))
    ax.set_ylabel(_with_unit("measured peak load", unit))
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax


def plot_exposure(limits, probability, distribution, n_encounters, *, mpm=None, unit="kN",
                  label="compound (Eq. 3.1–3.3)", ax=None):
    """Probability that the exposure maximum exceeds a limit, against the limit.

    Parameters
    ----------
    limits : array_like
        Load limits.
    probability, distribution, n_encounters
        As :func:`pas.records.exposure_probability`.
    mpm : dict of str -> float, optional
        MPMs of other routes (PAS, records, truth) marked as vertical lines;
        the curve crosses ``1 − e⁻¹`` at its own MPM.
    unit : str, default "kN"
    label : str
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    from ..records.impacts import exposure_load, exposure_probability

    own_figure = ax is None
    fig, ax = _new_axes(ax)
    lim = np.asarray(limits, dtype=float)
    ax.semilogy(lim, exposure_probability(lim, probability, distribution, n_encounters), "-",
                color="C0", label=label)
    level = 1.0 - np.exp(-1.0)
    own = exposure_load(level, probability, distribution, n_encounters)
    ax.axhline(level, color="0.5", lw=0.8, ls=":", label=f"1 − 1/e: MPM {own:.4g} {unit}")
    for i, (name, value) in enumerate((mpm or {}).items()):
        if value is not None and np.isfinite(value):
            p = exposure_probability(value, probability, distribution, n_encounters)
            ax.axvline(value, color=f"C{i + 1}", lw=1.0, ls="-.",
                       label=f"{name}: {value:.4g} {unit} (P = {p:.3g})")
    ax.set_xlabel(_with_unit("load limit", unit))
    ax.set_ylabel("P(exposure maximum > limit)")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax
