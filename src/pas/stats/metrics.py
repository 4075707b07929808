"""Validation metrics M1, M2, M3 (paper §4, Eq. 18–19).

Each takes a :class:`~pas.study.result.ScreeningResult` and the ground truth.
"At convergence" is the last fitted iteration of the result; the averages run
over the last ``n_last`` (10) true-positive iterations up to it.
"""

from __future__ import annotations

import numpy as np

from .exceedance import value_at_exceedance

__all__ = ["m1", "m2", "m3", "metrics"]


def m1(result) -> float:
    """Efficiency ``M1 = n_c / n_w``: HF samples used over wave encounters (Eq. 18)."""
    if not result.n_waves > 0:
        raise ValueError("result.n_waves is 0: M1 needs the wave encounters of the LF "
                         "Monte-Carlo (pass n_waves to the run)")
    return result.n_hf / result.n_waves


def _last_fitted(result, n_last):
    fitted = result.fitted
    if fitted.empty:
        raise ValueError("the result has no fitted iteration; metrics are undefined")
    return fitted.tail(n_last)


def m2(result, h_true: float, *, n_last: int = 10) -> float:
    """Relative MPM error averaged over the last ``n_last`` fitted iterations (Eq. 18)."""
    return float((_last_fitted(result, n_last)["mpm"].mean() - h_true) / h_true)


def m3(result, true_d, true_h, h_true: float, *, n_last: int = 10) -> float:
    """Signed largest deviation from the true distribution over ``[P_exp/2, 2 P_exp]`` (Eq. 19).

    ``true_d`` (ascending) and ``true_h`` describe the true exceedance
    distribution; it is interpolated on ``ln d`` at the stopping grid.
    """
    rows = _last_fitted(result, n_last)["row"]
    curves = result.range_curves.loc[rows]
    grid = np.asarray(curves.columns, dtype=float)
    mean_curve = curves.to_numpy().mean(axis=0)
    delta = mean_curve - value_at_exceedance(true_d, true_h, grid)
    return float(delta[np.argmax(np.abs(delta))] / h_true)


def metrics(result, true_d, true_h, h_true: float, *, n_last: int = 10) -> dict:
    """All three metrics as a dict ``{"M1", "M2", "M3"}``."""
    return {"M1": m1(result), "M2": m2(result, h_true, n_last=n_last),
            "M3": m3(result, true_d, true_h, h_true, n_last=n_last)}
