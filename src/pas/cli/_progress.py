"""What ``pas run`` and ``pas study run`` print while a study runs, and how they stop.

:class:`Progress` prints one line per told result and, even when quiet, one
stderr line per failed HF evaluation; :func:`stopped_message` is the one line
printed when Ctrl-C or a closed pipe ends a run early; :func:`resuming_line` and
:func:`retried_line` say what a continued run reuses and runs again.
"""

from __future__ import annotations

import math
import os
import sys

__all__ = ["Progress", "RunStopped", "failure_line", "precision_text", "stopped", "stopped_message",
           "resuming_line", "retried_line", "EXIT_INTERRUPTED", "EXIT_BROKEN_PIPE"]

#: Exit codes of an early stop: Ctrl-C (128 + SIGINT) and a closed pipe (128 + SIGPIPE),
#: what a shell reports for a process those signals killed.
EXIT_INTERRUPTED, EXIT_BROKEN_PIPE = 130, 141


class RunStopped(Exception):
    """A run ended early (Ctrl-C, closed pipe); the message says what was kept and how to resume.

    ``code`` is the exit code :func:`pas.cli.main` returns.
    """

    def __init__(self, message: str, code: int):
        super().__init__(message)
        self.code = code


def failure_line(command: str, study, row) -> str:
    """One line naming a failed HF evaluation: event, LF rank among the peaks, error."""
    rank = row["position"] + 1
    largest = " (the largest LF peak)" if rank == 1 else ""
    return (f"{command}: HF evaluation failed for event {row['event_id']}, LF rank {rank} of "
            f"{study.lfset.n}{largest}, LF {row['lf']:.4g}: {row.get('error')}; "
            "it is left out of the model")


class Progress:
    """``callback(study, row)`` printing one line per told result.

    Iteration, HF count, event, LF, the HF value (or the failure), and once a
    model is fitted the MPM with the sampling part of its U95 (the z-draw
    band of Eq. 10; the reported U95 adds the model part at the end), the
    copula family, ``Ē`` and the COV against their limits.

    Parameters
    ----------
    stream : file, optional
        Where to print the progress lines; default ``sys.stderr`` (read when called).
    quiet : bool, default False
        Print nothing but the failure lines.
    command : str, default "pas run"
        Prefix of the failure lines.

    Notes
    -----
    A failed HF evaluation always gives one line on stderr (:func:`failure_line`),
    also when ``quiet``: a failure of the largest LF event moves the MPM.
    """

    def __init__(self, stream=None, *, quiet: bool = False, command: str = "pas run"):
        self.stream = stream
        self.quiet = bool(quiet)
        self.command = command

    def __call__(self, study, row) -> None:
        stream = self.stream or sys.stderr
        failed = row.get("status") == "failed"
        if failed and (self.quiet or stream is not sys.stderr):
            print(failure_line(self.command, study, row), file=sys.stderr, flush=True)
        if self.quiet:
            return
        print(self.line(study, row), file=stream, flush=True)

    @staticmethod
    def line(study, row) -> str:
        status = row.get("status")
        if status == "failed":
            what = (f"FAILED (LF rank {row['position'] + 1} of {study.lfset.n}: "
                    f"{row.get('error')})")
        elif status == "false_positive":
            what = "HF 0 (false positive)"
        else:
            what = f"HF {row.get('hf'):.4g}"
        if not _finite(row.get("mpm")):
            model = ("no refit (the model of the last fit stands)"
                     if any(_finite(r.get("mpm")) for r in study.rows if r is not row)
                     else "no fit yet")
        else:
            fam = f" {row['family']}" if row.get("family") else ""
            model = (f"MPM {row['mpm']:.4g} (sampling band {_num(row.get('mpm_low'), '.4g')}–"
                     f"{_num(row.get('mpm_high'), '.4g')}){fam}")
            rule = study.rule
            if rule.eps1 is not None:
                model += (f"  E_bar {_num(row.get('E_bar'))} (eps1 {rule.eps1:g})  "
                          f"COV {_num(row.get('COV'))} (eps2 {rule.eps2:g})")
            if rule.precision is not None:
                model += "  " + precision_text(row, rule.precision)
            if row.get("stop"):
                model += "  converged"
        return (f"[pas] it {row['row'] + 1:>4}  n_HF {study.n_hf:>4}  event {row['event_id']}  "
                f"LF {row['lf']:.4g}  {what}  {model}")


def precision_text(row, target: float) -> str:
    """The precision part of a progress line: the U95's half-width where this fit computed it
    (else the sampling part's) against the target, and the forecast of further HF.

    Examples
    --------
    >>> precision_text({"halfwidth": 0.142, "halfwidth_sampling": 0.03, "forecast_hf": 58.6,
    ...                 "forecast_hf_low": 40.2, "forecast_hf_high": 95.0}, 0.1)
    'U95 ±14.2 % (target ±10 %), about 59 more HF (40–95)'
    >>> precision_text({"halfwidth_sampling": 0.031}, 0.1)
    'sampling part ±3.1 % (target ±10 %)'
    >>> precision_text({"halfwidth_sampling": 0.031, "fit_check_p": 0.004,
    ...                 "fit_misfit": "the transforms' shape (KS)"}, 0.1)
    'sampling part ±3.1 % (target ±10 %), the model fails the fit check (p 0.004)'
    >>> precision_text({"halfwidth": 0.3, "forecast_hf": math.inf, "forecast_hf_low": math.inf,
    ...                 "forecast_hf_high": math.inf}, 0.15)  # doctest: +NORMALIZE_WHITESPACE
    'U95 ±30 % (target ±15 %), more HF are not expected to reach ±15 %: the band has not
    narrowed with the pairs; the run goes on to its budget: further HF still correct the MPM
    and its band, and the forecast is revised with each band'
    """
    from ..study.stop_text import FURTHER_HF, HFForecast, forecast_text, percent

    if _finite(row.get("halfwidth")):
        text = f"U95 {percent(row['halfwidth'])} (target {percent(target)})"
    else:
        text = f"sampling part {percent(row.get('halfwidth_sampling', math.nan))} " \
               f"(target {percent(target)})"
    expected = row.get("forecast_hf")
    if expected is not None and not math.isnan(expected):
        ahead = HFForecast(expected, row["forecast_hf_low"], row["forecast_hf_high"])
        text += ", " + forecast_text(ahead, target).replace(f" for {percent(target)}", "")
        if math.isinf(expected):
            text += f"; the run goes on to its budget: {FURTHER_HF}"
    if isinstance(row.get("fit_misfit"), str):
        text += f", the model fails the fit check (p {row['fit_check_p']:.2g})"
    return text


def stopped(command: str, exc: BaseException, study, *, oracle=None, **where) -> RunStopped:
    """The :class:`RunStopped` for a run that ``exc`` (Ctrl-C, SIGTERM, a closed pipe) ended early.

    The HF programs ``oracle`` (a command oracle) started and that still run are
    ended first, or left running with ``on_interrupt="leave"``
    (:func:`hf_programs_line`).  ``where`` is passed to :func:`stopped_message`
    (``store``, ``out``, ``resume``).
    """
    from ..study.signals import EXIT_TERMINATED, Terminated

    if isinstance(exc, BrokenPipeError):
        why, code = "output pipe closed", EXIT_BROKEN_PIPE
    elif isinstance(exc, Terminated):
        why, code = "terminated (SIGTERM)", EXIT_TERMINATED
    else:
        why, code = "interrupted", EXIT_INTERRUPTED
    return RunStopped(stopped_message(command, why, n_results=len(study.rows),
                                      programs=hf_programs_line(oracle), **where), code)


def hf_programs_line(oracle) -> str | None:
    """End the HF programs ``oracle`` started that still run (``on_interrupt="end"``, the
    default) or list them (``"leave"``): what the stop message says of them, None when
    none ran.  Without a command oracle (None, or a command that has no stop of its own)
    it says the programs ended in this process (:data:`pas.study.hf_programs.ENDED`)."""
    from ..study import hf_programs

    root = getattr(oracle, "root", None)
    if root is None or not hasattr(oracle, "on_interrupt"):
        root = None  # no oracle known: only the programs ended in this process are said
    elif oracle.on_interrupt == "leave":
        mine = [r for r in hf_programs.running(root)
                if os.getpid() in (r.get("run_pid"), r.get("parent_pid"))]
        if not mine:
            return None
        return ("left running (on_interrupt = leave): "
                + "; ".join(hf_programs.describe(r) for r in mine)
                + "; a resumed run waits for each until its time-out and reuses its result "
                  "('pas study hf-stop' ends them)")
    ended = hf_programs.end_programs(root)
    if not ended:
        return None
    return ("ended the HF program(s) still running: "
            + "; ".join(hf_programs.describe(r) for r in ended)
            + "; their events run again on resume")


def stopped_message(command: str, why: str, *, n_results: int, store=None, out=None,
                    resume: str | None = None, programs: str | None = None) -> str:
    """The line printed when a run stops early (Ctrl-C, closed pipe).

    Says what was kept, how to resume and what became of the HF programs a
    command oracle had running (``programs``, from :func:`hf_programs_line`).
    """
    parts = [f"{command}: {why} after {n_results} HF result(s)"]
    if out is not None:
        parts.append(f"partial result written to {out}/")
    if store is not None:
        parts.append(f"every HF result is in {store}; run "
                     f"{resume or 'the same command'} again to resume")
    else:
        parts.append("nothing was stored to resume from (--no-store)")
    if programs:
        parts.append(programs)
    return "; ".join(parts)


def _finite(x) -> bool:
    return x is not None and math.isfinite(x)


def _num(x, fmt=".3g") -> str:
    return format(x, fmt) if _finite(x) else "-"


def retried_line(report: dict) -> str:
    """The line ``pas run --retry-failed`` prints: what runs again and what was kept."""
    if not report["retried"]:
        return "pas run: --retry-failed: the study has no failed event to retry"
    n = len(report["retried"])
    return (f"pas run: retrying {n} failed event(s) ({', '.join(report['retried'][:5])}"
            f"{', ...' if n > 5 else ''}); {report['dropped']} later ask(s) taken out of the "
            f"study's log, {report['kept']} of their results kept and reused if asked again")


def resuming_line(study, store) -> str:
    """The line ``pas run`` prints when it continues a stored study: what it reuses."""
    waiting = study.store.outstanding()
    with_result = sum(r.has_result for r in waiting)
    reused = study.n_told + with_result
    line = f"pas run: resuming {store}: {reused} results reused"
    parts = [f"{study.n_failed} failed"] if study.n_failed else []
    if with_result:
        parts.append(f"{with_result} stored but not yet used by the study")
    if parts:
        line += f" ({', '.join(parts)})"
    if len(waiting) > with_result:
        line += f", {len(waiting) - with_result} pending event(s) to run again"
    return line
