"""The copula selection of a screening result: ΔAIC of every candidate per iteration and the
family selected (van Essen & Seyffert 2026, Fig. 17 and 18).

See :mod:`pas.plotting.figures` for the conventions shared by all figures
(``ax=None`` -> ``(fig, ax)``, units in the axis labels).
"""

from __future__ import annotations

import numpy as np

from ._common import _fitted, _history, _legend_below

__all__ = ["plot_aic", "aic_to_selected"]


def _passed_over(fitted, families, selected, aic):
    """Iterations whose lowest-AIC family was not selected, split by the reason.

    ``(mask, marker, reason)`` for: its fit sat on a parameter bound and was
    not eligible (PAS ``exclude_at_bound``, history column ``ineligible``);
    it was less than ΔAIC below the current family (hysteresis); unknown
    (results written before the history recorded eligibility).
    """
    finite = np.where(np.isnan(aic), np.inf, aic)
    ok = np.isfinite(finite).any(axis=1)
    lowest = np.array(families, dtype=object)[np.argmin(finite, axis=1)]
    passed = ok & (lowest != selected)
    if "ineligible" not in fitted:
        return [(passed, "s", "ΔAIC hysteresis or a parameter at its bound")]
    excluded = np.array([fam in str(x).split() for fam, x in
                         zip(lowest, fitted["ineligible"].fillna("").to_numpy())])
    return [(passed & excluded, "X", "parameter at its bound (not eligible)"),
            (passed & ~excluded, "^", "less than ΔAIC below the current family")]


# -- copula selection (paper Fig. 17 and 18) --------------------------------
def plot_aic(result, *, ax=None, axes=None):
    """ΔAIC of every copula candidate per iteration and the family selected (Fig. 17/18).

    Parameters
    ----------
    result : ScreeningResult
        A PAS result: its history has ``aic_<family>`` and ``family`` columns.
    ax : matplotlib.axes.Axes, optional
        Draw a single panel: the ΔAIC curves, the selected family marked by
        filled markers at 0.
    axes : sequence of two Axes, optional
        Draw two panels: ΔAIC curves (top) and the selected family per
        iteration (bottom).  When neither ``ax`` nor ``axes`` is given, a new
        two-panel figure is made.

    Notes
    -----
    The paper's Fig. 17 draws raw AIC; the curves then lie close together
    (AIC grows with the number of pairs) and hide the few units that decide
    the selection.  Here each candidate is drawn as its AIC minus that of the
    family selected at the same iteration (:func:`aic_to_selected`), so the
    selected one sits at 0 and a dashed line marks ``−delta_aic``, the
    study's hysteresis threshold: a family below it replaces the selected
    one.  The axis ends at 8 ``delta_aic`` above 0; far worse fits run off
    its top (the legend says so).
    Where the family with the lowest AIC is not the one selected, its ΔAIC is
    marked and the legend says why: its fit sat on a parameter bound (e.g.
    Student-t ν = 2), which PAS's ``exclude_at_bound`` makes ineligible, or
    it was less than ΔAIC = 4 below the current family (§2.2 hysteresis).

    Returns
    -------
    fig : matplotlib.figure.Figure
    ax : matplotlib.axes.Axes or ndarray of two Axes
        The single Axes with ``ax=``, otherwise both panels.
    """
    hist = _history(result)
    fitted = _fitted(hist)
    aic_cols = [c for c in hist.columns if c.startswith("aic_")]
    if not aic_cols or fitted.empty:
        raise ValueError("result: no AIC in the history (plot_aic needs a fitted PAS result)")
    if ax is not None and axes is not None:
        raise ValueError("give ax (one panel) or axes (two panels), not both")
    own_figure = ax is None and axes is None
    if ax is not None:
        fig, top, bottom = ax.figure, ax, None
    elif axes is not None:
        top, bottom = axes
        fig = top.figure
    else:
        import matplotlib.pyplot as plt

        fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.0, 6.0), sharex=True,
                                          height_ratios=(2.2, 1.0), layout="constrained")
    n = fitted["n_hf"].to_numpy(dtype=float)
    families = [c[4:] for c in aic_cols]
    selected = fitted["family"].astype(str).to_numpy()
    delta = aic_to_selected(fitted, families)
    threshold = _delta_aic_setting(result)
    colors = {}
    for k, fam in enumerate(families):
        (line,) = top.plot(n, delta[:, k], "-", lw=1.2, label=f"{fam}")
        colors[fam] = line.get_color()
        chosen = selected == fam
        if chosen.any():
            top.plot(n[chosen], delta[chosen, k], "o", ms=3.5, color=line.get_color())
    top.plot([], [], "o", ms=3.5, color="0.3", label="selected family (ΔAIC = 0)")
    top.axhline(-threshold, color="k", lw=1.0, ls="--",
                label=f"ΔAIC = −{threshold:g}: a family this far below replaces the selected one")
    for why, marker, text in _passed_over(fitted, families, selected, delta):
        if why.any():
            k = np.nanargmin(np.where(np.isnan(delta), np.inf, delta), axis=1)[why]
            top.plot(n[why], delta[why, k], marker, ms=6, mfc="none", mew=1.1, color="k",
                     ls="none", label=f"lowest AIC, not selected: {text} ×{int(why.sum())}")
    _cut_far_worse(top, delta, threshold)
    top.set_ylabel("ΔAIC to the selected family [-]\n(AIC − AIC$_{selected}$; lower is better)")
    top.grid(True, lw=0.3, alpha=0.5)
    if bottom is None:
        top.set_xlabel("number of HF samples $n_c$ [-]")
        _legend_below(top, ncol=2, grow=own_figure)
        return fig, top
    idx = {f: i for i, f in enumerate(families)}
    for fam in families:
        sel = selected == fam
        if sel.any():
            bottom.plot(n[sel], np.full(sel.sum(), idx[fam]), "s", ms=4, color=colors[fam],
                        ls="none", label=f"{fam} ×{int(sel.sum())}")
    bottom.set_yticks(range(len(families)), families)
    bottom.set_ylim(-0.6, len(families) - 0.4)
    bottom.set_ylabel("selected copula")
    bottom.set_xlabel("number of HF samples $n_c$ [-]")
    bottom.grid(True, axis="x", lw=0.3, alpha=0.5)
    _legend_below(bottom, *top.get_legend_handles_labels(), ncol=2, grow=own_figure)
    return fig, np.array([top, bottom])


_FAR_WORSE = 8.0
"""ΔAIC axis ends at this many hysteresis thresholds above 0 (far worse fits are cut)."""


def _cut_far_worse(ax, delta, threshold):
    """Keep the ΔAIC axis on the few units around 0 and the threshold that decide."""
    finite = delta[np.isfinite(delta)]
    top = _FAR_WORSE * threshold
    if finite.size and finite.max() > top:
        low = min(float(finite.min()), -threshold)
        ax.set_ylim(low - 0.08 * (top - low), top)
        ax.plot([], [], " ", label=f"ΔAIC above {top:g} cut off at the top (far worse fits)")


def aic_to_selected(fitted, families) -> np.ndarray:
    """ΔAIC of every candidate to the family selected at each fitted iteration.

    Parameters
    ----------
    fitted : pandas.DataFrame
        Fitted history rows with ``family`` and ``aic_<family>`` columns.
    families : sequence of str
        The candidates, in the column order of the result.

    Returns
    -------
    ndarray, shape (n_rows, n_families)
        ``AIC_family − AIC_selected``: 0 for the selected family, negative for
        a family that fits better but was not taken (hysteresis or a bound).
    """
    aic = fitted[[f"aic_{f}" for f in families]].to_numpy(dtype=float)
    index = {f: k for k, f in enumerate(families)}
    rows = np.array([index.get(str(f), -1) for f in fitted["family"]])
    ref = np.where(rows >= 0, aic[np.arange(len(rows)), np.maximum(rows, 0)], np.nan)
    return aic - ref[:, None]


def _delta_aic_setting(result) -> float:
    """The study's hysteresis threshold ΔAIC (PAS ``delta_aic``, §2.2), 4 when unrecorded."""
    settings = getattr(result, "settings", None) or {}
    value = (settings.get("strategy_settings") or {}).get("delta_aic", 4.0)
    return float(value) if value is not None else 4.0
