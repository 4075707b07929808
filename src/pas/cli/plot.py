"""``pas plot``: draw the figures of a finished ``pas run`` from its output folder.

::

    pas plot RESULT_DIR [--kind mpm|distribution|scatter|aic|all] [--out FILE]

Reads the files :meth:`pas.study.result.ScreeningResult.save` wrote (``summary.json``,
``history.csv``, ``distribution.csv``, ``pairs.csv``, ``range_curves.csv``,
``lf_curve.csv``) and draws them with :mod:`pas.plotting.figures`.  The
scatter shows every evaluated LF–HF pair (false positives at HF = 0) with
the final copula; no oracle is called again.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from ._parsers import command_parser

__all__ = ["add_parser", "run", "load_result", "KINDS"]

KINDS = ("mpm", "distribution", "scatter", "aic")

EPILOG = """\
examples:
  pas plot run1                                   # MPM convergence -> run1/mpm.png
  pas plot run1 --kind distribution --out dist.pdf
  pas plot run1 --kind all                        # every figure -> run1/figures/*.png
  pas plot run1 --kind all --out report/ --format svg
  pas plot run1 --kind mpm --truth 10.53 --unit m # with the true MPM and a unit
"""


def load_result(path):
    """Read a ``pas run`` output folder (:meth:`pas.study.result.ScreeningResult.load`).

    Returns
    -------
    result : ScreeningResult
    summary : dict
        ``summary.json`` (including the run's ``inputs``).
    lf_curve : tuple of ndarray or None
        ``(d, l)`` of the LF peaks over the threshold, when saved.
    """
    import pandas as pd

    from ..study.result import ScreeningResult, read_summary

    try:
        summary = read_summary(path)
    except FileNotFoundError as exc:
        raise FileNotFoundError(f"RESULT_DIR {exc}") from None
    lf_curve = None
    if (Path(path) / "lf_curve.csv").exists():
        lc = pd.read_csv(Path(path) / "lf_curve.csv")
        lf_curve = (lc["d"].to_numpy(dtype=float), lc["lf"].to_numpy(dtype=float))
    return ScreeningResult.load(path), summary, lf_curve


def _draw(kind, result, summary, lf_curve, args):
    from ..plotting import figures
    from ..plotting._common import current_rows

    inputs = summary.get("inputs") or {}
    unit = args.unit if args.unit is not None else inputs.get("unit")
    lf_unit = args.lf_unit if args.lf_unit is not None else inputs.get("lf_unit")
    if kind == "mpm":
        return figures.plot_mpm_convergence(result, truth=args.truth, unit=unit)[0]
    if kind == "distribution":
        return figures.plot_distribution(result, lf=lf_curve, unit=unit, lf_unit=lf_unit)[0]
    if kind == "scatter":
        h = current_rows(result.history)  # a replaced result is no evaluated event
        ok = h["status"].isin(["true_positive", "false_positive"]).to_numpy()
        lf = h["lf"].to_numpy(dtype=float)[ok]
        hf = h["hf"].to_numpy(dtype=float)[ok]
        return figures.plot_scatter(lf, hf, result=result, lf_unit=lf_unit, unit=unit,
                                    label="evaluated events")[0]
    if kind == "aic":
        return figures.plot_aic(result)[0]
    raise ValueError(f"--kind: unknown figure {kind!r}")  # argparse prevents this


def add_parser(sub) -> None:
    """Register ``pas plot`` on the sub-command parser ``sub``."""
    p = command_parser(
        sub, "plot", "draw the figures of a 'pas run' output folder", __doc__, EPILOG
    )
    p.add_argument("result_dir", metavar="RESULT_DIR", help="the --out folder of 'pas run'")
    p.add_argument("--kind", choices=KINDS + ("all",), default="mpm",
                   help="which figure (default: mpm); 'all' draws every figure that applies")
    p.add_argument("--out", metavar="FILE",
                   help="output file (one kind; format from the extension) or folder (--kind all);"
                        " default RESULT_DIR/<kind>.png or RESULT_DIR/figures/")
    p.add_argument("--format", default="png", choices=("png", "pdf", "svg"),
                   help="file format for --kind all (default png)")
    p.add_argument("--dpi", type=int, default=150, help="resolution of raster output (default 150)")
    p.add_argument("--truth", type=float, metavar="H", help="true MPM to draw on the mpm figure")
    p.add_argument("--unit", help="HF load unit for the axes (default: from pas run --unit)")
    p.add_argument("--lf-unit", help="LF indicator unit (default: from pas run --lf-unit)")
    p.set_defaults(func=run)


def run(args) -> int:
    """Execute ``pas plot``; prints the path of every file written."""
    import matplotlib

    if "matplotlib.pyplot" not in sys.modules:
        # a fresh CLI process draws files only, also without a display; called from a
        # notebook or a GUI session, the user's backend is left alone
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if args.truth is not None and not math.isfinite(args.truth):
        raise ValueError(f"--truth must be a finite number, got {args.truth}")
    if args.dpi <= 0:
        raise ValueError(f"--dpi must be positive, got {args.dpi}")
    result, summary, lf_curve = load_result(args.result_dir)
    if result.distribution.empty or not np.isfinite(result.mpm):
        raise ValueError(f"RESULT_DIR {args.result_dir}: the run made no fit yet, nothing to draw")
    base = Path(args.result_dir)
    if args.kind == "all":
        folder = Path(args.out) if args.out else base / "figures"
        folder.mkdir(parents=True, exist_ok=True)
        kinds = [k for k in KINDS if k != "aic" or result.strategy == "pas"]
        targets = [(k, folder / f"{k}.{args.format}") for k in kinds]
    else:
        target = Path(args.out) if args.out else base / f"{args.kind}.png"
        if target.suffix.lower().lstrip(".") not in ("png", "pdf", "svg"):
            raise ValueError(f"--out: {target.name} needs a .png, .pdf or .svg extension")
        target.parent.mkdir(parents=True, exist_ok=True)
        targets = [(args.kind, target)]
    for kind, target in targets:
        fig = _draw(kind, result, summary, lf_curve, args)
        fig.savefig(target, dpi=args.dpi)
        plt.close(fig)
        print(target)
    return 0
