"""Checking an HF oracle's answer: one load, or several named loads of one HF run.

One CFD run or basin test gives many signals (panels, pressure sensors,
forces): an oracle may answer ``{name: load}``; the study screens on its
``target`` and the store keeps every load (:mod:`pas.study.loads`), so
:func:`pas.study.refit.refit` can analyse another one on the same events.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

__all__ = ["check_hf_value", "check_hf_answer", "screened_load", "check_target", "lacks_target"]


def check_hf_value(value):
    """Validate an oracle's answer: ``(float, None)`` or ``(None, error message)``.

    0 is a valid answer (no impact, a false positive); NaN, inf, negative and
    non-numeric answers are failures, never taken as 0.
    """
    if isinstance(value, bool):
        return None, f"oracle returned a bool ({value!r}), expected a load"
    try:
        v = float(value)
    except (TypeError, ValueError):
        return None, f"oracle returned {value!r}, not a number"
    if not math.isfinite(v):
        return None, f"oracle returned {v!r}"
    if v < 0:
        return None, f"oracle returned a negative load {v!r}"
    return v, None


def check_target(target):
    """``target`` (the name of the load a study screens on) checked: None or a non-empty str."""
    if target is not None and not (isinstance(target, str) and target.strip()):
        raise ValueError(f"target must be the name of one load (a non-empty string) or None, "
                         f"got {target!r}")
    return target


def lacks_target(loads, target) -> bool:
    """True when an answer of several named loads came to a study with no ``target``."""
    return target is None and loads is not None and len(loads) > 1


def check_hf_answer(answer, target=None):
    """Validate an oracle's answer, one load or named loads: ``(value, error, loads)``.

    ``value, error`` are the screened load as :func:`check_hf_value` gives
    them.  A bare number is that load, the target's when a target is set
    (``loads`` None).  A mapping ``{name:
    load}`` is screened on its ``target`` entry (on its only entry when
    ``target`` is None); ``loads`` is ``{name: (value, error)}`` with every
    entry checked by :func:`check_hf_value`.  A missing target entry fails the
    event, never gives 0; several entries without a target fail it with a
    message naming ``target`` (:func:`lacks_target`).  A NaN, negative or
    non-numeric entry other than the target keeps the event: that load is
    missing (its error kept) for a refit on it
    (:func:`pas.study.refit.refit`).
    """
    if not isinstance(answer, Mapping):
        return (*check_hf_value(answer), None)
    if not answer:
        return None, "oracle returned an empty mapping, expected {name: load}", None
    bad = [k for k in answer if not (isinstance(k, str) and k.strip())]
    if bad:
        return None, (f"oracle returned a mapping with the load name {bad[0]!r}, expected "
                      "non-empty strings"), None
    loads = {name: check_hf_value(v) for name, v in answer.items()}
    return (*screened_load(loads, target), loads)


def screened_load(loads: dict, target):
    """``(value, error)`` of the screened load, from checked ``{name: (value, error)}``."""
    if lacks_target(loads, target):
        return None, (f"oracle returned {len(loads)} loads ({', '.join(loads)}) and the study "
                      "has no target: name the one to screen on with target= "
                      "(pas run --target NAME)")
    name = next(iter(loads)) if target is None else target
    if name not in loads:
        return None, f"oracle's answer has no load {name!r} (the target; it has {', '.join(loads)})"
    value, error = loads[name]
    return value, None if error is None else f"load {name!r}: {error}"
