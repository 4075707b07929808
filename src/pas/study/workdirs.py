"""Working-directory names of HF events: one folder per event, never two events in one.

:class:`~pas.study.oracles.CommandOracle` runs each event in ``root/<name>``
and reuses a result file it finds there, so two events must never share a
name: an id that is not a safe file name gets its index appended, and an
event of a long-term analysis (:mod:`pas.longterm`, where ids repeat across
sea states) lives under its sea state's folder.
"""

from __future__ import annotations

import hashlib
import os
import re

__all__ = ["event_dir"]

_SAFE = re.compile(r"[^A-Za-z0-9._-]")


def _safe(text: str, suffix) -> str:
    name = _SAFE.sub("_", text)
    return name if name == text and name not in (".", "..") else f"{name}-{suffix}"


def event_dir(event) -> str:
    """``<id>``, or ``<sea state>/<id>`` for an event of a long-term analysis."""
    name = _safe(str(event.id), event.index)
    sea_state = getattr(event, "sea_state", None)
    if sea_state is None:
        return name
    digest = hashlib.sha256(str(sea_state).encode()).hexdigest()[:8]
    return os.path.join(_safe(str(sea_state), digest), name)
