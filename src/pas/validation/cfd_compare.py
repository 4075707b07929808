"""The CFD case's comparison: strategies against the brute-force CFD truth, from the CFD table.

Every strategy reads the same CFD results (``data/cfd_green_water.csv``), so
this runs in seconds and says what each strategy would have asked of the
solver and what it would have answered:

* PAS with the defaults and with the paper's preset, and AS, over strategy
  seeds, with the LF threshold at the table's cut (every event above it was
  run in CFD);
* the industry habit: the ``N`` largest LF events run in CFD (``N`` = the
  median HF count of PAS), their loads ranked as if the LF ranks held
  (``d = k / n_w``) and read at ``p_exp`` on ``ln d``;
* a design wave: the MLER wave of the linear crest MPM run in the same tank
  (``data/cfd_green_water_design.csv``), its load taken as the MPM.

CFD hours are the number of events a strategy asked for times the table's
median wall time of one run (one core each).
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from ..stats.exceedance import exceedance_probabilities, value_at_exceedance
from .case_cfd import CFD_CASE, cfd_cut, cfd_lf_record, cfd_table, cfd_truth

__all__ = ["EPS1", "compare_cfd", "summarise_cfd", "top_n_estimate"]

EPS1 = 5000.0
"""Stopping limit of the comparison (N/m): 2 % of 250 kN/m, the wall-force scale of the
first CFD runs of this tank, chosen before the truth was known."""


def top_n_estimate(events, table, n, n_waves, p_exp, *, load=CFD_CASE.load):
    """The top-N habit: the ``n`` largest LF events' loads ranked as ``d = k / n_w`` and
    read at ``p_exp`` on ``ln d`` (the largest exceedance beyond them is extrapolated
    linearly on ``ln d`` from the last two)."""
    top = events.nlargest(n, "lf")["id"]
    loads = table.set_index("id").loc[top, load].to_numpy(float)
    d, h = exceedance_probabilities(loads, n_waves)
    if p_exp <= d[-1]:
        return float(value_at_exceedance(d, h, p_exp)), list(top)
    slope = (h[-1] - h[-2]) / (np.log(d[-1]) - np.log(d[-2]))
    return float(h[-1] + slope * (np.log(p_exp) - np.log(d[-1]))), list(top)


def _hours(table, ids):
    """CFD hours of ``ids`` runs at the table's median wall time per run (the per-run times
    were taken on a machine shared with other work, so their median stands for each)."""
    return float(len(set(ids)) * table["wall_seconds"].median() / 3600.0)


def compare_cfd(*, seeds=range(5), max_hf=160, strategies=("pas", "paper", "as")):
    """One row per strategy run (and one for the top-N habit and the design wave).

    Returns
    -------
    runs : pandas.DataFrame
        ``strategy``, ``seed``, ``mpm``, ``lo``, ``hi``, ``error`` (against the
        truth), ``holds`` (the U95 holds the truth), ``n_hf``, ``cfd_hours``,
        ``converged``.
    facts : dict
        ``truth``, ``n_waves``, ``p_exp``, ``cut`` (the LF threshold),
        ``n_cfd`` (events in the table), ``truth_hours``.
    """
    from ..api import run_as, run_pas
    from ..strategies.pas import PAS
    from ..study.oracles import TableOracle

    events, n_waves, p_exp = cfd_lf_record()
    table = cfd_table()
    ok = table[table["status"] == "ok"]
    truth = cfd_truth(events, ok, n_waves, p_exp)
    n_top, cut = cfd_cut(events, ok)
    frame = events[events["lf"] > cut].set_index("id")[["lf", "seed", "t_peak"]]
    oracle = TableOracle(ok, id_column="id", value_column=CFD_CASE.load)
    rows = []
    for name in strategies:
        for seed in seeds:
            kw = dict(n_waves=n_waves, p_exp=p_exp, threshold=cut, eps1=EPS1, seed=seed,
                      max_hf=max_hf)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                if name == "as":
                    res = run_as(frame, oracle, **kw)
                else:
                    res = run_pas(frame, oracle, strategy=PAS.paper() if name == "paper"
                                  else None, **kw)
            asked = res.history["event_id"].dropna().astype(str).unique().tolist()
            lo, hi = res.mpm_band
            rows.append({"strategy": name, "seed": seed, "mpm": res.mpm, "lo": lo, "hi": hi,
                         "n_hf": res.n_hf, "converged": bool(res.converged),
                         "cfd_hours": _hours(ok, asked)})
    runs = pd.DataFrame(rows)
    n = int(np.median(runs.loc[runs["strategy"] == "pas", "n_hf"])) if "pas" in strategies \
        else 30
    est, top = top_n_estimate(events, ok, n, n_waves, p_exp)
    runs = pd.concat([runs, pd.DataFrame([{
        "strategy": f"top-{n} LF events", "seed": np.nan, "mpm": est, "lo": np.nan,
        "hi": np.nan, "n_hf": n, "converged": np.nan, "cfd_hours": _hours(ok, top)}])],
        ignore_index=True)
    design = _design_row()
    if design is not None:
        runs = pd.concat([runs, pd.DataFrame([design])], ignore_index=True)
    runs["error"] = runs["mpm"] / truth - 1.0
    runs["holds"] = np.where(runs["lo"].notna(), (runs["lo"] <= truth) & (truth <= runs["hi"]),
                             np.nan)
    facts = {"truth": truth, "n_waves": n_waves, "p_exp": p_exp, "cut": cut, "n_cfd": len(ok),
             "n_above_cut": n_top, "truth_hours": _hours(ok, ok["id"])}
    return runs, facts


def _design_row():
    from importlib import resources

    ref = resources.files("pas.validation") / "data" / "cfd_green_water_design.csv"
    if not ref.is_file():
        return None
    with resources.as_file(ref) as path:
        d = pd.read_csv(path)
    d = d[d["status"] == "ok"]
    if d.empty:
        return None
    r = d.iloc[0]
    return {"strategy": f"design wave ({r['method']})", "seed": np.nan,
            "mpm": float(r[CFD_CASE.load]), "lo": np.nan, "hi": np.nan, "n_hf": len(d),
            "converged": np.nan, "cfd_hours": float(d["wall_seconds"].median() / 3600.0)}


def summarise_cfd(runs, facts):
    """The comparison table: one row per strategy, over its seeds."""
    out = []
    for name, g in runs.groupby("strategy", sort=False):
        err = g["error"].abs()
        holds = g["holds"].dropna()
        out.append({"strategy": name, "runs": len(g),
                    "MPM (kN/m, median)": g["mpm"].median() / 1e3,
                    "error median": g["error"].median(), "|error| worst": err.max(),
                    "U95 holds truth": f"{int(holds.sum())}/{len(holds)}" if len(holds)
                    else "-",
                    "HF (median)": g["n_hf"].median(),
                    "CFD hours (median)": g["cfd_hours"].median()})
    table = pd.DataFrame(out)
    table.attrs.update(facts)
    return table


def format_cfd(table) -> str:
    """The comparison as text, with the truth and what one data set can show."""
    f = table.attrs
    head = (f"CFD case (green water on a fixed bow, OpenFOAM): truth MPM "
            f"{f['truth'] / 1e3:.1f} kN/m from {f['n_cfd']} CFD runs "
            f"({f['n_above_cut']} above the LF cut {f['cut']:.2f} m, the rest a sample below), "
            f"n_w {f['n_waves']}, p_exp {f['p_exp']:.3g}, {f['truth_hours']:.2f} CFD hours.\n")
    fmt = table.copy()
    for c in ("error median", "|error| worst"):
        fmt[c] = fmt[c].map(lambda v: f"{v:+.1%}" if c == "error median" else f"{v:.1%}")
    for c in ("MPM (kN/m, median)", "CFD hours (median)"):
        fmt[c] = fmt[c].map(lambda v: f"{v:.2f}" if c.startswith("CFD") else f"{v:.1f}")
    tail = ("\nOne LF record and one CFD table: the spread over strategy seeds shows the "
            "strategies' own randomness, not the scatter over redrawn records.")
    return head + fmt.to_string(index=False) + tail
