"""Command-line types of the stopping options: ``--precision 10%`` and ``--eps1 none``."""

from __future__ import annotations

import argparse
import math

__all__ = ["precision_option", "optional_number"]


def precision_option(text):
    """``--precision``: a fraction (of the MPM, or of the long-term value), as ``0.1`` or ``10%``.

    Examples
    --------
    >>> precision_option("10%"), precision_option("0.1"), precision_option(" 2.5 % ")
    (0.1, 0.1, 0.025)
    """
    word = str(text).strip()
    scale = 100.0 if word.endswith("%") else 1.0
    try:
        value = float(word.rstrip("%").strip()) / scale
    except ValueError:
        value = math.nan
    if not 0.0 < value < 1.0:
        raise argparse.ArgumentTypeError(f"expected a fraction such as 10% or 0.1, "
                                         f"got {text!r}")
    return value


def optional_number(text):
    """``--eps1``: a number, or ``none``."""
    if str(text).strip().lower() == "none":
        return None
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number or 'none', got {text!r}") from None
