"""The long-term validation table: four methods on the same redrawn data sets (issue 29).

Run: python benchmarks/studies/long_term.py run ANALOGUE --seeds N --out DIR  (one analogue: 3 or 2)
         [--p-exceed P] [--scale S] [--first F]   (the level, default 2e-6; S × 100 h per
         kept cell; data sets F … N, default 1 … N)
     python benchmarks/studies/long_term.py pool ANALOGUE --seeds N --out DIR [--scale S]
     python benchmarks/studies/long_term.py write DIR [DIR ...] --page docs/results/long-term.md

``run`` generates data sets of a long-term analogue
(:func:`pas.validation.long_term_compare.long_term_data`: the North-Atlantic
scatter, the cells a pilot keeps with 100 · S one-hour realisations each, the
others 4), computes the brute-force truth at 5e-6, 2e-6 and 1e-6 per
encounter on the whole set and on its two halves (odd and even
realisations: the convergence check) and the 20-year level, then runs the
four methods (:data:`~pas.validation.long_term_compare.METHODS`) at
``--p-exceed``; it appends to ``runs_<a>.csv``, ``truth_<a>.csv`` and
``cells_<a>.csv`` in DIR seed by seed (``run`` again skips the finished
seeds).  ``pool`` writes the truth over data sets 1 … N together.  ``write``
puts the tables between the page's markers (``<!-- BEGIN long_term.py NAME
-->`` … ``<!-- END … NAME -->``): the page's numbers are this script's output.

A data set is named by its analogue, hours per kept cell (``kept_hours``) and
data seed; a run also by its level ``p_exceed``.  The comparison table holds,
per analogue, the (level, record length) of its PAS long-term runs; every
finished run is in the every-run table.  Rows written before these columns
existed are the 100 h data sets at 2e-6.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pas.validation.long_term_compare import P_VALIDATED

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.long_term_data_sets import p_exceed_of_return_period, pool_data_sets  # noqa: E402
from harness.result_tables import write_between_markers  # noqa: E402

LEVELS = (5e-6, 2e-6, 1e-6)
TARGET_CV = 0.02      # the truth's spread the green-water goal needs


def _kept_hours(plan, scale):
    """Hours per kept cell of a data set made at ``scale`` (as ``long_term_data`` makes it)."""
    from pas.validation.long_term_compare import KEPT_HOURS as hours

    return max(int(plan.attrs["pilot_hours"]), round(hours * float(scale)))


def _truth_row(data, seconds, plan, p_exceed, kept_hours):
    from pas.validation.long_term import value_at_exceedance_long_term

    row = {"analogue": data.analogue, "data_seed": data.seed, "kept_hours": kept_hours,
           "p_exceed": p_exceed, "generation_s": seconds,
           "hf_events": int(sum(v.size for v in data.hf.values()))}
    for half in (0, 1):
        hf = {s: data.hf[s][data.meta[s]["seed_no"].to_numpy() % 2 == half] for s in data.hf}
        for p in LEVELS:
            row[f"half{half}_{p:g}"] = value_at_exceedance_long_term(p, data.weights, hf)
    for p in LEVELS:
        row[f"truth_{p:g}"] = data.truth(p)
    p20 = p_exceed_of_return_period(data, 20)
    share = data.contributions(p_exceed).set_index("sea_state")
    dropped = list(plan["name"][~plan["kept"]])
    row.update({"p_20y": p20, "truth_20y": data.truth(p20),
                "dropped_share": share.loc[dropped, "share"].sum(),
                "dropped_share_u95": share.loc[dropped, "share_u95"].sum()})
    return row


def _pending(first, last, done):
    """The data seeds ``first … last`` not yet in ``done``, in order."""
    return [seed for seed in range(int(first), int(last) + 1) if seed not in done]


def _data_set(analogue, seed, scale, p_exceed):
    """A data set (cached), its cell plan, hours per kept cell and its truth row."""
    from pas.validation.long_term_compare import _lf_only as lf_only
    from pas.validation.long_term_compare import long_term_data

    t0 = time.perf_counter()
    data, plan = long_term_data(analogue, seed=seed, scale=scale, p_exceed=p_exceed)
    hours = _kept_hours(plan, scale)
    truth = _truth_row(data, time.perf_counter() - t0, plan, p_exceed, hours)
    truth["lf_only_20y"] = lf_only(data, truth["p_20y"])[0]
    return data, plan, hours, truth


def run(analogue, seeds, out, methods, *, p_exceed=P_VALIDATED, scale=1.0, first=1):
    """Data sets ``first … seeds`` and the ``methods`` on each at ``p_exceed``; appends to
    ``out``."""
    from pas.validation.long_term_compare import compare

    out.mkdir(parents=True, exist_ok=True)
    runs_file, truth_file = out / f"runs_{analogue}.csv", out / f"truth_{analogue}.csv"
    done = set(pd.read_csv(truth_file)["data_seed"]) if truth_file.exists() else set()
    for seed in _pending(first, seeds, done):
        t0 = time.perf_counter()
        data, plan, hours, truth = _data_set(analogue, seed, scale, p_exceed)
        kept = list(plan["name"][plan["kept"]])
        table = compare(data, p_exceed, kept=kept, methods=methods, seed=0,
                        progress=lambda m: print(m, flush=True))
        table.insert(2, "kept_hours", hours)
        table.to_csv(runs_file, mode="a", header=not runs_file.exists(), index=False)
        pd.DataFrame([truth]).to_csv(truth_file, mode="a", header=not truth_file.exists(),
                                     index=False)
        plan.assign(l_min=plan.attrs["l_min"], p_exceed=p_exceed, kept_hours=hours).to_csv(
            out / f"cells_{analogue}.csv", index=False)
        print(f"seed {seed}: truth {truth[f'truth_{p_exceed:g}']:.5g}, "
              f"{time.perf_counter() - t0:.0f} s", flush=True)


def truth_only(analogue, seeds, out, *, p_exceed=P_VALIDATED, scale=1.0):
    """Rewrite ``truth_<a>.csv`` from the cached data sets (no method is run)."""
    rows = [_data_set(analogue, seed, scale, p_exceed)[3] for seed in range(1, seeds + 1)]
    out.mkdir(parents=True, exist_ok=True)
    pd.DataFrame(rows).to_csv(out / f"truth_{analogue}.csv", index=False)


def pool(analogue, seeds, out, *, p_exceed=P_VALIDATED, scale=1.0):
    """Write ``pooled_<a>.csv``: the truth over data sets ``1 … seeds`` together (cached)."""
    made = [_data_set(analogue, seed, scale, p_exceed) for seed in range(1, seeds + 1)]
    pooled = pool_data_sets([m[0] for m in made])
    row = {"analogue": analogue, "kept_hours": made[0][2], "p_exceed": p_exceed,
           "data_sets": seeds, **{f"truth_{p:g}": pooled.truth(p) for p in LEVELS}}
    out.mkdir(parents=True, exist_ok=True)
    pd.DataFrame([row]).to_csv(out / f"pooled_{analogue}.csv", index=False)


def _fmt(v):
    return "n/a" if not np.isfinite(v) else f"{v:.4g}"


def _pct(v):
    return "n/a" if not np.isfinite(v) else f"{100 * v:+.1f} %"


def _truth_cv(g, p):
    """CV of the truth over data sets at level ``p``: of the halves (every half its own value)
    and of the full sets."""
    full = g[f"truth_{p:g}"].to_numpy(float)
    halves = np.concatenate([g[f"half0_{p:g}"], g[f"half1_{p:g}"]]).astype(float)
    return (float(np.std(halves, ddof=1) / np.mean(halves)),
            float(np.std(full, ddof=1) / np.mean(full)))


def _hours_for(cv, hours, target=TARGET_CV):
    """The record length (hours per kept cell) at which ``cv`` measured at ``hours`` falls to
    ``target``, extrapolated as 1/√length."""
    return hours * (cv / target) ** 2


def _summary_row(label, method, g):
    """One method's line of a comparison table over the runs ``g`` (``label``: its first cells)."""
    if g["value"].isna().all():
        return f"| {label} | {method} | {len(g)} | not run: {g['note'].iloc[0]} | | | | | | |"
    err = g["error"].abs()
    cov = g["covered"].dropna()
    width = ((g["band_high"] - g["band_low"]) / g["truth"]).median()
    return (f"| {label} | {method} | {len(g)} | {100 * err.median():.1f} % | "
            f"{100 * err.max():.1f} % | {_pct(g['error'].median())} | "
            + (f"{int(cov.astype(bool).sum())}/{len(cov)}" if len(cov) else "–")
            + f" | {f'{100 * width:.1f} %' if np.isfinite(width) else '–'} | "
            f"{g['n_hf'].median():g} | {g['seconds'].median():.0f} s |")


DATA_SET = ["analogue", "kept_hours", "data_seed"]
"""What names a data set: its analogue, hours per kept cell and data seed."""
LABELS = {"3": "green water (kN)", "2": "hogging VBM (N m)"}


def _read(dirs, stem):
    """Every ``<stem>_*.csv`` of ``dirs``, with the columns older files lack filled in (the 100 h
    data sets at 2e-6: the files written before ``--p-exceed`` and ``--scale``)."""
    from pas.validation.long_term_compare import KEPT_HOURS as hours

    frames = []
    for d in dirs:
        for f in sorted(Path(d).glob(f"{stem}_*.csv")):
            t = pd.read_csv(f)
            if "analogue" not in t:
                t["analogue"] = f.stem.rsplit("_", 1)[-1]
            t["analogue"] = [str(int(float(a))) for a in t["analogue"]]
            for col, default in (("kept_hours", hours), ("p_exceed", P_VALIDATED)):
                t[col] = t[col].fillna(default) if col in t else default
            frames.append(t.astype({"kept_hours": int}))
    return pd.concat(frames, ignore_index=True)


def _head(columns):
    """A markdown table's header and rule for ``columns`` ("a | b | c")."""
    return [f"| {columns} |", "|" + "---|" * (columns.count(" | ") + 1)]


def _ordered(frame, *cols):
    """Green water first, then by ``cols`` ascending."""
    return frame.sort_values(["analogue", *cols], ascending=[False] + [True] * len(cols),
                             kind="stable")


def _label(r):
    """The leading cells of a row: analogue, level, hours per kept cell."""
    return f"{LABELS[r['analogue']]} | {r['p_exceed']:g} | {int(r['kept_hours'])} h"


def _method_rows(runs):
    """The runs to tabulate: a later folder wins, a method that was run beats "not run"."""
    from pas.validation.long_term_compare import METHODS

    # rows of a process started before pas.run_long_term was in the build: not a result
    runs = runs[~runs["note"].fillna("").str.contains("not available in this build")]
    runs = (runs.assign(ran=runs["value"].notna()).sort_values("ran", kind="stable")
            .drop_duplicates(DATA_SET + ["p_exceed", "method"], keep="last").sort_index())
    runs = runs.assign(order=runs["method"].map(METHODS.index))
    return _ordered(runs, "p_exceed", "kept_hours", "order", "data_seed")


def _comparison_tables(runs):
    """The comparison (same data sets) and every-run tables, and the per-run table."""
    columns = ("analogue | level | h per kept cell | method | data sets | median \\|error\\| | "
               "worst \\|error\\| | median error | U95 coverage | median band width | "
               "HF spent (median) | wall time (median)")
    comp = _head(columns)
    every = _head(columns.replace("U95 coverage", "U95 coverage (≥ 10 runs to claim it)"))
    for _, g in runs.groupby(["analogue", "p_exceed", "kept_hours"], sort=False):
        label = _label(g.iloc[0])
        for m, gm in g.groupby("method", sort=False):
            every.append(_summary_row(label, m, gm))
        if not (g["method"] == "pas-long-term").any():
            continue        # no PAS long-term at this level: not a comparison of the methods
        common = set.intersection(*(set(gm["data_seed"]) for _, gm in g.groupby("method")))
        for m, gm in g[g["data_seed"].isin(common)].groupby("method", sort=False):
            comp.append(_summary_row(label, m, gm))
    per_run = _head("analogue | level | h per kept cell | data set | method | truth | value | "
                    "error | U95 | HF | wall time")
    for _, r in runs.iterrows():
        per_run.append(f"| {_label(r)} | {int(r['data_seed'])} | {r['method']} | "
                       f"{_fmt(r['truth'])} | {_fmt(r['value'])} | {_pct(r['error'])} | "
                       f"{_fmt(r['band_low'])} … {_fmt(r['band_high'])} | {int(r['n_hf'])} | "
                       f"{r['seconds']:.0f} s |")
    return comp, every, per_run


def _truth_tables(truth):
    """The convergence table (every data set), the spread and the record-length tables."""
    conv = _head("analogue | h per kept cell | data set | HF events | truth 5e-6 | halves | "
                 "truth 2e-6 | halves | truth 1e-6 | halves | 20-year level | brute force | "
                 "LF-only | build (cache)")
    for _, r in truth.iterrows():
        cols = []
        for p in LEVELS:
            cols += [_fmt(r[f"truth_{p:g}"]),
                     f"{_fmt(r[f'half0_{p:g}'])} / {_fmt(r[f'half1_{p:g}'])}"]
        conv.append(f"| {LABELS[r['analogue']]} | {int(r['kept_hours'])} h | "
                    f"{int(r['data_seed'])} | {int(r['hf_events'])} | " + " | ".join(cols)
                    + f" | {r['p_20y']:.3g} | {_fmt(r['truth_20y'])} (not validated) | "
                    f"{_fmt(r['lf_only_20y'])} | {r['generation_s']:.0f} s |")
    spread = _head("analogue | h per kept cell | level | CV of the truth over data sets | "
                   "median \\|half − half\\| / truth")
    hours = _head("analogue | h per kept cell | level | data sets | CV of the halves (half the "
                  "record) | CV of the full sets | half/full | hours per kept cell for a 2 % "
                  "CV, from the halves | from the full sets")
    for (a, h), g in truth.groupby(["analogue", "kept_hours"], sort=False):
        for p in LEVELS:
            t = g[f"truth_{p:g}"]
            half = (g[f"half0_{p:g}"] - g[f"half1_{p:g}"]).abs() / t
            spread.append(f"| {LABELS[a]} | {h} h | {p:g} | {100 * t.std() / t.mean():.1f} % | "
                          f"{100 * half.median():.1f} % |")
            cv_half, cv_full = _truth_cv(g, p)
            hours.append(f"| {LABELS[a]} | {h} h | {p:g} | {len(g)} | {100 * cv_half:.1f} % | "
                         f"{100 * cv_full:.1f} % | {cv_half / cv_full:.2f} (√2 = 1.41) | "
                         f"{_hours_for(cv_half, h / 2):.0f} h | "
                         f"{_hours_for(cv_full, h):.0f} h |")
    return conv, spread, hours


def _cells_table(cells, truth):
    """One row per cell plan (analogue, level, record length): kept and dropped cells."""
    plan = _head("analogue | level | h per kept cell | cells | kept | dropped: estimated share "
                 "of Q | largest dropped | dropped: measured share (data sets, median) | its "
                 "95 % upper bound | l_min (LF)")
    cells = cells.drop_duplicates(["analogue", "p_exceed", "kept_hours", "name"], keep="last")
    for (a, p, h), c in _ordered(cells, "p_exceed", "kept_hours").groupby(
            ["analogue", "p_exceed", "kept_hours"], sort=False):
        dropped = c[~c["kept"]]
        t = truth[(truth["analogue"] == a) & (truth["kept_hours"] == h)
                  & np.isclose(truth["p_exceed"], p, rtol=1e-9)]
        measured = (f"{100 * t['dropped_share'].median():.2f} % | "
                    f"{100 * t['dropped_share_u95'].median():.1f} %"
                    if len(t) and "dropped_share" in t else "– | –")
        plan.append(f"| {LABELS[a]} | {p:g} | {h} h | {len(c)} | {int(c['kept'].sum())} | "
                    f"{100 * dropped['share_rayleigh'].sum():.2f} % | "
                    f"{100 * dropped['share_rayleigh'].max():.2f} % | {measured} | "
                    f"{_fmt(c['l_min'].iloc[0])} |")
    return plan


def _pooled_table(runs, truth, pooled):
    """Each method's error and coverage against the pooled truth of its data sets' group, and
    how far the data sets' own truths lie from it."""
    rows = _head("analogue | level | h per kept cell | pooled truth (data sets) | against it | "
                 "runs | median \\|error\\| | worst \\|error\\| | median error | "
                 "U95 coverage")
    for _, ref in pooled.iterrows():
        same = (runs["analogue"] == ref["analogue"]) & (runs["kept_hours"] == ref["kept_hours"])
        for p in sorted(set(runs.loc[same, "p_exceed"])):
            ref_value = ref.get(f"truth_{p:g}", np.nan)
            g = runs[same & np.isclose(runs["p_exceed"], p, rtol=1e-9)]
            t = truth[(truth["analogue"] == ref["analogue"])
                      & (truth["kept_hours"] == ref["kept_hours"])]
            lead = (f"| {LABELS[ref['analogue']]} | {p:g} | {int(ref['kept_hours'])} h | "
                    f"{_fmt(ref_value)} ({int(ref['data_sets'])}) |")
            own = t[f"truth_{p:g}"] / ref_value - 1.0
            rows.append(f"{lead} each data set's own truth | {len(t)} | "
                        f"{100 * own.abs().median():.1f} % | {100 * own.abs().max():.1f} % | "
                        f"{_pct(own.median())} | – |")
            for m, gm in g.groupby("method", sort=False):
                err = gm["value"] / ref_value - 1.0
                banded = gm[np.isfinite(gm["band_low"] + gm["band_high"])]
                inside = ((banded["band_low"] <= ref_value)
                          & (ref_value <= banded["band_high"])).sum()
                rows.append(f"{lead} {m} | {len(gm)} | {100 * err.abs().median():.1f} % | "
                            f"{100 * err.abs().max():.1f} % | {_pct(err.median())} | "
                            + (f"{inside}/{len(banded)} |" if len(banded) else "– |"))
    return rows


def tables(dirs):
    """The page's tables from the CSV files of ``dirs`` (a later folder wins a repeated row)."""
    runs = _method_rows(_read(dirs, "runs"))
    truth = _ordered(_read(dirs, "truth").drop_duplicates(DATA_SET, keep="last"),
                     "kept_hours", "data_seed")
    comp, every, per_run = _comparison_tables(runs)
    conv, spread, hours = _truth_tables(truth)
    blocks = {"comparison": "\n".join(comp), "every_run": "\n".join(every),
            "runs": "\n".join(per_run), "convergence": "\n".join(conv),
            "spread": "\n".join(spread), "truth_hours": "\n".join(hours),
            "cells": "\n".join(_cells_table(_read(dirs, "cells"), truth))}
    if any(list(Path(d).glob("pooled_*.csv")) for d in dirs):
        blocks["pooled"] = "\n".join(_pooled_table(runs, truth, _read(dirs, "pooled")))
    return blocks


def _positive(text):
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be a number > 0, got {text!r}")
    return value


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    t = sub.add_parser("truth", help="only the truth table, from the cached data sets")
    o = sub.add_parser("pool", help="the truth over data sets 1 … N together, from the cache")
    for p in (r, t, o):
        p.add_argument("analogue", choices=("3", "2"))
        p.add_argument("--seeds", type=int, default=5)
        p.add_argument("--out", type=Path, required=True)
        p.add_argument("--p-exceed", type=_positive, default=P_VALIDATED,
                       help="the level per encounter (default 2e-6, the validated one)")
        p.add_argument("--scale", type=_positive, default=1.0,
                       help="hours per kept cell, in units of 100 h (default 1)")
    r.add_argument("--methods", default="pas-long-term,uniform,contour,lf-only")
    r.add_argument("--first", type=int, default=1,
                   help="the first data seed to run (default 1; the last is --seeds)")
    w = sub.add_parser("write")
    w.add_argument("dirs", nargs="+", type=Path)
    w.add_argument("--page", type=Path)
    args = parser.parse_args(argv)
    if args.cmd == "run":
        run(args.analogue, args.seeds, args.out, tuple(args.methods.split(",")),
            p_exceed=args.p_exceed, scale=args.scale, first=args.first)
        return
    if args.cmd == "pool":
        pool(args.analogue, args.seeds, args.out, p_exceed=args.p_exceed, scale=args.scale)
        return
    if args.cmd == "truth":
        truth_only(args.analogue, args.seeds, args.out, p_exceed=args.p_exceed,
                   scale=args.scale)
        return
    blocks = tables(args.dirs)
    print(*blocks.values(), sep="\n\n")
    if args.page:
        page = args.page.read_text(encoding="utf-8")
        args.page.write_text(write_between_markers(page, blocks, "long_term.py"),
                             encoding="utf-8")
    return blocks


if __name__ == "__main__":
    main()
