"""``pas impacts``: statistics of an impact record (green water, slamming) from a CSV.

::

    pas impacts EVENTS.csv [--load COL] [--time COL] [--seed COL] [--n-encounters N]
                [--t-min S] [--levels L ...] [--exposure-encounters N | --exposure-hours H
                --encounter-period T] [--limit P] [--out DIR]

The table has one row per impact, or one per wave encounter with load 0 for
none (then ``--n-encounters`` defaults to the number of rows); a ``seed``
column, when there is one, keeps gaps from spanning two runs. Prints the impact
probability per encounter with its interval, the inter-arrival test before and
after declustering, the ranked peak-load distributions and the exposure
probability of the best fit (:mod:`pas.records.impacts`, :mod:`pas.records.load_fits`).
``--out`` writes the tables as CSV and the figures (inter-arrival times, Q–Q, exposure) as PNG.
"""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_parser", "run"]

EPILOG = """\
examples:
  pas impacts events.csv                                 # per-encounter table, column 'load'
  pas impacts impacts.csv --n-encounters 15198 --t-min 20
  pas impacts events.csv --load hf --time t_start --seed seed_no \\
      --exposure-hours 3 --encounter-period 8.2 --limit 2000 --out report/
"""


def add_parser(sub):
    from . import plain_text

    p = sub.add_parser("impacts", help="impact rates, clustering, load distributions, exposure",
                       description=plain_text(__doc__), epilog=EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("events", help="CSV with one row per impact or per wave encounter")
    p.add_argument("--load", default="load", help="peak-load column (default: load)")
    p.add_argument("--time", default="t", help="impact time column, s (default: t)")
    p.add_argument("--seed", help="seed/run column; 'none' for one continuous record "
                                  "(default: 'seed' if the table has it, else none)")
    p.add_argument("--n-encounters", type=float,
                   help="wave encounters in the record (default: rows of the table)")
    p.add_argument("--t-min", type=float,
                   help="declustering separation, s (a few encounter periods; default: none)")
    p.add_argument("--levels", type=float, nargs="*", default=[],
                   help="load levels for exceedance rates Pr(EX)")
    p.add_argument("--loc", type=float, help="fix the location of the fitted distributions")
    p.add_argument("--exposure-encounters", type=float, help="encounters in the exposure")
    p.add_argument("--exposure-hours", type=float, help="exposure duration, h")
    p.add_argument("--encounter-period", type=float, help="mean encounter period, s")
    p.add_argument("--limit", type=float, help="load limit for the exposure probability")
    p.add_argument("--out", help="folder for rates.csv, fits.csv, exposure.csv and figures")
    p.set_defaults(func=run)
    return p


def _exposure_encounters(args):
    if args.exposure_encounters is not None:
        return args.exposure_encounters
    if args.exposure_hours is not None:
        if not args.encounter_period:
            raise ValueError("--exposure-hours needs --encounter-period (s)")
        return args.exposure_hours * 3600.0 / args.encounter_period
    return None


def _read_events(path, pd):
    """The EVENTS table, or a one-line error naming the file."""
    try:
        events = pd.read_csv(path)
    except (pd.errors.EmptyDataError, pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise ValueError(f"EVENTS {path}: not a readable CSV table ({exc})".splitlines()[0]
                         ) from None
    if events.empty:
        raise ValueError(f"EVENTS {path} has a header but no rows")
    return events


def _need_column(events, column, option, path) -> None:
    if column not in events.columns:
        raise ValueError(f"{option}: column {column!r} not found in {path.name}; the table has "
                         f"{list(events.columns)}")


def _seed_column(events, seed, path):
    """``--seed``: its column, None for one continuous record; by default 'seed' if present."""
    if seed is None:
        return "seed" if "seed" in events.columns else None
    if str(seed).lower() == "none":
        return None
    if seed not in events.columns:
        raise ValueError(f"--seed: column {seed!r} not found in {path.name}; the table has "
                         f"{list(events.columns)} (--seed none: one continuous record)")
    return seed


def run(args) -> int:
    import numpy as np
    import pandas as pd

    from ..records import impacts as imp
    from ..records.load_fits import compare_load_distributions

    path = Path(args.events)
    if not path.exists():
        raise FileNotFoundError(f"EVENTS {path} does not exist")
    events = _read_events(path, pd)
    _need_column(events, args.load, "--load", path)
    _need_column(events, args.time, "--time", path)
    seed = _seed_column(events, args.seed, path)
    n_w = args.n_encounters if args.n_encounters is not None else len(events)
    rates = imp.impact_rates(events, n_w, value=args.load, levels=args.levels)
    print(f"{path.name}: {int(rates.loc['impact', 'n_events'])} impacts in {int(n_w)} encounters")
    print(rates.to_string(float_format=lambda v: f"{v:.4g}"))

    gaps = imp.inter_arrival_times(events, time=args.time, seed=seed, value=args.load)
    ks = imp.exponential_test(gaps)
    print(f"\ninter-arrival times: {ks['n']:.0f} gaps, mean {ks['mean']:.4g} s, "
          f"KS against exponential p = {ks['pvalue']:.3g}")
    impacts, gaps_dc = events[events[args.load] > 0], None
    if args.t_min:
        z = imp.clustering_test(gaps, args.t_min)
        impacts = imp.decluster(events, args.t_min, time=args.time, seed=seed, value=args.load)
        gaps_dc = imp.inter_arrival_times(impacts, time=args.time, seed=seed)
        print(f"gaps <= {args.t_min:g} s: {z['n_short']:.0f} (Poisson: {z['expected_short']:.1f}), "
              f"zero-inflation {z['zero_inflation']:.3f}, p = {z['pvalue']:.3g}")
        print(f"declustered (t_min {args.t_min:g} s): {len(impacts)} clusters, KS p = "
              f"{imp.exponential_test(gaps_dc, loc=args.t_min)['pvalue']:.3g} "
              f"(gaps beyond t_min against the exponential)")
    loads = impacts[args.load].to_numpy(dtype=float)
    fits = compare_load_distributions(loads, loc=args.loc)
    shown = fits[["distribution", "aic", "delta_aic", "ks_statistic", "ks_pvalue"]]
    what = "cluster maxima" if args.t_min else "peak loads"
    print(f"\n{what} ({loads.size}), ML fits ranked by AIC:")
    print(shown.to_string(float_format=lambda v: f"{v:.4g}"))

    best, pr = fits.iloc[0], loads.size / n_w
    n_exp = _exposure_encounters(args)
    exposure = None
    if n_exp is not None:
        mpm = imp.exposure_load(1.0 - np.exp(-1.0), pr, best["dist"], n_exp)
        print(f"\nexposure of {n_exp:.0f} encounters, {fits.index[0]} fit, Pr = {pr:.4g} per "
              f"encounter: MPM (exceeded with 1 - 1/e) {mpm:.4g}")
        grid = np.linspace(np.min(loads), 3.0 * np.max(loads), 200)
        if args.limit is not None:
            grid = np.unique(np.r_[grid, args.limit])
            print(f"P(maximum > {args.limit:g}) = "
                  f"{imp.exposure_probability(args.limit, pr, best['dist'], n_exp):.4g}")
        exposure = imp.exposure_probability(grid, pr, best["dist"], n_exp)
    if args.out:
        _write(Path(args.out), rates, fits, exposure, gaps, gaps_dc, loads, best, pr, n_exp,
               args.t_min or 0.0)
    return 0


def _write(out, rates, fits, exposure, gaps, gaps_dc, loads, best, pr, n_exp, t_min):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plotting.impacts import plot_exposure, plot_inter_arrival, plot_qq

    out.mkdir(parents=True, exist_ok=True)
    rates.to_csv(out / "rates.csv")
    fits.drop(columns=["dist"]).to_csv(out / "fits.csv")
    figs = {"inter_arrival": plot_inter_arrival(gaps, declustered=gaps_dc, t_min=t_min)[0],
            "qq": plot_qq(loads, fits.head(3))[0]}
    if exposure is not None:
        exposure.to_csv(out / "exposure.csv")
        figs["exposure"] = plot_exposure(exposure.index, pr, best["dist"], n_exp)[0]
    for name, fig in figs.items():
        fig.savefig(out / f"{name}.png", dpi=110)
        plt.close(fig)
    print(f"\nwrote {out}/: rates.csv, fits.csv{', exposure.csv' if exposure is not None else ''}"
          f", {', '.join(f'{n}.png' for n in figs)}")
