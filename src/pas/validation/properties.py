"""Data properties of a validation analogue, beside the paper's where it states them.

What an analogue must share with the paper's data before any strategy is run
on it: the dependence on the pairs a copula sees (Kendall τ,
empirical λ_U and λ_L at q = 0.9, LF over the threshold and HF > 0), the share
of *misses* (HF = 0 for an LF peak in the pool: over the LF threshold, or all
peaks without one) among all pool events and among 50 events spread uniformly
in ``ln d`` (the way PAS's initial samples and MD spread them, paper §2.4–2.5),
the impact rate, the shape β of the truth's Weibull fit, the truth MPM against
Table 4, and the copula family the population pairs favour by AIC.

Paper values (where stated): case 3a at convergence 51 HF samples of which 28
true positives (Fig. 9 caption: 45 % misses); λ_L ≥ λ_U for cases 3–4 and
Gaussian, then Clayton, as selected families (App. F); green-water rates about
3 % (Heavy) and 8 % (Extreme) of encounters (basin rates, project spec); truth
MPMs (Table 4).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..models.copulas import fit_candidates, pseudo_observations
from ..strategies.acquisition import initial_targets, nearest_available
from .registry import get_case

__all__ = ["ln_uniform_sample", "miss_shares", "data_properties", "properties_table",
           "format_properties", "PAPER_PROPERTIES"]

PAPER_PROPERTIES = {
    "3a": {"miss_lnu50": 23 / 51, "impact_rate": 0.03},
    "3b": {"impact_rate": 0.08},
}
"""Properties the paper (or the basin, for the rates) states per sub-case."""
PAPER_FAMILY = "Gaussian, then Clayton"
"""App. F, Fig. 18: the families PAS selected on the paper's data (cases 1–4)."""


def _pool(lf, threshold):
    lf = np.asarray(lf, float)
    return np.ones(lf.size, bool) if threshold is None else lf > threshold


def ln_uniform_sample(lf, threshold=None, n=50):
    """Indices of ``n`` pool events spread uniformly in ``ln d`` (largest LF first).

    The pool is the LF peaks over ``threshold`` (all without one), ranked
    descending so that ``d ∝ rank``; the targets are ``n`` points evenly
    spaced in ``ln d`` from the largest to the smallest peak, each taking the
    nearest event not yet taken — PAS's initial sampling (§2.5) with ``n``
    samples.  Fewer than ``n`` events in the pool: all of them.

    Examples
    --------
    >>> ln_uniform_sample([5.0, 1.0, 4.0, 3.0, 2.0], n=3).tolist()
    [0, 2, 1]
    """
    lf = np.asarray(lf, float)
    idx = np.flatnonzero(_pool(lf, threshold))
    order = idx[np.argsort(-lf[idx], kind="stable")]
    if order.size <= n:
        return order
    ln_d = np.log(np.arange(1, order.size + 1, dtype=float))
    available = np.ones(order.size, bool)
    picked = []
    for target in initial_targets(ln_d, n):
        p = nearest_available(ln_d, available, target)
        available[p] = False
        picked.append(p)
    return order[np.array(picked)]


def miss_shares(lf, hf, threshold=None, n=50):
    """Share of HF = 0 among all pool events and among :func:`ln_uniform_sample`."""
    lf, hf = np.asarray(lf, float), np.asarray(hf, float)
    pool = _pool(lf, threshold)
    if not pool.any():
        return float("nan"), float("nan")
    s = ln_uniform_sample(lf, threshold, n)
    return float(np.mean(hf[pool] == 0)), float(np.mean(hf[s] == 0))


def _aic_family(lf, hf, threshold):
    keep = _pool(lf, threshold) & (np.asarray(hf) > 0)
    if keep.sum() < 10:
        return None, float("nan")
    u, v = pseudo_observations(np.asarray(lf)[keep], np.asarray(hf)[keep])
    aic = {name: f.aic for name, f in fit_candidates(u, v).items()}
    ranked = sorted(aic, key=aic.get)
    return ranked[0], float(aic[ranked[1]] - aic[ranked[0]])


def data_properties(data) -> dict:
    """Properties of one :class:`~pas.validation.CaseData` (module docs), paper values beside.

    Returns
    -------
    dict
        ``case``, ``variant``, ``tau``, ``lambda_u``, ``lambda_l``,
        ``miss_all``, ``miss_lnu50``, ``impact_rate`` (share of ``n_w`` with
        HF > 0; cases 3–4), ``weibull_beta`` (truth fit; cases 3–4),
        ``truth_mpm``, ``paper_truth``, ``truth_vs_paper``, ``family`` and
        ``aic_gap`` (to the runner-up), and ``paper_*`` entries where the
        paper states a value.
    """
    spec = get_case(data.case)
    miss_all, miss_lnu = miss_shares(data.lf, data.hf, data.threshold)
    family, gap = _aic_family(data.lf, data.hf, data.threshold)
    impact = spec.family in "34"
    w = data.info.get("weibull") or {}
    out = {"case": spec.id, "variant": spec.variant, "unit": spec.unit,
           "tau": data.tau, "lambda_u": data.lambda_u, "lambda_l": data.lambda_l,
           "miss_all": miss_all, "miss_lnu50": miss_lnu,
           "impact_rate": float(np.sum(data.hf > 0) / data.n_waves) if impact else float("nan"),
           "weibull_beta": float(w.get("beta", np.nan)),
           "truth_mpm": data.truth_mpm, "paper_truth": spec.paper_truth,
           "truth_vs_paper": data.truth_mpm / spec.paper_truth - 1.0,
           "family": family, "aic_gap": gap}
    paper = PAPER_PROPERTIES.get(spec.paper_id, {})
    out.update({f"paper_{k}": v for k, v in paper.items()})
    out["paper_tail"] = "λ_L ≥ λ_U" if impact else ""
    out["paper_family"] = PAPER_FAMILY
    return out


def properties_table(datasets) -> pd.DataFrame:
    """:func:`data_properties` of each data set (``{case: CaseData}``), one row per case."""
    return pd.DataFrame([data_properties(d) for d in datasets.values()])


def format_properties(table: pd.DataFrame) -> str:
    """The properties as aligned text; the paper's value in brackets where it states one."""
    def pct(v):
        return f"{100 * v:.0f}%" if np.isfinite(v) else "–"

    def with_paper(row, key, fmt):
        own = fmt(row[key])
        ref = row.get(f"paper_{key}", np.nan)
        return f"{own} [{fmt(ref)}]" if isinstance(ref, float) and np.isfinite(ref) else own

    rows = []
    for _, r in table.iterrows():
        rows.append({
            "case": r["case"], "tau": f"{r['tau']:.2f}",
            "λ_U/λ_L": f"{r['lambda_u']:.2f}/{r['lambda_l']:.2f}",
            "miss all": pct(r["miss_all"]),
            "miss ln-d 50": with_paper(r, "miss_lnu50", pct),
            "impact rate": with_paper(r, "impact_rate", lambda v: f"{100 * v:.1f}%"
                                      if np.isfinite(v) else "–"),
            "truth β": f"{r['weibull_beta']:.2f}" if np.isfinite(r["weibull_beta"]) else "–",
            "truth": f"{r['truth_mpm']:.4g}", "paper truth": f"{r['paper_truth']:.4g}",
            "Δ": f"{100 * r['truth_vs_paper']:+.1f}%",
            "AIC family (gap)": f"{r['family']} ({r['aic_gap']:.0f})" if r["family"] else "–",
        })
    text = pd.DataFrame(rows).to_string(index=False)
    brackets = "paper values in brackets; " if "[" in text else ""
    return (text + f"\n[{brackets}paper: λ_L ≥ λ_U on cases 3–4 and "
            f"families {PAPER_FAMILY} (App. F); misses = HF 0 in the LF pool]")
