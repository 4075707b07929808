"""Strict JSON for everything pas writes: numpy values converted, NaN and inf as null."""

from __future__ import annotations

import json
import math

import numpy as np

__all__ = ["json_data", "dumps"]


def _default(x):
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"{type(x).__name__} is not JSON-serialisable")


def _clean(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {str(k): _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    return x


def json_data(x):
    """``x`` as plain JSON data: numpy scalars and arrays converted, tuples as lists,
    keys as strings, non-finite floats as None.

    Examples
    --------
    >>> json_data({"a": np.float64("nan"), 1: (np.int64(2), np.bool_(True))})
    {'a': None, '1': [2, True]}
    """
    return _clean(json.loads(json.dumps(x, default=_default)))


def dumps(x, **kwargs) -> str:
    """Strict JSON text of ``x`` (:func:`json_data`), keys sorted unless told otherwise."""
    kwargs.setdefault("sort_keys", True)
    return json.dumps(json_data(x), allow_nan=False, **kwargs)
