"""CFD in the loop: an OpenFOAM oracle, its example green-water tank and the event's loads.

:func:`openfoam_oracle` is a :class:`~pas.study.command_oracle.CommandOracle`
that runs :mod:`pas.cfd.event` per event: the event's linear waves
(:func:`pas.waves.event_wave`) written into an OpenFOAM case, the solver run,
the loads read back from its ``forces`` output (:mod:`pas.cfd.results`).
:class:`GreenWaterTank` writes the example case: a 2D tank with a fixed bow,
a deck and a deckhouse wall.  OpenFOAM itself is not a Python dependency:
install it from your system's packages (``apt-get install openfoam``).
"""

from .oracle import LOADS, openfoam_oracle
from .results import event_loads, read_forces, read_gauge
from .tank import GreenWaterTank

__all__ = ["GreenWaterTank", "LOADS", "event_loads", "openfoam_oracle", "read_forces",
           "read_gauge"]
