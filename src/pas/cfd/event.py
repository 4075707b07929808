"""Run one LF event in OpenFOAM: the per-event program behind :func:`pas.cfd.openfoam_oracle`.

``python -m pas.cfd.event --sea sea.json --seed S --t-peak T --out result.json``
rebuilds the event's linear sea from the LF record's recipe (``sea.json``)
and seed, refers its components to the tank's inlet and start time
(:func:`pas.waves.event_wave`), writes the case into ``./case`` (the example
tank, or a copy of ``--template``), runs the mesh, the fields and the solver,
and writes the event's loads (:func:`pas.cfd.results.event_loads`) as a JSON
object of named loads to ``--out``.  What the run was (wave, mesh, wall time,
OpenFOAM version, the linear and CFD crests at the bow) goes to
``event.json`` beside it.  A solver that stops, diverges or leaves no force
history exits non-zero with the reason on stderr: the event fails, never
answers 0.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

__all__ = ["main", "sea_from_recipe", "run_event"]

DEFAULT_LEAD = 15.0
DEFAULT_AFTER = 3.5
DEFAULT_UPWAVE = 50.0
MIN_TIME_STEP = 1e-6
"""A run whose adaptive time step falls below this (s) has diverged: it is stopped and its
event fails."""


def sea_from_recipe(recipe, seed):
    """The LF record's linear sea from ``recipe`` (``hs``, ``tp``, ``gamma``, ``depth``,
    ``duration``, ``omega_max``) and the event's ``seed``."""
    from ..waves import jonswap, linear_sea

    hs, tp, gamma = float(recipe["hs"]), float(recipe["tp"]), float(recipe.get("gamma", 3.3))
    return linear_sea(lambda w: jonswap(w, hs, tp, gamma), float(recipe["duration"]),
                      seed=int(seed), depth=float(recipe["depth"]),
                      omega_max=float(recipe.get("omega_max", 3.0)))


def mler_wave(recipe, target, *, upwave, lead):
    """The MLER wave of the recipe's sea whose linear crest at the structure is ``target`` (m)
    (Adegeest et al. 1998; Dietz 2004), as an :class:`~pas.waves.event_wave.EventWave`
    with its crest at run time ``lead``."""
    from ..waves import ComponentSea, jonswap, mler_amplitudes
    from ..waves.event_wave import event_wave

    df = 1.0 / float(recipe["duration"])
    omega = 2 * np.pi * df * np.arange(1, int(float(recipe.get("omega_max", 3.0))
                                                / (2 * np.pi * df)) + 1)
    s = jonswap(omega, float(recipe["hs"]), float(recipe["tp"]), float(recipe.get("gamma", 3.3)))
    sigma = np.sqrt(s * 2 * np.pi * df)
    amp = mler_amplitudes(sigma, np.ones(omega.size), target, omega_e=omega)
    sea = ComponentSea(omega=omega, amplitude=amp, depth=float(recipe["depth"]))
    return event_wave(sea, 0.0, upwave=upwave, lead=lead)


def _foam_env():
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    return env


def _run(cmd, log, env, cwd, *, watch=False):
    """Run ``cmd`` in ``cwd`` with its output in ``log``; with ``watch``, stop it once its
    time step falls below :data:`MIN_TIME_STEP` (a diverging run can grind for hours)."""
    path = os.path.join(cwd, log)
    with open(path, "w") as out:
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
        diverged = None
        while proc.poll() is None:
            time.sleep(1.0)
            if watch and diverged is None:
                step = _last_time_step(path)
                if step is not None and step < MIN_TIME_STEP:
                    diverged = step
                    proc.terminate()
        rc = proc.wait()
    with open(path, errors="replace") as f:
        text = f.read()
    if diverged is not None:
        raise RuntimeError(f"{cmd[0]} diverged: its time step fell to {diverged:.2g} s (see "
                           f"{log}); try a smaller Courant limit or a finer mesh")
    if rc != 0 or "FOAM FATAL" in text:
        tail = [ln for ln in text.splitlines() if ln.strip()][-3:]
        raise RuntimeError(f"{cmd[0]} failed (exit {rc}, see {log}): " + " | ".join(tail)[-300:])
    return text


def _last_time_step(path):
    """The last ``deltaT`` a solver log holds (read from its end), or None."""
    with open(path, "rb") as f:
        f.seek(0, os.SEEK_END)
        f.seek(max(0, f.tell() - 4096))
        tail = f.read().decode(errors="replace")
    found = re.findall(r"^deltaT = (\S+)", tail, flags=re.M)
    try:
        return float(found[-1]) if found else None
    except ValueError:
        return None


def _version(text):
    for line in text.splitlines():
        if line.startswith("Build"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def run_event(wave, *, case="case", template=None, tank=None, after=DEFAULT_AFTER, procs=1,
              window=(-1.0, DEFAULT_AFTER)):
    """Write and run the case of ``wave`` (an :class:`~pas.waves.event_wave.EventWave`) in
    folder ``case``; returns ``(loads, info)``."""
    from .results import event_loads, read_gauge
    from .tank import GreenWaterTank

    if template is not None:
        shutil.rmtree(case, ignore_errors=True)
        shutil.copytree(template, case)
    else:
        tank = tank or GreenWaterTank(upwave=wave.upwave)
        tank.write(case)
    end = wave.t_event + after
    with open(os.path.join(case, "0.orig", "U")) as f:
        outlet = "outlet" if re.search(r"^\s*outlet\b", f.read(), flags=re.M) else None
    with open(os.path.join(case, "constant", "waveProperties"), "w") as f:
        f.write(wave.openfoam_dict(outlet=outlet))
    with open(os.path.join(case, "system", "pasEvent"), "w") as f:
        f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
                f"    object pasEvent;\n}}\nendTime {end:.6g};\n")
    shutil.rmtree(os.path.join(case, "0"), ignore_errors=True)
    shutil.copytree(os.path.join(case, "0.orig"), os.path.join(case, "0"))
    shutil.rmtree(os.path.join(case, "postProcessing"), ignore_errors=True)
    env = _foam_env()
    t0 = time.perf_counter()
    mesh = _run(["blockMesh"], "log.blockMesh", env, case)
    _run(["setFields"], "log.setFields", env, case)
    if procs > 1:
        _run(["decomposePar", "-force"], "log.decomposePar", env, case)
        text = _run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(procs),
                     "interFoam", "-parallel"], "log.interFoam", env, case, watch=True)
    else:
        text = _run(["interFoam"], "log.interFoam", env, case, watch=True)
    wall = time.perf_counter() - t0
    if "\nEnd" not in text:
        raise RuntimeError("interFoam did not reach its end time (see log.interFoam)")
    crest, t_crest = wave.crest()
    info = {"t_start": wave.t_start, "t_peak": wave.t_peak, "t_event": wave.t_event,
            "end_time": end, "window": list(window), "n_components": wave.n_components,
            "energy": wave.energy, "linear_crest": crest, "linear_crest_time": t_crest,
            "wall_seconds": wall, "procs": procs, "openfoam": _version(text)}
    cells = re.search(r"nCells:\s*(\d+)", mesh)
    info["n_cells"] = int(cells.group(1)) if cells else None
    info["structure"] = outlet is None
    try:
        tg, eta = read_gauge(case, "bow")
        near = (tg >= t_crest - 2.0) & (tg <= t_crest + 2.0)
        k = np.flatnonzero(near)[np.argmax(eta[near])]
        info.update({"bow_crest": float(eta[k]), "bow_crest_time": float(tg[k])})
    except (FileNotFoundError, ValueError):
        pass
    if outlet is not None:
        return {}, info
    loads = event_loads(case, wave.t_event, window=window)
    info["loads"] = loads
    return {k: v for k, v in loads.items() if k != "run_wall_peak_time"}, info


def main(argv=None):
    from ..waves.event_wave import event_wave
    from .tank import GreenWaterTank

    p = argparse.ArgumentParser(prog="python -m pas.cfd.event",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("--sea", required=True, help="JSON recipe of the LF record's sea")
    p.add_argument("--seed", type=int, help="the event's seed ({seed})")
    p.add_argument("--t-peak", type=float, help="LF crest time ({t_peak})")
    p.add_argument("--mler", type=float, metavar="CREST",
                   help="instead of an event: the MLER wave of this linear crest (m)")
    p.add_argument("--out", required=True, help="result file ({result})")
    p.add_argument("--template", help="your case folder, copied per event (default: the "
                                      "example tank)")
    p.add_argument("--cell", type=float, default=0.5, help="example tank: cell size (m)")
    p.add_argument("--max-courant", type=float, default=0.65,
                   help="example tank: Courant limit of the time step")
    p.add_argument("--no-structure", action="store_true",
                   help="example tank without the structure (incident waves only)")
    p.add_argument("--upwave", type=float, default=DEFAULT_UPWAVE, help="inlet to bow (m)")
    p.add_argument("--lead", type=float, default=DEFAULT_LEAD, help="run time before the crest (s)")
    p.add_argument("--after", type=float, default=DEFAULT_AFTER, help="run time after it (s)")
    p.add_argument("--energy", type=float, default=1.0, help="share of wave energy kept")
    p.add_argument("--procs", type=int, default=1, help="MPI processes (2: decomposePar)")
    a = p.parse_args(argv)
    with open("starts.log", "a") as f:          # one line per solver start: runs are counted
        f.write(f"{time.strftime('%Y-%m-%dT%H:%M:%S')} pid {os.getpid()}\n")
    try:
        with open(a.sea) as f:
            recipe = json.load(f)
        if a.mler is not None:
            wave = mler_wave(recipe, a.mler, upwave=a.upwave, lead=a.lead)
        elif a.seed is None or a.t_peak is None:
            raise ValueError("give --seed and --t-peak of the event (or --mler CREST)")
        else:
            wave = event_wave(sea_from_recipe(recipe, a.seed), a.t_peak, upwave=a.upwave,
                              lead=a.lead, energy=a.energy)
        tank = None if a.template else GreenWaterTank(
            upwave=a.upwave, cell=a.cell, structure=not a.no_structure,
            depth=float(recipe["depth"]), max_courant=a.max_courant)
        loads, info = run_event(wave, template=a.template, tank=tank, after=a.after,
                                procs=a.procs, window=(-1.0, a.after))
    except (OSError, ValueError, KeyError, RuntimeError) as exc:
        print(f"pas.cfd.event: {exc}", file=sys.stderr)
        return 1
    with open("event.json", "w") as f:
        json.dump(info, f, indent=1)
    if loads:
        with open(a.out, "w") as f:
            json.dump(loads, f)
    else:                                  # no structure: the bow crest is the answer
        with open(a.out, "w") as f:
            json.dump({"bow_crest": info.get("bow_crest", float("nan"))}, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
