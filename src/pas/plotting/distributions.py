"""Distribution figures of a screening result: the predicted HF exceedance
distribution (paper Fig. 6/7, bottom) and the LF–HF scatter with the fitted
copula (Fig. 4/16/19), plus :func:`conditional_quantile_curves` behind it.

No statistics are re-implemented here: the scatter figure refits the
strategy's copula and marginals from :attr:`ScreeningResult.pairs` with
:mod:`pas.models.copulas`, :func:`pas.models.marginals.fit_marginal` and
:func:`pas.strategies.pas.remove_outliers`.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ._common import (
    _exceedance_axes,
    _fmt,
    _has_band,
    _is_design,
    _legend_below,
    _new_axes,
    _p_exp_line,
    _plot_with_band,
    _strategy_name,
    _with_unit,
)

__all__ = ["plot_distribution", "plot_scatter", "conditional_quantile_curves"]


_MIN_TAIL_POINTS = 10
"""Fewest pairs beyond ``q_tail`` for the scatter figure to report λU and λL."""


def _pair_curve(value, name, sym, alternative=""):
    """A ``(d, values)`` pair of equal-length 1-D arrays, or a ValueError naming ``name``."""
    try:
        d, values = value
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected a (d, {sym}) pair of arrays{alternative}") from None
    d, values = np.asarray(d, dtype=float), np.asarray(values, dtype=float)
    if d.shape != values.shape or d.ndim != 1:
        raise ValueError(f"{name}: d and {sym} must be 1-D of equal length, "
                         f"got {d.shape} and {values.shape}")
    return d, values


def _lf_curve(lf):
    """``(d, l)`` from a tuple/array pair or an object with ``d`` and ``lf`` (an LFSet)."""
    if hasattr(lf, "d") and hasattr(lf, "lf"):
        lf = (lf.d, lf.lf)
    return _pair_curve(lf, "lf", "l", " or an LFSet")


def _truth_curve(truth):
    return _pair_curve(truth, "truth", "h")


# -- exceedance distribution (paper Fig. 6/7 bottom) ------------------------
def plot_distribution(result, *, lf=None, truth=None, ax=None, label=None, unit=None,
                      quantity="HF load", lf_label="LF indicator", lf_unit=None, color=None,
                      show_samples=True):
    """Predicted HF exceedance distribution h*(d) with its band and the MPM's U95 (Fig. 6/7 bottom).

    Parameters
    ----------
    result : ScreeningResult
        Uses ``result.distribution`` (``exceedance_probability``, ``h_mean``,
        ``h_low``, ``h_high``), ``result.pairs``, ``result.p_exp`` and
        ``result.mpm``/``mpm_band``.
    lf : (d, l) tuple of arrays or LFSet, optional
        The LF indicator distribution to draw for reference, in its own
        panel above the HF one (same exceedance axis; it is another quantity
        in another unit) unless ``lf_unit`` equals ``unit``.
    truth : (d, h) tuple of arrays, optional
        The true HF exceedance distribution (e.g. from a brute-force HF
        Monte-Carlo run).
    ax : matplotlib.axes.Axes, optional
    label : str, optional
        Legend name of this result (default: strategy and copula).
    unit : str, optional
        Unit of the HF load (and of the LF curve if drawn) for the axis label.
    quantity : str, default "HF load"
        Name of the quantity on the value axis.
    lf_label : str, default "LF indicator"
        Legend text of the LF curve.
    lf_unit : str, optional
        Unit of the LF indicator, for its axis label.
    color : color, optional
    show_samples : bool, default True
        Draw the HF load of every evaluated event (true positives) at the LF
        exceedance probability ``d`` of that event, and say so in the legend:
        the HF exceedance of a sample is unknown (it is what the study
        estimates), and the LF position is the one AS assumes for its order
        statistics; PAS does not.  A sample above the curve at small ``d``
        is a large load of a rare LF event, not a point of an empirical HF
        distribution.

    Returns
    -------
    fig, ax

    Notes
    -----
    The exceedance axis is logarithmic and reversed, so rarer events lie to
    the right; ``P_exp`` is a vertical line.  The shaded band is the sampling
    band of the mean distribution (``h* ± 1.96 σ`` over the z conditional
    draws, Eq. 10; the legend says "sampling band").  The MPM marker carries the one reported U95
    (:attr:`ScreeningResult.mpm_band <pas.study.result.ScreeningResult.mpm_band>`)
    as a thin error bar, with its sampling part as a thick bar inside it.
    Where the mean distribution is exactly 0 although no evaluated event
    gave 0, the draws fell below the HF marginal's support and were clipped;
    that part is not drawn and the legend says from where.  A design-wave
    result (:func:`pas.run_rcw`) is drawn by
    :func:`~pas.plotting.design.plot_design_points`: one HF episode per level,
    no curve and no band.  The legend sits under the x axis label, where it
    covers no curve.

    Examples
    --------
    >>> import numpy as np, pas
    >>> from pas.plotting import plot_distribution
    >>> lf = np.random.default_rng(0).rayleigh(2.0, 3000)
    >>> res = pas.run_pas(lf, lambda ev: 1.2 * ev.lf ** 1.1, n_waves=3000, p_exp=1e-2,
    ...                   eps1=0.05, seed=1, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    >>> fig, ax = plot_distribution(res, unit="m")
    >>> ax.get_xscale()
    'log'
    """
    dist = getattr(result, "distribution", None)
    if not isinstance(dist, pd.DataFrame) or dist.empty:
        raise ValueError("result: no predicted distribution (no fitted iteration yet)")
    if _is_design(result):
        from .design import plot_design_points

        return plot_design_points(result, ax=ax, label=label, unit=unit, quantity=quantity,
                                  color=color)
    own_figure = ax is None
    lf_apart = lf is not None and not (lf_unit is not None and lf_unit == unit)
    if own_figure and lf_apart:
        import matplotlib.pyplot as plt

        fig, (lf_panel, ax) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 6.0),
                                           height_ratios=(1.0, 2.6), layout="constrained")
        ax._pas_lf_axes = lf_panel
    else:
        fig, ax = _new_axes(ax)
    name = _strategy_name(result, label)
    d = dist["exceedance_probability"].to_numpy(dtype=float)
    h = dist["h_mean"].to_numpy(dtype=float)
    clipped = _clipped(result, h)
    shown = dist.mask(pd.Series(clipped, index=dist.index), np.nan) if clipped.any() else dist
    banded = _has_band(shown, "h_low", "h_high")
    c = _plot_with_band(ax, d, shown, "h_mean", "h_low", "h_high", "-", name=name,
                        label="predicted mean" + (", shaded: its sampling band" if banded
                                                  else ""), color=color, lw=1.6, band_label=None)
    if clipped.any():
        ax.plot([], [], " ", label=f"{name}: not drawn for d ≥ {d[clipped].min():.2g}: "
                                   "draws clipped at 0 (below the HF marginal)")
    if lf is not None:
        d_l, l_v = _lf_curve(lf)
        lf_ax = _lf_axes(ax) if lf_apart else ax
        lf_ax.plot(d_l, l_v, "-", color="0.5", lw=1.0,
                   label=lf_label + (" (upper panel)" if lf_apart else ""))
        if lf_ax is not ax:
            lf_ax.set_ylabel(_with_unit(lf_label, lf_unit))
            lf_ax.grid(True, which="both", lw=0.3, alpha=0.5)
            lf_ax.tick_params(axis="x", labelbottom=False)
    pairs = getattr(result, "pairs", None)
    if show_samples and isinstance(pairs, pd.DataFrame) and {"d", "hf"} <= set(pairs.columns) \
            and not pairs.empty:
        ax.plot(pairs["d"].to_numpy(dtype=float), pairs["hf"].to_numpy(dtype=float), "o", ms=4,
                mfc="none", mew=1.0, color=c,
                label=f"{name}: HF loads of the {len(pairs)} evaluated events with a load, "
                      "each at its LF exceedance $d$")
    if truth is not None:
        d_t, h_t = _truth_curve(truth)
        ax.plot(d_t, h_t, "k--", lw=1.2, label="truth (HF Monte-Carlo)")
    p_exp = _p_exp_line(ax, result.p_exp)
    mpm = float(result.mpm)
    if np.isfinite(mpm):
        _mpm_marker(ax, result, p_exp, mpm, c, name, unit)
    # far from P_exp the Weibull marginals may extrapolate the mean curve below every
    # observed load (even below 0); keep the view on the data
    seen = [h[(d <= 10 * p_exp) & ~clipped]]
    if isinstance(pairs, pd.DataFrame) and "hf" in pairs:
        seen.append(pairs["hf"].to_numpy(dtype=float))
    if truth is not None:
        seen.append(_truth_curve(truth)[1])
    seen = np.concatenate([np.ravel(x) for x in seen])
    seen = seen[np.isfinite(seen)]
    # (a sampling band far wider than the data, e.g. an AS GPR between sparse samples,
    # runs off the bottom instead of squashing the curves)
    low_band = pd.to_numeric(shown.get("h_low", pd.Series(dtype=float)), errors="coerce").min()
    if seen.size and min(np.nanmin(h), low_band if np.isfinite(low_band) else np.inf) \
            < seen.min():
        lo, hi = ax.get_ylim()
        span = hi - min(seen.min(), 0.0)
        ax.set_ylim(max(lo, min(seen.min(), 0.0) - 0.05 * span), hi)
    _exceedance_axes(ax, quantity, unit, grow=own_figure)
    return fig, ax


def _clipped(result, h) -> np.ndarray:
    """Rows where the mean distribution is exactly 0 although no evaluated event gave 0
    (:attr:`ScreeningResult.clipped_from <pas.study.result.ScreeningResult.clipped_from>`)."""
    if getattr(result, "n_false_positive", 0) or not np.any(h == 0.0):
        return np.zeros(h.shape, dtype=bool)
    return h == 0.0


def _lf_axes(ax):
    """The LF curve's own panel above ``ax`` (same exceedance axis, its own value axis), made
    once per Axes: the LF indicator is another quantity, so it never shares a value axis."""
    panel = getattr(ax, "_pas_lf_axes", None)
    if panel is None:
        spec = ax.get_subplotspec()
        if spec is not None:  # a grid cell: split it, the LF panel on top
            from matplotlib.gridspec import GridSpecFromSubplotSpec

            cells = GridSpecFromSubplotSpec(2, 1, subplot_spec=spec, height_ratios=(1.0, 2.6))
            ax.set_subplotspec(cells[1])
            panel = ax.figure.add_subplot(cells[0], sharex=ax)
        else:
            panel = ax.inset_axes([0.0, 1.06, 1.0, 0.38], sharex=ax)
        ax._pas_lf_axes = panel
    return panel


def _mpm_marker(ax, result, p_exp, mpm, c, name, unit):
    """The MPM at ``P_exp`` with its U95 (thin bar) and the sampling part (thick bar)."""
    lo, hi = (float(x) for x in result.mpm_band)
    if not (np.isfinite(lo) and np.isfinite(hi)):
        ax.plot([p_exp], [mpm], "D", ms=6, color=c, mec="k", mew=0.6,
                label=f"{name}: MPM {_fmt(mpm, unit)}")
        return
    s_lo, s_hi = (float(x) for x in getattr(result, "mpm_band_sampling", (np.nan, np.nan)))
    thick = np.isfinite(s_lo) and np.isfinite(s_hi) and (s_lo, s_hi) != (lo, hi)
    if thick:
        ax.plot([p_exp, p_exp], [s_lo, s_hi], "-", color=c, lw=3.5, alpha=0.6,
                solid_capstyle="butt")
    ax.errorbar([p_exp], [mpm], yerr=[[max(mpm - lo, 0.0)], [max(hi - mpm, 0.0)]], fmt="D",
                ms=6, color=c, mec="k", mew=0.6, capsize=4, elinewidth=0.9,
                label=f"{name}: MPM {_fmt(mpm, unit)}, U95 {lo:.4g}–{hi:.4g}"
                      + (f" (thick: sampling part {s_lo:.4g}–{s_hi:.4g})" if thick else ""))


# -- LF–HF scatter with the fitted copula (paper Fig. 4, 16, 19) ------------
def conditional_quantile_curves(result, lf_grid, quantiles=(0.05, 0.5, 0.95)):
    """Quantiles of HF given LF (and an impact) in real space from a PAS result's final model.

    Refits what the strategy fitted in its last iteration, with the result's
    own settings (:func:`pas.strategies.refit.refit`); then
    ``h_q(l) = F_h⁻¹(C⁻¹_{V|U}(q | u(l)))``.

    Parameters
    ----------
    result : ScreeningResult
        A PAS result (``result.family`` set, ``result.pairs`` with ``lf``, ``hf``).
    lf_grid : array-like
        LF values at which to evaluate the curves.
    quantiles : sequence of float, default (0.05, 0.5, 0.95)
        Conditional probabilities, each in (0, 1).

    Returns
    -------
    dict of float -> ndarray
        One HF curve per quantile, aligned with ``lf_grid``.
    """
    from ..models.copulas import EXTRA_FAMILIES, PAPER_FAMILIES
    from ..strategies.refit import refit

    family = getattr(result, "family", None)
    if family not in PAPER_FAMILIES + EXTRA_FAMILIES:
        raise ValueError(f"result.family is {family!r}: only a PAS result has a fitted copula")
    model = refit(result)
    grid = np.asarray(lf_grid, dtype=float)
    out = {}
    for q in quantiles:
        if not 0.0 < q < 1.0:
            raise ValueError(f"quantiles: {q} is not in (0, 1)")
        out[float(q)] = model.conditional_quantiles(grid, q)
    return out


def plot_scatter(lf, hf, *, result=None, ax=None, lf_unit=None, unit=None,
                 lf_label="LF indicator peak", hf_label="HF peak",
                 quantiles=(0.05, 0.5, 0.95), q_tail=0.9, label="all events"):
    """Scatter of matched LF–HF peaks with Kendall's τ and tail dependence (paper Fig. 16).

    Parameters
    ----------
    lf, hf : array-like, shape (n,)
        Matched LF indicator and HF load peaks (e.g. a validation Monte-Carlo
        run); HF = 0 marks an event without impact.
    result : ScreeningResult, optional
        Highlights the selected LF–HF pairs and, for a PAS result, draws the
        final fitted copula in real space: the conditional median and the
        5–95 % quantiles of HF given LF
        (:func:`conditional_quantile_curves`), over the LF range where the
        copula is defined (``l ≥ min(l_sel)``).
    ax : matplotlib.axes.Axes, optional
    lf_unit, unit : str, optional
        Units of the LF indicator (x axis) and the HF load (y axis).
    lf_label, hf_label : str
        Names of the two quantities for the axis labels.
    quantiles : sequence of three floats, default (0.05, 0.5, 0.95)
        Lower, middle and upper conditional quantile drawn.
    q_tail : float, default 0.9
        Level of the empirical tail dependence
        (:func:`pas.stats.dependence.empirical_tail_dependence`).
    label : str, default "all events"
        Legend name of the ``lf``/``hf`` points.

    Returns
    -------
    fig, ax

    Notes
    -----
    τ (Kendall's rank correlation), λU and λL (upper and lower tail
    dependence) are computed on all the given pairs and shown in the title
    in words, on two lines (one would be wider than the figure); the legend
    sits under the x axis label.  λU and λL are fractions of the pairs
    beyond ``q_tail``; with fewer than 10 such pairs (fewer than 100 pairs at
    q = 0.9) they would be 0, 0.5 or 1 from a handful of points and are not
    shown.  Large samples are rasterised in vector output.
    """
    from ..stats.dependence import empirical_tail_dependence, kendall_tau

    x, y = np.asarray(lf, dtype=float), np.asarray(hf, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"lf and hf must be 1-D of equal length, got {x.shape} and {y.shape}")
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if x.size < 3:
        raise ValueError(f"lf, hf: need at least 3 finite pairs, got {x.size}")
    own_figure = ax is None
    fig, ax = _new_axes(ax, figsize=(6.0, 5.0))
    tau = kendall_tau(x, y)
    n_tail = int(np.sum(np.arange(1, x.size + 1) / (x.size + 1) > q_tail))  # pairs with u > q
    if n_tail >= _MIN_TAIL_POINTS:
        lam_u, lam_l = empirical_tail_dependence(x, y, q=q_tail)
        stats_txt = (f"rank correlation (Kendall) {tau:.2f}\ntail dependence beyond the "
                     f"{q_tail:.0%} quantile: upper {lam_u:.2f}, lower {lam_l:.2f}")
    else:
        stats_txt = (f"rank correlation (Kendall) {tau:.2f}\ntail dependence not estimated: "
                     f"{n_tail} of {x.size} pairs beyond the {q_tail:.0%} quantile "
                     f"(needs {_MIN_TAIL_POINTS})")
    many = x.size > 2000
    ax.scatter(
        x,
        y,
        s=4 if many else 14,
        color="0.6" if many else "0.45",
        alpha=0.5 if many else 0.8,
        lw=0,
        rasterized=many,
        label=f"{label} (n = {x.size})",
    )
    if result is not None:
        pairs = result.pairs
        ax.plot(pairs["lf"], pairs["hf"], "o", ms=5, mfc="none", mew=1.2, color="tab:red",
                label=f"selected HF samples (n = {len(pairs)} true positives)")
        family = getattr(result, "family", None)
        if isinstance(family, str) and family and len(pairs) >= 4:
            lo_q, mid_q, hi_q = quantiles
            l_sel = pairs["lf"].to_numpy(dtype=float)
            grid = np.linspace(l_sel.min(), max(l_sel.max(), x.max()), 200)
            curves = conditional_quantile_curves(result, grid, (lo_q, mid_q, hi_q))
            ax.fill_between(grid, curves[lo_q], curves[hi_q], color="tab:blue", alpha=0.2, lw=0,
                            label=f"{family} copula: {lo_q:.0%}–{hi_q:.0%} of HF given LF")
            ax.plot(
                grid,
                curves[mid_q],
                "-",
                color="tab:blue",
                lw=1.5,
                label=(
                    f"{family} copula: conditional "
                    f"{'median' if mid_q == 0.5 else f'{mid_q:.0%}'}"
                ),
            )
    ax.set_xlabel(_with_unit(lf_label, lf_unit))
    ax.set_ylabel(_with_unit(hf_label, unit))
    ax.set_title(stats_txt, fontsize=9)
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax
