"""How many more HF evaluations a precision target needs: a power law fitted to the band.

The model part of the MPM's U95 (a bootstrap over the evaluated events,
:meth:`pas.strategies.pas.PAS.model_band`) narrows as pairs are added, about
as ``n^-b`` (``b ≈ 1/2`` for a sample statistic).  :func:`forecast_pairs` fits
``ln w = a − b ln n`` by least squares to the relative half-widths ``w`` the
study measured over its last two doublings of ``n`` and solves it for the ``n``
at which ``w`` reaches the target; the interval carries the fit's uncertainty
(delta method on ``ln n``, a Student-t quantile for the few points there are).
The sampling part (the z-draw band of Eq. 10) does not narrow with ``n`` — it
is the spread of the realisations given the model — so a target below it is
out of reach however many pairs are added: the forecast is then infinite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = ["Forecast", "forecast_pairs", "relative_half_width", "MIN_POINTS", "SPAN"]

MIN_POINTS = 3
"""Fewest measured widths a forecast is fitted to."""

SPAN = 4.0
"""The fit uses the widths measured at ``n ≥ n_last / SPAN`` (the last two doublings)."""


def relative_half_width(mpm: float, band) -> float:
    """``max(high − MPM, MPM − low) / |MPM|``: the larger side of ``band`` as a share of the MPM.

    The larger side, not the mean of the two, so a lopsided band is not called
    narrower than its wide side.

    Examples
    --------
    >>> round(relative_half_width(100.0, (95.0, 112.0)), 12)
    0.12
    """
    lo, hi = band
    if not (math.isfinite(mpm) and mpm != 0 and math.isfinite(lo) and math.isfinite(hi)):
        return math.inf
    return max(hi - mpm, mpm - lo) / abs(mpm)


@dataclass(frozen=True)
class Forecast:
    """Pairs at which the band is expected to reach the target, with a 95 % interval.

    ``n_pairs``, ``low`` and ``high`` are numbers of true-positive pairs
    (``inf`` when the band does not narrow or the target lies below its
    sampling part); ``exponent`` is the fitted ``b`` of ``w ∝ n^-b``.
    """

    n_pairs: float
    low: float
    high: float
    exponent: float

    def further(self, n_now: int, per_pair: float = 1.0) -> tuple[float, float, float]:
        """``(expected, low, high)`` further evaluations from ``n_now`` pairs, ``per_pair``
        evaluations per pair (more than 1 when some evaluations are false positives)."""
        return tuple(max(0.0, x - n_now) * per_pair for x in (self.n_pairs, self.low, self.high))


def forecast_pairs(n, widths, target: float, floor: float = 0.0) -> Forecast | None:
    """The power-law forecast of the pairs needed for ``widths`` to reach ``target``.

    Parameters
    ----------
    n : sequence of int
        Pairs at each measurement, increasing.
    widths : sequence of float
        Relative half-width of the narrowing band part at each ``n``.
    target : float
        The precision target (e.g. 0.10).
    floor : float, default 0
        The part that does not narrow (the sampling part's relative
        half-width now); at or above ``target`` the forecast is infinite.

    Returns
    -------
    Forecast or None
        None with fewer than :data:`MIN_POINTS` finite widths over the span.

    Examples
    --------
    >>> f = forecast_pairs([10, 20, 40], [0.4, 0.4 / 2 ** 0.5, 0.2], 0.1)
    >>> round(f.n_pairs, 6), round(f.exponent, 6)
    (160.0, 0.5)
    """
    n, w = np.asarray(n, dtype=float), np.asarray(widths, dtype=float)
    keep = np.isfinite(w) & (w > 0) & (n >= n[-1] / SPAN) if n.size else n.astype(bool)
    n, w = n[keep], w[keep]
    if n.size < MIN_POINTS or np.ptp(n) == 0:
        return None
    inf = math.inf
    if floor >= target:
        return Forecast(inf, inf, inf, math.nan)
    x, y = np.log(n), np.log(w)
    x_mean, y_mean = x.mean(), y.mean()
    sxx = float(np.sum((x - x_mean) ** 2))
    slope = float(np.sum((x - x_mean) * (y - y_mean)) / sxx)
    if slope >= 0:
        return Forecast(inf, inf, inf, -slope)
    gap = math.log(target) - y_mean
    log_n = x_mean + gap / slope
    resid = y - (y_mean + slope * (x - x_mean))
    s2 = float(np.sum(resid ** 2) / (n.size - 2)) if n.size > 2 else 0.0
    se = math.sqrt(s2 / n.size / slope ** 2 + (gap / slope ** 2) ** 2 * s2 / sxx)
    t = float(stats.t.ppf(0.975, max(n.size - 2, 1)))
    big = 700.0  # exp() of more overflows: as good as never
    return Forecast(math.exp(min(log_n, big)), math.exp(min(log_n - t * se, big)),
                    math.exp(min(log_n + t * se, big)), -slope)
