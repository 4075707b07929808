"""Check: a refactor changes no result — the MPMs of PAS (defaults, no band) and the paper preset.

Runs :func:`pas.validation.reproduce.run_case` for PAS with
``PAS(band=ModelBand(n_bootstrap=0))`` and for ``PAS.paper()`` on the analogues
(every case, or ``--cases``) and data seeds (``--seeds``), and
:func:`pas.run_pas` with the same two strategies on the first type of each
known-truth group (``--known-truth``, replications ``--seeds``), there also the
default PAS with its model band (band ends compared); writes
``{"case/seed/strategy": {"mpm", "n_hf"}}`` to ``--out`` and, with
``--compare BASELINE.json`` (the same file written before the change, e.g. by
an earlier commit's ``pas``), prints each MPM beside the baseline's and the
largest relative difference; the exit code is 1 when it exceeds ``--rtol``
(default 1e-9: same machine, same code path) or an HF count differs.

Run: ``python benchmarks/studies/refactor_check.py --cases 1a,3a,4a-hard --seeds 0,1
--compare baseline.json`` (about 1–3 s a run).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import pas
from pas.strategies.band import ModelBand
from pas.validation import CASE_IDS, generate_case
from pas.validation.reproduce import run_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.known_truth import GROUPS, TUNING_TYPES, make_problem  # noqa: E402

VARIANTS = {"pas": ("pas", {"n_bootstrap": 0}), "pas-paper": ("pas-paper", {})}
"""Label -> (strategy of run_case, its flat settings): PAS(band=ModelBand(n_bootstrap=0))
and PAS.paper() (run_case reads them through pas.study.flat.from_flat)."""


def run(cases, seeds) -> dict:
    """``{"case/seed/label": {"mpm", "n_hf"}}`` of every variant, case and seed."""
    rows = {}
    for case in cases:
        for seed in seeds:
            data = generate_case(case, seed=seed)
            for label, (strategy, settings) in VARIANTS.items():
                t0 = time.perf_counter()
                res, _ = run_case(data, strategy=strategy, seed=seed, settings=settings)
                rows[f"{case}/{seed}/{label}"] = {"mpm": float(res.mpm), "n_hf": int(res.n_hf)}
                print(f"{case} seed {seed} {label}: MPM {res.mpm:.10g}, {res.n_hf} HF "
                      f"({time.perf_counter() - t0:.1f} s)", flush=True)
    return rows


def known_truth_strategies() -> dict:
    """Label -> the strategy of :func:`pas.run_pas` (built anew per run); ``pas-band`` is the
    default PAS, model band included, whose band ends are compared too."""
    return {"pas": lambda: pas.PAS(band=ModelBand(n_bootstrap=0)), "pas-paper": pas.PAS.paper,
            "pas-band": pas.PAS}


def run_known_truth(groups, seeds) -> dict:
    """``{"kt/type/seed/label": {"mpm", "n_hf"}}`` on the first tuning type of each group."""
    rows = {}
    for group in groups:
        name = next(n for n in TUNING_TYPES if n.split("-")[0] == group)
        for seed in seeds:
            problem = make_problem(TUNING_TYPES[name], seed)
            for label, strategy in known_truth_strategies().items():
                t0 = time.perf_counter()
                res = pas.run_pas(problem.lf, problem.oracle(), n_waves=problem.n_waves,
                                  p_exp=problem.p_exp, threshold=problem.threshold,
                                  eps1=problem.eps1, seed=seed, strategy=strategy())
                rows[f"kt/{name}/{seed}/{label}"] = {
                    "mpm": float(res.mpm), "n_hf": int(res.n_hf),
                    **({"band": [float(x) for x in res.mpm_band]} if label == "pas-band" else {})}
                print(f"{name} seed {seed} {label}: MPM {res.mpm:.10g}, {res.n_hf} HF "
                      f"({time.perf_counter() - t0:.1f} s)", flush=True)
    return rows


def compare(rows: dict, baseline: dict) -> tuple[float, list[str]]:
    """The largest relative MPM difference to ``baseline`` and the keys whose HF count
    differs or that the baseline lacks."""
    worst, differ = 0.0, []
    for key, row in rows.items():
        old = baseline.get(key)
        if old is None or old["n_hf"] != row["n_hf"]:
            differ.append(key)
            continue
        rel = max([abs(row["mpm"] - old["mpm"]) / abs(old["mpm"])]
                  + [abs(a - b) / abs(b) for a, b in zip(row.get("band", []),
                                                         old.get("band", []))])
        worst = max(worst, rel)
        print(f"{key}: {row['mpm']:.12g} against {old['mpm']:.12g} (relative, band ends "
              f"included, {rel:.2e})")
    return worst, differ


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", default=",".join(CASE_IDS), help="comma-separated case ids")
    ap.add_argument("--seeds", default="0", help="comma-separated data seeds")
    ap.add_argument("--known-truth", default=",".join(GROUPS),
                    help="comma-separated known-truth groups ('' for none)")
    ap.add_argument("--out", default="pas-output/refactor_check.json")
    ap.add_argument("--compare", metavar="BASELINE.json", help="MPMs written before the change")
    ap.add_argument("--rtol", type=float, default=1e-9)
    args = ap.parse_args(argv)
    seeds = [int(s) for s in args.seeds.split(",")]
    rows = run([c for c in args.cases.split(",") if c], seeds)
    rows.update(run_known_truth([g for g in args.known_truth.split(",") if g], seeds))
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"pas_version": pas.__version__, **rows}, f, indent=1)
    if not args.compare:
        return 0
    with open(args.compare) as f:
        baseline = json.load(f)
    worst, differ = compare(rows, baseline)
    print(f"{len(rows) - len(differ)} runs compared: largest relative MPM difference "
          f"{worst:.2e} (limit {args.rtol:g}); {len(differ)} differ in HF count or are "
          f"missing from the baseline{': ' + ', '.join(differ) if differ else ''}")
    return 0 if worst <= args.rtol and not differ else 1


if __name__ == "__main__":
    sys.exit(main())
