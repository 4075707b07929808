"""How far the MPM still moves at the end of a study, against the stopping tolerance.

A study stops when the predicted distribution has moved less than ε1 over the
last K1 = 20 true-positive iterations (``stop_measure="window"``, the default)
or, with the paper's Eq. 28 (``"step"``), when the *mean per-iteration* change
is below ε1.  This script asks whether "converged within 160 HF" is within
reach on an analogue at all:

* **PAS** — each data set is run with both measures (HF budget 160, no model
  band: the band does not change the MPM).  Printed per data set: the MPM
  error (M2, Eq. 18), the HF count, whether the study stopped, and ``move20``: how
  far the MPM moved over the last 20 true-positive iterations, relative to
  the truth, beside ε1 relative to the truth.  ``move20`` is the window
  measure read at the MPM alone: ``max_i |MPM_last − MPM_i|`` over the 20
  iterations before the last (the rule itself averages that change over
  ``d ∈ [P_exp/2, 2 P_exp]``).
* **known law** — the same measure for the reference estimator of
  ``sampling_reference.py`` (k loads i.i.d. from the data set's truth Weibull,
  its family and location told, scale and shape by ML), refitted as the 20
  next loads arrive one by one from k = PAS's median number of true-positive
  pairs at 160 HF.  For an efficient estimator the change from k to k + 20
  loads has the variance Var(k) − Var(k + 20), about its own error times
  sqrt(20 / (k + 20)): it can stay within ε1 only if its error is of the order
  of ε1.  The script prints the estimator's median |error| at k beside it.
* **known law + LF (Gumbel)** — the same with the Gumbel copula at the data
  set's τ (the more favourable of that script's two copula references): pool,
  ln-d order of the events and conditional ML as there, the 20 next events in
  their drawn order.

``--max-hf B`` also runs the default rule with the HF budget raised to B and
prints where it stops.

``--csv FILE`` saves one summary row per case; ``--write [PAGE] --from-csv
A,B,…`` runs nothing and writes the ``move20`` table of
``docs/results/investigations.md`` from such files, between its
``stop_movement.py`` markers.

Run: python benchmarks/investigations/stop_movement.py [N] [--cases 4a,4b,3b] [--draws 100]
     [--max-hf B] [--csv FILE]
     python benchmarks/investigations/stop_movement.py --write --from-csv A.csv,B.csv
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import optimize, stats

from pas.validation import generate_case
from pas.validation.reproduce import run_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.error_tables import add_write_options, saved_results, write_tables  # noqa: E402
from harness.references import (  # noqa: E402
    copula_at_tau,
    lf_reference_nll,
    lf_reference_pool,
    truth_law,
)

WINDOW = 20
PAGE, TAG = Path("docs/results/investigations.md"), "stop_movement.py"
MEASURES = (("window", {}), ("step", {"stop_measure": "step"}))


def mpm_range(mpms, truth: float) -> float:
    """The window measure at the MPM: ``max_i |MPM_last − MPM_i|`` over the ``WINDOW``
    iterations before the last, relative to the truth."""
    last = np.asarray(mpms, float)[-(WINDOW + 1):]
    return float(np.max(np.abs(last[:-1] - last[-1])) / truth)


def study_movement(data, seed: int, settings: dict, max_hf: int = 160) -> dict:
    """One PAS study: error, HF, stopped, and how far the MPM moved at the end."""
    res, row = run_case(data, seed=seed, max_hf=max_hf, settings={**settings, "n_bootstrap": 0})
    h = res.history
    tp = h[h["status"] == "true_positive"].dropna(subset=["mpm"])
    return {"error": row["M2"], "n_hf": res.n_hf, "stopped": bool(res.converged),
            "pairs": int(tp["n_pairs"].iloc[-1]),
            "move20": mpm_range(tp["mpm"].to_numpy(), data.truth_mpm)}


def _weibull_mpm(theta, a, b, q):
    return theta + a * (-np.log(q)) ** (1.0 / b)


def known_law_movement(data, k: int, draws: int, seed: int) -> np.ndarray:
    """``move20`` of the known-law estimator refitted at k, k + 1, …, k + 20 i.i.d. loads,
    and its relative error at k."""
    theta, alpha, beta, _, q = truth_law(data)
    rng = np.random.default_rng([seed, k, 17])
    out, errors = [], []
    for _ in range(draws):
        x = alpha * rng.weibull(beta, size=k + WINDOW)
        mpms = []
        for m in range(k, k + WINDOW + 1):
            shape, _, scale = stats.weibull_min.fit(x[:m], floc=0.0)
            mpms.append(_weibull_mpm(theta, scale, shape, q))
        out.append(mpm_range(mpms, data.truth_mpm))
        errors.append(mpms[0] / data.truth_mpm - 1.0)
    return np.asarray(out), np.asarray(errors)


def known_law_lf_movement(data, k: int, draws: int, seed: int, copula: str = "gumbel"):
    """``move20`` of the known-law + LF estimator as the next 20 ln-d events arrive,
    and its relative error at k."""
    theta, alpha, beta, n, q = truth_law(data)
    cop, par = copula_at_tau(copula, data.tau)
    rng = np.random.default_rng([seed, k, 19])
    nll = lf_reference_nll(copula, par)
    out, errors = [], []
    for _ in range(draws):
        u_l, y, pick = lf_reference_pool(cop, n, alpha, beta, k + WINDOW, rng, oversample=40)
        shape, _, scale = stats.weibull_min.fit(y[pick[:k]], floc=0.0)
        x0, mpms = np.log([scale, shape]), []
        for m in range(k, k + WINDOW + 1):
            x0 = optimize.minimize(nll, x0, args=(u_l[pick[:m]], y[pick[:m]]),
                                   method="Nelder-Mead",
                                   options={"xatol": 1e-8, "fatol": 1e-10}).x
            mpms.append(_weibull_mpm(theta, *np.exp(x0), q))
        out.append(mpm_range(mpms, data.truth_mpm))
        errors.append(mpms[0] / data.truth_mpm - 1.0)
    return np.asarray(out), np.asarray(errors)


def _reference_line(label, moves, errors, eps, draws, k):
    below = np.mean(moves < np.repeat(eps, draws))
    return (f"  {label}, k {k} -> {k + WINDOW}: move20 median {np.median(moves):.3f}, "
            f"p10 {np.percentile(moves, 10):.3f}, share below eps1 {below:.3f}; "
            f"median |error| at k {np.median(np.abs(errors)):.3f}")


def _summary(values) -> str:
    v = np.asarray(values, float)
    return f"{np.median(v):.3f} [{v.min():.3f}, {v.max():.3f}]"


def case_row(case, eps, pas_runs, k, law, lf) -> dict:
    """One case's summary for ``--csv``: ε1 / truth, PAS's ``move20`` at its end, and the
    references' ``move20``, share within ε1 and median |error| at k (``law``, ``lf``:
    ``(move20, errors)`` per data set)."""
    moves = [r["move20"] for r in pas_runs]
    row = {"case": case, "k": k, "eps1_rel": float(np.median(eps)),
           "pas_move20": float(np.median(moves)), "pas_move20_min": float(np.min(moves)),
           "pas_move20_max": float(np.max(moves)),
           "pas_stopped": int(sum(r["stopped"] for r in pas_runs)),
           "pas_max_hf": int(max(r["n_hf"] for r in pas_runs))}
    for name, per_set in (("law", law), ("lf", lf)):
        draws = len(per_set[0][0])
        moved, errors = (np.concatenate(parts) for parts in zip(*per_set))
        row.update({f"{name}_move20": float(np.median(moved)),
                    f"{name}_within_eps1": float(np.mean(moved < np.repeat(eps, draws))),
                    f"{name}_draws": int(moved.size),
                    f"{name}_error": float(np.median(np.abs(errors)))})
    return row


def _pct(value: float) -> str:
    return f"{100 * value:.1f}"


def markdown(cases: pd.DataFrame) -> str:
    """The page's ``move20`` table, one row per case of ``--csv``."""
    lines = [
        (
            "| case | ε1 / truth | PAS (default) at its end | known law | known law + LF (Gumbel) "
            "| references within ε1 | their median \\|error\\| at k |"
        ),
        "|---" * 7 + "|",
    ]
    for _, r in cases.iterrows():
        end = "at 160 HF" if r["pas_stopped"] == 0 else "at its stop or 160 HF"
        lines.append(
            f"| {r['case']} (k {r['k']}) | {_pct(r['eps1_rel'])} % | {_pct(r['pas_move20'])} % "
            f"[{_pct(r['pas_move20_min'])}, {_pct(r['pas_move20_max'])}] {end} | "
            f"{_pct(r['law_move20'])} % | {_pct(r['lf_move20'])} % | "
            f"{100 * r['law_within_eps1']:.0f} % of {r['law_draws']}, "
            f"{100 * r['lf_within_eps1']:.0f} % of {r['lf_draws']} | "
            f"{_pct(r['law_error'])} / {_pct(r['lf_error'])} % |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("n", nargs="?", type=int, default=10, help="data seeds 0 … N-1")
    ap.add_argument("--cases", default="4a,4b,3b")
    ap.add_argument("--draws", type=int, default=100, help="draws of each reference")
    ap.add_argument("--max-hf", type=int, default=None,
                    help="also run the default rule with this HF budget")
    add_write_options(ap, PAGE)
    args = ap.parse_args(argv)
    if args.write:
        rows = saved_results(ap, args)
        return write_tables(args.write, {"move20": markdown(rows)}, TAG)
    cases, draws, budget, n = args.cases.split(","), args.draws, args.max_hf, args.n
    summary = []
    warnings.simplefilter("ignore")
    for case in cases:
        runs = {name: [] for name, _ in MEASURES}
        datasets = []
        for seed in range(n):
            data = generate_case(case, seed=seed)
            datasets.append(data)
            line = [f"{case} {seed}  eps1/truth {data.eps1 / data.truth_mpm:.3f}"]
            for name, settings in MEASURES:
                r = study_movement(data, seed, settings)
                runs[name].append(r)
                line.append(f"{name}: error {r['error']:+.3f} HF {r['n_hf']} "
                            f"stopped {int(r['stopped'])} move20 {r['move20']:.3f}")
            if budget:
                r = study_movement(data, seed, {}, max_hf=budget)
                runs.setdefault(f"window, budget {budget}", []).append(r)
                line.append(f"budget {budget}: error {r['error']:+.3f} HF {r['n_hf']} "
                            f"stopped {int(r['stopped'])}")
            print(" | ".join(line), flush=True)
        eps = [d.eps1 / d.truth_mpm for d in datasets]
        print(f"\n{case}: eps1 / truth {_summary(eps)}")
        for name, rs in runs.items():
            err, hf = np.abs([r["error"] for r in rs]), [r["n_hf"] for r in rs]
            print(f"  PAS {name}: median |error| {np.median(err):.3f}, worst {err.max():.3f}, "
                  f"stopped {sum(r['stopped'] for r in rs)}/{n}, HF median {np.median(hf):.0f} "
                  f"[{min(hf)}, {max(hf)}], move20 {_summary([r['move20'] for r in rs])}")
        k = int(np.median([r["pairs"] for r in runs["window"]]))
        law = [known_law_movement(d, k, draws, s) for s, d in enumerate(datasets)]
        print(_reference_line("known law", *map(np.concatenate, zip(*law)), eps, draws, k),
              flush=True)
        lf_draws = max(1, draws // 4)
        lf = [known_law_lf_movement(d, k, lf_draws, s) for s, d in enumerate(datasets)]
        print(_reference_line("known law + LF (gumbel)", *map(np.concatenate, zip(*lf)), eps,
                              lf_draws, k) + "\n", flush=True)
        summary.append(case_row(case, eps, runs["window"], k, law, lf))
        if args.csv:
            pd.DataFrame(summary).to_csv(args.csv, index=False)


if __name__ == "__main__":
    main()
