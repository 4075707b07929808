"""Run the CFD case's events in OpenFOAM and grow its tables, resumably.

Jobs (in this order): ``truth`` -- every event of the LF record above the cut
(the ``--top`` largest LF crests) and a random sample of ``--below`` events
ranked ``top+1 .. --below-from``, with the structure at the case's mesh;
``equivalence`` -- the ``--equivalence`` largest events without the structure
(the CFD crest at the bow position against the linear one); ``mesh`` -- the
``--mesh-events`` events on the cell sizes ``--cells``.  Each event runs in
``ROOT/<job>/<id>`` through ``python -m pas.cfd.event`` (what
``pas.cfd.openfoam_oracle`` runs); a folder that holds a result is read, not
run again, so a killed run resumes.  Rows are appended to
``src/pas/validation/data/cfd_green_water*.csv`` as events finish.

    python benchmarks/cfd/green_water_runs.py --root cfd-runs --workers 2
"""

import argparse
import json
import os
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from pas.validation.case_cfd import CFD_CASE, cfd_lf_record

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.cfd import write_sea_recipe  # noqa: E402

DATA = Path(os.environ.get(
    "PAS_CFD_DATA", Path(__file__).resolve().parents[2] / "src" / "pas" / "validation" / "data"))
TABLES = {"truth": "cfd_green_water.csv", "equivalence": "cfd_green_water_equivalence.csv",
          "mesh": "cfd_green_water_mesh.csv", "design": "cfd_green_water_design.csv"}
LOCK = threading.Lock()
COURANT = (0.65, 0.4, 0.25)
"""Courant limits tried in turn: a run that diverges is run again at the next."""


def jobs(events, a):
    ranked = events.sort_values("lf", ascending=False).reset_index(drop=True)
    top = ranked.iloc[:a.top]
    rng = np.random.default_rng(a.seed)
    pool = ranked.iloc[a.top:a.below_from]
    below = pool.iloc[np.sort(rng.choice(len(pool), a.below, replace=False))]
    first = min(60, a.top)
    out = [("truth", r, 0.5, True) for _, r in top.iloc[:first].iterrows()]
    out += [("truth", r, 0.5, True) for _, r in below.iterrows()]
    out += [("truth", r, 0.5, True) for _, r in top.iloc[first:].iterrows()]
    out += [("equivalence", r, 0.5, False) for _, r in ranked.iloc[:a.equivalence].iterrows()]
    mesh_ids = ranked.iloc[:a.top].iloc[np.linspace(0, a.top - 1, a.mesh_events).astype(int)]
    out += [("mesh", r, c, True) for c in a.cells for _, r in mesh_ids.iterrows() if c != 0.5]
    out.append(("design", {"id": "mler", "lf": mler_target(), "seed": -1, "t_peak": 0.0},
                0.5, True))
    return out


def mler_target():
    """The linear crest MPM of the exposure (Rayleigh on the realised spectrum's m0)."""
    from pas.waves import jonswap
    from pas.waves.design import rayleigh_target

    c = CFD_CASE
    df = 1.0 / c.duration
    w = 2 * np.pi * df * np.arange(1, int(c.omega_max / (2 * np.pi * df)) + 1)
    m0 = float(np.sum(jonswap(w, c.hs, c.tp, c.gamma)) * 2 * np.pi * df)
    return float(rayleigh_target(m0, cfd_lf_record()[2]))


def run(job, root, recipe):
    kind, ev, cell, structure = job
    folder = Path(root) / kind / (ev["id"] if kind != "mesh" else f"{ev['id']}-c{cell:g}")
    folder.mkdir(parents=True, exist_ok=True)
    result = folder / "result.json"
    courant, failures = COURANT[0], []
    for courant in COURANT:                    # a run that diverges is run again, more gently
        sub = folder if courant == COURANT[0] else folder / f"co{courant:g}"
        sub.mkdir(exist_ok=True)
        result = sub / "result.json"
        if result.exists():
            break
        which = (["--mler", repr(float(ev["lf"]))] if kind == "design" else
                 ["--seed", str(int(ev["seed"])), "--t-peak", repr(float(ev["t_peak"]))])
        cmd = [sys.executable, "-m", "pas.cfd.event", "--sea", recipe, *which, "--out",
               str(result), "--cell", str(cell), "--max-courant", str(courant)]
        cmd += [] if structure else ["--no-structure"]
        with open(sub / "stdout.log", "w") as o, open(sub / "stderr.log", "w") as e:
            rc = subprocess.run(cmd, cwd=sub, stdout=o, stderr=e).returncode
        if rc == 0:
            break
        msg = (sub / "stderr.log").read_text().strip().splitlines()[-1:]
        failures.append(msg[0] if msg else f"exit {rc}")
    else:
        return kind, {"id": ev["id"], "lf": float(ev["lf"]), "seed": int(ev["seed"]),
                      "t_peak": float(ev["t_peak"]), "cell": cell, "status": "failed",
                      "message": " || ".join(failures)[-300:]}
    info = json.loads((result.parent / "event.json").read_text())
    row = {"id": ev["id"], "lf": float(ev["lf"]), "seed": int(ev["seed"]),
           "t_peak": float(ev["t_peak"]), "status": "ok", "cell": cell, "max_courant": courant,
           "failed_tries": len(failures)}
    if kind == "design":
        row["method"] = "MLER"
    row.update(info.get("loads", {}))
    for k in ("linear_crest", "linear_crest_time", "bow_crest", "bow_crest_time", "t_event",
              "n_components", "energy", "n_cells", "wall_seconds", "openfoam"):
        row[k] = info.get(k)
    return kind, row


def append(kind, row):
    path = DATA / TABLES[kind]
    with LOCK:
        old = pd.read_csv(path) if path.exists() else pd.DataFrame()
        key = ["id", "cell"] if kind == "mesh" else ["id"]
        if len(old):
            same = np.ones(len(old), bool)
            for k in key:
                same &= old[k].astype(str).to_numpy() == str(row[k])
            old = old[~same]
        new = pd.concat([old, pd.DataFrame([row])], ignore_index=True)
        new.to_csv(path, index=False, float_format="%.6g")
        print(f"{kind} {row['id']} {row.get('status')} "
              f"{row.get('wall_peak_filtered', row.get('bow_crest', ''))} "
              f"({len(new)} rows)", flush=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default="cfd-runs")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--top", type=int, default=150)
    p.add_argument("--below", type=int, default=30)
    p.add_argument("--below-from", type=int, default=1000)
    p.add_argument("--equivalence", type=int, default=25)
    p.add_argument("--mesh-events", type=int, default=5)
    p.add_argument("--cells", type=float, nargs="+", default=[0.7, 0.5, 0.35])
    p.add_argument("--seed", type=int, default=2026)
    p.add_argument("--only", choices=sorted(TABLES), nargs="+")
    a = p.parse_args(argv)
    events, n_waves, p_exp = cfd_lf_record()
    os.makedirs(a.root, exist_ok=True)
    recipe = write_sea_recipe(Path(a.root).resolve() / "sea.json")
    todo = [j for j in jobs(events, a) if a.only is None or j[0] in a.only]
    print(f"{len(todo)} runs; n_waves {n_waves}, p_exp {p_exp:.4g}", flush=True)
    with ThreadPoolExecutor(a.workers) as pool:
        for kind, row in pool.map(lambda j: run(j, a.root, recipe), todo):
            append(kind, row)


if __name__ == "__main__":
    main()
