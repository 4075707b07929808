"""Command-line interface: ``pas <command> ...``.

Each sub-command lives in its own module with two functions,
``add_parser(subparsers)`` and ``run(args) -> int``; :data:`COMMANDS` lists
the modules.  Errors the user can fix print one line and exit with code 2;
warnings print one line (``pas <command>: warning: ...``).  Ctrl-C exits with
code 130 and a closed output pipe (``pas ... | head``) with 141 (128 + SIGPIPE,
what a shell reports for a process killed by that signal), each after one
line on stderr; commands that run a study first write what they have and say
how to resume (:class:`pas.cli._progress.RunStopped`).

Only the standard library is imported here and by ``add_parser``: the
numerical stack is imported by the command that runs, so ``pas --help`` and
``pas study tell`` start fast.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import sys
import warnings

from ._progress import EXIT_BROKEN_PIPE, EXIT_INTERRUPTED, RunStopped

COMMANDS = ("reproduce", "run", "study", "plot", "impacts")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pas",
        description="Probabilistic Adaptive Screening: extreme non-linear wave loads from a long "
                    "low-fidelity run and a few high-fidelity events.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Run 'pas <command> --help' for the options and examples of each command.",
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
        return _main(argv)
    except KeyboardInterrupt:  # while parsing or importing
        _say("pas: interrupted")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        _mute_closed_streams()
        return EXIT_BROKEN_PIPE


def console() -> int:
    """The ``pas`` program (and ``python -m pas``): :func:`main`, then a quick exit.

    Everything is written when :func:`main` returns; the interpreter's
    collections at exit, over every object numpy, scipy and pandas made,
    took 1.5–2.5 s on a loaded 2-core machine, longer than the run's own
    Ctrl-C handling, so the objects are frozen out of them.
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
        except KeyboardInterrupt:
            _say(f"{name}: interrupted")
            return EXIT_INTERRUPTED
        except BrokenPipeError:
            _mute_closed_streams()
            _say(f"{name}: output pipe closed")
            return EXIT_BROKEN_PIPE
        except (ValueError, FileNotFoundError, KeyError) as exc:
            msg = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
            _say(f"{name}: error: {msg}")
            return 2


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
