"""``pas run``: one screening study from an LF peak file and an HF oracle, in one go.

::

    pas run LF_FILE --oracle KIND:ARGS --n-waves N --p-exp P (--precision P | --eps1 E) [options]

``LF_FILE`` is a CSV or Parquet table (one row per wave event; ``--lf-column``
names the LF peak column, ``--id-column`` the event ids) or a NumPy ``.npy``
file (a 1-D array, or a structured array with named columns).  The oracle
(:func:`pas.study.oracle_spec.oracle_from_spec`) is one of

``table:FILE[:ID_COLUMN:VALUE_COLUMN]``
    HF results looked up by event id in a CSV/Parquet table (basin tests, a
    finished HF Monte-Carlo): :class:`pas.study.oracles.TableOracle`;
    columns default to ``id`` and ``hf``.  Several value columns,
    ``table:FILE:ID:COL1,COL2``, answer one named load per column: screen
    on one with ``--target COL1`` (the store keeps all; ``pas study refit``).
``python:MODULE:FUNCTION``
    A Python function ``f(event) -> float``; ``MODULE`` is an importable
    module name or a path to a ``.py`` file.
``command:ARGS``
    An external program per event (CFD), given as an argument list split
    like a shell would split it but never run through a shell:
    :class:`pas.study.command_oracle.CommandOracle` with placeholders ``{id}``,
    ``{index}``, ``{lf}``, ``{d}``, ``{workdir}``, ``{result}`` and the
    ``--meta-columns``, and ``{cwd}``, the folder the study was first run
    from; each event runs in ``OUT/hf-runs/<id>/``, and the program and the
    arguments that name files or folders in ``{cwd}`` (``python
    cfd_event.py``) are taken from there, also when the run is resumed from
    another folder.  The result file holds a number, or a JSON object of
    named loads (``{"deck_force": 812.0, "panel_p3": 41.2}``, with ``--target``).

Progress goes to stderr (one line per HF result: iteration, HF count, MPM
with the sampling part of its band, Ē, COV; with ``--quiet`` only one line
per failed HF evaluation, naming the event and its LF rank); the result
summary to stdout (``--json`` for machine-readable), with the MPM's U95 and
its two labelled parts.  ``--n-waves`` below the number of LF peaks over the
threshold is an error (exceedance probabilities would exceed 1) unless
``--n-waves-convention spectral`` says that n_w = T_MCS/T_p,e on purpose.
Ctrl-C, SIGTERM (a batch job's time limit) or a closed pipe writes the
partial result and says how to resume.
A run that ends with failed HF evaluations left out of its fit exits with
code 3, one stopped at the failure limit with 1 (:data:`pas.cli.EXIT_CODES`).
The output folder receives ``history.csv``, ``distribution.csv``,
``pairs.csv``, ``range_curves.csv``, ``lf_curve.csv`` and ``summary.json``
— everything ``pas plot`` needs to redraw the figures — and, unless
``--no-store``, the crash-safe study store ``study.sqlite``: run the same
command again after a crash and no HF result is lost or re-run (stderr says
how many results it reused).  On a resumed study ``--eps1``, ``--precision``, ``--eps2``,
``--max-hf`` and ``--max-failures`` change the stored values only when given.
More than ``--max-failures`` failed HF evaluations stop the run (exit code 1);
``--retry-failed`` on the same ``--out`` runs the failed events again once
the oracle is fixed, and the study continues as if they had not failed
(:meth:`pas.study.study.Study.retry_failed`).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from .._support import docs_page
from ..study.schema import DEFAULT_MAX_HF, RESUMABLE
from ._parsers import command_parser
from ._stopping_options import optional_number, precision_option

__all__ = ["add_parser", "run"]

EPILOG = """\
examples:
  # basin or HF Monte-Carlo results keyed by event id (columns "id" and "hf")
  pas run lf_peaks.csv --lf-column rwe --oracle table:basin.csv \\
      --n-waves 16364 --p-exp 2.55e-3 --eps1 0.1 --threshold 12 --out run1

  # stop once the design load is known to +-10 %, whatever its unit
  pas run lf_peaks.csv --oracle table:basin.csv --n-waves 16364 --p-exp 2.55e-3 \\
      --precision 10% --out run2

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

exit codes: 0 done; 1 stopped at the failure limit (partial result written); 2 bad input;
3 done, but failed HF evaluations were left out of the fit; 130 interrupted (Ctrl-C);
143 terminated (SIGTERM, e.g. a batch job's time limit); both write the partial result
(see 'pas --help')
"""


_INPUTS = (
    "lf_file",
    "lf_column",
    "id_column",
    "oracle",
    "n_waves",
    "n_waves_convention",
    "p_exp",
    "eps1",
    "precision",
    "eps2",
    "threshold",
    "strategy",
    "preset",
    "max_hf",
    "batch_size",
    "unit",
    "lf_unit",
    "target",
)
"""The options written to ``summary.json`` as the run's ``inputs``."""

_LF_FILE_NAMES = {"file": "LF_FILE", "column": "--lf-column", "id_column": "--id-column",
                  "meta_columns": "--meta-columns"}


def _budget(text):
    """``--max-hf``: a positive integer, ``none`` for no budget, or ``default``."""
    word = str(text).strip().lower()
    return None if word == "none" else "default" if word == "default" else _positive_int(text)


class _NotGiven:
    """Default of an option that a resumed study keeps as stored unless it is given."""

    def __init__(self, value):
        self.value = value


def _count(text):
    """``--max-failures``: an integer >= 0."""
    try:
        v = int(text)
    except ValueError:
        v = -1
    if v < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return v


def _positive_int(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if v <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return v


STRATEGY_NAMES = ("pas", "as")
DEPARTURES_PAGE = docs_page("explanation/departures.md")
"""The names of :data:`pas.study.factory.STRATEGIES`, kept here so ``pas --help`` imports
no strategy (a test checks that the two agree)."""


def add_parser(sub) -> None:
    """Register ``pas run`` on the sub-command parser ``sub``."""
    p = command_parser(
        sub, "run", "run PAS (or AS) on an LF peak file with an HF oracle", __doc__, EPILOG
    )
    p.add_argument(
        "lf_file", metavar="LF_FILE", help="LF peaks: .csv (header row), .parquet or .npy"
    )
    p.add_argument("--lf-column", metavar="COL",
                   help="column with the LF peaks (default: 'lf', or the only column)")
    p.add_argument("--id-column", metavar="COL",
                   help="column with event ids (default: 'id' if present, else the row number)")
    p.add_argument("--meta-columns", metavar="A,B", type=lambda s: [c for c in s.split(",") if c],
                   default=[], help="columns handed to the oracle as event.meta (comma separated)")
    p.add_argument("--oracle", required=True, metavar="KIND:ARGS",
                   help="table:FILE[:ID_COL:VALUE_COL] | python:MODULE:FUNCTION | command:ARGS")
    p.add_argument("--n-waves", required=True, type=_positive_int, metavar="N",
                   help="wave encounters in the LF Monte-Carlo run (n_w)")
    p.add_argument("--n-waves-convention", choices=("count", "spectral"), default="count",
                   help="'count' (default): N counted wave encounters, at least the LF peaks "
                        "over the threshold; 'spectral': N = T_MCS/T_p,e on purpose (paper "
                        "Table 2), may lie below the number of peaks")
    p.add_argument("--p-exp", required=True, type=float, metavar="P",
                   help="target exceedance probability (e.g. T_1/T_exp)")
    p.add_argument("--eps1", type=optional_number, default=_NotGiven(None), metavar="E",
                   help="stopping limit on the distribution change, load units (~1-2%% of the "
                        "max; the paper's rule); 'none' drops it from a resumed study")
    p.add_argument("--precision", type=precision_option, default=_NotGiven(None), metavar="P",
                   help="stop once the U95 of the MPM is within +-P of it, e.g. 10%% or 0.1 "
                        "(scale-free); give this, --eps1 or both (both must hold)")
    p.add_argument("--eps2", type=float, default=_NotGiven(0.1), metavar="C",
                   help="stopping limit on the COV of the MPM (default 0.1)")
    p.add_argument("--threshold", type=float, metavar="L0", help="LF threshold l0_input")
    p.add_argument("--seed", type=int, help="random seed (default: drawn and reported)")
    p.add_argument("--max-hf", type=_budget, default=_NotGiven("default"), metavar="N",
                   help=f"budget of HF evaluations (default {DEFAULT_MAX_HF}, the most the paper "
                        "needed, or none with --preset paper; 'none': no budget)")
    p.add_argument("--max-failures", type=_count, default=_NotGiven(None), metavar="N",
                   help="failed HF evaluations tolerated before the run stops (default 10)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run the failed events of the study in --out again (after fixing the "
                        "oracle): the study continues as if they had not failed")
    p.add_argument("--preset", choices=("default", "paper"), default="default",
                   help="PAS settings: the package's defaults, or 'paper' to run the method as "
                        f"van Essen & Seyffert (2026) wrote it ({DEPARTURES_PAGE})")
    p.add_argument("--strategy", choices=STRATEGY_NAMES, default="pas",
                   help="PAS (copula, default) or AS (GPR on order statistics)")
    p.add_argument("--target", metavar="NAME",
                   help="with an oracle answering several named loads: the one to screen on "
                        "(the study store keeps all; 'pas study refit' analyses another)")
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
    p.add_argument("--quiet", action="store_true",
                   help="no progress on stderr, only one line per failed HF evaluation")
    p.add_argument("--json", action="store_true", help="print the result summary as JSON")
    p.set_defaults(func=run)



def output_and_oracle(args):
    """``(--out folder, the oracle of --oracle)``, each checked with a one-line error; the
    oracle's runs go to ``OUT/hf-runs`` (``pas run``, ``pas long-term``)."""
    from ..study.oracle_spec import oracle_from_spec

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {out} is a file; give a folder (it is created when missing)")
    try:
        oracle = oracle_from_spec(args.oracle, root=(out / "hf-runs").resolve(),
                                  timeout=args.timeout)
    except (ValueError, FileNotFoundError) as exc:
        raise type(exc)(f"--oracle: {exc}") from None
    return out, oracle

def run(args) -> int:
    """Execute ``pas run``; returns the exit code (:data:`pas.cli.EXIT_CODES`)."""
    from ..api import make_study
    from ..strategies.screening import check_n_waves
    from ..study.command_oracle import CommandOracle
    from ..study.inputs import lf_table, read_lf_peaks
    from ..study.oracle_spec import keep_start_dir, recorded_start_dir, started_oracle
    from ..study.oracles import OracleFailureLimit
    from ..study.replay import attach
    from ..study.settings import lacks_a_limit
    from ..study.store import StoreError, read_settings
    from . import EXIT_FAILED_LEFT_OUT, EXIT_STOPPED
    from ._progress import Progress, resuming_line, retried_line, stopped

    _check_numbers(args)
    lf, ids, meta = read_lf_peaks(args.lf_file, column=args.lf_column, id_column=args.id_column,
                                  meta_columns=args.meta_columns, guess_columns=True,
                                  names=_LF_FILE_NAMES)
    note = check_n_waves(lf, args.n_waves, args.threshold, convention=args.n_waves_convention,
                         names={"n_waves": "--n-waves",
                                "convention": "--n-waves-convention spectral"})
    if note is not None:
        print(f"pas run: warning: {note}", file=sys.stderr)
    out, oracle = output_and_oracle(args)
    store = None if args.no_store else out / "study.sqlite"
    if args.retry_failed and store is None:
        raise ValueError("--retry-failed needs the study store of an earlier run: drop --no-store")
    failed = None
    try:
        stored = {} if store is None else read_settings(store)
        seed = args.seed if args.seed is not None or store is None else stored.get("seed")
        settings = _resumable_settings(args, stored)
        if (missing := lacks_a_limit(settings, spell=lambda name: "--" + name)) is not None:
            raise ValueError(missing)
        objects = _settings_objects(args, settings)
        inputs = {name: getattr(args, name) for name in _INPUTS}
        study = make_study(objects.pop("strategy"), lf_table(lf, ids, meta, "--meta-columns"),
                           n_waves=args.n_waves, p_exp=args.p_exp, threshold=args.threshold,
                           seed=seed, target=args.target, **objects,
                           n_waves_convention="spectral")  # checked above, with option names
        # the command, against the folder the study was started in, before anything is
        # recorded (a new study's before its folder is made)
        if isinstance(oracle, CommandOracle):
            started_oracle(oracle, recorded_start_dir(store))[0].check(study.lfset.event(0))
        if store is not None:  # only now: bad inputs leave no output folder behind
            out.mkdir(parents=True, exist_ok=True)
            for ch in attach(study, store):
                print(f"pas run: {ch['key']} changed from {ch['old']} to {ch['new']} on resuming "
                      f"(recorded in {store})", file=sys.stderr)
            oracle, note = keep_start_dir(oracle, study.store)
            for line in (note or "").splitlines():
                print(f"pas run: {line}", file=sys.stderr)
            if args.retry_failed:
                print(retried_line(study.retry_failed()), file=sys.stderr)
            if stored:
                print(resuming_line(study, store), file=sys.stderr)
        try:
            result = study.optimize(oracle, batch_size=args.batch_size, n_workers=args.workers,
                                    callback=Progress(quiet=args.quiet))
        except (KeyboardInterrupt, BrokenPipeError) as exc:
            written = _save_partial(study, out, inputs, args)
            raise stopped("pas run", exc, study, store=store, out=written,
                          resume="the same 'pas run' command", oracle=oracle) from None
    except StoreError as exc:
        raise ValueError(f"{exc} (to start a new study use another --out or --no-store)") from None
    except OracleFailureLimit as exc:
        result, failed = exc.result, getattr(exc, "reason", str(exc))
    summary = result.save(out, inputs={**inputs, "lf_file": str(args.lf_file), "seed": result.seed},
                          lfset=study.lfset)
    if store is not None:
        study.store.close()  # the .sqlite file alone holds the study
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(result.summary(unit=args.unit))
        print(f"results written to {out}/ (draw them with: pas plot {out} --kind all)")
    if failed is not None:
        how = ("fix the oracle and rerun with --retry-failed (same --out)" if store is not None
               else "fix the oracle and run again")
        print(f"pas run: error: {failed}; {how}, or raise --max-failures (partial result "
              f"written to {out}/)", file=sys.stderr)
        return EXIT_STOPPED
    return EXIT_FAILED_LEFT_OUT if result.n_failed else 0


def _settings_objects(args, flat: dict) -> dict:
    """The strategy, ``stopping`` and ``budget`` of the run (:func:`pas.study.flat.from_flat`)
    from the flat settings of :func:`_resumable_settings` and ``--preset``."""
    from ..study.flat import from_flat

    given = {k: v for k, v in flat.items() if not (k == "max_hf" and v == "default")}
    return from_flat(given, strategy=args.strategy, preset=args.preset)


def _resumable_settings(args, stored: dict) -> dict:
    """The stopping settings and budgets (:data:`~pas.study.schema.RESUMABLE`) to build with.

    An option given on the command line wins; otherwise a resumed study keeps
    its stored value (e.g. one changed with ``pas study set``) and a new one
    gets the option's default.  The options not given are set on ``args`` to
    the values used, for ``summary.json``.
    """
    from ..study.schema import with_legacy_settings

    stored = with_legacy_settings(stored) if stored else {}
    out = {}
    for key in RESUMABLE:
        given = getattr(args, key, _NotGiven(None))
        if not isinstance(given, _NotGiven):
            out[key] = given
        elif key in stored:
            out[key] = stored[key]
        elif given.value is not None:
            out[key] = given.value
        if hasattr(args, key):
            setattr(args, key, out.get(key))
    return out


def _save_partial(study, out, inputs, args):
    """Write the result so far to ``out`` after Ctrl-C or a closed pipe; the folder or None."""
    import warnings

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the partial result's own caveats
            # no bootstrap model band: its refits would hold up Ctrl-C for seconds
            partial = study.result(model_band=False)
            partial.save(out, inputs={**inputs, "lf_file": str(args.lf_file), "seed": study.seed,
                                      "stopped_early": True}, lfset=study.lfset)
    except (OSError, ValueError):
        return None
    return out


def _check_numbers(args) -> None:
    """Errors naming the option for numbers the study would reject under another name."""
    if not (0.0 < args.p_exp < 1.0):
        raise ValueError(f"--p-exp must lie in (0, 1), got {args.p_exp:g}")
    for name in ("eps1", "eps2"):
        v = getattr(args, name)
        if isinstance(v, _NotGiven) or v is None:
            continue
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"--{name} must be a positive number, got {v:g}")
    if args.timeout is not None and not args.timeout > 0:
        raise ValueError(f"--timeout must be a positive number of seconds, got {args.timeout:g}")
