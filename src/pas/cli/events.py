"""``pas events``: the events table of an LF time series, one event per zero-up-crossing wave.

::

    pas events SERIES... [--dt S] [--column COL] [--time COL] [--threshold L]
               [--exposure-hours H] [--out events.csv]

Each ``SERIES`` file is one LF record (e.g. one seed of the linear relative
wave elevation at the bow): a ``.npy`` file with a 1-D array of samples at
step ``--dt``, or a CSV with a header row, its time column (s; ``--time``,
default ``t`` or ``time`` when present, else the samples are ``--dt`` apart)
and its signal column (``--column``, default the only other column).  The
file name (without suffix) names the record.  Every complete zero-up-crossing
wave is one event: its crest is the LF peak, its window the up-crossing and
the next (``t_start``, ``t_end``) with the crest time ``t_peak``
(:func:`pas.waves.lf_events.lf_events`).  Prints the number of waves
``n_waves`` (all of them, also with ``--threshold``), their mean period and,
with ``--exposure-hours``, ``p_exp`` = mean period / exposure; writes the
table (``id``, ``lf``, ``record``, ``wave``, ``t_start``, ``t_peak``,
``t_end``) for ``pas run``.  ``--threshold`` keeps only the events with an LF
peak above it; give the same ``--threshold`` to ``pas run``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_parser", "run"]

EPILOG = """\
examples:
  pas events bow_rwe.npy --dt 0.5 --exposure-hours 3 --out events.csv
  pas events seed1.csv seed2.csv seed3.csv --column rwe --threshold 2.0 --out events.csv
  pas run events.csv --meta-columns record,t_start,t_end --threshold 2.0 \\
      --n-waves N --p-exp P --oracle 'command:python cfd.py --record {record} --t0 {t_start}'
"""


def add_parser(sub) -> None:
    """Register ``pas events`` on the sub-command parser ``sub``."""
    from . import plain_text

    p = sub.add_parser("events", help="the events table (one per wave), n_waves and p_exp of "
                       "an LF time series", description=plain_text(__doc__), epilog=EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("series", metavar="SERIES", nargs="+",
                   help="LF records: .npy (1-D samples, needs --dt) or .csv (header row)")
    p.add_argument("--dt", type=float, metavar="S",
                   help="time step of the samples, s (.npy files; CSV files without a time "
                        "column)")
    p.add_argument("--column", metavar="COL",
                   help="CSV column with the LF signal (default: the only non-time column)")
    p.add_argument("--time", metavar="COL",
                   help="CSV column with the time, s (default: 't' or 'time' if present)")
    p.add_argument("--threshold", type=float, metavar="L",
                   help="keep only events with an LF peak above L (n_waves still counts all)")
    p.add_argument("--exposure-hours", type=float, metavar="H",
                   help="exposure duration, h, for p_exp = mean period / exposure")
    p.add_argument("--out", metavar="FILE", default="events.csv",
                   help="the events table, CSV (default: events.csv)")
    p.set_defaults(func=run)


def _read_series(path: Path, args, np, pd):
    """One record of ``SERIES``: an array (samples at --dt) or a Series indexed by time."""
    if not path.exists():
        raise FileNotFoundError(f"SERIES {path} does not exist")
    if path.suffix.lower() == ".npy":
        try:
            return np.load(path, allow_pickle=False)
        except ValueError as exc:
            raise ValueError(f"SERIES {path}: not a plain .npy array ({exc})") from None
    try:
        table = pd.read_csv(path)
    except (pd.errors.EmptyDataError, pd.errors.ParserError, UnicodeDecodeError) as exc:
        raise ValueError(f"SERIES {path}: not a readable CSV table ({exc})".splitlines()[0]
                         ) from None
    cols = list(table.columns)
    time = args.time or next((c for c in ("t", "time") if c in cols), None)
    if time is not None and time not in cols:
        raise ValueError(f"--time: column {time!r} not found in {path.name}; it has {cols}")
    rest = [c for c in cols if c != time]
    if args.column is None and len(rest) != 1:
        raise ValueError(f"--column: {path.name} has the columns {rest} besides the time; "
                         "name the LF signal's with --column")
    column = args.column or rest[0]
    if column not in cols:
        raise ValueError(f"--column: column {column!r} not found in {path.name}; it has {cols}")
    values = table[column]
    if time is None:
        return values.to_numpy()
    return pd.Series(values.to_numpy(), index=pd.Index(table[time].to_numpy(dtype=float)))


def run(args) -> int:
    import numpy as np
    import pandas as pd

    from ..waves.lf_events import lf_events

    paths = [Path(s) for s in args.series]
    names = [p.stem for p in paths]
    if len(set(names)) != len(names):
        raise ValueError("SERIES: two files have the same name; records are named by their "
                         "file name, so rename one")
    records = {name: _read_series(p, args, np, pd) for name, p in zip(names, paths)}
    exposure = None if args.exposure_hours is None else args.exposure_hours * 3600.0
    if exposure is not None and not exposure > 0:
        raise ValueError(f"--exposure-hours must be > 0, got {args.exposure_hours}")
    try:
        ev = lf_events(records, dt=args.dt, threshold=args.threshold, exposure=exposure)
    except ValueError as exc:  # series['seed1']: ... -> SERIES seed1.csv: ...
        message = str(exc)
        for name, path in zip(names, paths):
            message = message.replace(f"series[{name!r}]", f"SERIES {path}")
        raise ValueError(message) from None
    ev.table.to_csv(args.out, index=False)
    print(ev.summary())
    print(f"n_waves {ev.n_waves}  (counted zero-up-crossing waves, all records)")
    print(f"mean_period {ev.mean_period:.6g} s  (mean length of those waves)")
    if ev.p_exp is not None:
        print(f"p_exp {ev.p_exp:.6g}  (mean period / {args.exposure_hours:g} h)")
    print(f"wrote {len(ev.table)} events to {args.out}")
    return 0
