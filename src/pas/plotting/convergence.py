"""Convergence figure of a screening result: MPM against the number of HF samples
(paper Fig. 6/7, top); the copula AIC per iteration is :mod:`pas.plotting.aic`.

See :mod:`pas.plotting.figures` for the conventions shared by all figures
(``ax=None`` -> ``(fig, ax)``, units in the axis labels).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ._common import (
    _fitted,
    _fmt,
    _forecast_mark,
    _has_band,
    _history,
    _is_design,
    _legend_below,
    _new_axes,
    _plot_with_band,
    _strategy_name,
    _with_unit,
)

__all__ = ["plot_mpm_convergence", "stop_text"]

_FP_COLOR = "tab:red"
_FAIL_COLOR = "0.45"


def _convergence_row(hist: pd.DataFrame):
    """The first history row where the stopping criterion held, or None."""
    if "stop" not in hist:
        return None
    stop = hist["stop"].map(lambda s: s is True or s == 1 or str(s).lower() == "true")
    hits = hist[stop.to_numpy(dtype=bool)]
    return None if hits.empty else hits.iloc[0]


# -- MPM convergence (paper Fig. 6/7 top) -----------------------------------
def plot_mpm_convergence(result, *, truth=None, ax=None, label=None, unit=None,
                         quantity="MPM", color=None):
    """MPM against the number of HF samples, with its U95 band (paper Fig. 6/7, top).

    Parameters
    ----------
    result : ScreeningResult
        From :func:`pas.run_pas` / :func:`pas.run_as` (or rebuilt from files,
        see :func:`pas.cli.plot.load_result`).
    truth : float, optional
        True MPM, drawn as a horizontal line.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when omitted.
    label : str, optional
        Legend name of this result (default: strategy and final copula, e.g.
        ``"PAS (gumbel)"``, or the strategy alone when the copula family changed
        during the study); use it when composing several results.
    unit : str, optional
        Unit of the HF load for the axis label (e.g. ``"m"``, ``"kN"``).
    quantity : str, default "MPM"
        Name of the predicted quantity for the axis label.
    color : color, optional
        Line colour (default: the Axes' next colour).

    Returns
    -------
    fig : matplotlib.figure.Figure
    ax : matplotlib.axes.Axes

    Notes
    -----
    The x axis counts HF evaluations ``n_c`` (false positives included,
    failed calls not).  The shaded band is ``mpm_low``–``mpm_high`` of each
    fitted iteration: the sampling part of the U95 (the paper's z-draw band,
    Eq. 10); when the copula family changed during the study, each family has
    its own marker shape along the line, named in the legend with the HF
    counts it was used at; the error bar at the last iteration is the reported U95
    (:attr:`ScreeningResult.mpm_band <pas.study.result.ScreeningResult.mpm_band>`,
    sampling and model parts together).  False positives (HF = 0)
    are marked at the MPM of the iteration they interrupted; the
    convergence point is the first iteration meeting the App. C criterion.
    A study that did not converge gets a dashed line at its last sample and
    says why it ended (:func:`stop_text`: budget, failure limit, or not
    converged yet), also as the title of a figure made here (which names
    the convergence point when there is one).  With a precision target the
    figure adds the target ``MPM × (1 ± precision)`` (dotted), the U95 where
    the loop computed it and, for a study short of its target, the forecast
    of the further HF it needs (a bar over its interval from the last sample).  A design-wave
    result (:func:`pas.run_rcw`) is one point at its number of episodes.
    The legend sits under the x axis label, where it covers no curve.

    Examples
    --------
    >>> import numpy as np, pas
    >>> from pas.plotting import plot_mpm_convergence
    >>> lf = np.random.default_rng(0).rayleigh(2.0, 3000)
    >>> res = pas.run_pas(lf, lambda ev: 1.2 * ev.lf ** 1.1, n_waves=3000, p_exp=1e-2,
    ...                   eps1=0.05, seed=1, strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))
    >>> fig, ax = plot_mpm_convergence(res, unit="m")
    >>> ax.get_ylabel()
    'MPM [m]'
    """
    hist = _history(result)
    fitted = _fitted(hist)
    if fitted.empty:
        raise ValueError("result: no fitted iteration yet, nothing to plot")
    own_figure = ax is None
    fig, ax = _new_axes(ax)
    name = _strategy_name(result, label)
    if _is_design(result):
        _design_wave_mpm(ax, result, name, color, unit)
        return _finish_convergence_axes(ax, quantity, unit, truth, own_figure)
    n = fitted["n_hf"].to_numpy(dtype=float)
    banded = _has_band(fitted, "mpm_low", "mpm_high")
    families = _families(fitted)
    if len(families) > 1 and not label:
        name = _strategy_name(result, str(getattr(result, "strategy", "") or "").upper())
    c = _plot_with_band(ax, n, fitted, "mpm", "mpm_low", "mpm_high",
                        "-" if len(families) > 1 else "-o", name=name,
                        label="MPM, shaded: its sampling band (from the HF events drawn)"
                        if banded else "MPM", color=color, ms=2.5, lw=1.3, band_label=None)
    if len(families) > 1:
        _family_marks(ax, fitted, families, c)
    lo, hi = (float(x) for x in getattr(result, "mpm_band", (np.nan, np.nan)))
    mpm = float(getattr(result, "mpm", np.nan))
    if np.isfinite(mpm) and np.isfinite(lo) and np.isfinite(hi):
        ax.errorbar([n[-1]], [mpm], yerr=[[max(mpm - lo, 0.0)], [max(hi - mpm, 0.0)]], fmt="none",
                    ecolor=c, elinewidth=1.0, capsize=4,
                    label=f"{name}: final U95 {lo:.4g}–{hi:.4g}")
    target = (getattr(result, "settings", None) or {}).get("precision")
    if target is not None:
        _precision_marks(ax, result, fitted, float(target), c, name)
    running = pd.to_numeric(hist["mpm"], errors="coerce").ffill().bfill()
    for status, marker, mcolor, text in (
        ("false_positive", "x", _FP_COLOR, "false positive (HF = 0)"),
        ("failed", "v", _FAIL_COLOR, "failed HF call"),
    ):
        sel = (hist["status"] == status).to_numpy()
        if sel.any():
            ax.plot(hist["n_hf"].to_numpy(dtype=float)[sel], running.to_numpy(dtype=float)[sel],
                    ls="none", marker=marker, ms=6, mew=1.5, color=mcolor,
                    label=f"{name}: {text} ×{int(sel.sum())}")
    conv = _convergence_row(hist)
    if conv is not None:
        ax.axvline(float(conv["n_hf"]), color=c, lw=0.9, ls=":")
        ax.plot([float(conv["n_hf"])], [float(conv["mpm"])], marker="*", ms=13, color=c,
                mec="k", mew=0.6, ls="none",
                label=f"{name}: converged at {int(conv['n_hf'])} HF samples, "
                      f"MPM {_fmt(float(conv['mpm']), unit)}")
        if own_figure:
            ax.set_title(f"converged at {int(conv['n_hf'])} HF samples", fontsize=10)
    else:
        stop = stop_text(result)
        ax.axvline(float(hist["n_hf"].max()), color=c, lw=1.2, ls="--",
                   label=f"{name}: {stop}")
        if own_figure:
            ax.set_title(stop, color=_FP_COLOR, fontsize=10)
    return _finish_convergence_axes(ax, quantity, unit, truth, own_figure)


_FAMILY_MARKERS = ("o", "s", "D", "^", "v", "P", "X")


def _families(fitted) -> list:
    """The copula families of the fitted rows, in the order they were first selected."""
    if "family" not in fitted.columns:
        return []
    return list(dict.fromkeys(f for f in fitted["family"] if isinstance(f, str) and f))


def _family_marks(ax, fitted, families, color):
    """A marker shape per copula family at the MPM of each iteration that used it, with the
    iterations it spans in the legend: where the model changed family shows on the line."""
    n = fitted["n_hf"].to_numpy(dtype=float)
    mpm = fitted["mpm"].to_numpy(dtype=float)
    fam = fitted["family"].to_numpy(dtype=object)
    for k, f in enumerate(families):
        sel = fam == f
        ax.plot(n[sel], mpm[sel], _FAMILY_MARKERS[k % len(_FAMILY_MARKERS)], ms=5, mfc="white",
                mec=color, mew=1.1, ls="none",
                label=f"{f} copula ({_spans(n[sel])} HF)")


def _spans(n) -> str:
    """``4–7, 9`` for HF counts 4, 5, 6, 7, 9 (consecutive fitted counts joined)."""
    n = [int(v) for v in n]
    runs, start = [], n[0]
    for a, b in zip(n, n[1:] + [None]):
        if b is None or b != a + 1:
            runs.append(f"{start}" if start == a else f"{start}–{a}")
            start = b
    return ", ".join(runs)


def _precision_marks(ax, result, fitted, target, color, name):
    """A precision study's target (``MPM × (1 ± precision)``, dotted), the U95 where the loop
    computed it (thin bars) and the forecast of further HF from the last sample (a bar over
    its interval, the expected count marked)."""
    n = fitted["n_hf"].to_numpy(dtype=float)
    mpm = fitted["mpm"].to_numpy(dtype=float)
    for sign in (-1.0, 1.0):
        ax.plot(n, mpm * (1.0 + sign * target), ls=":", lw=0.9, color=color,
                label=f"{name}: target MPM ±{100 * target:g} %" if sign > 0 else None)
    if {"model_low", "model_high"} <= set(fitted):
        at = fitted["model_low"].notna().to_numpy()
        if at.any():
            low = np.minimum(fitted["model_low"], fitted["mpm_low"]).to_numpy(dtype=float)[at]
            high = np.maximum(fitted["model_high"], fitted["mpm_high"]).to_numpy(dtype=float)[at]
            ax.errorbar(n[at], mpm[at], yerr=[mpm[at] - low, high - mpm[at]], fmt="none",
                        ecolor="0.35", elinewidth=0.8, capsize=2,
                        label=f"{name}: U95 where the loop computed it")
    _forecast_mark(ax, result, n[-1], float(getattr(result, "mpm", mpm[-1])), color,
                   f"{name}: forecast", target)


def stop_text(result) -> str:
    """Why a study that did not converge ended where it did, for the convergence figure.

    ``"budget reached (max_hf = 20) — not converged"``, ``"stopped by the failure
    limit (11 failed, max_failures = 10) — not converged"``, or ``"not converged at
    N HF samples"`` (a study still running, or stopped by its user or an empty pool).
    """
    settings = getattr(result, "settings", None) or {}
    n_failed, max_failures = int(getattr(result, "n_failed", 0)), settings.get("max_failures")
    if max_failures is not None and n_failed > int(max_failures):
        return (f"stopped by the failure limit ({n_failed} failed, "
                f"max_failures = {int(max_failures)}) — not converged")
    max_hf = settings.get("max_hf")
    gap = ""
    if settings.get("precision") is not None:
        from ..strategies.forecast import relative_half_width

        width = relative_half_width(float(result.mpm), tuple(result.mpm_band))
        if np.isfinite(width):
            gap = f": U95 ±{100 * width:.3g} % against ±{100 * settings['precision']:g} %"
    if max_hf is not None and int(result.n_hf) >= int(max_hf):
        return f"budget reached (max_hf = {int(max_hf)}) — not converged{gap}"
    return f"not converged at {int(result.n_hf)} HF samples{gap}"


def _design_wave_mpm(ax, result, name, color, unit):
    """A design-wave MPM: one point at the episodes it took, with no band to draw."""
    ax.plot([float(result.n_hf)], [float(result.mpm)], "D", ms=7, color=color, mec="k", mew=0.6,
            ls="none", label=f"{name}: MPM {_fmt(float(result.mpm), unit)}, HF of the $P_{{exp}}$ "
                             f"design wave ({int(result.n_hf)} episodes, one per level; no band)")


def _finish_convergence_axes(ax, quantity, unit, truth, own_figure):
    if truth is not None:
        label = f"true MPM {_fmt(float(truth), unit)}"
        if label in ax.get_legend_handles_labels()[1]:
            label = "_" + label
        ax.axhline(float(truth), color="k", lw=1.2, ls="--", label=label)
    ax.set_xlabel("number of HF samples $n_c$ [-]")
    ax.set_ylabel(_with_unit(quantity, unit))
    ax.grid(True, lw=0.3, alpha=0.5)
    _legend_below(ax, grow=own_figure)
    return ax.figure, ax
