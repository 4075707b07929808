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

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .allocation import curves_of, proxy_ratios, shares
from .combination import extension_bounds, level_at

__all__ = ["LongTermResult"]


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
        ``h_low``, ``h_high`` (the value at each probability and its band).
    contributions : pandas.DataFrame
        One row per sea state: ``sea_state``, ``probability``, ``weight``
        (``p_s ν_s / Σ p ν``), ``share`` of the exceedance at the value,
        ``n_hf``, ``n_false_positive``, ``n_failed``, ``p_exp`` of its study,
        ``mpm`` (short-term MPM at that ``p_exp``), ``mpm_low``, ``mpm_high``,
        ``read_off`` (where its exceedance at the value comes from: ``pas``,
        ``tail`` above its record, ``proxy`` below its PAS range, ``lf`` the
        LF-only proxy of a sea state without a PAS model, ``lf tail`` that
        proxy above its LF record).
    lf_value : float
        The LF-only long-term value of the LF indicator (what chose the studies).
    extension_bounds : tuple of float
        The value with the LF proxy below each PAS range at its lower and
        upper bound (:func:`pas.longterm.combination.extension_bounds`).
    seed : int
    results : dict
        ``name -> ScreeningResult`` of every sea state that has a study.
    target : None
        Reserved for a precision target and forecast (not implemented yet).
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
    target: None = None

    @classmethod
    def build(cls, states, weights, studies, p, lf_value, seed, model_band, top):
        """The result of the studies as they stand."""
        results = {s.name: st.result(model_band=model_band)
                   for s, st in zip(states, studies) if st is not None}
        ratios = proxy_ratios(studies)
        triples = [curves_of(s, st, ratios, model_band=_model(results.get(s.name)))
                   for s, st in zip(states, studies)]
        start = top * ratios[1]
        levels = [[level_at([t[k] for t in triples], weights, q, start) for k in (1, 0, 2)]
                  for q in _probabilities(p)]
        value, low, high = (level_at([t[k] for t in triples], weights, p, start) for k in (1, 0, 2))
        distribution = pd.DataFrame(levels, columns=["h_mean", "h_low", "h_high"])
        distribution.insert(0, "exceedance_probability", _probabilities(p))
        share = shares([t[1] for t in triples], weights, value) if np.isfinite(value) else \
            np.zeros(len(states))
        rows = []
        for s, st, w, sh, t in zip(states, studies, weights, share, triples):
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
                "read_off": _read_off(t[1], value)})
        bounds = extension_bounds([t[1] for t in triples], weights, p, start)
        return cls(value=value, band=(low, high), p_exceed=p,
                   n_hf=sum(st.n_hf for st in studies if st is not None),
                   distribution=distribution, contributions=pd.DataFrame(rows),
                   lf_value=lf_value, extension_bounds=bounds, seed=seed, results=results)

    def summary(self) -> str:
        """A few lines: the value and band, HF spent, the sea states that decide it."""
        lo, hi = self.band
        c = self.contributions.sort_values("share", ascending=False)
        lines = [f"long-term value at p_exceed = {self.p_exceed:.3g} per wave encounter: "
                 f"{self.value:.4g} (U95 {lo:.4g} – {hi:.4g})",
                 f"HF evaluations: {self.n_hf} over {int((c['n_hf'] > 0).sum())} of {len(c)} "
                 f"sea states; LF-only long-term level of the indicator: {self.lf_value:.4g}"]
        for row in c.head(5).itertuples():
            lines.append(f"  {row.sea_state}: share {row.share:.1%}, {row.n_hf} HF, "
                         f"read off {row.read_off}")
        off = c.loc[c["read_off"] != "pas", "share"].sum()
        if off > 0.1:
            lines.append(f"note: {off:.0%} of the exceedance at the value is not read off a PAS "
                         "distribution but off a tail above a record or an LF-only proxy "
                         "(column read_off); with the proxy below the PAS ranges at its bounds "
                         f"the value is {self.extension_bounds[0]:.4g} – "
                         f"{self.extension_bounds[1]:.4g}")
        return "\n".join(lines)


def _model(result):
    return None if result is None else result.mpm_band_model


def _probabilities(p) -> np.ndarray:
    """The probabilities of the distribution: three decades above ``p`` to one below, and ``p``."""
    grid = 10.0 ** np.arange(np.floor(np.log10(p)) - 1, min(np.log10(p) + 3, -0.5), 0.25)
    return np.unique(np.append(grid, p))


def _read_off(curve, x) -> str:
    """Where the sea state's exceedance at ``x`` comes from (:attr:`LongTermResult.contributions`)."""
    if not np.isfinite(x):
        return "none"
    if x > curve.h[0]:
        return "lf tail" if curve.is_proxy else "tail"
    if curve.is_proxy:
        return "lf"
    return "proxy" if x < curve.h_end else "pas"
