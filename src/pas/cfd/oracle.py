"""The OpenFOAM oracle: a command oracle that runs :mod:`pas.cfd.event` per event."""

from __future__ import annotations

import json
import os
import sys

from ..study.command_oracle import CommandOracle
from .tank import GreenWaterTank

__all__ = ["openfoam_oracle", "LOADS"]

LOADS = ("wall_peak_filtered", "wall_peak", "wall_impulse", "deck_peak", "run_wall_peak")
"""The named loads an event answers (N/m, N s/m): see :func:`pas.cfd.results.event_loads`."""


def openfoam_oracle(sea, root, *, case=None, upwave=None, lead=15.0, after=3.5,
                    energy=1.0, procs=1, timeout=None, cwd=None) -> CommandOracle:
    """An HF oracle that runs each event in OpenFOAM.

    Each event runs ``python -m pas.cfd.event`` in ``root/<event id>``: the
    event's linear waves (rebuilt from ``sea`` and the event's ``seed``,
    referred to the inlet ``upwave`` m before the structure and to a start
    ``lead`` s before its crest ``t_peak``) go into ``constant/waveProperties``
    of the case, the mesh, fields and solver run, and the event answers the
    named loads of :data:`LOADS` from its own window.  Study with
    ``target="wall_peak_filtered"`` (or another of them).  Everything the
    :class:`~pas.study.command_oracle.CommandOracle` does holds: a folder per
    event with its logs, a time-out, a failed run recorded as failed (never
    0), a finished result reused after an interrupted campaign.

    Parameters
    ----------
    sea : dict or path
        The LF record's sea: ``hs``, ``tp``, ``gamma``, ``depth``, ``duration``,
        ``omega_max`` (as :func:`pas.cfd.event.sea_from_recipe` reads it), or a
        JSON file of them.  Events need ``seed`` and ``t_peak`` in their meta.
    root : path
        Folder of the events' run folders.
    case : path or GreenWaterTank, optional
        Your own case folder, copied per event (see the guide page "PAS with
        OpenFOAM" for what it must contain), or a
        :class:`~pas.cfd.tank.GreenWaterTank`, written once to
        ``root/template``; default ``GreenWaterTank()``.
    upwave : float, optional
        Inlet to structure distance (m); default the tank's ``upwave``
        (required with a case folder).
    lead, after, energy, procs
        As the options of ``python -m pas.cfd.event``.
    timeout : float, optional
        Seconds before a run is ended and the event failed.
    cwd : path, optional
        The folder the campaign is started from (relative paths resolve there).
    """
    cwd = os.path.abspath(os.getcwd() if cwd is None else os.fspath(cwd))
    root_abs = os.path.normpath(os.path.join(cwd, os.fspath(root)))
    if isinstance(sea, dict):
        missing = {"hs", "tp", "depth", "duration"} - set(sea)
        if missing:
            raise ValueError(f"sea: missing {sorted(missing)}; give hs, tp, depth and duration "
                             "of the LF record's sea")
        os.makedirs(root_abs, exist_ok=True)
        path = os.path.join(root_abs, "sea.json")
        with open(path, "w") as f:
            json.dump(sea, f, indent=1)
    else:
        path = os.path.normpath(os.path.join(cwd, os.fspath(sea)))
        if not os.path.isfile(path):
            raise ValueError(f"sea: {path} is not a file (give the sea's JSON recipe or a dict)")
    if case is None or isinstance(case, GreenWaterTank):
        tank = case or GreenWaterTank()
        upwave = tank.upwave if upwave is None else upwave
        template = tank.write(os.path.join(root_abs, "template"))
    else:
        template = os.path.normpath(os.path.join(cwd, os.fspath(case)))
        if not os.path.isdir(os.path.join(template, "system")):
            raise ValueError(f"case: {template} is not an OpenFOAM case folder (no system/)")
        if upwave is None:
            raise ValueError("upwave: give the inlet-to-structure distance of your case (m)")
    args = [sys.executable, "-m", "pas.cfd.event", "--sea", path, "--seed", "{seed}",
            "--t-peak", "{t_peak}", "--out", "{result}", "--upwave", repr(float(upwave)),
            "--lead", repr(float(lead)), "--after", repr(float(after)),
            "--energy", repr(float(energy)), "--procs", str(int(procs)), "--template", template]
    return CommandOracle(args, root=root_abs, cwd=cwd, timeout=timeout,
                         result_name="result.json")
