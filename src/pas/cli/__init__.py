"""Command-line interface: ``pas <command> ...``.

Each sub-command lives in its own module with two functions,
``add_parser(subparsers)`` and ``run(args) -> int``; :data:`COMMANDS` lists
the modules.  Errors the user can fix print one line and exit with code 2;
warnings print one line (``pas <command>: warning: ...``).  Ctrl-C exits with
code 130, SIGTERM (a batch scheduler's time limit, ``kill``) with 143 and a
closed output pipe (``pas ... | head``) with 141 (128 + SIGPIPE,
what a shell reports for a process killed by that signal), each after one
line on stderr; commands that run a study first write what they have and say
how to resume (:class:`pas.cli._progress.RunStopped`).

Exit codes (:data:`EXIT_CODES`, also printed by ``pas --help``)::

    0    done
    1    the study stopped at its failure limit (more failed HF evaluations than
         max_failures; the partial result is written), or no command given
    2    bad input: a one-line error names the argument and the fix
    3    done, but failed HF evaluations were left out of the final fit
    130  interrupted (Ctrl-C); the result so far is written
    143  terminated (SIGTERM, e.g. a batch job's time limit); the result so far is written
    141  the output pipe was closed

Only the standard library is imported here and by ``add_parser``: the
numerical stack is imported by the command that runs, so ``pas --help`` and
``pas study tell`` start fast.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import re
import sys
import warnings

from ..study.signals import EXIT_TERMINATED, Terminated, terminate_as_interrupt
from ._progress import EXIT_BROKEN_PIPE, EXIT_INTERRUPTED, RunStopped

COMMANDS = ("reproduce", "run", "long_term", "study", "plot", "impacts", "events")

EXIT_STOPPED = 1
EXIT_BAD_INPUT = 2
EXIT_FAILED_LEFT_OUT = 3
EXIT_CODES = {0: "done",
              EXIT_STOPPED: "the study stopped at its failure limit (partial result written), "
                            "or no command given",
              EXIT_BAD_INPUT: "bad input (a one-line error names the argument)",
              EXIT_FAILED_LEFT_OUT: "done, but failed HF evaluations were left out of the fit",
              EXIT_INTERRUPTED: "interrupted (Ctrl-C); the result so far is written",
              EXIT_TERMINATED: "terminated (SIGTERM, e.g. a batch job's time limit); the result "
                               "so far is written",
              EXIT_BROKEN_PIPE: "the output pipe was closed"}
"""What each exit code of ``pas`` means."""


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line, pointing at ``--help``.

    The sub-command parsers inherit the class, so ``pas run --p-exp x`` says
    ``pas run: error: argument --p-exp: invalid float value: 'x' (see 'pas run --help')``
    and exits with code 2, like every other bad input.
    """

    def error(self, message):
        _say(f"{self.prog}: error: {message} (see '{self.prog} --help')")
        self.exit(EXIT_BAD_INPUT)


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="pas",
        description="Probabilistic Adaptive Screening: extreme non-linear wave loads from a long "
                    "low-fidelity run and a few high-fidelity events.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Run 'pas <command> --help' for the options and examples of each command.\n\n"
               "exit codes:\n" + "\n".join(f"  {code:<4} {text}"
                                            for code, text in EXIT_CODES.items()),
    )
    from .._version import __version__

    parser.add_argument("--version", action="version", version=f"pas {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="<command>")
    for name in COMMANDS:
        try:
            mod = importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            continue
        mod.add_parser(sub)
    return parser


def main(argv=None) -> int:
    try:
        with terminate_as_interrupt():
            return _main(argv)
    except KeyboardInterrupt as exc:  # while parsing or importing
        return _interrupted("pas", exc)
    except BrokenPipeError:
        _mute_closed_streams()
        return EXIT_BROKEN_PIPE


def console() -> int:
    """The ``pas`` program (and ``python -m pas``): :func:`main`, then a quick exit.

    Everything is written when :func:`main` returns; the interpreter's
    collections at exit, over every object numpy, scipy and pandas made,
    can take seconds on a loaded machine, longer than the run's own Ctrl-C
    handling, so the objects are frozen out of them.
    """
    code = main()
    gc.freeze()
    return code


def _main(argv) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 1
    name = f"pas {args.command}"
    with warnings.catch_warnings():
        warnings.showwarning = _one_line_warning(name)
        try:
            return int(args.func(args) or 0)
        except RunStopped as exc:
            _mute_closed_streams()
            _say(str(exc))
            return exc.code
        except KeyboardInterrupt as exc:
            return _interrupted(name, exc)
        except BrokenPipeError:
            _mute_closed_streams()
            _say(f"{name}: output pipe closed")
            return EXIT_BROKEN_PIPE
        except (ValueError, OSError, KeyError) as exc:
            msg = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
            if getattr(args, "study_command", None) != "create":  # its settings are a file's
                msg = option_named(str(msg), parser, args.command)
            _say(f"{name}: error: {msg}")
            return EXIT_BAD_INPUT


_POSITIONAL_NAMES = {"run": {"lf_peaks": "LF_FILE"}, "events": {"series": "SERIES"}}
"""Python argument names a command's errors should call by its positional argument."""


def option_named(message: str, parser, command: str) -> str:
    """``message`` of the Python API with its leading argument named as the command's option.

    ``seed must be ...`` becomes ``--seed must be ...`` when ``--seed`` is an
    option of ``pas``; ``lf_peaks ...`` of ``pas run`` becomes ``LF_FILE ...``.

    Examples
    --------
    >>> option_named("max_hf must be an integer ≥ 4, got 2", build_parser(), "run")
    '--max-hf must be an integer ≥ 4, got 2'
    >>> option_named("p_exp=1e-09 lies outside the LF range", build_parser(), "run")
    '--p-exp=1e-09 lies outside the LF range'
    """
    m = re.match(r"([a-z][a-z0-9_]*)(?= must | is |=|: )", message)
    if m is None:
        return message
    word = m.group(1)
    option = _POSITIONAL_NAMES.get(command, {}).get(word, "--" + word.replace("_", "-"))
    if option.startswith("--") and option not in _option_strings(parser):
        return message
    return option + message[len(word):]


def _option_strings(parser) -> set:
    """Every option string of ``parser`` and of its sub-command parsers."""
    found = set()
    for action in parser._actions:
        found.update(action.option_strings)
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                found |= _option_strings(sub)
    return found


def plain_text(doc: str) -> str:
    r"""A command module's docstring as ``--help`` text: the literal ``::`` usage block
    left out (argparse prints its own usage) and the reST markup dropped.

    Examples
    --------
    >>> plain_text("``pas x``: one line.\n\n::\n\n    pas x A\n\nUses :mod:`pas.stats` (fast).")
    'pas x: one line.\n\nUses pas.stats (fast).'
    """
    paragraphs = [par for par in doc.strip().split("\n\n")
                  if par.strip() != "::" and not par.startswith((" ", "\t"))]
    text = "\n\n".join(paragraphs)
    text = re.sub(r":[a-z]+:`~?([^`]+)`", r"\1", text)
    return text.replace("``", "")


def _interrupted(name: str, exc: KeyboardInterrupt) -> int:
    """Say that Ctrl-C or SIGTERM (:class:`~pas.study.signals.Terminated`) ended ``name``."""
    from ._progress import hf_programs_line

    programs = hf_programs_line(None)
    tail = f"; {programs}" if programs else ""
    if isinstance(exc, Terminated):
        _say(f"{name}: terminated (SIGTERM){tail}")
        return EXIT_TERMINATED
    _say(f"{name}: interrupted{tail}")
    return EXIT_INTERRUPTED


def _one_line_warning(name):
    def show(message, category, filename, lineno, file=None, line=None):
        _say(f"{name}: warning: {message}")
    return show


def _say(line: str) -> None:
    """Print ``line`` on stderr unless stderr is gone (a closed pipe)."""
    try:
        print(line, file=sys.stderr, flush=True)
    except (BrokenPipeError, OSError, ValueError):
        pass


def _mute_closed_streams() -> None:
    """Point a closed stdout/stderr at /dev/null, so the exit flush raises nothing."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (BrokenPipeError, OSError, ValueError):
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, stream.fileno())
            except (OSError, ValueError, AttributeError):
                pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
