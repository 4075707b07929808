"""What k impact loads can tell: a sampling reference for the impact analogues.

PAS on cases 3–4 is scored against a truth read from the *whole* HF record (a
3-parameter Weibull fitted to the top 30 % of the non-zero HF peaks, the
paper's truth).  How close can any method come with k HF values?  This script
gives a reference that asks for no model of LF–HF dependence at all: an
oracle that knows which events are impacts draws k of them at random (no
false positive ever evaluated) and applies

* ``truth-estimator``: the truth's own estimator (the same Weibull fit, top
  30 % of the k loads, scaled by the known impact rate), and
* ``empirical``: the empirical quantile of the k loads at the MPM's
  exceedance probability among impacts, ``P_exp / rate``.

Two model references ask what k impact loads could tell if nothing were
misspecified.  They are models, not bounds: no estimator is shown unable to
beat them, and they are told more than PAS knows (the law's family and
location, the impact rate, the copula); they also draw every load from the
truth's Weibull, whereas 30–64 % of the analogues' impacts lie below its
location.  Their errors are against the law's own quantile (the data set's
truth), not against a fit to a record drawn from it.

* ``known law``: k loads drawn i.i.d. from the data set's truth Weibull, its
  family and location told, scale and shape by maximum likelihood, the MPM
  read at ``P_exp / rate``;
* ``known law + LF``: the same law joined to the LF by a copula at the data
  set's Kendall τ — Gaussian, and Gumbel (upper-tail dependent; its
  association among the top LF decile is closer to the analogues' on 4a/4b)
  — also told; a pool of as many events as the data set has impacts, k
  distinct ones drawn uniformly in ln d over the LF ranks, scale and shape
  by the likelihood of HF given LF.

For each, ``P(targets)``: one error drawn per data set, the chance that the
median |error| over the ten is ≤ 10 % and the worst ≤ 25 %.

With ``--pas-runs`` it also runs **PAS's own estimator on random pool events**:
for each data set, as many events as PAS evaluated there (its HF count),
drawn at random from the LF pool (over the threshold; impacts and misses
alike, no MD), 5 draws per data set.  Beside PAS's result this separates
the two things PAS does differently from the oracle: how it chooses events
(MD against random) and how it estimates (its conditional fit against the
truth's Weibull on impacts).

Per case and k it prints the median and 90th percentile of |error| over data
seeds 0…N−1 (new analogue data sets) × R random subsamples each, and
``P(worst of 10 ≤ 25 %)`` = ``P(|error| ≤ 25 %)¹⁰`` — the chance that ten
independent data sets all land within ±25 %.  PAS, which must find the
impacts and also spends HF on misses, is measured on the same data sets by
``benchmarks/studies/validation_spread.py``; compare at its number of true-positive
pairs (``--pas-runs`` reads them from that script's runs.csv).

``--csv FILE`` saves every printed row (case, k, reference, median, p90,
P(worst of 10 ≤ 25 %), P(targets), τ; PAS's own median / worst |M2| as
reference ``pas``); ``--write [PAGE] --from-csv A,B,…`` runs nothing and
writes the three tables of ``docs/results/investigations.md`` from such files
between its ``sampling_reference.py`` markers (the model references at k =
PAS's pairs and the largest k).

Run: python benchmarks/studies/sampling_reference.py [N] [--k 50,100,160] [--cases 3a,3b,4a,4b]
[--subsamples 40] [--pas-runs pas-output/spread/runs.csv] [--skip-random-events] [--csv FILE]
     python benchmarks/studies/sampling_reference.py --write --from-csv A.csv,B.csv
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pas.validation import generate_case

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/: the harness
from harness.error_tables import add_write_options, saved_results, write_tables  # noqa: E402
from harness.references import (  # noqa: E402
    COPULAS,
    copula_association,
    known_law_errors,
    known_law_lf_errors,
    reference_errors,
    targets_met,
    top_association,
)
from harness.result_tables import short_pct  # noqa: E402

PAGE, TAG = Path("docs/results/investigations.md"), "sampling_reference.py"


def pas_on_random_events(data, k: int, draws: int, seed: int):
    """Relative MPM errors of PAS's default estimator on ``draws`` random sets of k pool events."""
    from pas.strategies.band import ModelBand
    from pas.strategies.base import Pairs
    from pas.strategies.pas import PAS
    from pas.strategies.screening import LFSet

    s = LFSet(data.lf, n_waves=data.n_waves, p_exp=data.p_exp, threshold=data.threshold)
    hs = np.asarray(data.hf, float)[s.index]
    rng = np.random.default_rng([seed, k, 7])
    errors = []
    for _ in range(draws):
        pick = np.sort(rng.choice(s.n, size=min(k, s.n), replace=False))
        tp, fp = pick[hs[pick] > 0], pick[hs[pick] == 0]
        if tp.size < PAS.min_pairs:
            continue
        strategy = PAS(band=ModelBand(n_bootstrap=0))
        strategy.reset(seed)
        pairs = Pairs(tp, s.lf[tp], hs[tp], s.d[tp], s.lf[fp], fp)
        try:
            mpm = strategy.predict(pairs, s, np.random.default_rng(0)).mpm
        except ValueError:
            continue
        errors.append(mpm / data.truth_mpm - 1.0)
    return np.asarray(errors)


def _stats(errors) -> dict:
    a = np.abs(errors)
    return {"median": float(np.median(a)), "p90": float(np.quantile(a, 0.9)),
            "p_all10": float(np.mean(a <= 0.25) ** 10)}


def _row(errors):
    r = _stats(errors)
    return f"{100 * r['median']:5.1f} % {100 * r['p90']:6.1f} % {r['p_all10']:6.2f}"


def _joined(values, fmt) -> str:
    return " / ".join(format(v, fmt) for v in values)


def _pas_cell(rows: pd.DataFrame, pairs: bool = False) -> str:
    pas = rows[rows.reference == "pas"]
    if pas.empty:
        return "–"
    r = pas.iloc[0]
    cell = f"{short_pct(r['median'])} / {short_pct(r['worst'])} %"
    return cell + (f" ({r['k']} pairs)" if pairs else "")


def tables(rows: pd.DataFrame) -> dict[str, str]:
    """The page's three tables from the ``--csv`` rows of one or more runs (a row that two
    runs share is taken from the first)."""
    rows = rows.drop_duplicates(["case", "k", "reference"])
    impacts = [("| case | k | truth's estimator: median / p90 \\|error\\| | P(10 ≤ 25 %) | "
                "empirical quantile: median / p90 | PAS (validation): median / worst \\|M2\\| |"),
               "|---" * 6 + "|"]
    pool = [("| case | PAS's estimator, random pool events: median / p90 \\|error\\| | "
             "P(10 ≤ 25 %) | PAS (MD): median / worst \\|M2\\| |"), "|---" * 4 + "|"]
    models = [("| case | τ | k | known law: median · P(targets) | + LF, Gaussian: median · P | "
               "+ LF, Gumbel: median · P | PAS: median / worst \\|M2\\| |"), "|---" * 7 + "|"]
    for case, of_case in rows.groupby("case", sort=False):
        by = {name: g.sort_values("k") for name, g in of_case.groupby("reference")}
        if "truth-estimator" in by:
            t, e = by["truth-estimator"], by["empirical"]
            impacts.append(
                f"| {case} | {_joined(t.k, 'd')} | {_joined(100 * t['median'], '.0f')} % · "
                f"{_joined(100 * t.p90, '.0f')} % | {_joined(t.p_all10, '.2f')} | "
                f"{_joined(100 * e['median'], '.0f')} % · {_joined(100 * e.p90, '.0f')} % | "
                f"{_pas_cell(of_case, pairs=True)} |")
        if "pas-random-events" in by:
            r = by["pas-random-events"].iloc[0]
            pool.append(f"| {case} | {100 * r['median']:.1f} / {100 * r['p90']:.1f} % | "
                        f"{r['p_all10']:.2f} | {_pas_cell(of_case)} |")
        if "known law" in by:
            pas_k = by["pas"].k.tolist() if "pas" in by else []
            keep = sorted(set(pas_k) | {by["known law"].k.max()})
            cells = ["; ".join(f"{100 * r['median']:.1f} % · {r['p_targets']:.2f}"
                               for _, r in by[name][by[name].k.isin(keep)].iterrows())
                     for name in ("known law", *COPULAS)]
            models.append(f"| {case} | {of_case.tau.median():.2f} | {_joined(keep, 'd')} | "
                          + " | ".join(cells) + f" | {_pas_cell(of_case)} |")
    return {"random-impacts": "\n".join(impacts), "random-pool-events": "\n".join(pool),
            "model-references": "\n".join(models)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="?", type=int, default=10, help="data seeds 0…N−1")
    ap.add_argument("--k", default="50,100,160")
    ap.add_argument("--cases", default="3a,3b,4a,4b")
    ap.add_argument("--subsamples", type=int, default=40)
    ap.add_argument("--skip-random-events", action="store_true",
                    help="with --pas-runs: take PAS's pair counts, skip PAS on random events")
    ap.add_argument("--pas-runs", default=None,
                    help="runs.csv of validation_spread.py: adds k = PAS's median pairs")
    add_write_options(ap, PAGE)
    args = ap.parse_args(argv)
    if args.write:
        saved = saved_results(ap, args)
        return write_tables(args.write, tables(saved), TAG)
    cases = args.cases.split(",")
    saved = []

    def save(case, k, reference, errors=None, **values):
        taus = [d.tau for d in data_sets[case]]
        saved.append({"case": case, "k": k, "reference": reference,
                      "tau": float(np.median(taus)),
                      **(_stats(errors) if errors is not None else {}), **values})
        if args.csv:
            pd.DataFrame(saved).to_csv(args.csv, index=False)

    ks = {c: [int(x) for x in args.k.split(",")] for c in cases}
    data_sets = {c: [generate_case(c, seed=s) for s in range(args.n)] for c in cases}
    if args.pas_runs:
        runs = pd.read_csv(args.pas_runs)
        runs = runs[runs.strategy == "pas"]
        for c in cases:
            g = runs[runs.case == c]
            if len(g):
                pairs = int(np.median(g.n_hf - g.n_false_positive))
                ks[c] = sorted(set(ks[c]) | {pairs})
                save(c, pairs, "pas", median=float(g.M2.abs().median()),
                     worst=float(g.M2.abs().max()))
    print("| case | k impacts | truth-estimator: median / p90 \\|error\\| / P(worst of 10 ≤ 25 %) "
          "| empirical quantile: same |")
    print("|---|---|---|---|")
    for c in cases:
        data = data_sets[c]
        for k in ks[c]:
            errs = [reference_errors(d, k, args.subsamples, s) for s, d in enumerate(data)]
            t = np.concatenate([e[0] for e in errs])
            e = np.concatenate([e[1] for e in errs])
            print(f"| {c} | {k} | {_row(t)} | {_row(e)} |", flush=True)
            save(c, k, "truth-estimator", t)
            save(c, k, "empirical", e)
    print("\n| case | k impacts | known law (family and location told, ML): median / p90 "
          "\\|error\\| / P(worst of 10 ≤ 25 %) / P(median ≤ 10 % and worst ≤ 25 %) "
          + "".join(f"| known law + LF, {c} copula at the data's τ: same " for c in COPULAS) + "|")
    print("|---|---|" + "---|" * (1 + len(COPULAS)))
    for c in cases:
        for k in ks[c]:
            plain = [known_law_errors(d, k, 5 * args.subsamples, s)
                     for s, d in enumerate(data_sets[c])]
            cells = [f"{_row(np.concatenate(plain))} {targets_met(plain):6.2f}"]
            save(c, k, "known law", np.concatenate(plain), p_targets=targets_met(plain))
            for copula in COPULAS:
                with_lf = [known_law_lf_errors(d, k, 5 * args.subsamples, s, copula)
                           for s, d in enumerate(data_sets[c])]
                cells.append(f"{_row(np.concatenate(with_lf))} {targets_met(with_lf):6.2f}")
                save(c, k, copula, np.concatenate(with_lf), p_targets=targets_met(with_lf))
            print(f"| {c} | {k} | " + " | ".join(cells) + " |", flush=True)
    print("\n| case | P(HF in its top 30 % \\| LF in its top 10 %), impacts over the threshold: "
          "data (median of the data sets) | " + " | ".join(f"{c} at the data's τ" for c in COPULAS)
          + " |")
    print("|---|---|" + "---|" * len(COPULAS))
    for c in cases:
        assoc, taus = [], []
        for d in data_sets[c]:
            keep = np.asarray(d.hf) > 0
            if d.threshold is not None:
                keep &= np.asarray(d.lf) > d.threshold
            assoc.append(top_association(np.asarray(d.lf)[keep], np.asarray(d.hf)[keep]))
            taus.append(d.tau)
        cells = [f"{copula_association(k, float(np.median(taus))):.2f}" for k in COPULAS]
        print(f"| {c} | {np.median(assoc):.2f} | " + " | ".join(cells) + " |", flush=True)
    if not args.pas_runs or args.skip_random_events:
        return
    print("\n| case | PAS on random pool events (k = PAS's HF count per data set): median / p90 "
          "\\|error\\| / P(worst of 10 ≤ 25 %) | PAS (MD): median / worst \\|M2\\| |")
    print("|---|---|---|")
    for c in cases:
        g = runs[runs.case == c].set_index("seed")
        if not len(g):
            continue
        errs = np.concatenate([pas_on_random_events(d, int(g.n_hf[s]), 5, s)
                               for s, d in enumerate(data_sets[c]) if s in g.index])
        pas_m2 = g.M2.abs()
        save(c, int(np.median(g.n_hf)), "pas-random-events", errs)
        print(
            f"| {c} | {_row(errs)} | {100 * pas_m2.median():.1f} % / {100 * pas_m2.max():.1f} % |",
            flush=True,
        )


if __name__ == "__main__":
    main()
