"""The two-part stopping criterion (paper §2.6, App. C, Eq. 28–30).

Only true-positive iterations count.  ``E(j)`` is the mean absolute change of
the predicted distribution over ``d ∈ [P_exp/2, 2 P_exp]`` between successive
iterations; ``Ē`` its mean over the last ``K1`` iterations; ``C`` the
coefficient of variation (population standard deviation over mean) of the last
``K2`` MPMs.  Stop when ``Ē < ε1`` and ``C < ε2``, never before ``K1/3``
iterations.

``measure="window"`` (the package default, beyond the paper) takes for ``Ē``
the largest change of the distribution *across* the window instead,
``max_i mean |h*_j − h*_i|`` over the last ``K1`` iterations ``i`` (before
``K1`` exist, over the ``L`` available ones times ``K1/L``): a drift and a
back-and-forth between curves both count.  Eq. 28's per-step change
was tuned for conditional draws redrawn every iteration, whose noise kept it
high until the model settled; with common random numbers (each LF peak keeps
its uniforms) a step changes the distribution only by what one more pair
teaches, so a model still drifting by several per cent over twenty
iterations passed ``Ē < ε1`` (measured in ``docs/departures.md``).  The
window change asks that the distribution has moved less than ``ε1`` over the
whole window.  For a steady drift it is ``K1`` times stricter than Eq. 28 with
the same ``ε1``.  App. C's Eq. 30 prints the windows as 50 while its text says 20;
the defaults follow the text.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["range_grid", "distribution_change", "StoppingRule"]


def range_grid(p_exp: float, n: int = 41) -> np.ndarray:
    """Exceedance probabilities spanning ``[P_exp/2, 2 P_exp]``, uniform on ``ln d``.

    Distributions are compared on this fixed grid (interpolated on ``ln d``)
    because the conditioning set, and with it the native grid ``k / n_w``,
    changes when the lowest selected LF peak changes.
    """
    return np.geomspace(p_exp / 2.0, 2.0 * p_exp, n)


def distribution_change(h_prev, h_new) -> float:
    """``E(j) = mean |h*_j − h*_{j−1}|`` over the range grid (Eq. 28)."""
    return float(np.mean(np.abs(np.asarray(h_new) - np.asarray(h_prev))))


@dataclass
class StoppingRule:
    """Running state of the App. C criterion.

    Call :meth:`update` once per true-positive iteration with that iteration's
    distribution on :func:`range_grid` and its MPM; it returns the measures
    ``(E, E_bar, COV, stop)``.
    """

    eps1: float
    eps2: float = 0.1
    k1: int = 20
    k2: int = 20
    measure: str = "window"
    changes: list = field(default_factory=list)
    mpms: list = field(default_factory=list)
    curves: list = field(default_factory=list)

    def __post_init__(self):
        if self.measure not in ("window", "step"):
            raise ValueError(f"stop_measure must be 'window' or 'step', got {self.measure!r}")

    @property
    def min_iterations(self) -> int:
        return math.ceil(self.k1 / 3)

    def update(self, h_range, mpm: float):
        h_range = np.asarray(h_range, dtype=float)
        last = self.curves[-1] if self.curves else None
        e = distribution_change(last, h_range) if last is not None else float("nan")
        if last is not None:
            self.changes.append(e)
        self.curves.append(h_range)
        del self.curves[:-(self.k1 + 1)]
        self.mpms.append(float(mpm))
        if not self.changes:
            e_bar = float("nan")
        elif self.measure == "step":
            e_bar = float(np.mean(self.changes[-self.k1:]))
        else:  # across the window; over fewer steps, scaled up to K1 of them
            lag = len(self.curves) - 1
            e_bar = max(distribution_change(c, h_range) for c in self.curves[:-1]) * self.k1 / lag
        window = np.asarray(self.mpms[-self.k2:])
        cov = float(np.std(window) / abs(np.mean(window))) if np.mean(window) != 0 else float("inf")
        j = len(self.mpms)
        stop = bool(j >= self.min_iterations and e_bar < self.eps1 and cov < self.eps2)
        return e, e_bar, cov, stop
