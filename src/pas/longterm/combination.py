"""The long-term exceedance per wave encounter from the short-term distributions of the sea states.

``Q(x) = Σ_s p_s ν_s Q_s(x) / Σ_s p_s ν_s`` (``p_s`` the share of time,
``ν_s`` the encounter rate), the sum over the scatter diagram by which
class rules build the long-term distribution of a response; the design
value solves ``Q(x) = p_exceed``.

Each sea state's ``Q_s`` is the PAS distribution of its study (the mean
distribution and the ends of its U95 band, :class:`PASCurve`), read as an
exceedance per wave encounter on ``ln d``.  PAS predicts ``Q_s`` between the
largest LF peak (``d = 1/n_w``) and the lowest conditioning peak (``d_end``).
Outside that range:

above the record (``d < 1/n_w``)
    a Weibull tail, the least-squares line on ``ln(-ln Q)`` against ``ln x``
    through the top :data:`TAIL_RANKS` ranks of the distribution (exact for a
    Rayleigh or a two-parameter Weibull short-term distribution); where the
    record cannot give it, nothing is exceeded there (``Q_s = 0``);
below the range (``d > d_end``)
    the sea state's own LF exceedance at ``x`` scaled by the ratio HF/LF at
    ``d_end``, continuous there: the LF-only proxy.  It is used at a level
    ``x`` only when ``Q_s(x) > d_end``, and ``Q_s ≥ d_end`` holds whatever the
    proxy says, so the long-term value is bounded from both sides whatever
    the extension: :func:`extension_bounds` computes the value with the
    proxy replaced by ``d_end`` (its lower bound) and by 1 (its upper bound).
    A sea state whose conditioning set reaches below the design level (by
    default every LF peak is in the pool, and MD samples down to the lowest)
    never reads the proxy at the value, and the bounds then coincide with
    the value.

Sea states without a fitted PAS model (no HF events, or too few) use the
LF-only proxy throughout (:func:`proxy_curve`): their LF exceedance at
``x / r``, with ``r`` the HF/LF ratio at the design level of the fitted sea
states (1 before any fit, when the analysis is the LF-only one), and the
same tail above their LF record.
"""

from __future__ import annotations

import numpy as np

from ..strategies.base import Z95

__all__ = ["PASCurve", "proxy_curve", "long_term_exceedance", "level_at", "value_and_band",
           "extension_bounds", "RecordBand",
           "TAIL_RANKS", "GRID_POINTS"]

TAIL_RANKS = 20
"""The top ranks of a distribution whose Weibull-plot line gives the tail above the record."""


class PASCurve:
    """One sea state's HF exceedance per encounter from a PAS distribution ``(d, h)``.

    Parameters
    ----------
    d : array, ascending
        Exceedance probabilities per encounter (``k / n_w``).
    h : array
        The distribution (mean or a band end) at ``d``, non-increasing.
    state : SeaState
        For the LF-only proxy below the range.
    lf_end : float
        The LF peak at ``d[-1]`` (the lowest conditioning peak).
    below : {"proxy", "low", "high"}
        Below the range: the proxy, or its bounds ``d[-1]`` and 1.
    """

    is_proxy = False  #: True for the LF-only proxy (:func:`proxy_curve`)

    def __init__(self, d, h, state, lf_end, below="proxy"):
        self.d = np.asarray(d, dtype=float)
        self.h = np.minimum.accumulate(np.asarray(h, dtype=float))
        self.state, self.lf_end, self.below = state, float(lf_end), below
        self.tail = _weibull_tail(self.d, self.h)
        # np.interp wants ascending abscissae; kept, not rebuilt in every call of exceedance
        self._h_ascending = np.ascontiguousarray(self.h[::-1])
        self._log_d = np.ascontiguousarray(np.log(self.d[::-1]))

    @property
    def h_end(self) -> float:
        """The lowest value PAS predicts (at ``d[-1]``)."""
        return float(self.h[-1])

    def with_below(self, below: str) -> PASCurve:
        """This curve with another rule below the range (:func:`extension_bounds`)."""
        if self.is_proxy:
            return self
        return PASCurve(self.d, self.h, self.state, self.lf_end, below)

    def exceedance(self, x) -> np.ndarray:
        """``Q_s(x)``, the exceedance probability per wave encounter at levels ``x``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        inside = np.exp(np.interp(x, self._h_ascending, self._log_d))
        q = np.where(x > self.h[0], self._above(x), inside)
        under = x < self.h[-1]
        if under.any():
            q[under] = self._under(x[under])
        return q

    def _above(self, x):
        if self.tail is None:
            return np.zeros_like(x)
        a, b = self.tail
        with np.errstate(divide="ignore"):
            return np.exp(-np.exp(a + b * np.log(np.maximum(x, 1e-300))))

    def _under(self, x):
        if self.below == "low":
            return np.full_like(x, self.d[-1])
        if self.below == "high" or self.h_end <= 0 or self.lf_end <= 0:
            return np.full_like(x, 1.0 if self.below == "high" else self.d[-1])
        return np.maximum(self.state.lf_exceedance(x * self.lf_end / self.h_end), self.d[-1])


def _weibull_tail(d, h):
    """``(a, b)`` of the least-squares line ``ln(-ln Q) = a + b ln x`` through the top
    :data:`TAIL_RANKS` ranks, or None when fewer than 3 positive values lie there or the
    line does not fall."""
    top = slice(0, min(TAIL_RANKS, d.size))
    x, q = h[top], d[top]
    keep = (x > 0) & (q < 1)
    if keep.sum() < 3 or np.ptp(x[keep]) <= 0:
        return None
    b, a = np.polyfit(np.log(x[keep]), np.log(-np.log(q[keep])), 1)
    return (float(a), float(b)) if b > 0 else None


def proxy_curve(state, ratio: float, n_points: int = 400) -> PASCurve:
    """The LF-only proxy of a sea state without a PAS model: its LF record scaled by ``ratio``.

    The record's exceedance ``k / n_w`` at the top :data:`TAIL_RANKS` ranks and
    at ``n_points`` ranks spaced on ``ln k`` below (interpolated between them
    on ``ln d``, as a PAS distribution is), with the same Weibull tail above
    the record.
    """
    lf = state.sorted_lf[::-1]
    k = np.unique(np.concatenate([np.arange(1, min(TAIL_RANKS, lf.size) + 1),
                                  np.round(np.geomspace(1, lf.size, n_points)).astype(int)]))
    curve = PASCurve(k / state.n_waves, ratio * lf[k - 1], state, lf[-1])
    curve.is_proxy = True
    return curve


class RecordBand:
    """A band end of one sea state widened to the spread of an exceedance read off its record.

    ``Q_s`` at a level is known from ``n_w`` encounters only: its binomial
    standard deviation ``sqrt(Q_s (1 − Q_s) / n_w)`` is the part of the
    uncertainty no HF event removes (a model that predicted every HF load
    exactly would still carry it).  The band end is the farther of the
    PAS band's end and ``Q_s ± 1.96`` of those deviations (the union, as the
    MPM's band unites its sampling and model parts).
    """

    def __init__(self, end, mean, n_waves: int, side: int):
        self.end, self.mean, self.n_waves, self.side = end, mean, int(n_waves), side

    def exceedance(self, x) -> np.ndarray:
        q = self.mean.exceedance(x)
        spread = Z95 * np.sqrt(q * (1 - q) / self.n_waves)
        if self.side > 0:
            return np.maximum(self.end.exceedance(x), np.minimum(q + spread, 1.0))
        return np.minimum(self.end.exceedance(x), np.maximum(q - spread, 0.0))

    def with_below(self, below: str) -> RecordBand:
        return RecordBand(self.end.with_below(below), self.mean.with_below(below),
                          self.n_waves, self.side)


def long_term_exceedance(curves, weights, x) -> np.ndarray:
    """``Q(x) = Σ_s w_s Q_s(x)`` with ``w_s = p_s ν_s / Σ p ν``."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    return sum(w * c.exceedance(x) for c, w in zip(curves, weights) if w > 0)


GRID_POINTS = 33
"""Levels per narrowing step of :func:`level_at`: each step shrinks the bracket 32-fold."""


def level_at(curves, weights, p: float, start: float) -> float:
    """The level ``x`` where the long-term exceedance falls to ``p``.

    ``start`` is a level of the right order (e.g. the largest LF peak); the
    bracket is widened from it until it holds the level, then narrowed to a
    relative width of 1e-12 by evaluating :data:`GRID_POINTS` levels across
    it at once (every curve reads a vector of levels in one call: 8 calls
    where bisection needs 40).  ``nan`` when no level reaches ``p`` (every
    sea state's exceedance stays below it).
    """
    def q(v):
        return long_term_exceedance(curves, weights, v)

    lo = hi = max(abs(float(start)), 1e-12)
    for _ in range(200):
        if q(lo)[0] >= p:
            break
        lo /= 2
    else:
        return float("nan")
    for _ in range(200):
        if q(hi)[0] < p:
            break
        hi *= 2
    else:
        return float("inf")
    while hi - lo > 1e-12 * hi:
        grid = np.linspace(lo, hi, GRID_POINTS)
        below = np.flatnonzero(q(grid[1:-1]) < p)
        j = below[0] + 1 if below.size else GRID_POINTS - 1
        lo, hi = grid[j - 1], grid[j]
    return 0.5 * (lo + hi)


def value_and_band(triples, weights, p: float, start: float) -> tuple[float, float, float]:
    """``(value, low, high)``: :func:`level_at` of the mean curves and of the band ends of
    ``triples`` (``(low, mean, high)`` curves per sea state; the low exceedance gives the low
    level)."""
    return tuple(level_at([t[k] for t in triples], weights, p, start) for k in (1, 0, 2))


def extension_bounds(curves, weights, p: float, start: float) -> tuple[float, float]:
    """The value with the proxy below each PAS range replaced by its lower and upper bound.

    The lower one is 0 when, with every proxy at its lower bound, no level
    reaches ``p``: nothing below the PAS ranges bounds the value from below then.
    """
    low, high = (level_at([c.with_below(b) for c in curves], weights, p, start)
                 for b in ("low", "high"))
    return (0.0 if np.isnan(low) else low), high
