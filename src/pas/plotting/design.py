"""Figures of a design-wave result (:func:`pas.run_rcw`), like Dermatis et al. (2025)
Fig. 14 (HF value per exceedance level beside the Monte-Carlo curve) and Fig. 15
(non-linear factor ``f_NL = HF / linear − 1`` against the linear response)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ._common import (
    _exceedance_axes,
    _legend_below,
    _new_axes,
    _p_exp_line,
    _strategy_name,
    _with_unit,
)

__all__ = ["plot_design_points", "plot_nonlinear_factor"]


def _design_table(result) -> pd.DataFrame:
    dist = getattr(result, "distribution", None)
    need = {"exceedance_probability", "h_mean", "linear", "f_nl"}
    if not isinstance(dist, pd.DataFrame) or not need <= set(dist.columns):
        raise ValueError("result: expected a design-wave ScreeningResult (pas.run_rcw) whose "
                         "distribution has the columns linear and f_nl")
    return dist


def plot_design_points(result, *, ax=None, label=None, unit=None, quantity="HF load",
                       color=None, marker="o", show_linear=False, show_p_exp=True):
    """HF value of each design-wave episode at its exceedance level (Fig. 14).

    Parameters
    ----------
    result : ScreeningResult
        From :func:`pas.run_rcw`.
    ax : matplotlib.axes.Axes, optional
        Draw on it (e.g. the Axes of :func:`~pas.plotting.plot_distribution`).
    label : str, optional
        Legend name (default the strategy).
    unit : str, optional
    quantity : str, default "HF load"
    color : color, optional
    marker : str, default "o"
    show_linear : bool, default False
        Also draw the linear targets (useful when HF and target are the same
        quantity).
    show_p_exp : bool, default True
        Draw the ``P_exp`` line (labelled once per Axes).

    Returns
    -------
    fig, ax

    Examples
    --------
    >>> import pas
    >>> from pas.waves import jonswap
    >>> from pas.waves import response_surrogate
    >>> from pas.plotting.design import plot_design_points
    >>> s = response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: 1.0 + 0 * w,
    ...                        depth=30.0, omega_max=2.0, second_order=False)
    >>> res = pas.run_rcw(s, lambda ep: 1.1 * ep.target, p_exp=1e-3, levels=[1e-2])
    >>> fig, ax = plot_design_points(res, unit="m")
    >>> len(ax.lines[0].get_xdata())
    2
    """
    dist = _design_table(result)
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    name = _strategy_name(result, label)
    d = dist["exceedance_probability"].to_numpy(dtype=float)
    (pts,) = ax.plot(d, dist["h_mean"].to_numpy(dtype=float), marker, ls="none", ms=7,
                     color=color, mec="k", mew=0.6, label=f"{name}: one HF episode per level")
    if show_linear:
        ax.plot(d, dist["linear"].to_numpy(dtype=float), marker, ls="none", ms=6, mfc="none",
                color=pts.get_color(), label=f"{name}: linear target")
    if show_p_exp:
        _p_exp_line(ax, result.p_exp)
    _exceedance_axes(ax, quantity, unit, grow=own_figure)
    return fig, ax


def plot_nonlinear_factor(result=None, *, lf=None, truth=None, ax=None, label=None, unit=None,
                          color=None, marker="o", d_range=None):
    """Non-linear factor ``f_NL = HF / linear − 1`` against the linear response (Fig. 15).

    Parameters
    ----------
    result : ScreeningResult, optional
        From :func:`pas.run_rcw`: one point per episode (target, ``f_nl``).
    lf, truth : (d, values) pairs of arrays, optional
        LF (linear) and HF Monte-Carlo exceedance curves; together they give
        the Monte-Carlo ``f_NL(d) = h(d) / l(d) − 1`` drawn as a line against
        ``l(d)``.  Both must be the same quantity (e.g. linear and non-linear
        VBM).
    ax : matplotlib.axes.Axes, optional
    label : str, optional
    unit : str, optional
        Unit of the linear response.
    color : color, optional
    marker : str, default "o"
    d_range : (float, float), optional
        Exceedance range of the Monte-Carlo line; default that of the
        result's levels widened by 2 on each side, else the whole curves.

    Returns
    -------
    fig, ax
    """
    if result is None and (lf is None or truth is None):
        raise ValueError("give a design-wave result, or both lf and truth curves")
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    dist = _design_table(result) if result is not None else None
    if lf is not None and truth is not None:
        d_l, l_v = (np.asarray(a, dtype=float) for a in lf)
        d_t, h_t = (np.asarray(a, dtype=float) for a in truth)
        if d_range is None and dist is not None:
            lv = dist["exceedance_probability"].to_numpy(dtype=float)
            d_range = (lv.min() / 2.0, lv.max() * 2.0)
        lo, hi = d_range if d_range is not None else (max(d_l.min(), d_t.min()),
                                                      min(d_l.max(), d_t.max()))
        grid = np.geomspace(max(lo, d_l.min(), d_t.min()), min(hi, d_l.max(), d_t.max()), 60)
        lin = np.interp(np.log(grid), np.log(d_l), l_v)
        hf = np.interp(np.log(grid), np.log(d_t), h_t)
        ax.plot(lin, hf / lin - 1.0, "k-", lw=1.2, label="Monte-Carlo: HF(d) / LF(d) − 1")
    if dist is not None:
        name = _strategy_name(result, label)
        ax.plot(dist["linear"].to_numpy(dtype=float), dist["f_nl"].to_numpy(dtype=float), marker,
                ls="none", ms=7, color=color, mec="k", mew=0.6,
                label=f"{name}: HF / target − 1 per episode")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel(_with_unit("linear response", unit))
    ax.set_ylabel("non-linear factor $f_{NL}$ [-]")
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return fig, ax
