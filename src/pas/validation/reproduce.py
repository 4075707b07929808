"""Reproduce the paper's validation (Table 4, Fig. 6–8, 16) on the synthetic analogues.

For each case: generate (or load from the cache) the analogue, report its data
properties (:mod:`pas.validation.properties`: dependence, misses, impact
rate, truth against the paper), run PAS — and
AS — with the paper's settings (ε1 per case, ε2 = 0.1, K1 = K2 = 20, the
case's LF threshold) exactly as a user would (LF peaks in, table oracle out),
and the design waves of Dermatis et al. (2025) — ``"rcw"`` (FORM-RCW on the
second-order surrogate) and ``"mler"`` — with the case's episode oracle
(:mod:`.episodes`); score each run with M1, M2, M3 against the truth of the
*full* HF set, and write a Table-4-style CSV and figures.  With
``replications > 1`` PAS and AS are rerun with seeds ``0 … N−1`` on the same
frozen data set and the table reports the median, min and max of M2 and the
medians of the other columns; the design waves are deterministic on a frozen
data set and run once.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pandas as pd

from ..api import make_study
from ..stats.metrics import metrics
from ..study.flat import from_flat
from ..study.settings import DEFAULT_MAX_HF
from .episodes import run_rcw_case
from .generate import generate_case
from .registry import CASE_IDS, get_case

__all__ = ["reproduce", "run_case", "summarise", "PAPER_SETTINGS", "STRATEGIES"]

PAPER_SETTINGS = {"eps2": 0.1, "k1": 20, "k2": 20}
"""Stopping settings of the paper (§5); ε1 and the threshold come from the case."""


STRATEGIES = ("pas", "pas-paper", "as", "rcw", "mler")
"""Strategies :func:`run_case` knows: ``"pas-paper"`` is ``PAS.paper()``; the
design waves ``rcw`` and ``mler`` are deterministic."""
DETERMINISTIC = ("rcw", "mler")


def _strategies():
    """The default strategies: PAS, AS and FORM-RCW."""
    return ("pas", "as", "rcw")


def parse_strategies(text):
    """``"pas,as,rcw"`` -> ``("pas", "as", "rcw")``, checked against :data:`STRATEGIES`."""
    names = tuple(s.strip().lower() for s in str(text).split(",") if s.strip())
    bad = [s for s in names if s not in STRATEGIES]
    if bad or not names:
        raise ValueError(f"strategies: unknown {', '.join(bad) or 'empty list'}; choose from "
                         f"{', '.join(STRATEGIES)} (comma-separated)")
    return names


def run_case(data, *, strategy="pas", seed=0, max_hf=DEFAULT_MAX_HF, settings=None):
    """Run one strategy on a :class:`CaseData` with the paper's stopping settings.

    ``max_hf`` is the HF budget (default 160, as every study; None: none);
    ``settings`` further keyword settings of the PAS runs (e.g.
    ``{"band_marginals": "alternate"}``; AS and the design waves ignore them).
    ``"rcw"``/``"mler"`` run :func:`.episodes.run_rcw_case` (``seed`` and
    ``max_hf`` do not apply: one HF episode per level).

    Returns
    -------
    result : ScreeningResult
    row : dict
        MPM, its U95 band and whether it holds the truth, HF counts, M1–M3 and
        the run time.
    """
    if strategy not in STRATEGIES:
        raise ValueError(f"unknown strategy {strategy!r}; choose from {', '.join(STRATEGIES)}")
    t0 = time.perf_counter()
    if strategy in DETERMINISTIC:
        res = run_rcw_case(data, method="form" if strategy == "rcw" else "mler")
    else:
        res = _run_screening(data, strategy, seed, max_hf, settings or {})
    low, high = (float(b) for b in res.mpm_band)
    row = {"case": data.case, "strategy": strategy, "seed": seed, "mpm": res.mpm,
           "band_low": low, "band_high": high,
           "covered": bool(low <= data.truth_mpm <= high) if np.isfinite(low + high) else None,
           "n_hf": res.n_hf, "n_false_positive": res.n_false_positive,
           "converged": bool(res.converged), "family": res.family,
           "seconds": time.perf_counter() - t0}
    try:
        row.update(metrics(res, data.truth_d, data.truth_h, data.truth_mpm))
    except ValueError:
        row.update({"M1": res.n_hf / res.n_waves, "M2": np.nan, "M3": np.nan})
    return res, row


def _run_screening(data, strategy, seed, max_hf, settings):
    kwargs = data.run_kwargs()
    flat = {**PAPER_SETTINGS, "eps1": kwargs.pop("eps1"), "max_hf": max_hf,
            **(settings if strategy != "as" else {})}
    objects = from_flat(flat, strategy="as" if strategy == "as" else "pas",
                        preset="paper" if strategy == "pas-paper" else None)
    return make_study(objects.pop("strategy"), data.lf_table(), seed=seed, **objects,
                      **kwargs).optimize(data.oracle())


def summarise(runs: pd.DataFrame, datasets: dict) -> pd.DataFrame:
    """Table-4-style summary: one row per case and strategy (medians over replications)."""
    rows = []
    for (case, strat), g in runs.groupby(["case", "strategy"], sort=False):
        spec, data = get_case(case), datasets[case]
        a = g["M2"].abs()
        rows.append({
            "case": case, "strategy": strat.upper(), "unit": spec.unit,
            "truth_mpm": data.truth_mpm, "paper_truth": spec.paper_truth,
            "truth_vs_paper": data.truth_mpm / spec.paper_truth - 1,
            "predicted_mpm": g["mpm"].median(), "hf_samples": g["n_hf"].median(),
            "false_positives": g["n_false_positive"].median(),
            "M1": g["M1"].median(), "M2": g["M2"].median(), "M2_min": g["M2"].min(),
            "M2_max": g["M2"].max(), "abs_M2_median": a.median(), "abs_M2_worst": a.max(),
            "M3": g["M3"].median(), "converged": f"{int(g['converged'].sum())}/{len(g)}",
            "replications": len(g), "tau": data.tau,
            "paper_mpm": {"pas": spec.paper_pas, "pas-paper": spec.paper_pas,
                          "as": spec.paper_as}.get(strat, np.nan),
            "paper_hf_samples": {"pas": spec.paper_pas_n, "pas-paper": spec.paper_pas_n,
                                 "as": spec.paper_as_n}.get(strat, np.nan),
        })
    return pd.DataFrame(rows)


def format_table(table: pd.DataFrame) -> str:
    """The summary as aligned text (values in the case's unit, metrics in %)."""
    cols = ["case", "strategy", "unit", "truth_mpm", "paper_truth", "predicted_mpm", "hf_samples",
            "M1", "M2", "M2_min", "M2_max", "M3", "converged", "tau"]
    t = table[cols].copy()
    for c in ("truth_mpm", "paper_truth", "predicted_mpm"):
        t[c] = t[c].map(lambda v: f"{v:.4g}")
    for c in ("M1", "M2", "M2_min", "M2_max", "M3"):
        t[c] = t[c].map(lambda v: f"{100 * v:+.2f}%" if np.isfinite(v) else "nan")
    t["hf_samples"] = t["hf_samples"].map(lambda v: f"{v:g}")
    t["tau"] = t["tau"].map(lambda v: f"{v:.2f}")
    return t.to_string(index=False)


def reproduce(cases=None, *, replications=1, scale=1.0, out=None, seed=0, strategies=None,
              figures=True, cache=True, progress=None, properties_only=False):
    """Generate the analogues, run the strategies, score them, write table and figures.

    Parameters
    ----------
    cases : sequence of str, optional
        Case ids (default all twelve: the eight paper-like, then the four
        ``-hard`` impact variants).
    replications : int, default 1
        Strategy seeds ``0 … N−1`` per case, on the same frozen data set.
    scale : float, default 1.0
        Fraction of the paper's duration (quick runs: 0.1).
    out : str or Path, optional
        Output folder for ``table.csv``, ``runs.csv`` and the PNG figures.
    seed : int, default 0
        Data-set seed (waves and random parts of the HF models).
    strategies : sequence of str, optional
        Any of :data:`STRATEGIES` (default ``("pas", "as", "rcw")``).
    figures : bool, default True
    cache : bool, default True
        Use the ``.npz`` data cache (:func:`pas.validation.generate_case`).
    progress : callable, optional
        ``progress(str)`` for one line per finished run.
    properties_only : bool, default False
        Generate the data sets and compute their properties, run no strategy.

    Returns
    -------
    dict
        ``table`` (summary DataFrame), ``runs`` (one row per run), ``data``
        (CaseData per case), ``properties`` (data properties, one row per
        case), ``results`` (ScreeningResult of the first replication per case
        and strategy), ``files`` (written paths).
    """
    from .properties import properties_table

    ids = [get_case(c).id for c in (cases or CASE_IDS)]
    strategies = parse_strategies(",".join(strategies or _strategies()))
    replications = int(replications)
    if replications < 1:
        raise ValueError("replications must be >= 1")
    datasets, runs, first = {}, [], {}
    for cid in ids:
        data = datasets[cid] = generate_case(cid, seed=seed, scale=scale, cache=cache)
        for strat in () if properties_only else strategies:
            for r in range(1 if strat in DETERMINISTIC else replications):
                res, row = run_case(data, strategy=strat, seed=r)
                runs.append(row)
                first.setdefault((cid, strat), res)
                if progress:
                    progress(f"{cid} {strat.upper()} seed {r}: MPM {row['mpm']:.4g} "
                             f"(truth {data.truth_mpm:.4g}), {row['n_hf']} HF, "
                             f"M2 {100 * row['M2']:+.1f}%, {row['seconds']:.1f} s")
    props = properties_table(datasets)
    runs_df = pd.DataFrame(runs)
    table = summarise(runs_df, datasets) if runs else pd.DataFrame()
    files = []
    if out is not None:
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        props.to_csv(out / "properties.csv", index=False)
        files.append(out / "properties.csv")
        if runs:
            table.to_csv(out / "table.csv", index=False)
            runs_df.to_csv(out / "runs.csv", index=False)
            files += [out / "table.csv", out / "runs.csv"]
        if figures and runs:
            from .figures import write_figures
            files += write_figures(out, datasets, first, table)
    return {"table": table, "runs": runs_df, "data": datasets, "properties": props,
            "results": first, "files": files}
