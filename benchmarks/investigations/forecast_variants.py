"""Which forecast of the HF still needed holds up halfway: variants replayed on kept histories.

Issue 28 asks that the forecast made halfway (in HF count) to where a
precision study reached its target be within a factor 1.5 of the HF it then
still needed.  The histories of ``precision_stop.py --histories DIR`` (one CSV
per study, named ``<problem>_<set>_<target>.csv``) keep every fit's MPM, its
sampling half-width and the model bands the loop computed, so each variant is
replayed offline on what the study knew at its halfway fit:

- the least-squares fit of ``ln w = a − b ln n`` alone (``prior_sd=inf``, the
  forecast before this investigation; none with fewer than three bands);
- a prior on ``b`` centred on 1/2 (a sample statistic), from fixing it
  (``prior_sd`` 0.001) to shrinking the fitted ``b`` toward it (0.1–0.4), the
  level ``a`` from the mean, the median or the lowest of the points;
- each with the stopping rule's own floor (``StoppingRule.fewest_more_fits``:
  ``k2`` MPMs, and the window's MPMs within a band the target allows);
- "+ sampling widths" (the adopted variant only): where no model band was
  computed yet, the sampling half-widths of the fits stand in for the model
  band's;
- "first passage" (:func:`first_passage_pairs`): the widths scatter about the
  power law (mean level, ``b`` shrunk toward 1/2) and the rule stops at the
  first band below the target, bands every 1, 3 or 6 pairs: the median of
  that first passage, with the rule's floor.

Per variant: the studies that reached their target, the share whose halfway
forecast was within a factor 1.5 of the HF then needed (a missing forecast
counts as a miss), how often its 95 % interval held that number, and the
median ratio; per target as well.  ``--problems`` picks the histories of some
problems (e.g. the tuning types only); ``--write [PAGE]`` puts the table
between the ``<!-- BEGIN forecast_variants.py variants -->`` markers of
``docs/results/precision.md``.

Run: ``python benchmarks/investigations/forecast_variants.py DIR [--problems a,b] [--csv out.csv]
[--write]``
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pas.strategies.forecast import Forecast, forecast_pairs, relative_half_width
from pas.strategies.stopping import StoppingRule

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import rewrite_page  # noqa: E402

FACTOR = 1.5
PAGE, TAG = Path("docs/results/precision.md"), "forecast_variants.py"
VARIANTS = {
    "fit alone (before)": {"prior_sd": math.inf, "centre": "mean"},
    "b = 1/2, mean": {"prior_sd": 1e-3, "centre": "mean"},
    "b = 1/2, median": {"prior_sd": 1e-3, "centre": "median"},
    "b = 1/2, lowest": {"prior_sd": 1e-3, "centre": "min"},
    "shrink 0.1, lowest": {"prior_sd": 0.1, "centre": "min"},
    "shrink 0.2, median": {"prior_sd": 0.2, "centre": "median"},
    "shrink 0.2, mean": {"prior_sd": 0.2, "centre": "mean"},
    "shrink 0.2, lowest (adopted)": {"prior_sd": 0.2, "centre": "min"},
    "shrink 0.4, lowest": {"prior_sd": 0.4, "centre": "min"},
}
ADOPTED = "shrink 0.2, lowest (adopted)"


def halfway_states(directory: Path, problems=None):
    """What each study that reached its target knew at its halfway fit, and the HF it then
    still needed: dicts of ``problem``, ``target``, ``n_stop``, ``needed``, the band points
    ``n``/``w``, the sampling ``floor``, ``n_pairs``, ``n_hf``, ``mpms`` and the fits'
    sampling widths ``fit_n``/``fit_w``."""
    for path in sorted(directory.glob("*.csv")):
        problem, data_set, target = path.stem.rsplit("_", 2)
        if problems and problem not in problems:
            continue
        fitted = pd.read_csv(path)
        fitted = fitted[fitted["mpm"].notna()].reset_index(drop=True)
        stops = fitted["stop"].astype(str).str.lower() == "true"
        if not stops.any():
            continue
        n_stop = int(fitted.loc[stops.idxmax(), "n_hf"])
        upto = fitted[fitted["n_hf"] <= n_stop / 2]
        state = {"problem": problem, "data_set": int(data_set), "target": float(target),
                 "n_stop": n_stop, "needed": n_stop}
        if not upto.empty:
            now, bands = upto.iloc[-1], upto[upto["model_low"].notna()]
            state.update(needed=n_stop - int(now["n_hf"]), n=bands["n_pairs"].to_numpy(),
                         w=np.array([relative_half_width(m, (lo, hi)) for m, lo, hi in
                                     zip(bands["mpm"], bands["model_low"], bands["model_high"])]),
                         floor=float(now["halfwidth_sampling"]), n_pairs=int(now["n_pairs"]),
                         n_hf=int(now["n_hf"]), mpms=list(upto["mpm"]),
                         fit_n=upto["n_pairs"].to_numpy(),
                         fit_w=upto["halfwidth_sampling"].to_numpy())
        yield state


def further_hf(state: dict, *, rule_floor: bool, sampling_widths: bool = False, **kw):
    """``(expected, low, high)`` further HF a variant forecast at the halfway fit (NaN: none)."""
    if "n" not in state:
        return (np.nan,) * 3
    n, w = state["n"], state["w"]
    if sampling_widths and not len(n):
        n, w = state["fit_n"], state["fit_w"]
    ahead = forecast_pairs(n, w, state["target"], state["floor"], **kw) if len(n) else None
    if ahead is None:
        return (np.nan,) * 3
    return _further(state, ahead, rule_floor)


def _further(state: dict, ahead: Forecast, rule_floor: bool = True):
    """``(expected, low, high)`` further HF of the pairs ``ahead`` from the halfway fit,
    with ``rule_floor`` never before the stopping rule can hold (it did not there)."""
    if rule_floor:
        rule = StoppingRule(precision=state["target"])
        rule.mpms = list(state["mpms"])
        ahead = ahead.at_least(state["n_pairs"] + max(rule.fewest_more_fits(), 1))
    return ahead.further(state["n_pairs"], state["n_hf"] / max(state["n_pairs"], 1))


def first_passage_pairs(n, w, target: float, floor: float, n_now: int, *, every: int = 3,
                        prior_sd: float = 0.2, horizon: int = 2000):
    """``(median, 2.5 %, 97.5 %)`` pairs at which a band first falls below ``target`` if
    bands are computed every ``every`` pairs from ``n_now`` and scatter about the power
    law of :func:`forecast_pairs`'s fit (mean level, ``b`` shrunk toward 1/2) with the
    fitted scatter, independently: the first passage of the widths, not the trend's
    crossing (the rule stops at the first band below the target)."""
    from scipy import stats as st

    from pas.strategies.forecast import SPAN, _exponent

    n, w = np.asarray(n, float), np.asarray(w, float)
    keep = np.isfinite(w) & (w > 0) & (n >= n[-1] / SPAN)
    n, w = n[keep], w[keep]
    if n.size == 0:
        return None
    if floor >= target:
        return (math.inf,) * 3
    x, y = np.log(n), np.log(w)
    b, _, s2, _ = _exponent(x, y, prior_sd)
    level = float(np.mean(y + b * (x - x.mean())))
    future = n_now + every * np.arange(1, horizon + 1)
    mu = level - b * (np.log(future) - x.mean())
    p_above = st.norm.cdf((mu - math.log(target)) / math.sqrt(s2))
    survive = np.cumprod(p_above)
    out = []
    for q in (0.5, 0.025, 0.975):
        j = np.searchsorted(-survive, -(1 - q))  # first index where survive <= 1 - q
        out.append(float(future[j]) if j < future.size else math.inf)
    return tuple(out)


def further_first_passage(state: dict, *, every: int = 3, prior_sd: float = 0.2):
    """``(expected, low, high)`` further HF of :func:`first_passage_pairs`, with the rule's
    floor."""
    if "n" not in state or not len(state["n"]):
        return (np.nan,) * 3
    got = first_passage_pairs(state["n"], state["w"], state["target"], state["floor"],
                              state["n_pairs"], every=every, prior_sd=prior_sd)
    if got is None:
        return (np.nan,) * 3
    return _further(state, Forecast(*got, math.nan))


def evaluate(states: list) -> pd.DataFrame:
    """One row per (variant, study): the forecast halfway, the HF then needed."""
    rows = []
    for name, kw in VARIANTS.items():
        for rule_floor in (False, True):
            for sampling in (False, True) if rule_floor and name == ADOPTED else (False,):
                label = name + (" + k2 floor" if rule_floor else "") + (
                    " + sampling widths" if sampling else "")
                rows += [_row(label, s, further_hf(s, rule_floor=rule_floor,
                                                   sampling_widths=sampling, **kw))
                         for s in states]
    for every in (1, 3, 6):
        rows += [_row(f"first passage, a band every {every} pairs + k2 floor", s,
                      further_first_passage(s, every=every)) for s in states]
    return pd.DataFrame(rows)


def _row(variant: str, state: dict, forecast) -> dict:
    """A study's row of :func:`evaluate`: its halfway ``forecast`` (expected, low, high)."""
    expected, low, high = forecast
    return {"variant": variant, "problem": state["problem"], "data_set": state["data_set"],
            "target": state["target"], "needed": state["needed"], "forecast": expected,
            "low": low, "high": high}


def summary(runs: pd.DataFrame) -> pd.DataFrame:
    """Per variant: studies, forecasts, share within ×1.5, interval held, median ratio."""
    ratio = runs["forecast"] / runs["needed"]
    runs = runs.assign(ok=(ratio <= FACTOR) & (ratio >= 1 / FACTOR), ratio=ratio,
                       held=(runs["low"] <= runs["needed"]) & (runs["needed"] <= runs["high"]))
    out = runs.groupby("variant", sort=False).agg(
        studies=("ok", "size"), forecasts=("forecast", "count"), within=("ok", "mean"),
        interval_held=("held", "mean"), median_ratio=("ratio", "median"))
    for target, g in runs.groupby("target"):
        out[f"within at ±{target:g}"] = g.groupby("variant", sort=False)["ok"].mean()
    return out.reset_index()


def markdown(table: pd.DataFrame) -> str:
    """The summary as the page's Markdown table, shares in per cent."""
    targets = [c for c in table.columns if c.startswith("within at")]
    head = ["variant", "studies", "forecasts", "within ×1.5", "95 % interval held",
            "median ratio", *(f"within ×1.5, ±{100 * float(c[len('within at ±'):]):g} %"
                              for c in targets)]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for _, r in table.iterrows():
        cells = [r["variant"], str(int(r["studies"])), str(int(r["forecasts"])),
                 *(f"{100 * r[c]:.0f} %" if np.isfinite(r[c]) else "–"
                   for c in ("within", "interval_held")),
                 f"{r['median_ratio']:.2f}" if np.isfinite(r["median_ratio"]) else "–",
                 *(f"{100 * r[c]:.0f} %" if np.isfinite(r[c]) else "–" for c in targets)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("histories", type=Path, help="the --histories DIR of precision_stop.py")
    ap.add_argument("--problems", default="", help="comma-separated problem names (default all)")
    ap.add_argument("--csv", help="write the per-study forecasts here")
    ap.add_argument("--write", nargs="?", const=PAGE, type=Path, metavar="PAGE",
                    help=f"write the table between the markers of PAGE (default {PAGE})")
    args = ap.parse_args(argv)
    problems = {p for p in args.problems.split(",") if p}
    runs = evaluate(list(halfway_states(args.histories, problems)))
    if args.csv:
        runs.to_csv(args.csv, index=False)
    table = summary(runs)
    with pd.option_context("display.width", 220, "display.max_columns", 20):
        print(table.to_string(index=False, float_format=lambda x: f"{x:.2f}"))
    if args.write:
        rewrite_page(args.write, {"variants": markdown(table)}, TAG)


if __name__ == "__main__":
    main()
