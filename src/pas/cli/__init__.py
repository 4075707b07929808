"""Command-line interface: ``pas <command> ...``.

Each sub-command lives in its own module with two functions,
``add_parser(subparsers)`` and ``run(args) -> int``; :data:`COMMANDS` lists
the modules.  Errors the user can fix print one line and exit with code 2.
"""

from __future__ import annotations

import argparse
import importlib
import sys

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
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 1
    try:
        return int(args.func(args) or 0)
    except (ValueError, FileNotFoundError, KeyError) as exc:
        msg = exc.args[0] if isinstance(exc, KeyError) and exc.args else exc
        print(f"pas {args.command}: error: {msg}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
