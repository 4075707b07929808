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
iterations passed ``Ē < ε1`` (measured in ``docs/explanation/departures.md``).  The
window change asks that the distribution has moved less than ``ε1`` over the
whole window.  For a steady drift it is ``K1`` times stricter than Eq. 28 with
the same ``ε1``.  App. C's Eq. 30 prints the windows as 50 while its text says 20;
the defaults follow the text.

``precision`` (beyond the paper, scale-free) stops on the band instead: when
the U95 of the MPM lies within ``±precision × MPM`` of it, read
conservatively as ``max(high − MPM, MPM − low) ≤ precision × MPM``, and the
last ``K2`` MPMs lie inside that band.  The U95 is the union of the sampling
part (Eq. 10) and the model part (a bootstrap, seconds of refits), so the
model part is computed only when it can matter (:meth:`StoppingRule.band_due`):
at ``n ≥ FIRST_BAND_PAIRS`` pairs and whenever the pairs grew by
``BAND_GROWTH`` since the last one (the widths the forecast of
:mod:`pas.strategies.forecast` is fitted to), and, once the cheap necessary
conditions hold (the sampling part and the window within the target), every
``BAND_EVERY`` fitted iterations from where the forecast says the target may
be reached (the larger of its lower end and its expected pairs / ``BAND_GROWTH``).  With ``eps1``
and ``precision`` both given both rules
must hold; with ``eps1`` alone the rule above is unchanged.  ``fit_check``
(the study's, :func:`pas.study.precision.judge`): where the cheap conditions
hold, the fitted model must also pass :func:`pas.stats.fit_check.uniform_check`
on the evaluated loads at that level, else that fit computes no band and
cannot stop the study.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .forecast import Forecast, forecast_pairs, relative_half_width

__all__ = ["range_grid", "distribution_change", "StoppingRule", "FIRST_BAND_PAIRS",
           "BAND_GROWTH", "BAND_EVERY"]

FIRST_BAND_PAIRS = 10
"""Pairs at which a precision study first computes the model band."""

BAND_GROWTH = 1.5
"""A precision study computes the model band again once its pairs grew by this factor."""

BAND_EVERY = 3
"""Fitted iterations between model bands once the cheap conditions of the precision rule hold."""


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
    ``(E, E_bar, COV, stop)``, ``stop`` by ``eps1`` and ``eps2`` (True without
    ``eps1``).  With ``precision`` the study then asks :meth:`band_due`,
    records a computed model band with :meth:`record_band` and stops when
    :meth:`precision_met` holds too.
    """

    eps1: float | None = None
    eps2: float = 0.1
    k1: int = 20
    k2: int = 20
    measure: str = "window"
    precision: float | None = None
    fit_check: float | None = 0.01
    changes: list = field(default_factory=list)
    mpms: list = field(default_factory=list)
    curves: list = field(default_factory=list)
    band_pairs: list = field(default_factory=list)
    band_widths: list = field(default_factory=list)
    band_at: list = field(default_factory=list)

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
        if self.eps1 is None:
            return e, e_bar, cov, True
        stop = bool(j >= self.min_iterations and e_bar < self.eps1 and cov < self.eps2)
        return e, e_bar, cov, stop

    # -- the precision target ------------------------------------------------
    def _window_within(self, low: float, high: float) -> bool:
        window = self.mpms[-self.k2:]
        return len(self.mpms) >= self.k2 and all(low <= m <= high for m in window)

    def precision_gate(self, mpm: float, sampling_band) -> bool:
        """The cheap necessary conditions of :meth:`precision_met`: ``K2`` MPMs, the sampling
        part of the band and the window within ``±precision × MPM`` (the U95 holds the
        sampling part, and lies within that range when it meets the target)."""
        if self.precision is None:
            return False
        reach = self.precision * abs(mpm)
        return (relative_half_width(mpm, sampling_band) <= self.precision
                and self._window_within(mpm - reach, mpm + reach))

    def precision_met(self, mpm: float, band) -> bool:
        """True when ``band`` (the U95) lies within ``±precision × MPM`` of ``mpm`` and the
        last ``K2`` MPMs inside it."""
        return (self.precision is not None
                and relative_half_width(mpm, band) <= self.precision
                and self._window_within(*band))

    def band_due(self, n_pairs: int, gate: bool, floor: float) -> bool:
        """Whether this iteration computes the model band (module docs); ``gate``:
        :meth:`precision_gate` and the ``eps1`` rule hold; ``floor``: the sampling part's
        relative half-width."""
        if self.precision is None or n_pairs < FIRST_BAND_PAIRS:
            return False
        if not self.band_pairs or n_pairs >= BAND_GROWTH * self.band_pairs[-1]:
            return True
        if not gate or len(self.mpms) - self.band_at[-1] < BAND_EVERY:
            return False
        ahead = self.forecast(floor, n_now=n_pairs, may_stop_now=True)
        # the interval of a fit to a few widths is wide: its lower end alone would compute
        # the band at nearly every such iteration; the growth schedule bounds a late forecast
        return ahead is None or n_pairs >= max(ahead.low, ahead.n_pairs / BAND_GROWTH)

    def record_band(self, n_pairs: int, width: float) -> None:
        """Keep the relative half-width of the narrowing band part computed at ``n_pairs``."""
        self.band_pairs.append(int(n_pairs))
        self.band_widths.append(float(width))
        self.band_at.append(len(self.mpms))

    def fewest_more_fits(self) -> int:
        """Fewest further fitted iterations before :meth:`precision_met` can hold.

        It needs ``K2`` MPMs, and a band of half-width ``≤ precision × MPM'`` around
        the MPM ``MPM'`` then holding the MPMs of the window: the ones of today
        that stay in it span at most ``2 precision MPM' ≤ 2 precision min / (1 −
        precision)`` (for positive MPMs), so the ones that span more must first
        leave it, one per fit.
        """
        p, window = self.precision, self.mpms[-self.k2:]
        fewest = max(self.k2 - len(self.mpms), 0)
        if p is None or p >= 1:
            return fewest
        for more in range(fewest, self.k2 + 1):
            kept = window[len(window) - (self.k2 - more):] if more < self.k2 else []
            low = min(kept, default=0.0)
            if low <= 0 or max(kept) - low <= 2 * p * low / (1 - p):
                return more
        return self.k2

    def forecast(self, floor: float = 0.0, extra=None, n_now: int | None = None,
                 may_stop_now: bool = False) -> Forecast | None:
        """:func:`~pas.strategies.forecast.forecast_pairs` of the recorded widths (and an
        ``extra`` ``(n_pairs, width)`` measured since) against ``precision``; with the
        pairs ``n_now``, never fewer than ``n_now`` plus :meth:`fewest_more_fits` (one
        pair per fitted iteration), and at least one more unless the rule ``may_stop_now``
        (it held at this fit, or :meth:`band_due` asks whether a band now could meet it)."""
        n, w = list(self.band_pairs), list(self.band_widths)
        if extra is not None and (not n or extra[0] > n[-1]):
            n.append(extra[0])
            w.append(extra[1])
        ahead = forecast_pairs(n, w, self.precision, floor) if self.precision else None
        if ahead is None or n_now is None:
            return ahead
        return ahead.at_least(n_now + max(self.fewest_more_fits(), 0 if may_stop_now else 1))
