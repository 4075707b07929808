"""The precision target of a long-term analysis: when to compute its band, the stop, the forecast.

The rule is one sea state's (:mod:`pas.study.precision`, the precision part of
:class:`~pas.strategies.stopping.StoppingRule`), read on the long-term value:
stop once the U95 of the value lies within ``±precision × value`` of it (its
wider side) and the last ``k2`` values of the allocation rounds lie inside it.
The U95 needs every fitted sea state's model band — a bootstrap, seconds of
refits, kept per study until it is told more
(:func:`pas.study.precision.model_band`) — so it is computed only when it can
matter, on the one-sea-state schedule with the HF evaluations of the whole
analysis in place of pairs (:meth:`StoppingRule.band_due
<pas.strategies.stopping.StoppingRule.band_due>`): from
:data:`~pas.strategies.stopping.FIRST_BAND_PAIRS` evaluations on, each time
they grew by :data:`~pas.strategies.stopping.BAND_GROWTH`, and, once the
cheap necessary conditions hold (the band without the model bands and the
window of values within the target), every
:data:`~pas.strategies.stopping.BAND_EVERY` rounds from where the forecast
says the target may be reached.  Every round records the value and its band
without the model bands (each sea state's sampling band and the spread of
its record: :func:`pas.longterm.allocation.curves_of`) in
:attr:`LongTermTarget.rows`, the history a convergence figure draws.

The forecast fits the power law of :mod:`pas.strategies.forecast` to the
U95's relative half-width against the HF evaluations spent; its floor, the
part more HF events do not narrow, is the band without the model bands.  The
band widths are kept in the analysis's store (:data:`BANDS_KEY`), so a
resumed analysis forecasts from all of them; the window of values starts
anew (a resumed analysis needs ``k2`` rounds before it can stop).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..strategies.forecast import relative_half_width
from ..strategies.stopping import StoppingRule

__all__ = ["LongTermTarget", "BANDS_KEY", "K2"]

BANDS_KEY = "longterm_bands"
"""Key of the band widths ``{"n_hf": [...], "halfwidth": [...]}`` in the store's own scope."""

K2 = 20
"""Rounds whose values must lie inside the band (a study's ``k2``)."""


class LongTermTarget:
    """The precision rule of a long-term analysis and the history of its rounds.

    Parameters
    ----------
    precision : float or None
        The target, a fraction of the value (e.g. 0.10); None: no target, the
        history is still kept.
    max_hf : int, optional
        The analysis's budget (for the forecast's "the budget allows").
    k2 : int, default :data:`K2`
    """

    def __init__(self, precision=None, max_hf=None, k2: int = K2):
        if precision is not None:
            precision = float(precision)
            if not (math.isfinite(precision) and 0.0 < precision < 1.0):
                raise ValueError(f"precision must lie in (0, 1), e.g. 0.10 for ±10 % of the "
                                 f"long-term value, got {precision:g}")
        self.precision, self.max_hf = precision, max_hf
        self.rule = StoppingRule(precision=precision, k2=int(k2)) if precision else None
        self.rows: list[dict] = []
        self.reached = False

    def restore(self, stored) -> None:
        """Take the band widths a store kept (``{"n_hf": [...], "halfwidth": [...]}``)."""
        if self.rule is None or not stored:
            return
        for n, w in zip(stored.get("n_hf", []), stored.get("halfwidth", [])):
            self.rule.record_band(int(n), float(w))
        self.rule.band_at[:] = [0] * len(self.rule.band_at)

    def stored(self) -> dict:
        """The band widths to keep in the store (:meth:`restore` reads them)."""
        rule = self.rule
        return {"n_hf": list(rule.band_pairs), "halfwidth": list(rule.band_widths)} if rule \
            else {}

    def record(self, n_hf: int, value: float, sampling, *, lf_only: bool = False) -> dict:
        """The round's history row: the value and its band without the model bands;
        ``lf_only``: no sea state has a PAS model yet, the value is the LF-only proxy's."""
        floor = relative_half_width(value, sampling)
        row = {"n_hf": int(n_hf), "value": float(value), "low_sampling": float(sampling[0]),
               "high_sampling": float(sampling[1]), "halfwidth_sampling": floor,
               "low": np.nan, "high": np.nan, "halfwidth": np.nan, "lf_only": bool(lf_only)}
        self.rows.append(row)
        if self.rule is not None:
            self.rule.mpms.append(float(value))
        return row

    def band_due(self, row) -> bool:
        """Whether this round computes the full band (module docs)."""
        if self.rule is None:
            return False
        gate = self.rule.precision_gate(row["value"], (row["low_sampling"], row["high_sampling"]))
        return self.rule.band_due(row["n_hf"], gate, row["halfwidth_sampling"])

    def judge(self, row, band) -> bool:
        """Record the full band of this round's ``row``; True when the target is reached."""
        rule = self.rule
        width = relative_half_width(row["value"], band)
        row.update(low=float(band[0]), high=float(band[1]), halfwidth=width)
        rule.record_band(row["n_hf"], width)
        gate = rule.precision_gate(row["value"], (row["low_sampling"], row["high_sampling"]))
        self.reached = bool(gate and rule.precision_met(row["value"], band))
        return self.reached

    def forecast(self, n_hf: int, floor: float, extra=None) -> dict | None:
        """Further HF evaluations expected to reach the target (``forecast_hf``,
        ``forecast_hf_low``, ``forecast_hf_high``, ``out_of_reach``, ``sampling_halfwidth``,
        ``max_hf``),
        None without a target; ``extra``: ``(n_hf, halfwidth)`` of a band computed since."""
        if self.rule is None:
            return None
        ahead = self.rule.forecast(floor, extra, n_now=n_hf, may_stop_now=self.reached)
        nan = float("nan")
        out = {"forecast_hf": nan, "forecast_hf_low": nan, "forecast_hf_high": nan}
        if ahead is not None:
            out = dict(zip(out, ahead.further(n_hf)))
        return {**out, "out_of_reach": ahead is not None and not math.isfinite(ahead.n_pairs),
                "sampling_halfwidth": float(floor), "max_hf": self.max_hf}

    def forecast_into(self, row) -> None:
        """Add the forecast made at this round to its ``row`` (with a target)."""
        ahead = self.forecast(row["n_hf"], row["halfwidth_sampling"])
        if ahead is not None:
            row.update({k: ahead[k] for k in FORECAST_COLUMNS})

    def history(self) -> pd.DataFrame:
        """One row per allocation round (:meth:`record`, the full band where computed, the
        forecast made then with a target)."""
        columns = ["n_hf", "value", "low_sampling", "high_sampling", "halfwidth_sampling", "low",
                   "high", "halfwidth", "lf_only",
                   *(FORECAST_COLUMNS if self.rule is not None else ())]
        return pd.DataFrame(self.rows, columns=columns)


FORECAST_COLUMNS = ("forecast_hf", "forecast_hf_low", "forecast_hf_high")
"""The forecast's columns of :meth:`LongTermTarget.history`."""
