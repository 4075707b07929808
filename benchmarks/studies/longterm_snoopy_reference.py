"""Write tests/data/longterm_snoopy.json: Snoopy's linear long-term values for the test to match.

The external peer of :mod:`pas.waves.linear_longterm` (issue 29): Snoopy
(``snoopy-bv``, Bureau Veritas) ``Statistics.LongTermRao`` on the same RAO
and the same sea states. Snoopy is a large compiled package that pas does not
otherwise need, so it is kept out of the ``dev`` extra: this script runs it
once in a separate environment and the test reads the committed numbers::

    python -m venv /tmp/snoopy && /tmp/snoopy/bin/pip install snoopy-bv==2.6.0 pandas scipy
    PYTHONPATH=src /tmp/snoopy/bin/python benchmarks/studies/longterm_snoopy_reference.py

The cases (RAO from pas, sea states from the IACS Rec. 34 diagram in pas,
head seas, no spreading):

* ``rwe_ferry``: relative wave elevation at station 19 of the 190 m ferry
  (built-in closed-form model);
* ``rwe_ferry_5ms``: the same at 5 m/s (Snoopy forms the encounter
  frequencies itself from the RAO's forward speed);
* ``heave_box``: heave of the Capytaine box hull (the checked-in dataset).

Snoopy computes the spectral moments itself (its own JONSWAP with the same
``hs``, ``tp``, ``gamma``) and the long-term value with its cycle-independent
formula: ``pcycle_to_x(p)`` is the level ``x`` of ``Q(x) = p`` and
``rp_to_x(N)`` the level whose non-exceedance over ``N`` years is ``exp(-1)``.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from pas.waves import FERRY_190M, TransferFunction, north_atlantic

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "data" / "longterm_snoopy.json"
OMEGA = np.linspace(0.05, 3.0, 296)
P_EXCEED = (1e-4, 1e-6, 1e-8)
RETURN_PERIODS = (1.0, 20.0, 25.0)


def cases():
    """(name, pas transfer function, response spec) of the compared responses."""
    bow = ("rwe", FERRY_190M.station_x(19))
    box = TransferFunction.from_capytaine(ROOT / "src" / "pas" / "waves" / "data"
                                          / "box_hull_capytaine.nc")
    return [("rwe_ferry", TransferFunction.from_ship(FERRY_190M, OMEGA, heading=[180.0]), bow),
            ("rwe_ferry_5ms",
             TransferFunction.from_ship(FERRY_190M, OMEGA, heading=[180.0], speed=5.0), bow),
            ("heave_box", box, "heave")]


def snoopy_long_term(transfer, response, table):
    """Snoopy's moments and long-term values for one response on the sea-state table."""
    from Snoopy import (
        Spectral as sp,  # not a dependency of pas: only this script needs it
    )
    from Snoopy import Statistics as st

    w = transfer.omega
    h = transfer.response(response, w, 180.0)
    rao = sp.Rao(b=np.array([np.pi]), w=w, cvalue=h.reshape(1, -1, 1), modes=np.array([0]),
                 refPoint=np.zeros(3), waveRefPoint=np.zeros(2), forwardSpeed=transfer.speed,
                 depth=-1.0)
    ss_list = [sp.SeaState(sp.Jonswap(float(r.hs), float(r.tp), float(r.gamma), heading=np.pi),
                           probability=float(r.probability)) for r in table.itertuples()]
    lt = st.LongTermRao(rao, ss_list, dss="INDEP")
    m0, m2 = lt.m0s_m2s
    return {
        "m0": np.asarray(m0)[:, 0].tolist(), "m2": np.asarray(m2)[:, 0].tolist(),
        "pcycle_to_x": {f"{p:g}": float(lt.pcycle_to_x(p)[0]) for p in P_EXCEED},
        "rp_to_x": {f"{n:g}": float(lt.rp_to_x(n)[0]) for n in RETURN_PERIODS},
    }


def main(argv=None):
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args(argv)
    import Snoopy

    table = north_atlantic().sea_states()
    out = {"snoopy_version": getattr(Snoopy, "__version__", "2.6.0"), "omega": OMEGA.tolist(),
           "sea_states": table[["name", "probability", "hs", "tp", "gamma"]].to_dict("list"),
           "cases": {}}
    for name, transfer, response in cases():
        out["cases"][name] = snoopy_long_term(transfer, response, table)
        print(name, out["cases"][name]["pcycle_to_x"], out["cases"][name]["rp_to_x"])
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
