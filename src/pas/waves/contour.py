"""The environmental-contour design sea state: the industry comparator of a long-term analysis.

The IFORM contour (Winterstein et al. 1993) of a joint Hs-Tz model for a
return period, through virocon (Haselsteiner et al. 2022): the sea states
whose exceedance probability per sea state of ``state_duration`` hours is
``alpha = state_duration / (return_period * 8766)``. The design sea state is
the contour point with the largest short-term response; the rule value is a
fractile of that sea state's short-term maximum (e.g. the MPM, or the 0.9
fractile that compensates for the neglected short-term variability; DNV-RP-
C205 Sec. 3.7.3).

References
----------
Winterstein, S.R., Ude, T.C., Cornell, C.A., Bjerager, P., Haver, S. (1993).
Environmental parameters for extreme response: inverse FORM with omission
factors. ICOSSAR 93, Innsbruck.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .linear_longterm import rayleigh_extreme, short_term_linear
from .scatter import tz_over_tp

__all__ = ["iform_contour", "design_sea_state", "linear_design_sea_state"]


def iform_contour(model, return_period, *, state_duration=3.0, n_points=180, gamma=3.3,
                  period="tz"):
    """Points of the IFORM contour of a virocon joint model ``[Hs, period | Hs]``.

    Parameters
    ----------
    model : virocon.GlobalHierarchicalModel
        E.g. from :func:`pas.waves.scatter.fit_joint_model`.
    return_period : float
        Years.
    state_duration : float, default 3
        Hours per sea state (the model's observation interval).
    n_points : int, default 180
    gamma : float, default 3.3
        JONSWAP peak enhancement of the sea states (converts the period).
    period : {'tz', 'tp'}, default 'tz'
        What the model's second dimension is.

    Returns
    -------
    pandas.DataFrame
        ``name``, ``hs``, ``tz``, ``tp``, ``gamma``, and ``beta`` (the
        reliability index, the same for all points).
    """
    from virocon import IFORMContour, calculate_alpha

    if not return_period > 0 or not state_duration > 0:
        raise ValueError("return_period (years) and state_duration (hours) must be positive")
    if period not in ("tz", "tp"):
        raise ValueError(f"period must be 'tz' or 'tp', got {period!r}")
    contour = IFORMContour(model, calculate_alpha(state_duration, return_period),
                           n_points=int(n_points))
    hs, t = contour.coordinates[:, 0], contour.coordinates[:, 1]
    ratio = tz_over_tp(gamma)
    tz, tp = (t, t / ratio) if period == "tz" else (t * ratio, t)
    return pd.DataFrame({"name": [f"contour{i}" for i in range(hs.size)], "hs": hs, "tz": tz,
                         "tp": tp, "gamma": gamma, "beta": float(contour.beta)})


def design_sea_state(contour, short_term_value):
    """The contour point with the largest short-term value, and all the values.

    Parameters
    ----------
    contour : pandas.DataFrame
        From :func:`iform_contour` (any table of sea states).
    short_term_value : callable
        ``short_term_value(row) -> float`` for a contour row (a linear
        response extreme, or a PAS MPM for a non-linear load).

    Returns
    -------
    design : pandas.Series
        The row of the largest value, with ``value``.
    table : pandas.DataFrame
        The contour with ``value`` added.
    """
    table = contour.copy().reset_index(drop=True)
    table["value"] = [float(short_term_value(row)) for _, row in table.iterrows()]
    if not np.all(np.isfinite(table["value"])):
        raise ValueError("short_term_value returned a non-finite value on the contour")
    return table.loc[int(np.argmax(table["value"]))], table


def linear_design_sea_state(contour, transfer, response, *, duration=3 * 3600.0, fractile=None,
                            heading=180.0):
    """:func:`design_sea_state` with the linear short-term extreme of ``response``.

    The value is :func:`rayleigh_extreme` over ``duration`` seconds (the MPM
    when ``fractile`` is None).
    """
    table = contour.copy()
    table["probability"] = 1.0
    table["heading"] = heading
    table["speed"] = transfer.speed
    moments = short_term_linear(transfer, response, table)
    extremes = rayleigh_extreme(moments["m0"], moments["nu"], duration, fractile=fractile)
    lookup = dict(zip(moments["name"], extremes))
    design, out = design_sea_state(moments.drop(columns=["probability"]),
                                   lambda row: lookup[row["name"]])
    return design, out
