"""What cutting the event's components does to its linear crest at the structure.

For the ``--events`` largest LF events of the CFD case, the event's wave with
every component (up to 1.6 rad/s) against the fewest largest components
holding ``energy`` of the variance: relative crest error and time shift.

    python benchmarks/cfd/component_cut.py --events 50
"""

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pas.cfd.event import sea_from_recipe
from pas.validation.case_cfd import CFD_CASE, cfd_lf_record
from pas.waves.event_wave import event_wave

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.result_tables import rewrite_page  # noqa: E402

PAGE = Path(__file__).resolve().parents[2] / "docs" / "results" / "cfd.md"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--events", type=int, default=50)
    p.add_argument("--energy", type=float, nargs="+", default=[0.999, 0.99, 0.95, 0.9])
    p.add_argument("--write", action="store_true",
                   help="put the table between the markers of docs/results/cfd.md")
    a = p.parse_args(argv)
    events = cfd_lf_record()[0].nlargest(a.events, "lf")
    seas = {}
    rows = []
    for _, ev in events.iterrows():
        sea = seas.setdefault(ev["seed"], sea_from_recipe(CFD_CASE.recipe(), ev["seed"]))
        wave = event_wave(sea, ev["t_peak"], upwave=50.0, lead=15.0)
        for e in a.energy:
            rows.append({"id": ev["id"], **wave.cut_effect(e), "all": wave.n_components})
    df = pd.DataFrame(rows)
    out = df.groupby("energy").agg(
        components=("n_components", "median"), of=("all", "median"),
        crest_error_median=("crest_error", lambda x: np.median(np.abs(x))),
        crest_error_worst=("crest_error", lambda x: np.abs(x).max()),
        time_shift_worst=("time_shift", lambda x: np.abs(x).max()))
    out = out.sort_index(ascending=False)
    print(out.to_string(float_format=lambda v: f"{v:.4g}"))
    if a.write:
        lines = ["| energy kept | components | crest error, median | worst | time shift, worst |",
                 "|---|---|---|---|---|"]
        lines += [f"| {e:g} | {r.components:.0f} | {r.crest_error_median:.1%} | "
                  f"{r.crest_error_worst:.1%} | {r.time_shift_worst:.2f} s |"
                  for e, r in out.iterrows()]
        rewrite_page(PAGE, {"cut": "\n".join(lines)}, "component_cut.py")


if __name__ == "__main__":
    main()
