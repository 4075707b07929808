"""Figures for record analysis: exceedance of pooled peaks and seed maxima, R(N).

Both functions follow pyextremes: they take ``ax=None`` (a new figure is made
when omitted) and return ``(fig, ax)``; the legend sits under the x axis label.
"""

from __future__ import annotations

import numpy as np

from ._common import _legend_below, _new_axes

__all__ = ["plot_record_exceedance", "plot_convergence", "plot_record_analysis",
           "plot_record_convergence"]


def _unit(units):
    return f" [{units}]" if units else ""


def plot_record_exceedance(d, values, *, maxima=None, fit=None, fit_scale=1.0, fit_from=None,
                           mpm=None, p_target=None, q=0.368, units="m", variable="crest",
                           ax=None):
    """Exceedance plot (log probability axis) of a record's peaks and seed maxima.

    Parameters
    ----------
    d, values : array_like
        Pooled-peaks distribution: exceedance per encounter (ascending) and
        peaks (descending), e.g. from :func:`pas.records.pooled_peaks_distribution`.
    maxima : tuple (p, values), optional
        Seed-maxima distribution (exceedance per seed ``k/N``, maxima
        descending), from :func:`pas.records.seed_maxima_distribution`.
    fit : Weibull3, optional
        Weibull fit of a peak; drawn as ``fit_scale · fit.sf(x)`` for
        ``x ≥ fit_from``.
    fit_scale : float, default 1.0
        ``n_peaks / n_encounters`` (per-peak to per-encounter).
    fit_from : float, optional
        Smallest fitted value; default the smallest peak.
    mpm : dict of str -> float, optional
        MPM estimates to mark as vertical lines (label -> value).
    p_target : float, optional
        Target exceedance per encounter ``1/n_e,t``, marked as a horizontal line.
    q : float, default 0.368
        Quantile of the seed maxima used as MPM; ``1 − q`` is marked when
        ``maxima`` is given.
    units : str, default "m"
        Unit of the variable for the axis label.
    variable : str, default "crest"
        Name of the variable for the axis label.
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    d = np.asarray(d, dtype=float)
    v = np.asarray(values, dtype=float)
    if d.shape != v.shape or d.ndim != 1:
        raise ValueError("d and values must be 1-D arrays of equal length")
    ax.semilogy(v, d, ".", ms=3, color="C0", label=f"pooled peaks (n = {v.size})")
    if maxima is not None:
        p_m, v_m = (np.asarray(a, dtype=float) for a in maxima)
        ax.semilogy(v_m, p_m, "s", ms=4, mfc="none", color="C1",
                    label=f"seed maxima (N = {v_m.size}, per seed)")
        ax.axhline(1.0 - q, color="C1", lw=0.8, ls=":")
    if fit is not None:
        lo = float(v.min() if fit_from is None else fit_from)
        x = np.linspace(lo, float(v.max()) * 1.1 + 1e-12, 200)
        ax.semilogy(x, fit_scale * fit.sf(x), "-", color="C2", lw=1.2,
                    label=f"3-p Weibull (θ={fit.theta:.3g}, α={fit.alpha:.3g}, β={fit.beta:.3g})")
    if p_target is not None:
        ax.axhline(p_target, color="0.4", lw=0.8, ls="--", label=f"P_t = 1/n_e,t = {p_target:.3g}")
    for i, (label, value) in enumerate((mpm or {}).items()):
        if value is None or not np.isfinite(value):
            continue
        ax.axvline(value, color=f"C{3 + i}", lw=1.0, ls="-.",
                   label=f"MPM {label}: {value:.4g}{(' ' + units) if units else ''}")
    ax.set_xlabel(f"{variable}{_unit(units)}")
    ax.set_ylabel("exceedance probability")
    lo_p = min(d.min(), p_target or 1.0) / 3.0
    ax.set_ylim(lo_p, 1.5)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax


def plot_convergence(n, rms, *, criterion=None, bias=None, band=None, units="m", variable="MPM",
                     ax=None):
    """R(N), the RMS difference of N-seed MPMs from the all-seed MPM, against N.

    Parameters
    ----------
    n : array_like of int
        Numbers of seeds.
    rms : array_like or dict of str -> array_like
        R(N), one curve or one per variant.
    criterion : float, optional
        Tolerance drawn as a horizontal line (same unit as ``rms``).
    bias : dict of str -> array_like, optional
        bias(N) per variant, drawn dashed in the variant's colour.
    band : tuple (low, high) of dict of str -> array_like, optional
        Confidence band of R(N) per variant, shaded in the variant's colour.
    units : str, default "m"
    variable : str, default "MPM"
    ax : matplotlib Axes, optional

    Returns
    -------
    fig, ax
    """
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    n = np.asarray(n)
    curves = rms if isinstance(rms, dict) else {"R(N)": rms}
    for i, (label, r) in enumerate(curves.items()):
        r = np.asarray(r, dtype=float)
        if r.shape != n.shape:
            raise ValueError(f"rms[{label!r}] has shape {r.shape}, n has {n.shape}")
        ax.plot(
            n,
            r,
            "-o",
            ms=3,
            color=f"C{i}",
            label=f"R(N) {label}" if isinstance(rms, dict) else label,
        )
        if band is not None and label in band[0]:
            ax.fill_between(n, np.asarray(band[0][label], dtype=float),
                            np.asarray(band[1][label], dtype=float), color=f"C{i}", alpha=0.15,
                            lw=0)
        if bias is not None and label in bias:
            ax.plot(n, np.asarray(bias[label], dtype=float), "--", lw=0.9, color=f"C{i}",
                    label=f"bias {label}")
    if criterion is not None:
        ax.axhline(criterion, color="k", lw=1.0, ls=":",
                   label=f"criterion {criterion:.3g}{(' ' + units) if units else ''}")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("number of seeds N")
    ax.set_ylabel(f"RMS difference of {variable}{_unit(units)}")
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax


def plot_record_analysis(analysis, *, units="m", variable="crest", ax=None):
    """Exceedance plot of a :class:`~pas.records.record_analysis.RecordAnalysis`.

    Parameters
    ----------
    analysis : RecordAnalysis
        The result of :func:`pas.records.analyse_record`.
    units, variable, ax
        As in :func:`plot_record_exceedance`.

    Returns
    -------
    fig, ax : matplotlib Figure and Axes
    """
    k_fit = int(np.ceil(analysis.top_fraction * analysis.values.size))
    return plot_record_exceedance(
        analysis.d, analysis.values, maxima=(analysis.p_maxima, analysis.maxima),
        fit=analysis.fit, fit_scale=analysis.fit_scale, fit_from=analysis.values[k_fit - 1],
        mpm={"pooled peaks": analysis.mpm_pooled, "seed maxima": analysis.mpm_seed_maxima,
             f"Weibull fit (top {analysis.top_fraction:.0%})": analysis.mpm_fit},
        p_target=analysis.p_target, units=units, variable=variable, ax=ax)


def plot_record_convergence(convergence, *, criterion=None, units="m", variable="MPM", ax=None):
    """R(N) plot with its band of a :class:`~pas.records.convergence.MPMConvergence`.

    Parameters
    ----------
    convergence : MPMConvergence
        The result of :func:`pas.records.mpm_convergence`.
    criterion, units, variable, ax
        As in :func:`plot_convergence`.

    Returns
    -------
    fig, ax : matplotlib Figure and Axes
    """
    return plot_convergence(convergence.n, convergence.rms, criterion=criterion,
                            bias=convergence.bias,
                            band=(convergence.rms_low, convergence.rms_high), units=units,
                            variable=variable, ax=ax)
