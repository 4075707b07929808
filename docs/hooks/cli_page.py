"""mkdocs hook: the command-line reference page, from the parsers of ``pas.cli``.

Every ``pas`` command and sub-command is shown with its ``--help`` text, so
the page says what the installed program says, never a hand-kept copy.
"""

import argparse
import os
import sys
from pathlib import Path

from mkdocs.structure.files import File

_INTRO = """# Command line: `pas --help`

Generated from the program's own parsers when this site is built; the same
text is printed by `pas <command> --help`.
"""


def _subcommands(parser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            yield from action.choices.items()


def _sections(parser, prog, level=2):
    yield f"{'#' * level} `{prog}`\n\n```text\n{parser.format_help().rstrip()}\n```\n"
    for name, sub in _subcommands(parser):
        yield from _sections(sub, f"{prog} {name}", min(level + 1, 4))


def on_files(files, config):
    sys.path.insert(0, str(Path(config.config_file_path).parent / "src"))
    os.environ["COLUMNS"] = "88"  # argparse wraps the help text at the terminal width
    from pas.cli import build_parser

    text = "\n".join([_INTRO, *_sections(build_parser(), "pas")])
    files.append(File.generated(config, "guide/cli.md", content=text))
    return files
