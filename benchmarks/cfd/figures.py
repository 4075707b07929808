"""Figures of the guide page "PAS with OpenFOAM" and of docs/results/cfd.md, from the CFD tables.

    python benchmarks/cfd/figures.py --root cfd-runs --out docs/img/cfd

``--root`` is the runner's folder (``green_water_runs.py``): the snapshot of
the green water on the deck re-runs the largest event there with its fields
written around the impact (about 20 s of solver time) and the force history
is read from its run folder.  Everything else comes from the tables in the
package.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from pas.cfd.results import FILTER_SECONDS, _moving_average, read_forces  # noqa: E402
from pas.validation.case_cfd import CFD_CASE, cfd_lf_record, cfd_table, cfd_truth  # noqa: E402

DATA = Path(__file__).resolve().parents[2] / "src" / "pas" / "validation" / "data"


def _field(path):
    """The internalField of an ASCII OpenFOAM field (scalar or vector) as an array."""
    lines = Path(path).read_text().splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.startswith("internalField"))
    n = int(lines[i + 1])
    rows = [ln.strip("()").split() for ln in lines[i + 3:i + 3 + n]]
    return np.array(rows, float).squeeze()


def snapshot(root, out):
    """Green water on the deck of the largest event at its wall-force peak."""
    table = cfd_table()
    ev = table[table["status"] == "ok"].nlargest(1, "wall_peak_filtered").iloc[0]
    src = Path(root) / "truth" / ev["id"] / "case"
    work = Path(root) / "snapshot"
    if not (work / "18.5").is_dir():
        _rerun(src, work)
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR",
                                                          "/usr/share/openfoam"))
    peak = float(ev["run_wall_peak_time"])
    times = sorted((d for d in work.iterdir() if re.fullmatch(r"\d+\.?\d*", d.name)
                    and d.name != "0"), key=lambda d: float(d.name))
    best = min(times, key=lambda d: abs(float(d.name) - peak))
    subprocess.run(["postProcess", "-func", "writeCellCentres", "-time", best.name], cwd=work,
                   env=env, check=True, capture_output=True)
    alpha, c = _field(best / "alpha.water"), _field(best / "C")
    _draw_snapshot(alpha, c, best, ev, out)


def _rerun(src, work):
    """The case of ``src`` run again in ``work`` with its fields written every 0.1 s."""
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(src, work, ignore=shutil.ignore_patterns("postProcessing", "log.*"))
    ctl = (work / "system" / "controlDict").read_text()
    ctl = ctl.replace("writeFormat binary;", "writeFormat ascii;")
    ctl = ctl.replace("writeInterval 1000;", "writeInterval 0.1;")
    (work / "system" / "controlDict").write_text(ctl)
    for d in work.iterdir():
        if re.fullmatch(r"[\d.]+", d.name) and d.name != "0":
            shutil.rmtree(d)
    shutil.rmtree(work / "0", ignore_errors=True)
    shutil.copytree(work / "0.orig", work / "0")
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR",
                                                          "/usr/share/openfoam"))
    for cmd in (["setFields"], ["interFoam"]):
        subprocess.run(cmd, cwd=work, env=env, check=True, capture_output=True)


def _draw_snapshot(alpha, c, best, ev, out):
    fig, ax = plt.subplots(figsize=(8, 3.6))
    keep = (c[:, 0] > 20) & (c[:, 2] > -12)
    sc = ax.tricontourf(c[keep, 0], c[keep, 2], np.clip(alpha[keep], 0, 1),
                        levels=np.linspace(0, 1.0001, 11), cmap="Blues")
    ax.fill_between([50, 70], -12, 8, color="0.5", zorder=3)
    ax.plot([70, 70], [8, 30], color="0.2", lw=3, zorder=3)
    ax.annotate("deckhouse wall", (69.5, 27), ha="right", fontsize=8)
    ax.set(xlabel="x from the inlet (m)", ylabel="z above still water (m)", xlim=(20, 70),
           ylim=(-12, 30), aspect="equal",
           title=f"Green water at the wall-force peak, t = {float(best.name):.1f} s "
                 f"(event {ev['id']})")
    fig.colorbar(sc, ax=ax, label="water fraction")
    fig.tight_layout()
    fig.savefig(Path(out) / "cfd_green_water.png", dpi=110)
    plt.close(fig)


def force_history(root, out):
    table = cfd_table()
    ev = table[table["status"] == "ok"].nlargest(1, "wall_peak_filtered").iloc[0]
    case = Path(root) / "truth" / ev["id"] / "case"
    t, f = read_forces(case, "wallForce")
    fx = (f[:, 0] - f[0, 0]) / 1e3
    g, s = _moving_average(t, fx, FILTER_SECONDS)
    info = json.loads((case.parent / "event.json").read_text())
    lo, hi = info["t_event"] + info["window"][0], info["t_event"] + info["window"][1]
    fig, ax = plt.subplots(figsize=(7, 3.4))
    ax.plot(t, fx, lw=0.7, color="0.6", label="raw")
    ax.plot(g, s, lw=1.4, label=f"{FILTER_SECONDS} s moving average")
    ax.axvspan(lo, hi, color="C1", alpha=0.12, label="the event's window")
    ax.axvline(info["t_event"], color="C1", lw=0.8, ls="--")
    ax.set(xlabel="run time (s)", ylabel="horizontal force on the wall (kN/m)",
           title=f"Wall force of event {ev['id']} (linear crest {ev['lf']:.2f} m)")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(Path(out) / "cfd_force_history.png", dpi=110)
    plt.close(fig)


def scatter(out):
    events, n_waves, p_exp = cfd_lf_record()
    table = cfd_table()
    ok = table[table["status"] == "ok"]
    truth = cfd_truth(events, ok, n_waves, p_exp)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.scatter(ok["lf"], ok[CFD_CASE.load] / 1e3, s=12)
    ax.axhline(truth / 1e3, color="C3", lw=1, label=f"truth MPM {truth / 1e3:.0f} kN/m")
    ax.set(xlabel="linear crest at the bow, LF (m)",
           ylabel="wall force, filtered peak (kN/m)", title="CFD events: LF against HF")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(Path(out) / "cfd_scatter.png", dpi=110)
    plt.close(fig)


def equivalence(out):
    eq = pd.read_csv(DATA / "cfd_green_water_equivalence.csv")
    eq = eq[eq["status"] == "ok"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6))
    a.scatter(eq["linear_crest"], eq["bow_crest"], s=14)
    lim = [eq["linear_crest"].min() * 0.9, eq["bow_crest"].max() * 1.05]
    a.plot(lim, lim, color="0.5", lw=0.8)
    a.set(xlabel="linear crest, LF (m)", ylabel="CFD crest at the bow position (m)",
          title="Crest height, no structure")
    b.scatter(eq["linear_crest"], eq["bow_crest_time"] - eq["linear_crest_time"], s=14)
    b.axhline(0, color="0.5", lw=0.8)
    b.set(xlabel="linear crest, LF (m)", ylabel="CFD - linear crest time (s)",
          title="Crest timing, no structure")
    fig.tight_layout()
    fig.savefig(Path(out) / "cfd_equivalence.png", dpi=110)
    plt.close(fig)


def mesh(out):
    m = pd.read_csv(DATA / "cfd_green_water_mesh.csv")
    base = cfd_table().set_index("id")
    m = m[m["status"] == "ok"]
    rows = pd.concat([m, base.loc[m["id"].unique()].reset_index().assign(cell=0.5)])
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for key, g in rows.groupby("id"):
        g = g.sort_values("cell")
        ax.plot(g["cell"], g["wall_peak_filtered"] / 1e3, "o-", label=key)
        ax.plot(g["cell"], g["wall_peak"] / 1e3, "x:", color=ax.lines[-1].get_color())
    ax.set_yscale("log")
    ax.set(xlabel="cell size (m)", ylabel="wall force (kN/m, log scale)",
           title="Mesh: filtered peak (o) and raw peak (x)")
    ax.legend(frameon=False, fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(out) / "cfd_mesh.png", dpi=110)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default="cfd-runs")
    p.add_argument("--out", default="docs/img/cfd")
    p.add_argument("--only", nargs="+")
    a = p.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    jobs = {"snapshot": lambda: snapshot(a.root, a.out),
            "force": lambda: force_history(a.root, a.out), "scatter": lambda: scatter(a.out),
            "equivalence": lambda: equivalence(a.out), "mesh": lambda: mesh(a.out)}
    for name, job in jobs.items():
        if a.only is None or name in a.only:
            job()
            print("drew", name)


if __name__ == "__main__":
    main()
