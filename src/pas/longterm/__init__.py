"""Long-term design loads: PAS across a scatter diagram with one shared HF budget.

:func:`run_long_term` runs one PAS study per sea state that can reach the
design level (:mod:`~pas.longterm.runner`), gives each next HF event where it
narrows the long-term band most (:mod:`~pas.longterm.allocation`) and sums
the short-term distributions over the sea states
(:mod:`~pas.longterm.combination`) into a :class:`LongTermResult`
(:mod:`~pas.longterm.result`).
"""

from __future__ import annotations

from .._support.lazy import lazy_exports

_EXPORTS = {"run_long_term": "runner", "LongTermResult": "result",
            "read_sea_states": "inputs"}

__all__ = ["run_long_term", "LongTermResult", "read_sea_states"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
