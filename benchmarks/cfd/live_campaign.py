"""PAS with OpenFOAM in the loop, to its stop: killed once, resumed, checked against the table.

1. ``pas run`` on the CFD case's events above the LF cut with the OpenFOAM
   program as its command oracle (``python -m pas.cfd.event``), two CFD events
   at a time (``--batch-size 2 --workers 2``), the same settings as the
   comparison (``pas.validation.cfd_compare``);
2. ``kill -9`` of the ``pas run`` process once ``--kill-after`` events have
   finished, with its CFD programs still running; the same command again;
3. every event folder's ``starts.log`` counts the solver starts: an event
   run twice is a CFD run repeated;
4. ``pas run`` with the CFD table as a table oracle on the same events and
   settings: the same events asked, and the same answer.

    python benchmarks/cfd/live_campaign.py --dir cfd-live
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd

from pas.validation.case_cfd import CFD_CASE, cfd_lf_record, cfd_table
from pas.validation.cfd_compare import EPS1

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.cfd import write_sea_recipe  # noqa: E402


def command(out, oracle, events, n_waves, p_exp, cut, seed, max_hf):
    return [sys.executable, "-m", "pas", "run", str(events), "--oracle", oracle,
            "--meta-columns", "seed,t_peak", "--target", CFD_CASE.load, "--n-waves",
            str(n_waves), "--p-exp", repr(p_exp), "--eps1", repr(EPS1), "--threshold",
            repr(cut), "--seed", str(seed), "--max-hf", str(max_hf), "--batch-size", "2",
            "--workers", "2", "--unit", "N/m", "--lf-unit", "m", "--json", "--out", str(out)]


def finished(out):
    runs = Path(out) / "hf-runs"
    return sum(1 for d in runs.glob("*/result.txt")) if runs.is_dir() else 0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--dir", default="cfd-live")
    p.add_argument("--kill-after", type=int, default=12)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--top", type=int, default=150, help="events above the cut (the table's)")
    p.add_argument("--max-hf", type=int, default=40, help="the campaign's HF budget")
    p.add_argument("--compare-only", action="store_true",
                   help="the live run is done: count its runs and run the table-driven one")
    a = p.parse_args(argv)
    work = Path(a.dir).resolve()
    work.mkdir(parents=True, exist_ok=True)
    events, n_waves, p_exp = cfd_lf_record()
    ranked = events.sort_values("lf", ascending=False)
    cut = float(ranked["lf"].iloc[a.top - 1]) - 1e-9
    ev = ranked[ranked["lf"] > cut][["id", "lf", "seed", "t_peak"]]
    ev.to_csv(work / "events.csv", index=False)
    sea = write_sea_recipe(work / "sea.json")
    live = ("command:" + sys.executable + " -m pas.cfd.event --sea " + sea +
            " --seed {seed} --t-peak {t_peak} --out {result}")
    cmd = command(work / "live", live, work / "events.csv", n_waves, p_exp, cut, a.seed,
                  a.max_hf)
    if a.compare_only:
        previous = json.loads((work / "live_run.json").read_text())
        return compare(work, a, n_waves, p_exp, cut, **previous)
    t0 = time.time()
    proc = subprocess.Popen(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    while finished(work / "live") < a.kill_after and proc.poll() is None:
        time.sleep(1.0)
    killed_at = finished(work / "live")
    if proc.poll() is not None:
        raise SystemExit(f"pas run ended (exit {proc.returncode}) before {a.kill_after} "
                         "events had finished: nothing to kill")
    os.kill(proc.pid, signal.SIGKILL)         # the driver only: its CFD programs run on
    proc.wait()
    print(f"killed pas run (-9) after {killed_at} finished CFD events", flush=True)
    res = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    if res.returncode != 0:
        print(res.stderr[-2000:])
        raise SystemExit(f"resumed run failed with exit {res.returncode}")
    live_summary = json.loads(res.stdout)
    wall = time.time() - t0
    (work / "live_run.json").write_text(json.dumps({"killed_at": killed_at, "wall": wall,
                                                    "live_summary": live_summary}))
    return compare(work, a, n_waves, p_exp, cut, killed_at, wall, live_summary)


def compare(work, a, n_waves, p_exp, cut, killed_at, wall, live_summary):
    starts = {d.name: len((d / "starts.log").read_text().splitlines())
              for d in (work / "live" / "hf-runs").iterdir() if (d / "starts.log").exists()}
    repeated = sum(n - 1 for n in starts.values())
    cfd_table().query("status == 'ok'").to_csv(work / "cfd_table.csv", index=False)
    tab = subprocess.run(command(work / "table", f"table:{work / 'cfd_table.csv'}:id:"
                                 f"{CFD_CASE.load}", work / "events.csv", n_waves, p_exp, cut,
                                 a.seed, a.max_hf), cwd=work, capture_output=True, text=True,
                         check=True)
    table_summary = json.loads(tab.stdout)
    hist = {k: pd.read_csv(work / k / "history.csv") for k in ("live", "table")}
    same_events = hist["live"]["event_id"].astype(str).tolist() == \
        hist["table"]["event_id"].astype(str).tolist()
    out = {"killed_after": killed_at, "cfd_runs": sum(starts.values()), "events": len(starts),
           "repeated": repeated, "wall_seconds": wall, "same_events": same_events,
           "live": {k: live_summary.get(k) for k in ("mpm", "mpm_band", "n_hf", "converged",
                                                      "stop_reason")},
           "table": {k: table_summary.get(k) for k in ("mpm", "mpm_band", "n_hf", "converged",
                                                        "stop_reason")}}
    print(json.dumps(out, indent=1))
    (work / "live_campaign.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
