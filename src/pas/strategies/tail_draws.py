"""Long LF records: the top of every realisation without drawing the rest.

Step 9 draws ``z`` realisations of ``n0`` conditional HF values (Eq. 7), and an
iteration reads only the top of each: the MPM at ``P_exp`` and the stopping
range up to ``2 P_exp`` (:func:`~pas.strategies.stopping.range_grid`) need the
``k ≈ 2 P_exp n_w`` largest order statistics
(:func:`~pas.stats.exceedance.order_statistics_read`), a share ``k / n0`` of
the draws.  A draw ``v = C⁻¹(r | u)`` is increasing in its uniform ``r`` for
every copula, and the HF marginal and the clip at zero keep the order, so
``v > v_L`` exactly when ``r > C(v_L | u)``: one evaluation of the conditional
CDF per conditioning peak (:func:`pas.models.conditional_cdf.conditional_cdf`)
tells which of its ``z`` uniforms can reach the top.

:func:`top_draws` picks ``v_L`` so that every realisation expects
``SPARE_SD`` standard deviations more than ``k`` draws above it (estimated on
a stratified subsample of the peaks, then counted exactly), draws only the
uniforms above it with the functions the full draw uses (so the same values)
and checks that the ``k``-th largest of every row lies at or above the HF
value of ``v_L``; where a row falls short it lowers ``v_L`` and tries again,
where nothing would be saved it returns None.  The candidates are chosen at a
level ``MARGIN`` lower in ``1 − v`` than the one checked, so that the rounding
between the closed-form inverse and CDF (~1e-11 relative in ``1 − r``,
tests/models/test_conditional_cdf.py) cannot leave out a draw the check counts
on; the families without a closed-form inverse (Joe, BB1, TLL: pyvinecopulib's
numerical inverse of Joe is off by up to 0.3 % there) draw everything.

The whole distribution (the result's, a plot's) is drawn only when read
(:class:`TailPrediction`); for more than ``ROWWISE_ABOVE`` draws one
realisation at a time, twice, so that no array of the draws' size is alive.
"""

from __future__ import annotations

import functools

import numpy as np

from ..models.conditional_cdf import CLOSED_FORMS, conditional_cdf
from ..stats.exceedance import (
    mpm_of_realisations,
    order_statistics_read,
    value_at_exceedance,
)
from .base import Prediction, band95, read_only
from .steps import EPS, draw_conditional_hf, hf_distribution
from .stopping import range_grid

__all__ = ["top_draws", "full_distribution", "TailPrediction", "predict_from_top",
           "mpm_from_top", "whole_draws"]

MARGIN = 1e-3
"""The candidates' level lies this much lower, relative in ``1 − v``, than the level checked."""

SPARE_SD = 6.0
"""Expected draws above the level per realisation: ``k + SPARE_SD √k + 10``."""

STRATA = 512
"""Peaks of the stratified subsample that estimates the level."""

LEVELS = np.geomspace(2 * EPS, 1.0, 48)
"""The levels ``1 − v_L`` the subsample is evaluated at, before the exact count."""

BLOCK = 256
"""Peaks per block whose conditional CDF is bounded from its ends before it is evaluated."""

ROWWISE_ABOVE = 1 << 21
"""Above this many draws the whole distribution is drawn one realisation at a time."""


def _stratified_tail(copula, u, impact, target: float) -> float | None:
    """The smallest of :data:`LEVELS` whose expected draws above it per realisation reach
    ``target``, from one peak per stratum (geometric in position: fine at the top)."""
    edges = np.unique(np.round(np.geomspace(1, u.size + 1, STRATA + 1)).astype(np.int64)) - 1
    mid = (edges[:-1] + edges[1:] - 1) // 2
    weight = np.diff(edges) * (1.0 if impact is None else impact[mid])
    above = (1.0 - conditional_cdf(copula, np.maximum(1.0 - LEVELS, EPS)[:, None],
                                   u[mid][None, :])) @ weight
    enough = np.flatnonzero(above >= target)
    return None if enough.size == 0 else float(LEVELS[enough[0]])


def top_draws(model, r, q, r_max, k: int, uniforms, *, margin: float = MARGIN
              ) -> np.ndarray | None:
    """The ``k`` largest HF draws of every realisation, ``(z, k)``, each row unordered.

    The values :meth:`FittedModel.draws(r, q) <pas.strategies.steps.FittedModel.draws>`
    gives at those places, drawing only the uniforms that can reach them (module
    docs); ``r_max`` is each peak's largest ``r``, ``uniforms`` the
    :class:`~pas.strategies.random_numbers.PeakUniforms` that drew ``r`` and ``q``
    (:meth:`~pas.strategies.random_numbers.PeakUniforms.q_for`).  None where this saves nothing
    (``k`` a large share of ``n0``, too few impacts to fill the rows) or the family
    has no closed-form inverse (not in :data:`~pas.models.conditional_cdf.CLOSED_FORMS`).
    ``margin``: the relative margin below a checked level (:data:`MARGIN`).
    """
    n0 = r.shape[1]
    target = k + SPARE_SD * np.sqrt(k) + 10.0
    if 4 * target > n0 or model.copula.name.partition("_")[0] not in CLOSED_FORMS:
        return None
    u = np.clip(np.asarray(model.u_cond, float), EPS, 1 - EPS)
    tail = _stratified_tail(model.copula, u, model.impact, target)
    while tail is not None and tail * (1 + margin) < 1 - EPS:
        t_low = _cdf_where_reached(model.copula, 1.0 - tail * (1 + margin), u, r_max, margin)
        top, fewest = _top_above(model, r, q, r_max, t_low, k, 1.0 - tail, uniforms)
        if top is not None:
            return top
        tail *= max(2.0, 1.25 * target / max(fewest, 1))
    return None


def _single_peaked(copula, v: float) -> bool:
    """Whether ``C(v | u)`` has no interior minimum in ``u``, so that on an interval of ``u``
    it is least at an end: monotone for the Gaussian, Clayton, Gumbel and Frank
    copulas (stochastically increasing or decreasing) and their 180° rotations; for
    the Student-t ``T_{ν+1}((y − ρx)/s(x))``, whose argument has slope ``∝ −(ρν + xy)``
    in ``x``, rising then falling where ``y = t_ν⁻¹(v) > 0``."""
    base = copula.name.partition("_")[0]
    return base in ("gaussian", "clayton", "gumbel", "frank") or (base == "student" and v > 0.5)


def _cdf_where_reached(copula, v: float, u, r_max, margin: float = MARGIN) -> np.ndarray:
    """``C(v | u)`` at every peak whose largest uniform may exceed it, 2 elsewhere.

    Blocks of :data:`BLOCK` peaks whose largest uniform lies below the least ``C(v | u)``
    over the block's range of ``u`` (read at its ends, :func:`_single_peaked`; a
    relative ``margin`` below it) are left out: the draws there stay below ``v``.
    """
    v = np.array([v])
    if not _single_peaked(copula, v[0]):
        return conditional_cdf(copula, v, u)
    n0 = u.size
    pad = -n0 % BLOCK
    blocks = np.pad(u, (0, pad), mode="edge").reshape(-1, BLOCK)
    ends = conditional_cdf(copula, v, np.concatenate([blocks.min(axis=1), blocks.max(axis=1)]))
    least = ends.reshape(2, -1).min(axis=0)
    reached = np.pad(r_max, (0, pad)).reshape(-1, BLOCK).max(axis=1) > least - margin * (1 - least)
    where = np.flatnonzero(np.repeat(reached, BLOCK)[:n0])
    t = np.full(n0, 2.0)
    t[where] = conditional_cdf(copula, v, u[where])
    return t


def _top_above(model, r, q, r_max, t_low, k: int, level: float, uniforms):
    """:func:`top_draws` for the uniforms above ``t_low``: ``(top, fewest candidates in a
    row)``, top None when a row has fewer than ``k`` or its ``k``-th largest lies below
    the HF value of ``level`` (a draw left out could be larger)."""
    peaks = np.flatnonzero(r_max > t_low)
    r_peaks = r[:, peaks]
    hit = r_peaks > t_low[peaks]
    if model.impact is not None:  # the others are zeroed: below every candidate
        hit &= uniforms.q_for(q[:, peaks], model.impact[peaks], peaks) < model.impact[peaks]
    rows, cols = np.nonzero(hit)  # row by row
    counts = np.bincount(rows, minlength=r.shape[0])
    if counts.min() < k:
        return None, int(counts.min())
    h = draw_conditional_hf(model.copula, model.u_cond[peaks[cols]], model.hf_marginal,
                            r_peaks[rows, cols]).ravel()
    level = np.clip(np.array([level]), EPS, 1 - EPS)  # as the draws are
    floor = max(float(np.ravel(model.hf_marginal.ppf(level))[0]), 0.0)
    top = np.empty((r.shape[0], k))
    for j, row in enumerate(np.split(h, np.cumsum(counts)[:-1])):
        top[j] = np.partition(row, row.size - k)[row.size - k:]
        if top[j, 0] < floor:  # the k-th largest
            return None, int(counts.min())
    return top, int(counts.min())


def _q(model, q, uniforms, cols, rows=None):
    """The impact uniforms ``model.draws`` reads (None without an impact model)."""
    return None if model.impact is None else uniforms.q_for(q, model.impact[cols], cols, rows)


def _every_draw(model, r, q, uniforms) -> np.ndarray:
    """``model.draws`` of every uniform in ``r`` (shape ``(z, n0)``)."""
    return model.draws(r, _q(model, q, uniforms, np.arange(model.n0)))


def full_distribution(model, r, q, n_waves: int, uniforms, *,
                      rowwise_above: int = ROWWISE_ABOVE):
    """:func:`~pas.strategies.steps.hf_distribution` of ``model.draws(r, q)``.

    Above ``rowwise_above`` draws one realisation at a time (in pieces of
    ``rowwise_above / 8`` peaks), twice (the mean, then the spread about it),
    with the sums numpy's ``mean`` and ``std(ddof=1)`` over the realisations
    take, in their order.
    """
    z, n0 = r.shape
    if r.size <= rowwise_above:
        return hf_distribution(_every_draw(model, r, q, uniforms), n_waves)

    def sorted_row(j):
        h = np.empty(n0)
        for start in range(0, n0, rowwise_above // 8):  # a few MB of temporaries at a time
            cut = slice(start, start + rowwise_above // 8)
            peaks = np.arange(n0)[cut]
            h[cut] = model.draws(r[j:j + 1, cut], _q(model, None if q is None else q[j:j + 1, cut],
                                                     uniforms, peaks, [j]), peaks=cut)[0]
        h.sort()
        return h[::-1]

    mean = np.zeros(n0)
    for j in range(z):
        mean += sorted_row(j)
    mean /= z
    spread = np.zeros(n0)
    for j in range(z if z > 1 else 0):
        dev = sorted_row(j)
        dev -= mean
        dev *= dev
        spread += dev
    spread /= max(z - 1, 1)
    sd = np.sqrt(spread, out=spread)
    return np.arange(1, n0 + 1) / n_waves, mean, *band95(mean, sd)


class TailPrediction(Prediction):
    """A :class:`~pas.strategies.base.Prediction` from the top of each realisation.

    ``mpm``, ``mpm_band`` and :meth:`at` up to the top's last ``d`` read the
    top; ``h_mean``, ``h_low`` and ``h_high`` draw the whole distribution the
    first time they are read (``whole()``: :func:`full_distribution`), the
    same values the full draw gives.
    """

    def __init__(self, p_exp: float, n_waves: int, n0: int, top, whole, record=None,
                 columns=None):
        read = Prediction.read_at(p_exp, *top, record, columns)
        self.mpm, self.mpm_band, self.record, self.columns = (read.mpm, read.mpm_band,
                                                              read.record, read.columns)
        self._top, self._whole, self._n0, self._n_waves = top, whole, int(n0), n_waves
        self._full = None

    @property
    def d(self) -> np.ndarray:
        """``k / n_w`` of every order statistic, made when read (not kept: 12 MB at 1.5 M)."""
        return np.arange(1, self._n0 + 1) / self._n_waves if self._full is None else self._full[0]

    def _distribution(self):
        # read-only: the result's table shares them (result.distribution_frame)
        if self._full is None:
            self._full = tuple(read_only(a) for a in self._whole())
            self._whole = None
        return self._full

    h_mean = property(lambda self: self._distribution()[1], doc="The mean distribution.")
    h_low = property(lambda self: self._distribution()[2], doc="Its U95 band's lower end.")
    h_high = property(lambda self: self._distribution()[3], doc="Its U95 band's upper end.")

    def at(self, p):
        if np.all(np.asarray(p) <= self._top[0][-1]):
            return value_at_exceedance(self._top[0], self._top[1], p)
        return super().at(p)

    def __repr__(self) -> str:
        return (f"TailPrediction(mpm={self.mpm!r}, mpm_band={self.mpm_band!r}, n0={self._n0}, "
                f"top={self._top[0].size})")


def _whole(model, again, n_waves, uniforms):
    return full_distribution(model, *again(), n_waves, uniforms)


def predict_from_top(model, uniforms, lfset, rng, record=None, columns=None) -> Prediction:
    """Steps 9–12 of one iteration for ``model`` with ``uniforms``
    (:class:`~pas.strategies.random_numbers.PeakUniforms`): the top that the MPM and
    the stopping range read, the rest when read (:class:`TailPrediction`)."""
    r, q, r_max, again = uniforms.replayable(model.n0, rng, model.impact is not None)
    k = order_statistics_read(range_grid(lfset.p_exp)[-1], lfset.n_waves, model.n0)
    top = top_draws(model, r, q, r_max, k, uniforms)
    if top is None:
        return Prediction.read_at(lfset.p_exp, *full_distribution(model, r, q, lfset.n_waves,
                                                                  uniforms), record, columns)
    return TailPrediction(lfset.p_exp, lfset.n_waves, model.n0, hf_distribution(top, lfset.n_waves),
                          functools.partial(_whole, model, again, lfset.n_waves, uniforms), record,
                          columns)


def mpm_from_top(model, uniforms, lfset, rng) -> float:
    """The MPM of ``model`` (a band replicate's), from the top of each realisation."""
    r, q, r_max, _ = uniforms.replayable(model.n0, rng, model.impact is not None)
    k = order_statistics_read(lfset.p_exp, lfset.n_waves, model.n0)
    top = top_draws(model, r, q, r_max, k, uniforms)
    if top is None:
        top = _every_draw(model, r, q, uniforms)
    return mpm_of_realisations(top, lfset.n_waves, lfset.p_exp)


def whole_draws(model, uniforms, rng) -> np.ndarray:
    """Every draw of ``model`` (shape ``(z, n0)``), from the uniforms :func:`mpm_from_top` reads."""
    r, q, _, _ = uniforms.replayable(model.n0, rng, model.impact is not None)
    return _every_draw(model, r, q, uniforms)
