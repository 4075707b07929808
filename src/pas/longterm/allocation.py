"""One HF budget shared by the sea states: where the next HF event goes.

The rule, in one paragraph.  The long-term value ``x_N`` solves
``Σ_s w_s Q_s(x_N) = p_exceed``, so a sea state's part in the uncertainty of
``Q(x_N)`` — hence of ``x_N`` — is its share of the exceedance,
``share_s = w_s Q_s(x_N) / Q(x_N)``, times the relative width of its
short-term band at that level, ``width_s = (Q_s^+(x_N) − Q_s^−(x_N)) /
Q_s(x_N)`` (``Q^±`` read off the ends of its U95 band; 1 for a sea state
with no PAS model yet: the LF-only proxy says nothing about the HF load).  A
band fitted to ``n`` events narrows like ``1/√n``, so one more event in sea
state ``s`` narrows the long-term band by about ``gain_s = share_s · width_s
· (1 − √(n_s / (n_s + 1)))``; the next event goes to the sea state with the
largest gain (a new sea state gets its strategy's initial samples at once).
Only sea states that reach the LF-only long-term level — whose LF-only
share there is at least :data:`REACH_SHARE` (:func:`lf_shares`) — get a
study at all, and a sea state whose share at the current value is 0 has no
gain, so neither gets an HF event.  The gains use the
sampling band of each study's last fit (cheap, after every event); the
result's band adds the model band (:mod:`pas.longterm.result`).
"""

from __future__ import annotations

import numpy as np

from ..stats.exceedance import value_at_exceedance
from .combination import PASCurve, RecordBand, proxy_curve

__all__ = ["curves_of", "with_record", "proxy_ratios", "shares", "gains", "lf_shares",
           "REACH_SHARE",
           "UNFITTED_WIDTH"]

UNFITTED_WIDTH = 1.0
"""Relative width of the short-term band of a sea state with no PAS model yet."""


REACH_SHARE = 1e-3
"""A sea state whose LF-only share of the long-term exceedance at the LF-only design level
is below this cannot reach the design level: it gets no study and no HF event."""


def lf_shares(states, weights, lf_level: float) -> tuple[np.ndarray, np.ndarray]:
    """``(share, Q_s)``: each sea state's LF-only share and LF exceedance at ``lf_level``
    (its record, and the Weibull tail above it)."""
    q = np.array([float(proxy_curve(s, 1.0).exceedance(lf_level)[0]) for s in states])
    parts = np.asarray(weights) * q
    return (parts / parts.sum() if parts.sum() > 0 else parts), q


def _hf_lf_ratio(study) -> float:
    """HF over LF at the study's ``p_exp``: the MPM over the LF peak of that exceedance."""
    lf = value_at_exceedance(study.lfset.d, study.lfset.lf, study.lfset.p_exp)
    return float(study.last.mpm / lf) if lf > 0 else float("nan")


def proxy_ratios(studies) -> tuple[float, float, float]:
    """``(low, typical, high)`` HF/LF ratio of the fitted studies (1 when none is fitted)."""
    r = [_hf_lf_ratio(s) for s in studies if s is not None and s.last is not None]
    r = [x for x in r if np.isfinite(x) and x > 0]
    if not r:
        return 1.0, 1.0, 1.0
    return float(min(r)), float(np.median(r)), float(max(r))


def curves_of(state, study, ratios, model_band=None, record=True) -> tuple:
    """``(low, mean, high)`` exceedance curves of one sea state.

    From its study's last PAS distribution and the ends of its U95 band (the
    sampling band, widened to the model band ``(low, high)`` of the MPM
    scaled along the distribution when given), or the LF-only proxy at the
    ``ratios`` when it has no model yet; both ends widened to the spread of
    an exceedance read off a record of its length
    (:class:`~pas.longterm.combination.RecordBand`) unless ``record`` is False
    (the gains: HF events do not narrow that part).
    """
    triple = _band_ends(state, study, ratios, model_band)
    return with_record(state, triple) if record else triple


def with_record(state, triple) -> tuple:
    """``(low, mean, high)`` with both ends widened to the spread of the sea state's record."""
    low, mean, high = triple
    return (RecordBand(low, mean, state.n_waves, -1), mean,
            RecordBand(high, mean, state.n_waves, +1))


def _band_ends(state, study, ratios, model_band):
    pred = None if study is None else study.last
    if pred is None:
        return tuple(proxy_curve(state, r) for r in ratios)
    low, high = np.asarray(pred.h_low, float), np.asarray(pred.h_high, float)
    if model_band is not None and pred.mpm > 0:
        low = np.minimum(low, pred.h_mean * model_band[0] / pred.mpm)
        high = np.maximum(high, pred.h_mean * model_band[1] / pred.mpm)
    lf = pred.columns.get("lf")
    lf_end = lf[-1] if lf is not None else study.lfset.lf[len(pred.d) - 1]
    return tuple(PASCurve(pred.d, h, state, lf_end) for h in (low, pred.h_mean, high))


def shares(curves, weights, x: float) -> np.ndarray:
    """Each sea state's share of the long-term exceedance at ``x`` (mean curves)."""
    parts = np.array([w * float(c.exceedance(x)[0]) for c, w in zip(curves, weights)])
    total = parts.sum()
    return parts / total if total > 0 else parts


def gains(triples, weights, x: float, n_hf, fitted) -> np.ndarray:
    """``gain_s`` of the module's rule for every sea state at the value ``x``."""
    means = [t[1] for t in triples]
    share = shares(means, weights, x)
    out = np.zeros(len(triples))
    for i, (lo, mid, hi) in enumerate(triples):
        width = UNFITTED_WIDTH
        q = float(mid.exceedance(x)[0])
        if fitted[i] and q > 0:
            width = (float(hi.exceedance(x)[0]) - float(lo.exceedance(x)[0])) / q
        n = n_hf[i]
        out[i] = share[i] * max(width, 0.0) * (1.0 - np.sqrt(n / (n + 1.0)))
    return out
