"""The four long-term methods side by side on one :class:`~.long_term_data.LongTermData`.

* ``"pas-long-term"`` — :func:`pas.run_long_term`, one HF budget shared by all
  sea states, with the case's LF threshold in every sea state that has enough
  peaks over it (as the uniform allocation: like for like).
* ``"uniform"`` — every kept (contributing) sea state its own
  :func:`pas.run_pas` study with the default budget of 160, at the sea
  state's own target ``p_s = p_exceed Σw / w_s`` (the level where it alone
  would make ``Q = p_exceed``, clipped to ``[2/n_s, 0.1]``), then the same
  combination as the truth over the studies' predicted distributions (mean
  and U95 curves; ``ln d`` linear in the load beyond each curve's end; the
  sea states without a study contribute nothing).
* ``"contour"`` — the environmental-contour method: the IFORM contour of the
  scatter's joint model (Winterstein et al. 1993) at the return period of
  ``p_exceed`` in 3-hour sea states, its worst point by the linear 3-hour MPM
  of a 2-hour LF pilot at 12 contour points, then PAS there at the 3-hour
  extreme's fractile ``α = 0.9`` (DNV-RP-C205 §3.7.3 gives 85–95 %).
* ``"lf-only"`` — the LF (linear) long-term value: the truth's combination
  over the LF peaks (case 2: a moment; case 3: the bow RWE put through the
  quasi-static dam-break load ``C ρ g W h²`` without deflection or impulse).
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from ..api import run_pas
from ..study.settings import Stopping
from ..waves.contour import iform_contour
from . import case_impacts
from .data import table_oracle
from .long_term import (
    ANALOGUES,
    generate_cell,
    joint_model,
    tz_over_tp,
    value_at_exceedance_long_term,
)
from .registry import get_case

__all__ = ["METHODS", "combine_curves", "compare", "run_method"]

METHODS = ("pas-long-term", "uniform", "contour", "lf-only")
FRACTILE = 0.9
MIN_PEAKS_OVER = 4
"""Fewest LF peaks over the case's threshold for a sea state to use it (``run_pas``'s minimum)."""
SEA_STATE_HOURS = 3.0


def _case(data):
    return get_case(ANALOGUES[data.analogue]["case"])


def _pas_kwargs(data):
    spec = _case(data)
    return {"stopping": Stopping(eps1=spec.eps1, eps2=0.1, k1=20, k2=20)}


def _curve_exceedance(x, d, h):
    """``Q_s(x)`` from a predicted curve (``d`` ascending, ``h`` descending): ln d linear in h."""
    d, h = np.asarray(d, float), np.asarray(h, float)
    ok = np.isfinite(d) & np.isfinite(h) & (d > 0)
    d, h = d[ok], h[ok]
    order = np.argsort(h)
    h, ld = h[order], np.log(d[order])
    x = np.atleast_1d(np.asarray(x, float))
    if h.size < 2:
        return np.zeros(x.size)
    tail = max(2, h.size // 10)
    slope = np.polyfit(h[-tail:], ld[-tail:], 1)[0]
    out = np.interp(x, h, ld)
    over = x > h[-1]
    out[over] = ld[-1] + min(slope, 0.0) * (x[over] - h[-1])
    return np.exp(out)


def combine_curves(p, weights, curves):
    """The load where ``Σ_s w_s Q_s(x) / Σ w = p`` for curves ``{s: (d, h)}`` (others Q_s = 0)."""
    total = float(sum(weights.values()))

    def q(x):
        return sum(weights[s] * _curve_exceedance(x, *c)[0] for s, c in curves.items()) / total

    hs = np.concatenate([np.asarray(c[1], float) for c in curves.values()])
    lo, hi = float(np.nanmin(hs)), float(np.nanmax(hs))
    if q(lo) < p:
        return float("nan")
    while q(hi) > p:
        hi = 2.0 * hi if hi > 0 else 1.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if q(mid) > p else (lo, mid)
    return 0.5 * (lo + hi)


def _uniform(data, kept, p_exceed, seed, max_hf):
    w, tot = data.weights, float(sum(data.weights.values()))
    mean, low, high, n_hf, skipped = {}, {}, {}, 0, []
    for s in kept:
        n = int(data.sea_states.set_index("name").loc[s, "n_waves"])
        p_s = float(np.clip(p_exceed * tot / w[s], 2.0 / n, 0.1))
        res, note = _cell_study(data, s, n, p_s, seed, max_hf)
        if res is None:
            skipped.append(f"{s} ({note})")
            continue
        dist = res.distribution
        d = dist["exceedance_probability"].to_numpy()
        mean[s], low[s], high[s] = ((d, dist[c].to_numpy()) for c in ("h_mean", "h_low", "h_high"))
        n_hf += res.n_hf
    value = combine_curves(p_exceed, w, mean)
    band = (combine_curves(p_exceed, w, low), combine_curves(p_exceed, w, high))
    info = {"studies": len(mean)}
    if skipped:
        info["no study"] = ", ".join(skipped)
    return value, band, n_hf, info


def _cell_study(data, s, n, p_s, seed, max_hf):
    """PAS on one cell; without the case's LF threshold when too few peaks exceed it."""
    note = None
    for threshold in dict.fromkeys((_case(data).threshold, None)):
        try:
            lf = pd.DataFrame({"lf": data.lf[s]}, index=list(data.ids[s]))  # ids: the index
            return run_pas(lf, table_oracle(data.hf[s]), n_waves=n, p_exp=p_s,
                           seed=seed, max_hf=max_hf,
                           threshold=threshold, **_pas_kwargs(data)), None
        except ValueError as exc:
            note = str(exc).split(";")[0]
    return None, note


def _contour(data, p_exceed, seed, max_hf):
    a = ANALOGUES[data.analogue]
    t = data.sea_states
    nu_bar = float(np.sum(t["probability"] * t["n_waves"] / t["duration"])
                   / np.sum(t["probability"]))
    years = 1.0 / (p_exceed * nu_bar * 3600.0 * 8766.0)  # return period of p_exceed
    pts = iform_contour(joint_model(), years, state_duration=SEA_STATE_HOURS, n_points=12)
    beta = float(pts["beta"].iloc[0])
    pts = pts[pts["hs"] > np.median(pts["hs"])].reset_index(drop=True)  # the upper half
    pts["tp"] = pts["tz"] / tz_over_tp(a["gamma"])  # the scatter's DNV ratio, as its cells
    pts["name"] = [f"contour{i:02d}" for i in range(len(pts))]
    best, best_mpm = None, -np.inf
    for i, row in pts.iterrows():
        ev = generate_cell(data.analogue, row, 900 + data.seed, 500 + i, 2)
        lf = _lf_load(data.analogue, ev["lf"])
        n3 = ev["lf"].size * SEA_STATE_HOURS * 3600.0 / ev["duration"]
        mpm = float(np.quantile(lf, 1.0 - 1.0 / n3)) if lf.size > n3 else float(lf.max())
        if mpm > best_mpm:
            best, best_mpm = i, mpm
    row = pts.loc[best]
    rate = ev["lf"].size / ev["duration"]          # encounters per second of the pilot
    p_w = 1.0 - FRACTILE ** (1.0 / (rate * SEA_STATE_HOURS * 3600.0))
    hours = int(np.clip(np.ceil(20.0 / (p_w * rate * 3600.0)), 10, 400))  # ~20 events over
    ev = generate_cell(data.analogue, row, 900 + data.seed, 500 + best, hours)
    n = ev["lf"].size
    hf = ev["hf"]
    res = run_pas(ev["lf"], table_oracle(hf), n_waves=n, p_exp=p_w, seed=seed,
                  max_hf=max_hf, threshold=_case(data).threshold, **_pas_kwargs(data))
    return res.mpm, tuple(float(b) for b in res.mpm_band), res.n_hf, {
        "beta": beta, "hs": float(row["hs"]), "tp": float(row["tp"]), "hours": float(hours),
        "hf_mc_at_fractile": float(np.quantile(hf, 1.0 - p_w))}


def _lf_load(analogue, lf):
    """The LF peaks as a load: case 2 as they are; case 3 through the quasi-static dam-break
    load."""
    if analogue == "2":
        return np.asarray(lf, float)
    c = case_impacts.COEFFICIENTS
    h = np.maximum(np.asarray(lf, float) + c["bow_wave"] * ANALOGUES["3"]["speed"] ** 2
                   / (2.0 * 9.81) - c["freeboard"] - c["gw_margin"], 0.0)
    return c["C_gw"] * 1.025 * 9.81 * c["accommodation_width"] * h**2


def _lf_only(data, p_exceed):
    lf = {s: _lf_load(data.analogue, v) for s, v in data.lf.items()}
    return value_at_exceedance_long_term(p_exceed, data.weights, lf), (np.nan, np.nan), 0, {}


def _with_thresholds(data):
    """The sea-state table with the case's LF threshold in every sea state where at least
    :data:`MIN_PEAKS_OVER` peaks exceed it, none elsewhere: the rule of the uniform
    allocation (:func:`_cell_study`), so that both methods screen the same peaks."""
    threshold = _case(data).threshold
    table = data.sea_states.copy()
    if threshold is not None:
        table["threshold"] = [threshold if int(np.sum(data.lf[s] > threshold)) >= MIN_PEAKS_OVER
                              else np.nan for s in table["name"]]
    return table


def _pas_long_term(data, p_exceed, seed, max_hf):
    from ..longterm import run_long_term

    peaks = {s: pd.DataFrame({"lf": data.lf[s], "id": data.ids[s]}) for s in data.lf}
    res = run_long_term(_with_thresholds(data), peaks, data.oracle(), p_exceed=p_exceed,
                        seed=seed, max_hf=max_hf, eps1=_case(data).eps1)
    return res.value, tuple(float(b) for b in res.band), res.n_hf, {}


def run_method(data, method, p_exceed, *, kept=None, seed=0, max_hf=None):
    """Run one method on ``data``; a row with value, band, HF spent, error and wall time.

    ``kept``: the sea states of the uniform allocation (default all); ``max_hf``:
    the budget (default 400 shared for ``"pas-long-term"``, 160 per study otherwise).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    t0 = time.perf_counter()
    if method == "pas-long-term":
        out = _pas_long_term(data, p_exceed, seed, 400 if max_hf is None else max_hf)
    elif method == "uniform":
        out = _uniform(data, list(kept if kept is not None else data.hf), p_exceed, seed,
                       160 if max_hf is None else max_hf)
    elif method == "contour":
        out = _contour(data, p_exceed, seed, 160 if max_hf is None else max_hf)
    else:
        out = _lf_only(data, p_exceed)
    value, band, n_hf, info = out
    truth = data.truth(p_exceed)
    lo, hi = band
    return {"analogue": data.analogue, "data_seed": data.seed, "method": method,
            "p_exceed": p_exceed, "truth": truth, "value": value,
            "error": value / truth - 1.0 if np.isfinite(value) else np.nan,
            "band_low": lo, "band_high": hi,
            "covered": bool(lo <= truth <= hi) if np.isfinite(lo + hi) else None,
            "n_hf": int(n_hf), "seconds": time.perf_counter() - t0,
            "note": "; ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}: {v}"
                              for k, v in info.items())}


def compare(data, p_exceed, *, kept=None, methods=METHODS, seed=0, progress=None):
    """All ``methods`` on one data set: a DataFrame with one row per method."""
    rows = []
    for m in methods:
        rows.append(run_method(data, m, p_exceed, kept=kept, seed=seed))
        if progress:
            r = rows[-1]
            progress(f"{data.analogue} seed {data.seed} {m}: {r['value']:.4g} (truth "
                     f"{r['truth']:.4g}), {r['n_hf']} HF, {r['seconds']:.1f} s")
    return pd.DataFrame(rows)



LONG_TERM_IDS = ("long-term-3", "long-term-2")
"""The ids ``pas reproduce`` knows for the long-term analogues."""
P_VALIDATED = 2e-6
"""The per-encounter exceedance the long-term analogues are validated at."""
KEPT_HOURS = 100
"""One-hour realisations per kept cell at ``scale=1``; the other cells get the pilot's 4."""


def long_term_data(analogue, *, seed=1, scale=1.0, p_exceed=P_VALIDATED, min_share=3e-3,
                   cache=True, progress=None):
    """The data set used by :func:`reproduce_long_term` and the benchmark, and the cell plan."""
    from .long_term_data import generate_long_term, plan_cells

    plan = plan_cells(analogue, p_exceed, min_share=min_share, cache=cache)
    h = max(4, round(KEPT_HOURS * float(scale)))
    pilot = plan.attrs["pilot_hours"]
    hours = {n: (h if k else pilot) for n, k in zip(plan["name"], plan["kept"])}
    data = generate_long_term(analogue, seed=seed, hours=hours, cells=plan, cache=cache,
                              progress=progress)
    return data, plan


def reproduce_long_term(case_id, *, seed=1, scale=1.0, p_exceed=P_VALIDATED, out=None,
                        methods=METHODS, cache=True, progress=None):
    """``pas reproduce long-term-3`` / ``long-term-2``: the four methods on one data set.

    Returns
    -------
    dict
        ``table`` (one row per method), ``plan`` (the scatter cells, kept or
        not, with their estimated shares), ``data`` and ``files``.
    """
    if case_id not in LONG_TERM_IDS:
        raise ValueError(f"unknown long-term case {case_id!r}; choose from "
                         f"{', '.join(LONG_TERM_IDS)}")
    data, plan = long_term_data(case_id[-1], seed=seed, scale=scale, p_exceed=p_exceed,
                                cache=cache)
    kept = list(plan["name"][plan["kept"]])
    table = compare(data, p_exceed, kept=kept, methods=methods, seed=0, progress=progress)
    table.insert(0, "case", case_id)
    files = []
    if out is not None:
        from pathlib import Path
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        table.to_csv(out / f"{case_id}.csv", index=False)
        plan.to_csv(out / f"{case_id}_cells.csv", index=False)
        files += [out / f"{case_id}.csv", out / f"{case_id}_cells.csv"]
    return {"table": table, "plan": plan, "data": data, "files": files}


def format_long_term(table):
    """The comparison table as aligned text."""
    t = table[["case", "method", "truth", "value", "error", "band_low", "band_high", "covered",
               "n_hf", "seconds"]].copy()
    for c in ("truth", "value", "band_low", "band_high"):
        t[c] = t[c].map(lambda v: f"{v:.4g}")
    t["error"] = t["error"].map(lambda v: f"{100 * v:+.1f}%" if np.isfinite(v) else "n/a")
    t["seconds"] = t["seconds"].map(lambda v: f"{v:.1f}")
    return t.to_string(index=False)
