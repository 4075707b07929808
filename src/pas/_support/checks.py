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
            f"{name} contains {int(bad.sum())} NaN/inf value(s), "
            f"first at index {int(np.argmax(bad))}"
        )
    return arr


def check_positive_int(value, name: str) -> int:
    """Return ``value`` as int if it is a positive integer (bools rejected)."""
    return check_int(value, name, minimum=1)


def check_int(value, name: str, minimum: int = 0) -> int:
    """Return ``value`` as int if it is a whole number ≥ ``minimum`` (bools, text rejected).

    A float is taken when it is whole (``3.0``), so a number read from a
    JSON store or computed in Python passes.

    Examples
    --------
    >>> check_int(3.0, "k1", minimum=1)
    3
    >>> check_int("16364", "n_waves", minimum=1)
    Traceback (most recent call last):
    ...
    ValueError: n_waves must be a positive integer, got '16364' (a str; pass a number)
    """
    what = "a positive integer" if minimum == 1 else f"an integer ≥ {minimum}"
    whole = isinstance(value, numbers.Integral) or (
        isinstance(value, float | np.floating) and np.isfinite(value) and value == int(value))
    if isinstance(value, bool) or not whole:
        raise ValueError(f"{name} must be {what}, got {_shown(value)}")
    if int(value) < minimum:
        raise ValueError(f"{name} must be {what}, got {value!r}")
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
    """Return ``value`` as a finite float or raise ``ValueError``.

    Text is refused even when it reads as a number (``"2.55e-3"``), as for
    the integers (:func:`check_int`): a number given as text is a mistake
    upstream (a column read as strings), better named than guessed.
    """
    if isinstance(value, bool | str | bytes):
        raise ValueError(f"{name} must be a number, got {_shown(value)}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {_shown(value)}") from None
    if not np.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def check_precision(value, name: str = "precision") -> float:
    """A precision target as a fraction of the MPM, strictly between 0 and 1 (``0.1`` = ±10 %).

    Examples
    --------
    >>> check_precision(0.1)
    0.1
    >>> check_precision(10)
    Traceback (most recent call last):
    ...
    ValueError: precision must be a fraction of the MPM between 0 and 1 (0.1 for ±10 %), got 10
    """
    v = check_finite(value, name)
    if not 0.0 < v < 1.0:
        raise ValueError(f"{name} must be a fraction of the MPM between 0 and 1 (0.1 for ±10 %), "
                         f"got {value!r}")
    return v


def check_option(value, name: str, options) -> str:
    """Return ``value`` if it is one of ``options``."""
    if value not in options:
        raise ValueError(f"{name} must be one of {sorted(options)}, got {value!r}")
    return value


def _shown(value, wanted: str = "a number") -> str:
    """``value`` for an error message, text marked as such."""
    if isinstance(value, str | bytes):
        return f"{value!r} (a {type(value).__name__}; pass {wanted})"
    return repr(value)


def check_bool(value, name: str) -> bool:
    """Return ``value`` as bool if it is ``True``/``False`` (or a NumPy bool)."""
    if not isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {_shown(value, 'True or False')}")
    return bool(value)


def _optional(check):
    def optional(value, name):
        return None if value is None else check(value, name)
    return optional


def _int_from(minimum: int):
    def check(value, name):
        return check_int(value, name, minimum=minimum)
    return check


def _stop_measure(value, name):
    return check_option(value, name, {"window", "step"})


SETTING_CHECKS = {
    "n_waves": check_positive_int,
    "p_exp": check_open_unit,
    "threshold": _optional(check_finite),
    "eps1": _optional(check_positive),
    "precision": _optional(check_precision),
    "fit_check": _optional(check_open_unit),
    "eps2": check_positive,
    "k1": _int_from(1),
    "k2": _int_from(1),
    "stop_measure": _stop_measure,
    "seed": _optional(_int_from(0)),
    "max_hf": _optional(check_positive_int),
    "max_failures": _int_from(0),
    "stop_on_convergence": check_bool,
    "adaptive_threshold": check_bool,
    "threshold_step": check_positive,
    "fp_run": check_positive_int,
    "legacy_md": check_bool,
}
"""The rule of each LF and study setting (:data:`pas.study.factory.LF_SETTINGS` and
``STUDY_SETTINGS``), by name: the Python API, the study TOML file and ``pas study set``
all check a setting with :func:`check_setting`, so they accept and refuse the same values.
The strategy settings are checked by the strategy's constructor."""


def draw_seed(seed=None) -> int:
    """``seed``, or a seed drawn from the OS when it is None (recorded, so a run can be
    repeated)."""
    return int(np.random.SeedSequence().entropy % (2**63)) if seed is None else int(seed)


def check_setting(name: str, value):
    """``value`` of the study setting ``name`` checked by its rule in :data:`SETTING_CHECKS`.

    Examples
    --------
    >>> check_setting("k1", 5)
    5
    >>> check_setting("k1", -3)
    Traceback (most recent call last):
    ...
    ValueError: k1 must be a positive integer, got -3
    """
    return SETTING_CHECKS[name](value, name)
