"""``pas run``: one screening study from an LF peak file and an HF oracle, in one go.

::

    pas run LF_FILE --oracle SPEC --n-waves N --p-exp P --eps1 E [options]

``LF_FILE`` is a CSV or Parquet table (one row per wave event; ``--lf-column``
names the LF peak column, ``--id-column`` the event ids) or a NumPy ``.npy``
file (a 1-D array, or a structured array with named columns).  The oracle ``SPEC`` is one
of

``table:FILE[:ID_COLUMN:VALUE_COLUMN]``
    HF results looked up by event id in a CSV/Parquet table (basin tests, a
    finished HF Monte-Carlo): :class:`pas.study.oracles.TableOracle`;
    columns default to ``id`` and ``hf``.
``python:MODULE:FUNCTION``
    A Python function ``f(event) -> float``; ``MODULE`` is an importable
    module name or a path to a ``.py`` file.
``command:ARGS``
    An external program per event (CFD), given as an argument list split
    like a shell would split it but never run through a shell:
    :class:`pas.study.oracles.CommandOracle` with placeholders ``{id}``,
    ``{index}``, ``{lf}``, ``{d}``, ``{workdir}``, ``{result}`` and the
    ``--meta-columns``; each event runs in ``OUT/hf-runs/<id>/``.

Progress goes to stderr (one line per HF result: iteration, HF count, MPM,
Ē, COV); the result summary to stdout (``--json`` for machine-readable).
The output folder receives ``history.csv``, ``distribution.csv``,
``pairs.csv``, ``range_curves.csv``, ``lf_curve.csv`` and ``summary.json``
— everything ``pas plot`` needs to redraw the figures — and, unless
``--no-store``, the crash-safe study store ``study.sqlite``: run the same
command again after a crash and no HF result is lost or re-run.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import json
import math
import shlex
import sys
import warnings
from pathlib import Path

import numpy as np

__all__ = ["add_parser", "run", "load_lf_file", "make_oracle", "write_result", "OUTPUT_FILES"]

OUTPUT_FILES = ("history.csv", "distribution.csv", "pairs.csv", "range_curves.csv",
                "lf_curve.csv", "summary.json")
"""Files :func:`write_result` writes (and :func:`pas.cli.plot.load_result` reads)."""

EPILOG = """\
examples:
  # basin or HF Monte-Carlo results keyed by event id (columns "id" and "hf")
  pas run lf_peaks.csv --lf-column rwe --oracle table:basin.csv \\
      --n-waves 16364 --p-exp 2.55e-3 --eps1 0.1 --threshold 12 --out run1

  # the same table with other column names, AS instead of PAS, JSON summary
  pas run lf_peaks.csv --oracle table:basin.csv:event:force_kN --n-waves 16364 \\
      --p-exp 2.55e-3 --eps1 20 --strategy as --json --quiet

  # a Python function f(event) -> float in my_oracles.py
  pas run peaks.npy --oracle python:my_oracles.py:green_water --n-waves 20000 \\
      --p-exp 1e-3 --eps1 5 --seed 1 --max-hf 120

  # one CFD run per event, two at a time, 6 h time-out each
  pas run lf_peaks.csv --meta-columns seed,t_start \\
      --oracle 'command:python cfd_event.py --seed {seed} --t0 {t_start} --out {result}' \\
      --n-waves 16364 --p-exp 2.55e-3 --eps1 0.1 --workers 2 --timeout 21600 --out cfd

  # then draw the figures
  pas plot run1 --kind all
"""


# -- inputs -------------------------------------------------------------------
_LF_FILE_NAMES = {"file": "LF_FILE", "column": "--lf-column", "id_column": "--id-column",
                  "meta_columns": "--meta-columns"}


def load_lf_file(path, *, column=None, id_column=None, meta_columns=()):
    """Read LF peaks (and optional ids and metadata) for ``pas run``.

    :func:`pas.io.read_lf_peaks` with the defaults of ``pas run`` (column
    ``lf`` if present, else the only column; ids from ``id`` if present) and
    errors naming its options.

    Returns
    -------
    lf : ndarray
    ids : list or None
    meta : list of dict or None
    """
    from ..io import read_lf_peaks

    return read_lf_peaks(path, column=column, id_column=id_column, meta_columns=meta_columns,
                         guess_columns=True, names=_LF_FILE_NAMES)


def _load_python_function(target: str, func: str):
    if target.endswith(".py"):
        file = Path(target)
        if not file.exists():
            raise FileNotFoundError(f"--oracle: python file {file} does not exist")
        spec = importlib.util.spec_from_file_location(f"_pas_oracle_{file.stem}", file)
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # so a process pool can unpickle its functions
        try:
            spec.loader.exec_module(module)
        except Exception as exc:
            raise ValueError(f"--oracle: importing {file} failed: {type(exc).__name__}: {exc}") from None
    else:
        try:
            module = importlib.import_module(target)
        except ImportError as exc:
            raise ValueError(f"--oracle: cannot import module {target!r} ({exc})") from None
    fn = getattr(module, func, None)
    if not callable(fn):
        raise ValueError(f"--oracle: {target} has no function {func!r}")
    return fn


def make_oracle(spec: str, *, workdir=None, timeout=None):
    """Build the HF oracle from an ``--oracle`` specification (see the module docs).

    Parameters
    ----------
    spec : str
        ``table:FILE[:ID_COLUMN:VALUE_COLUMN]``, ``python:MODULE:FUNCTION`` or
        ``command:ARGS``.
    workdir : path, optional
        Root of the per-event working directories of a command oracle.
    timeout : float, optional
        Seconds per event for a command oracle.

    Returns
    -------
    callable
        ``oracle(event) -> float``.
    """
    kind, sep, rest = spec.partition(":")
    if not sep or not rest:
        raise ValueError(f"--oracle: {spec!r} is not table:FILE[:ID:VALUE], "
                         "python:MODULE:FUNCTION or command:ARGS")
    if kind == "table":
        from ..study.oracles import TableOracle

        parts = rest.split(":")
        if len(parts) == 1:
            path, id_col, val_col = parts[0], "id", "hf"
        elif len(parts) == 3 and all(parts):
            path, id_col, val_col = parts
        else:
            raise ValueError(f"--oracle: {spec!r}: expected table:FILE or "
                             "table:FILE:ID_COLUMN:VALUE_COLUMN")
        try:
            return TableOracle(path, id_column=id_col, value_column=val_col)
        except ValueError as exc:
            raise ValueError(f"--oracle: {exc}") from None
    if kind == "python":
        target, sep, func = rest.rpartition(":")
        if not sep or not target or not func:
            raise ValueError(f"--oracle: {spec!r}: expected python:MODULE:FUNCTION")
        return _load_python_function(target, func)
    if kind == "command":
        from ..study.oracles import CommandOracle

        try:
            args = shlex.split(rest)
        except ValueError as exc:
            raise ValueError(f"--oracle: cannot split the command {rest!r}: {exc}") from None
        if not args:
            raise ValueError("--oracle: command: is empty")
        return CommandOracle(args, root=workdir or "hf-runs", timeout=timeout)
    raise ValueError(f"--oracle: unknown kind {kind!r} (use table:, python: or command:)")


# -- outputs ------------------------------------------------------------------
def _json_safe(x):
    if isinstance(x, dict):
        return {str(k): _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, (np.floating, float)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, np.bool_):
        return bool(x)
    return x


def write_result(result, out, *, inputs=None, lfset=None) -> dict:
    """Write a :class:`~pas.study.result.ScreeningResult` to folder ``out``.

    Writes :data:`OUTPUT_FILES`: the history, the final distribution, the
    true-positive pairs, the per-iteration curves on the stopping range, the
    LF exceedance curve (when ``lfset`` is given) and ``summary.json``
    (``result.to_dict()`` plus ``inputs``).  :func:`pas.cli.plot.load_result`
    reads them back.

    Returns
    -------
    dict
        The summary written to ``summary.json``.
    """
    import pandas as pd

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    result.history.to_csv(out / "history.csv", index=False)
    result.distribution.to_csv(out / "distribution.csv", index=False)
    result.pairs.to_csv(out / "pairs.csv", index=False)
    result.range_curves.to_csv(out / "range_curves.csv", index_label="row")
    if lfset is not None:
        pd.DataFrame({"d": lfset.d, "lf": lfset.lf}).to_csv(out / "lf_curve.csv", index=False)
    summary = _json_safe({**result.to_dict(), "summary": result.summary(),
                          "inputs": dict(inputs or {})})
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    return summary


class _Progress:
    """``callback(study, row)`` printing one line per HF result on stderr."""

    def __init__(self, stream=None):
        self.stream = stream or sys.stderr

    def __call__(self, study, row) -> None:
        status = row.get("status")
        hf = row.get("hf")
        if status == "failed":
            what = f"FAILED ({row.get('error')})"
        elif status == "false_positive":
            what = "HF 0 (false positive)"
        else:
            what = f"HF {hf:.4g}"
        mpm = row.get("mpm")
        model = "no fit yet"
        if mpm is not None and np.isfinite(mpm):
            e_bar, cov = row.get("E_bar"), row.get("COV")
            fam = f" {row['family']}" if row.get("family") else ""
            model = (f"MPM {mpm:.4g} [{row.get('mpm_low', np.nan):.4g}, "
                     f"{row.get('mpm_high', np.nan):.4g}]{fam}  "
                     f"E_bar {_num(e_bar)} (eps1 {study.stopping.eps1:g})  "
                     f"COV {_num(cov)} (eps2 {study.stopping.eps2:g})")
            if row.get("stop"):
                model += "  converged"
        print(f"[pas] it {row['row'] + 1:>4}  n_HF {study.n_hf:>4}  event {row['event_id']}  "
              f"LF {row['lf']:.4g}  {what}  {model}", file=self.stream, flush=True)


def _num(x) -> str:
    return "-" if x is None or not np.isfinite(x) else f"{x:.3g}"


# -- command ----------------------------------------------------------------
def _positive_int(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if v <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return v


def add_parser(sub) -> None:
    """Register ``pas run`` on the sub-command parser ``sub``."""
    p = sub.add_parser(
        "run", help="run PAS (or AS) on an LF peak file with an HF oracle",
        description=__doc__.split("\n\n")[0].replace("``", ""),
        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=EPILOG)
    p.add_argument("lf_file", metavar="LF_FILE", help="LF peaks: .csv (header row), .parquet or .npy")
    p.add_argument("--lf-column", metavar="COL",
                   help="column with the LF peaks (default: 'lf', or the only column)")
    p.add_argument("--id-column", metavar="COL",
                   help="column with event ids (default: 'id' if present, else the row number)")
    p.add_argument("--meta-columns", metavar="A,B", type=lambda s: [c for c in s.split(",") if c],
                   default=[], help="columns handed to the oracle as event.meta (comma separated)")
    p.add_argument("--oracle", required=True, metavar="SPEC",
                   help="table:FILE[:ID_COL:VALUE_COL] | python:MODULE:FUNCTION | command:ARGS")
    p.add_argument("--n-waves", required=True, type=_positive_int, metavar="N",
                   help="wave encounters in the LF Monte-Carlo run (n_w)")
    p.add_argument("--p-exp", required=True, type=float, metavar="P",
                   help="target exceedance probability (e.g. T_1/T_exp)")
    p.add_argument("--eps1", required=True, type=float, metavar="E",
                   help="stopping limit on the distribution change, load units (~1-2%% of the max)")
    p.add_argument("--eps2", type=float, default=0.1, metavar="C",
                   help="stopping limit on the COV of the MPM (default 0.1)")
    p.add_argument("--threshold", type=float, metavar="L0", help="LF threshold l0_input")
    p.add_argument("--seed", type=int, help="random seed (default: drawn and reported)")
    p.add_argument("--max-hf", type=_positive_int, metavar="N", help="budget of HF evaluations")
    p.add_argument("--strategy", choices=("pas", "as"), default="pas",
                   help="PAS (copula, default) or AS (GPR on order statistics)")
    p.add_argument("--batch-size", type=_positive_int, default=1, metavar="Q",
                   help="events per iteration (default 1)")
    p.add_argument("--workers", type=_positive_int, metavar="N",
                   help="run a batch's oracle calls in N local processes")
    p.add_argument("--timeout", type=float, metavar="S", help="seconds per event (command oracle)")
    p.add_argument("--unit", help="unit of the HF load, for the figures (e.g. kN)")
    p.add_argument("--lf-unit", help="unit of the LF indicator, for the figures (e.g. m)")
    p.add_argument("--out", default="pas-run", metavar="DIR",
                   help="output folder (default: pas-run)")
    p.add_argument("--no-store", action="store_true",
                   help="do not keep the crash-safe study store OUT/study.sqlite")
    p.add_argument("--quiet", action="store_true", help="no progress output on stderr")
    p.add_argument("--json", action="store_true", help="print the result summary as JSON")
    p.set_defaults(func=run)


def run(args) -> int:
    """Execute ``pas run``; returns the exit code (0 done, 1 oracle failure limit)."""
    from ..api import run_as, run_pas
    from ..screening import LFSet
    from ..study.store import StoreError
    from ..study.study import OracleFailureLimit

    if not (0.0 < args.p_exp < 1.0):
        raise ValueError(f"--p-exp must lie in (0, 1), got {args.p_exp:g}")
    for name in ("eps1", "eps2"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"--{name} must be a positive number, got {v:g}")
    if args.timeout is not None and not args.timeout > 0:
        raise ValueError(f"--timeout must be a positive number of seconds, got {args.timeout:g}")
    lf, ids, meta = load_lf_file(args.lf_file, column=args.lf_column, id_column=args.id_column,
                                 meta_columns=args.meta_columns)
    with warnings.catch_warnings():  # the run itself repeats any warning about the inputs
        warnings.simplefilter("ignore")
        lfset = LFSet(lf, n_waves=args.n_waves, p_exp=args.p_exp, threshold=args.threshold)
    out = Path(args.out)
    oracle = make_oracle(args.oracle, workdir=out / "hf-runs", timeout=args.timeout)
    out.mkdir(parents=True, exist_ok=True)
    inputs = {
        "lf_file": str(args.lf_file), "lf_column": args.lf_column, "id_column": args.id_column,
        "oracle": args.oracle, "n_waves": args.n_waves, "p_exp": args.p_exp, "eps1": args.eps1,
        "eps2": args.eps2, "threshold": args.threshold, "strategy": args.strategy,
        "max_hf": args.max_hf, "batch_size": args.batch_size, "unit": args.unit,
        "lf_unit": args.lf_unit,
    }
    fn = run_pas if args.strategy == "pas" else run_as
    store = None if args.no_store else str(out / "study.sqlite")
    kw = dict(n_waves=args.n_waves, p_exp=args.p_exp, eps1=args.eps1, eps2=args.eps2,
              threshold=args.threshold, seed=args.seed, max_hf=args.max_hf, ids=ids, meta=meta,
              batch_size=args.batch_size, n_workers=args.workers, study=store,
              callback=None if args.quiet else _Progress())
    failed = None
    try:
        result = fn(lf, oracle, **kw)
    except StoreError as exc:
        raise ValueError(f"{exc} (to start a new study use another --out or --no-store)") from None
    except OracleFailureLimit as exc:
        if exc.result is None:
            raise ValueError(str(exc)) from None
        result, failed = exc.result, str(exc)
    summary = write_result(result, out, inputs={**inputs, "seed": result.seed}, lfset=lfset)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(result.summary())
        print(f"results written to {out}/ (draw them with: pas plot {out} --kind all)")
    if failed is not None:
        print(f"pas run: error: {failed} (partial result written to {out}/)", file=sys.stderr)
        return 1
    return 0
