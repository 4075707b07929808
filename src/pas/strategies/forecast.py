"""How many more HF evaluations a precision target needs: a power law fitted to the band.

The model part of the MPM's U95 (a bootstrap over the evaluated events,
:meth:`pas.strategies.pas.PAS.model_band`) narrows as pairs are added, about
as ``n^-b`` (``b ≈ 1/2`` for a sample statistic).  :func:`forecast_pairs` fits
``ln w = a − b ln n`` to the relative half-widths ``w`` the study measured
over its last two doublings of ``n`` and solves it for the ``n`` at which
``w`` reaches the target.  Three or four bootstrap widths are too few and too
noisy to fit ``b`` alone (measured: 1 in 4 halfway forecasts within a factor
1.5), so the fitted ``b`` is shrunk toward 1/2 by its weight against a prior
of standard deviation :data:`PRIOR_SD` (one width is then enough), and the
level ``a`` is the lowest of the points' (:data:`CENTRE`); the choice was
measured on kept study histories, ``docs/results/precision.md``.  The
interval carries the uncertainty of ``a`` and ``b`` (delta method on
``ln n``).  The stopping rule's own floor — ``k2`` MPMs inside a band the
target allows — is :meth:`pas.strategies.stopping.StoppingRule.forecast`'s.
The sampling part (the z-draw band of Eq. 10) does not narrow with ``n`` — it
is the spread of the realisations given the model — so a target below it is
out of reach however many pairs are added: the forecast is then infinite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = [
    "CENTRE",
    "MIN_POINTS",
    "PRIOR_EXPONENT",
    "PRIOR_SD",
    "SCATTER",
    "SCATTER_DOF",
    "SPAN",
    "Forecast",
    "forecast_pairs",
    "relative_half_width",
]

MIN_POINTS = 3
"""Fewest measured widths the exponent is fitted to (with fewer, the prior's exponent)."""

PRIOR_EXPONENT = 0.5
"""The exponent of ``w ∝ n^-b`` a sample statistic has, the centre of the prior on ``b``."""

PRIOR_SD = 0.2
"""Standard deviation of the prior on ``b``."""

SCATTER = 0.25
"""Scatter of ``ln w`` about the power law assumed before it is measured."""

SCATTER_DOF = 2
"""Degrees of freedom :data:`SCATTER` counts for when pooled with the measured scatter."""

CENTRE = "min"
"""How the level of the power law is taken from the widths (:func:`forecast_pairs`)."""

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

    def at_least(self, n_min: float) -> Forecast:
        """This forecast with ``n_pairs``, ``low`` and ``high`` raised to ``n_min`` (the
        fewest pairs at which the stopping rule can stop, whatever the band does)."""
        return Forecast(max(self.n_pairs, n_min), max(self.low, n_min),
                        max(self.high, n_min), self.exponent)

    def further(self, n_now: int, per_pair: float = 1.0) -> tuple[float, float, float]:
        """``(expected, low, high)`` further evaluations from ``n_now`` pairs, ``per_pair``
        evaluations per pair (more than 1 when some evaluations are false positives)."""
        return tuple(max(0.0, x - n_now) * per_pair for x in (self.n_pairs, self.low, self.high))


def _exponent(x, y, prior_sd: float):
    """``(b, var_b, s2, dof)``: the exponent of ``ln w = a − b x``, its variance, the scatter
    of ``y`` about the line and that scatter's degrees of freedom.

    Three or more points give the least-squares slope; a finite ``prior_sd`` combines it
    with :data:`PRIOR_EXPONENT` (precision-weighted) and pools the scatter with
    :data:`SCATTER` (:data:`SCATTER_DOF` degrees of freedom); with fewer points the
    exponent and the scatter are the prior's.
    """
    k = x.size
    if k < MIN_POINTS or np.ptp(x) == 0:
        return PRIOR_EXPONENT, prior_sd ** 2, SCATTER ** 2, SCATTER_DOF
    dx = x - x.mean()
    sxx = float(np.sum(dx ** 2))
    slope = float(np.sum(dx * (y - y.mean())) / sxx)
    s2 = float(np.sum((y - y.mean() - slope * dx) ** 2) / (k - 2))
    if math.isinf(prior_sd):
        return -slope, s2 / sxx, s2, k - 2
    s2 = ((k - 2) * s2 + SCATTER_DOF * SCATTER ** 2) / (k - 2 + SCATTER_DOF)
    weight_data, weight_prior = sxx / s2, prior_sd ** -2
    b = (-slope * weight_data + PRIOR_EXPONENT * weight_prior) / (weight_data + weight_prior)
    return b, 1.0 / (weight_data + weight_prior), s2, k - 2 + SCATTER_DOF


def forecast_pairs(n, widths, target: float, floor: float = 0.0, *, prior_sd: float = PRIOR_SD,
                   centre: str = CENTRE) -> Forecast | None:
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
    prior_sd : float, default :data:`PRIOR_SD`
        Standard deviation of the prior on the exponent ``b`` (centred on
        :data:`PRIOR_EXPONENT`); ``inf`` fits ``b`` by least squares alone
        (and needs :data:`MIN_POINTS` widths), a small value fixes it.
    centre : {"min", "median", "mean"}, default :data:`CENTRE`
        How the level ``a`` is taken from the points given ``b``: ``"min"``
        the lowest (a bootstrap width errs upward — replicates that fall apart
        widen it, none narrows it — and the rule stops at the first band below
        the target, before the trend reaches it); ``"median"`` ignores one
        wild width.

    Returns
    -------
    Forecast or None
        None without a finite width over the span (or, with ``prior_sd=inf``,
        with fewer than :data:`MIN_POINTS`).

    Examples
    --------
    >>> f = forecast_pairs([10, 20, 40], [0.4, 0.4 / 2 ** 0.5, 0.2], 0.1)
    >>> round(f.n_pairs, 6), round(f.exponent, 6)
    (160.0, 0.5)
    """
    if centre not in ("min", "median", "mean"):
        raise ValueError(f"centre must be 'min', 'median' or 'mean', got {centre!r}")
    n, w = np.asarray(n, dtype=float), np.asarray(widths, dtype=float)
    keep = np.isfinite(w) & (w > 0) & (n >= n[-1] / SPAN) if n.size else n.astype(bool)
    n, w = n[keep], w[keep]
    if n.size == 0 or (math.isinf(prior_sd) and (n.size < MIN_POINTS or np.ptp(n) == 0)):
        return None
    inf = math.inf
    if floor >= target:
        return Forecast(inf, inf, inf, math.nan)
    x, y = np.log(n), np.log(w)
    b, var_b, s2, dof = _exponent(x, y, prior_sd)
    if b <= 0:
        return Forecast(inf, inf, inf, b)
    level = y + b * (x - x.mean())  # ln w at the mean ln n, one value per point
    pick = {"median": np.median, "mean": np.mean, "min": np.min}[centre]
    gap = float(pick(level)) - math.log(target)
    log_n = x.mean() + gap / b
    # the lowest point carries one point's scatter, the mean 1/k of it
    median = math.pi / 2 / n.size if n.size > 2 else 1 / n.size
    spread = s2 * {"mean": 1 / n.size, "median": median}.get(centre, 1.0)
    se = math.sqrt(spread / b ** 2 + (gap / b ** 2) ** 2 * var_b)
    t = float(stats.t.ppf(0.975, max(dof, 1)))
    big = 700.0  # exp() of more overflows: as good as never
    return Forecast(math.exp(min(log_n, big)), math.exp(min(log_n - t * se, big)),
                    math.exp(min(log_n + t * se, big)), b)
