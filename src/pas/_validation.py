"""Tiny input checks shared by the public entry points.

Every error names the argument, so a user reading a one-line message knows
which input to fix.
"""

from __future__ import annotations

import numbers

import numpy as np


def check_peaks(values, name: str = "lf_peaks") -> np.ndarray:
    """Return ``values`` as a finite 1-D float array or raise ``ValueError``."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a 1-D array of numbers ({exc})") from None
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{name} is empty")
    bad = ~np.isfinite(arr)
    if bad.any():
        raise ValueError(
            f"{name} contains {int(bad.sum())} NaN/inf value(s), first at index {int(np.argmax(bad))}"
        )
    return arr


def check_positive_int(value, name: str) -> int:
    """Return ``value`` as int if it is a positive integer (bools rejected)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral | float | np.floating):
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if isinstance(value, float | np.floating) and (not np.isfinite(value) or value != int(value)):
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if int(value) <= 0:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def check_open_unit(value, name: str) -> float:
    """Return ``value`` as float if it lies strictly inside (0, 1)."""
    v = check_finite(value, name)
    if not 0.0 < v < 1.0:
        raise ValueError(f"{name} must lie strictly between 0 and 1, got {value!r}")
    return v


def check_positive(value, name: str) -> float:
    """Return ``value`` as float if it is finite and > 0."""
    v = check_finite(value, name)
    if v <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return v


def check_finite(value, name: str) -> float:
    """Return ``value`` as a finite float or raise ``ValueError``."""
    if isinstance(value, bool):
        raise ValueError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def check_option(value, name: str, options) -> str:
    """Return ``value`` if it is one of ``options``."""
    if value not in options:
        raise ValueError(f"{name} must be one of {sorted(options)}, got {value!r}")
    return value
