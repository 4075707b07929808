"""Numbers of docs/results/cfd.md from the CFD tables: the truth and its check below the cut,
event equivalence, mesh sensitivity, and the strategies' comparison over seeds.

    python benchmarks/cfd/report.py --replications 10
"""

import argparse
import sys
from pathlib import Path

import pandas as pd

from pas.validation.case_cfd import cfd_cut, cfd_lf_record, cfd_table, cfd_truth
from pas.validation.cfd_compare import compare_cfd, format_cfd, summarise_cfd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.cfd import top_n_errors  # noqa: E402
from harness.result_tables import rewrite_page  # noqa: E402

DATA = Path(__file__).resolve().parents[2] / "src" / "pas" / "validation" / "data"
PAGE = Path(__file__).resolve().parents[2] / "docs" / "results" / "cfd.md"
NAMES = {"pas": "PAS (defaults)", "paper": "PAS, paper preset", "as": "AS"}


def truth_check():
    events, n_waves, p_exp = cfd_lf_record()
    t = cfd_table()
    ok = t[t["status"] == "ok"]
    truth = cfd_truth(events, ok, n_waves, p_exp)
    ranked = events.sort_values("lf", ascending=False)["id"].tolist()
    n_top, cut = cfd_cut(events, ok)
    top, below = ok[ok["id"].isin(ranked[:n_top])], ok[~ok["id"].isin(ranked[:n_top])]
    k = p_exp * n_waves
    print(f"events {len(events)}, p_exp {p_exp:.4g}, exceedances of the MPM {k:.1f}")
    print(f"CFD runs {len(t)} ({(t['status'] != 'ok').sum()} failed), above the cut {n_top} "
          f"(LF >= {cut:.3f} m), "
          f"sample below {len(below)}")
    print(f"truth MPM {truth:.0f} N/m; loads above it: {(ok['wall_peak_filtered'] > truth).sum()}")
    print(f"below the cut: largest load {below['wall_peak_filtered'].max():.0f} N/m "
          f"({below['wall_peak_filtered'].max() / truth:.2f} of the truth), "
          f"{(below['wall_peak_filtered'] > 0.5 * truth).sum()} above half the truth")
    print(f"wall seconds per event: median {ok['wall_seconds'].median():.1f}, "
          f"cells {int(ok['n_cells'].median())}, retried at a lower Courant limit "
          f"{int((ok.get('failed_tries', 0) > 0).sum())}")
    print(f"Kendall tau (LF, HF) above the cut: "
          f"{top[['lf', 'wall_peak_filtered']].corr('kendall').iloc[0, 1]:.2f}")
    return truth


def equivalence():
    path = DATA / "cfd_green_water_equivalence.csv"
    if not path.exists():
        return
    e = pd.read_csv(path)
    e = e[e["status"] == "ok"]
    ratio = e["bow_crest"] / e["linear_crest"]
    shift = e["bow_crest_time"] - e["linear_crest_time"]
    print(f"equivalence, {len(e)} events without the structure: CFD/linear crest median "
          f"{ratio.median():.3f} (range {ratio.min():.3f}-{ratio.max():.3f}), time shift "
          f"median {shift.median():+.2f} s (range {shift.min():+.2f} to {shift.max():+.2f})")


def _signed(v):
    """A percentage with a typographic sign: +4.4 %, −2.7 %."""
    return ("+" if v > 0 else "−" if v < 0 else "") + f"{abs(v):.1%}"


def comparison_table(runs, facts):
    """The comparison as the page's Markdown table (with the brute-force row)."""
    lines = ["| strategy | runs | MPM (kN/m, median) | error, median | \\|error\\|, worst "
             "| U95 holds the truth | CFD runs | CFD hours |", "|---|---|---|---|---|---|---|---|"]
    for name, g in runs.groupby("strategy", sort=False):
        holds = g["holds"].dropna()
        n = g["n_hf"]
        span = f" ({n.min():.0f}–{n.max():.0f})" if n.min() != n.max() else ""
        lines.append(
            f"| {NAMES.get(name, name)} | {len(g)} | {g['mpm'].median() / 1e3:.1f} | "
            f"{_signed(g['error'].median())} | {g['error'].abs().max():.1%} | "
            + (f"{int(holds.sum())}/{len(holds)}" if len(holds) else "–")
            + f" | {n.median():.0f}{span} | {g['cfd_hours'].median():.2f} |")
    lines.append(f"| brute force (the truth) | – | {facts['truth'] / 1e3:.1f} | – | – | – | "
                 f"{facts['n_cfd']} | {facts['truth_hours']:.2f} |")
    return "\n".join(lines)


def mesh_rows():
    """The mesh study's runs with the same events' 0.5 m runs of the truth table."""
    m = pd.read_csv(DATA / "cfd_green_water_mesh.csv")
    m = m[m["status"] == "ok"]
    base = cfd_table().set_index("id")
    return pd.concat([m, base.loc[m["id"].unique()].reset_index().assign(cell=0.5)])


def mesh_table():
    piv = mesh_rows().pivot_table(index="id", columns="cell", values="wall_peak_filtered")
    lines = ["| event | filtered peak at 0.5 m (kN/m) | 0.35 m / 0.5 m | 0.7 m / 0.5 m |",
             "|---|---|---|---|"]
    for e, r in piv.iterrows():
        lines.append(f"| {e} | {r[0.5] / 1e3:.1f} | {r[0.35] / r[0.5]:.2f} | "
                     f"{r[0.7] / r[0.5]:.2f} |")
    return "\n".join(lines)


def mesh():
    if not (DATA / "cfd_green_water_mesh.csv").exists():
        return
    rows = mesh_rows()
    for load in ("wall_peak_filtered", "wall_peak"):
        piv = rows.pivot_table(index="id", columns="cell", values=load)
        rel = piv.div(piv[0.5], axis=0)
        print(f"mesh, {load} relative to 0.5 m cells:")
        print(rel.round(3).to_string())
        spread = (piv.max(axis=1) / piv.min(axis=1))
        print(f"  max/min over meshes: median {spread.median():.2f}, worst {spread.max():.2f}")
    cost = rows.groupby("cell")["wall_seconds"].median()
    print("wall seconds per event by cell size:", cost.round(1).to_dict())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--replications", type=int, default=10)
    p.add_argument("--write", action="store_true",
                   help="put the comparison and mesh tables between the markers of "
                        "docs/results/cfd.md")
    a = p.parse_args(argv)
    truth_check()
    equivalence()
    mesh()
    print("top-N habit, error against the truth:",
          top_n_errors().round(3).to_string(index=False))
    runs, facts = compare_cfd(seeds=range(a.replications))
    print(format_cfd(summarise_cfd(runs, facts)))
    with pd.option_context("display.width", 200):
        print(runs.round(4).to_string())
    if a.write:
        rewrite_page(PAGE, {"comparison": comparison_table(runs, facts),
                            "mesh": mesh_table()}, "report.py")


if __name__ == "__main__":
    main()
