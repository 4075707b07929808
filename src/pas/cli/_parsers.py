"""The shape every ``pas`` sub-command's parser shares."""

from __future__ import annotations

import argparse

__all__ = ["command_parser"]


def command_parser(sub, name: str, help: str, doc: str, epilog: str):
    """Register sub-command ``name`` on ``sub``: ``help`` in the command list, the first
    paragraph of its module's ``doc`` as description, ``epilog`` verbatim (examples)."""
    return sub.add_parser(name, help=help, description=doc.split("\n\n")[0].replace("``", ""),
                          formatter_class=argparse.RawDescriptionHelpFormatter, epilog=epilog)
