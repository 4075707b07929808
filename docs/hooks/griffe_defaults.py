"""griffe extension: a default given by a sentinel shows the value it stands for.

``max_hf=UNSET`` in :func:`pas.run_pas` means "the budget's default": 160 HF
evaluations (none with ``strategy=PAS.paper()``, as its parameter text says).
The API reference shows that value in the signature and the parameter table
instead of the sentinel's name; the code keeps the sentinel, so an omitted
``max_hf`` stays distinguishable from ``max_hf=None`` (no budget).
"""

from __future__ import annotations

import griffe

from pas.study.settings import DEFAULT_MAX_HF

#: Sentinel name -> the default it stands for, as shown in the reference.
SHOWN = {"UNSET": str(DEFAULT_MAX_HF)}


class SentinelDefaults(griffe.Extension):
    def on_function(self, *, func, **kwargs) -> None:
        for parameter in func.parameters:
            if str(parameter.default) in SHOWN:
                parameter.default = SHOWN[str(parameter.default)]

    on_function_instance = on_function
