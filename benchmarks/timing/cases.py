"""Benchmark: the validation analogues end to end (SPEC §7: the eight cases <= 3 min on 2 cores).

Default: all twelve ids (the eight paper-like cases and the four ``-hard``
impact variants); ``--cases 1a,1b,...`` for a subset, e.g. the eight of the
budget (``pas.validation.PAPER_CASE_IDS``).

Generates every case at full scale into a fresh temporary cache (timed
separately: the user's ``./pas-cache`` is never read), then runs PAS — and AS
when available — once per case with the paper's settings, scores it, and
draws the figures into a temporary folder.  Prints one line per case and the
totals.  Run: ``python benchmarks/timing/cases.py [--replications N]``.
"""

import argparse
import tempfile
import time

import pandas as pd

from pas.validation import CASE_IDS, generate_case
from pas.validation.figures import write_figures
from pas.validation.reproduce import _strategies, run_case, summarise


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--replications", type=int, default=1)
    ap.add_argument("--scale", type=float, default=1.0)
    ap.add_argument("--cases", default=",".join(CASE_IDS))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        t_gen, t_run, data, rows, first = {}, {}, {}, [], {}
        for cid in args.cases.split(","):
            t0 = time.perf_counter()
            data[cid] = generate_case(cid, scale=args.scale, path=cache)
            t_gen[cid] = time.perf_counter() - t0
            t0 = time.perf_counter()
            for strat in _strategies():
                for r in range(args.replications):
                    res, row = run_case(data[cid], strategy=strat, seed=r)
                    rows.append(row)
                    first.setdefault((cid, strat), res)
            t_run[cid] = time.perf_counter() - t0
            d = data[cid]
            per = ", ".join(
                f"{r['strategy'].upper()} {r['n_hf']} HF M2 {100 * r['M2']:+.1f}% "
                f"{r['seconds']:.1f} s"
                for r in rows
                if r["case"] == cid and r["seed"] == 0
            )
            print(f"{cid}: {d.n_events} events, generate {t_gen[cid]:5.1f} s, "
                  f"strategies {t_run[cid]:5.1f} s ({per})", flush=True)
        t0 = time.perf_counter()
        table = summarise(pd.DataFrame(rows), data)
        write_figures(out, data, first, table)
        t_fig = time.perf_counter() - t0
    g, r = sum(t_gen.values()), sum(t_run.values())
    print(f"total: generate {g:.1f} s + strategies {r:.1f} s + figures {t_fig:.1f} s "
          f"= {g + r + t_fig:.1f} s (target <= 180 s)")


if __name__ == "__main__":
    main()
