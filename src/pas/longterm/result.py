"""The result of a long-term analysis: the design value, its band, the distribution, the sea states.

The band (U95) of the value is propagated from the sea states' bands by
their ends: the low (high) long-term curve sums every sea state's
exceedance read off the low (high) end of its short-term band, and the band
of the value is where those curves cross ``p_exceed``.  The short-term band
of a fitted sea state is its sampling band (Eq. 10 of van Essen & Seyffert
2026) widened to its model band (the bootstrap band of the MPM, scaled along
the distribution).  Taking every sea state at its band end together treats
their errors as fully dependent: for independent studies that is wider
than the band of the sum, exact when one sea state dominates, and needs
only what each study reports (the bootstrap keeps the replicates' MPMs, not
their distributions).  Its coverage is measured in
``tests/longterm/test_coverage.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..strategies.forecast import relative_half_width
from ..study import precision, stop_text
from .allocation import curves_of, proxy_ratios, shares
from .combination import extension_bounds, level_at, value_and_band
from .inputs import REQUIRED_COLUMNS

__all__ = ["LongTermResult", "CONTRIBUTION_COLUMNS"]


@dataclass
class LongTermResult:
    """What :func:`pas.run_long_term` returns.

    Attributes
    ----------
    value : float
        The long-term design value: ``Q(value) = p_exceed``.
    band : tuple of float
        Its U95 (module docs for how it is propagated).
    p_exceed : float
        Long-term exceedance probability per wave encounter of the value.
    n_hf : int
        HF evaluations of all sea states (false positives included, failures not).
    distribution : pandas.DataFrame
        The long-term exceedance: ``exceedance_probability``, ``h_mean``,
        ``h_low``, ``h_high`` (the value at each probability and its band),
        ``proxy_share`` (the share of the exceedance at the level read off the
        LF-only proxy), ``from_proxy`` (that share above 5 %: the level leans
        on the proxy there and the band says nothing about that part) and
        ``proxy_low`` (the level with the proxy's part taken out).
    contributions : pandas.DataFrame
        One row per sea state: ``sea_state``, ``probability``, ``weight``
        (``p_s ν_s / Σ p ν``), ``share`` of the exceedance at the value,
        ``n_hf``, ``n_false_positive``, ``n_failed``, ``p_exp`` of its study,
        ``mpm`` (short-term MPM at that ``p_exp``), ``mpm_low``, ``mpm_high``,
        ``read_off`` (where its exceedance at the value comes from: ``pas``,
        ``tail`` above its record, ``proxy`` below its PAS range, ``lf`` the
        LF-only proxy of a sea state without a PAS model, ``lf tail`` that
        proxy above its LF record), ``fit_seconds`` (wall time of its study's
        fits and model bands in this call, the oracle's time not included),
        then the sea-state table's descriptive columns (``hs``, ``tp`` ...).
    lf_value : float
        The LF-only long-term value of the LF indicator (what chose the studies).
    extension_bounds : tuple of float
        The value with the LF proxy below each PAS range at its lower and
        upper bound (:func:`pas.longterm.combination.extension_bounds`).
    seed : int
    results : dict
        ``name -> ScreeningResult`` of every sea state that has a study.
    precision : float or None
        The precision target the analysis was given (a fraction of the value).
    converged : bool
        True exactly when the analysis stopped on its precision target and
        the band above still meets it (:mod:`pas.longterm.target`); False
        without a target.
    forecast : dict or None
        With a target: ``forecast_hf``, ``forecast_hf_low``,
        ``forecast_hf_high`` (further HF evaluations expected to reach it and
        a 95 % interval; NaN before enough bands were measured),
        ``out_of_reach`` and ``sampling_halfwidth`` (the band's half-width
        without the model bands: the part more HF events do not narrow).
    seconds : float
        Wall time of the whole call (oracle included).
    history : pandas.DataFrame
        One row per allocation round of this call: ``n_hf``, ``value``,
        ``low_sampling``/``high_sampling`` (the band without the model
        bands), ``halfwidth_sampling``, and ``low``/``high``/``halfwidth`` of
        the full band where it was computed (a precision target computes it
        on a schedule, :mod:`pas.longterm.target`); with a target also
        ``forecast_hf``, ``forecast_hf_low``, ``forecast_hf_high``, the
        forecast made at that round.
    """

    value: float
    band: tuple
    p_exceed: float
    n_hf: int
    distribution: pd.DataFrame
    contributions: pd.DataFrame
    lf_value: float
    extension_bounds: tuple
    seed: int
    results: dict = field(default_factory=dict, repr=False)
    precision: float | None = None
    converged: bool = False
    forecast: dict | None = None
    history: pd.DataFrame = field(default_factory=pd.DataFrame, repr=False)
    seconds: float = float("nan")

    @classmethod
    def build(cls, states, weights, studies, p, lf_value, seed, model_band, top, target=None,
              table=None, seconds=None):
        """The result of the studies as they stand (``target``: the
        :class:`~pas.longterm.target.LongTermTarget` of the run; ``table``: the sea-state
        table, for its descriptive columns; ``seconds``: wall time spent in each study's fits
        and bands so far, by position)."""
        seconds = dict(seconds or {})
        if model_band:  # every sea state's band at once, one a core (the same bands)
            for i, wall in precision.model_bands(studies).items():
                seconds[i] = seconds.get(i, 0.0) + wall
        results = {}
        for i, (s, st) in enumerate(zip(states, studies)):
            if st is not None:
                t0 = time.perf_counter()
                results[s.name] = st.result(model_band=model_band)
                seconds[i] = seconds.get(i, 0.0) + time.perf_counter() - t0
        ratios = proxy_ratios(studies)
        triples = [curves_of(s, st, ratios, model_band=_model(results.get(s.name)))
                   for s, st in zip(states, studies)]
        start = top * ratios[1]
        levels = [value_and_band(triples, weights, q, start) for q in _probabilities(p)]
        value, low, high = value_and_band(triples, weights, p, start)
        distribution = pd.DataFrame(levels, columns=["h_mean", "h_low", "h_high"])
        distribution.insert(0, "exceedance_probability", _probabilities(p))
        _mark_proxy(distribution, [t[1] for t in triples], weights, start)
        share = shares([t[1] for t in triples], weights, value) if np.isfinite(value) else \
            np.zeros(len(states))
        rows = []
        for i, (s, st, w, sh, t) in enumerate(zip(states, studies, weights, share, triples)):
            r = results.get(s.name)
            rows.append({
                "sea_state": s.name, "probability": s.probability, "weight": float(w),
                "share": float(sh), "n_hf": 0 if st is None else st.n_hf,
                "n_false_positive": 0 if st is None else st.n_false_positive,
                "n_failed": 0 if st is None else st.n_failed,
                "p_exp": np.nan if st is None else st.lfset.p_exp,
                "mpm": np.nan if r is None else r.mpm,
                "mpm_low": np.nan if r is None else r.mpm_band[0],
                "mpm_high": np.nan if r is None else r.mpm_band[1],
                "read_off": _read_off(t[1], value),
                "fit_seconds": seconds.get(i, 0.0) if st is not None else 0.0})
        bounds = extension_bounds([t[1] for t in triples], weights, p, start)
        n_hf = sum(st.n_hf for st in studies if st is not None)
        converged, forecast = False, None
        if target is not None and target.precision is not None:
            cheap = [curves_of(s, st, ratios) for s, st in zip(states, studies)]
            floor = relative_half_width(value, value_and_band(cheap, weights, p, start)[1:])
            width = relative_half_width(value, (low, high))
            converged = target.reached and target.rule.precision_met(value, (low, high))
            forecast = target.forecast(n_hf, floor, (n_hf, width) if model_band else None)
        return cls(value=value, band=(low, high), p_exceed=p, n_hf=n_hf,
                   distribution=distribution,
                   contributions=_described(pd.DataFrame(rows), table),
                   lf_value=lf_value, extension_bounds=bounds, seed=seed, results=results,
                   precision=None if target is None else target.precision,
                   converged=bool(converged), forecast=forecast,
                   history=pd.DataFrame() if target is None else target.history())

    @property
    def forecast_hf(self) -> stop_text.HFForecast | None:
        """Further HF evaluations expected to reach the precision target: ``(expected, low,
        high)``, 0 once reached, ``inf`` out of reach; None without a target or a forecast yet."""
        return stop_text.hf_forecast(self.forecast)

    def precision_text(self) -> str:
        """The precision target's line of :meth:`summary` (empty without a target)."""
        if self.precision is None:
            return ""
        max_hf = (self.forecast or {}).get("max_hf")
        return stop_text.precision_state(
            relative_half_width(self.value, self.band), self.precision, self.converged,
            self.forecast, None if max_hf is None else max_hf - self.n_hf, of="the value",
            words=("precision reached", "precision NOT reached"), floor_name=FLOOR_NAME)

    def summary(self, unit: str | None = None) -> str:
        """A few lines: the value and band, HF spent, the sea states that decide it.

        ``unit`` (e.g. ``"kN"``) is appended to the value and its bands.
        """
        lo, hi = self.band
        u = f" {unit}" if unit else ""
        c = self.contributions.sort_values("share", ascending=False)
        lines = [f"long-term value at p_exceed = {self.p_exceed:.3g} per wave encounter: "
                 f"{self.value:.4g}{u} (U95 {lo:.4g} – {hi:.4g}{u})",
                 f"HF evaluations: {self.n_hf} over {int((c['n_hf'] > 0).sum())} of {len(c)} "
                 f"sea states; LF-only long-term level of the indicator: {self.lf_value:.4g}"]
        if self.precision is not None:
            lines.append(self.precision_text())
        if np.isfinite(self.seconds):
            busy = c.sort_values("fit_seconds", ascending=False).iloc[0]
            lines.append(f"wall time {self.seconds:.1f} s, of it {c['fit_seconds'].sum():.1f} s in "
                         f"the sea states' fits and model bands (most: {busy['sea_state']}, "
                         f"{busy['fit_seconds']:.1f} s)")
        for row in c.head(5).itertuples():
            lines.append(f"  {row.sea_state}: share {row.share:.1%}, {row.n_hf} HF, "
                         f"read off {row.read_off}")
        off = c.loc[c["read_off"] != "pas", "share"].sum()
        if off > 0.1:
            lines.append(f"note: {off:.0%} of the exceedance at the value is not read off a PAS "
                         "distribution but off a tail above a record or an LF-only proxy "
                         "(column read_off); with the proxy below the PAS ranges at its bounds "
                         f"the value is {self.extension_bounds[0]:.4g} – "
                         f"{self.extension_bounds[1]:.4g}{u}")
        return "\n".join(lines)


CONTRIBUTION_COLUMNS = ("sea_state", "probability", "weight", "share", "n_hf", "n_false_positive",
                        "n_failed", "p_exp", "mpm", "mpm_low", "mpm_high", "read_off",
                        "fit_seconds")
"""The columns of :attr:`LongTermResult.contributions` before the table's descriptive ones."""

FLOOR_NAME = "the band without the model bands (the sea states' sampling bands and records)"
"""What the part of the long-term band that more HF events do not narrow is called in a summary."""


def _described(contributions, table):
    """The contributions with the sea-state table's descriptive columns, in table order."""
    if table is None:
        return contributions
    extra = [c for c in table.columns if c not in (*REQUIRED_COLUMNS, "probability", "threshold")]
    if not extra:
        return contributions
    described = table[["name", *extra]].assign(name=table["name"].astype(str))
    return contributions.merge(described.rename(columns={"name": "sea_state"}), on="sea_state",
                               how="left", suffixes=("", "_table"))


def _model(result):
    return None if result is None else result.mpm_band_model


PROXY_SHARE_LIMIT = 0.05
"""Share of the exceedance at a level read off the LF-only proxy above which the level is
marked ``from_proxy``: the U95 band there covers the PAS part only."""


class _NoExceedance:
    def exceedance(self, x):
        return np.zeros_like(np.atleast_1d(np.asarray(x, dtype=float)))


def _mark_proxy(distribution, curves, weights, start) -> None:
    """Add ``proxy_share`` (the share of the exceedance at each level read off the LF-only
    proxy: a sea state without a PAS model, or below its PAS range), ``from_proxy`` (that
    share above :data:`PROXY_SHARE_LIMIT`) and ``proxy_low`` (the level with the proxy's part
    taken out: what the PAS parts alone bound it to, 0 when they never reach the
    probability)."""
    w = np.asarray(weights, dtype=float)
    share = []
    for h in distribution["h_mean"].to_numpy(dtype=float):
        if not np.isfinite(h):
            share.append(np.nan)
            continue
        parts = np.array([wi * float(c.exceedance(h)[0]) for c, wi in zip(curves, w)])
        proxy = np.array([_read_off(c, h) in ("proxy", "lf", "lf tail") for c in curves])
        total = parts.sum()
        share.append(float(parts[proxy].sum() / total) if total > 0 else 0.0)
    without = [_NoExceedance() if c.is_proxy else c.with_below("low") for c in curves]
    low = np.array([level_at(without, w, q, start)
                    for q in distribution["exceedance_probability"]], dtype=float)
    distribution["proxy_share"] = share
    distribution["from_proxy"] = distribution["proxy_share"].to_numpy(float) > PROXY_SHARE_LIMIT
    distribution["proxy_low"] = np.where(np.isnan(low), 0.0, low)


def _probabilities(p) -> np.ndarray:
    """The probabilities of the distribution: three decades above ``p`` to one below, and ``p``."""
    grid = 10.0 ** np.arange(np.floor(np.log10(p)) - 1, min(np.log10(p) + 3, -0.5), 0.25)
    return np.unique(np.append(grid, p))


def _read_off(curve, x) -> str:
    """Where the sea state's exceedance at ``x`` comes from
    (:attr:`LongTermResult.contributions`)."""
    if not np.isfinite(x):
        return "none"
    if x > curve.h[0]:
        return "lf tail" if curve.is_proxy else "tail"
    if curve.is_proxy:
        return "lf"
    return "proxy" if x < curve.h_end else "pas"
