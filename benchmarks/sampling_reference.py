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
``benchmarks/validation_spread.py``; compare at its number of true-positive
pairs (``--pas-runs`` reads them from that script's runs.csv).

Run: python benchmarks/sampling_reference.py [N] [--k 50,100,160] [--cases 3a,3b,4a,4b]
[--subsamples 40] [--pas-runs pas-output/spread/runs.csv] [--skip-random-events]
"""

from __future__ import annotations

import argparse

import numpy as np
from scipy import stats

from pas.stats.weibull import fit_weibull3_ls
from pas.validation import generate_case


def reference_errors(data, k: int, subsamples: int, seed: int):
    """Relative MPM errors of both reference estimators on ``subsamples`` draws of k impacts."""
    hf = np.asarray(data.hf, float)
    impacts = hf[hf > 0]
    q = data.p_exp / (impacts.size / data.n_waves)  # exceedance probability among impacts
    rng = np.random.default_rng([seed, k])
    truth_est, empirical = [], []
    for _ in range(subsamples):
        s = rng.choice(impacts, size=min(k, impacts.size), replace=False)
        truth_est.append(fit_weibull3_ls(s, top_fraction=0.3).isf(q) / data.truth_mpm - 1.0)
        empirical.append(np.quantile(s, 1.0 - q) / data.truth_mpm - 1.0)
    return np.asarray(truth_est), np.asarray(empirical)


def truth_law(data):
    """The data set's truth Weibull ``(θ, α, β)``, its number of impacts and ``P_exp / rate``."""
    w = data.info["weibull"]
    n = int(np.sum(np.asarray(data.hf) > 0))
    return w["theta"], w["alpha"], w["beta"], n, data.p_exp / (n / data.n_waves)


def known_law_errors(data, k: int, subsamples: int, seed: int):
    """Relative MPM errors of the maximum-likelihood estimator told the truth's family and location.

    ``k`` loads are drawn i.i.d. from the data set's truth Weibull (θ, α, β); the
    scale and shape are fitted by ML with θ known (scipy's ``weibull_min.fit``,
    ``floc=0`` on the loads less θ), and the MPM is read at ``P_exp / rate``.
    """
    theta, alpha, beta, _, q = truth_law(data)
    rng = np.random.default_rng([seed, k, 11])
    excess = alpha * rng.weibull(beta, size=(subsamples, k))
    errors = []
    for x in excess:
        shape, _, scale = stats.weibull_min.fit(x, floc=0.0)
        errors.append((theta + scale * (-np.log(q)) ** (1.0 / shape)) / data.truth_mpm - 1.0)
    return np.asarray(errors)


COPULAS = ("gaussian", "gumbel")
"""Copulas of the known-law + LF reference, each at the data set's Kendall τ."""


def copula_at_tau(copula: str, tau: float):
    """The pyvinecopulib copula of family ``copula`` with Kendall's τ, and its parameter."""
    import pyvinecopulib as pv

    cop = pv.Bicop(family=getattr(pv.BicopFamily, copula))
    par = float(np.ravel(cop.tau_to_parameters(tau))[0])
    cop.parameters = np.array([[par]])
    return cop, par


def known_law_lf_errors(data, k: int, subsamples: int, seed: int, copula: str = "gaussian"):
    """Relative MPM errors of the conditional ML estimator told the law and the copula.

    The HF law is the truth's Weibull, joined to the LF by ``copula`` at the data
    set's Kendall τ (Gaussian ρ = sin(πτ/2), Gumbel θ = 1/(1 − τ)); a pool of as many
    events as the data set has impacts, k distinct ones drawn at random uniformly in
    ln d over the LF ranks (MD spreads them deterministically); the scale and shape
    fitted by the likelihood of HF given LF with θ_W, the copula and the impact rate
    known, started from the fit that ignores the LF.
    """
    from scipy import optimize

    theta, alpha, beta, n, q = truth_law(data)
    cop, par = copula_at_tau(copula, data.tau)
    rng = np.random.default_rng([seed, k, 13, COPULAS.index(copula)])
    nll = lf_reference_nll(copula, par)
    errors = []
    for _ in range(subsamples):
        u_l, y, pick = lf_reference_pool(cop, n, alpha, beta, k, rng)
        shape, _, scale = stats.weibull_min.fit(y[pick], floc=0.0)
        x = optimize.minimize(nll, np.log([scale, shape]), args=(u_l[pick], y[pick]),
                              method="Nelder-Mead", options={"xatol": 1e-8, "fatol": 1e-10}).x
        a, b = np.exp(x)
        errors.append((theta + a * (-np.log(q)) ** (1.0 / b)) / data.truth_mpm - 1.0)
    return np.asarray(errors)


def lf_reference_nll(copula: str, par: float):
    """``nll(ln (α, β), u_l, y)``: the likelihood of loads ``y = h − θ_W`` given LF ranks
    ``u_l`` under a Weibull (α, β) joined by ``copula`` with parameter ``par``."""
    from pas.models.copula_densities import copula_logpdf

    def nll(x, u_l, y):
        a, b = np.exp(x)
        log_s = -(y / a) ** b
        log_f = np.log(b / a) + (b - 1.0) * np.log(y / a) + log_s
        v = np.clip(-np.expm1(log_s), 1e-300, 1.0 - 1e-15)
        return -np.sum(log_f + copula_logpdf(copula, (par,), u_l, v))

    return nll


def lf_reference_pool(cop, n: int, alpha: float, beta: float, k: int, rng, oversample: int = 20):
    """A pool of ``n`` events from ``cop`` with Weibull (α, β) loads above θ_W, and ``k``
    distinct ones drawn uniformly in ln d over the LF ranks, in draw order.

    Returns ``(u_l, y, pick)``: the LF ranks, the loads less θ_W, the picked indices.
    """
    uv = cop.sample(n, seeds=[int(x) for x in rng.integers(0, 2**31 - 1, 4)])
    u_l, v = uv[:, 0], uv[:, 1]
    y = alpha * (-np.log1p(-v)) ** (1.0 / beta)
    ranks = np.argsort(-u_l)
    d = np.exp(rng.uniform(np.log(1.0 / n), 0.0, oversample * k))  # uniform in ln d, d = rank/n
    idx = np.clip(np.ceil(d * n).astype(int) - 1, 0, n - 1)
    first = np.sort(np.unique(idx, return_index=True)[1])[:k]  # distinct, in draw order
    if first.size < k:
        raise RuntimeError(f"only {first.size} distinct events of {k} drawn")
    return u_l, y, ranks[idx[first]]


def top_association(lf, hf) -> float:
    """P(HF among its top 30 % | LF among its top 10 %): how well the top LF points at the top HF."""
    lf, hf = np.asarray(lf, float), np.asarray(hf, float)
    top_lf = lf >= np.quantile(lf, 0.9)
    return float(np.mean(hf[top_lf] >= np.quantile(hf, 0.7)))


def copula_association(copula: str, tau: float, n: int = 200_000) -> float:
    """:func:`top_association` of ``copula`` at Kendall τ (``n`` simulated pairs)."""
    uv = copula_at_tau(copula, tau)[0].sample(n, seeds=[1, 2, 3])
    return top_association(uv[:, 0], uv[:, 1])


def targets_met(errors_by_data_set, draws: int = 4000, seed: int = 0) -> float:
    """P(median |error| ≤ 10 % and worst ≤ 25 % over one run on each data set)."""
    rng = np.random.default_rng(seed)
    e = np.abs(np.stack([rng.choice(x, draws) for x in errors_by_data_set]))
    return float(np.mean((np.median(e, axis=0) <= 0.10) & (e.max(axis=0) <= 0.25)))


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


def _row(errors):
    a = np.abs(errors)
    return (f"{100 * np.median(a):5.1f} % {100 * np.quantile(a, 0.9):6.1f} % "
            f"{np.mean(a <= 0.25) ** 10:6.2f}")


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
    args = ap.parse_args(argv)
    cases = args.cases.split(",")
    ks = {c: [int(x) for x in args.k.split(",")] for c in cases}
    if args.pas_runs:
        import pandas as pd

        runs = pd.read_csv(args.pas_runs)
        runs = runs[runs.strategy == "pas"]
        for c in cases:
            g = runs[runs.case == c]
            if len(g):
                ks[c] = sorted(set(ks[c]) | {int(np.median(g.n_hf - g.n_false_positive))})
    print("| case | k impacts | truth-estimator: median / p90 \\|error\\| / P(worst of 10 ≤ 25 %) "
          "| empirical quantile: same |")
    print("|---|---|---|---|")
    data_sets = {c: [generate_case(c, seed=s) for s in range(args.n)] for c in cases}
    for c in cases:
        data = data_sets[c]
        for k in ks[c]:
            errs = [reference_errors(d, k, args.subsamples, s) for s, d in enumerate(data)]
            t = np.concatenate([e[0] for e in errs])
            e = np.concatenate([e[1] for e in errs])
            print(f"| {c} | {k} | {_row(t)} | {_row(e)} |", flush=True)
    print("\n| case | k impacts | known law (family and location told, ML): median / p90 "
          "\\|error\\| / P(worst of 10 ≤ 25 %) / P(median ≤ 10 % and worst ≤ 25 %) "
          + "".join(f"| known law + LF, {c} copula at the data's τ: same " for c in COPULAS) + "|")
    print("|---|---|" + "---|" * (1 + len(COPULAS)))
    for c in cases:
        for k in ks[c]:
            plain = [known_law_errors(d, k, 5 * args.subsamples, s)
                     for s, d in enumerate(data_sets[c])]
            cells = [f"{_row(np.concatenate(plain))} {targets_met(plain):6.2f}"]
            for copula in COPULAS:
                with_lf = [known_law_lf_errors(d, k, 5 * args.subsamples, s, copula)
                           for s, d in enumerate(data_sets[c])]
                cells.append(f"{_row(np.concatenate(with_lf))} {targets_met(with_lf):6.2f}")
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
        print(f"| {c} | {_row(errs)} | {100 * pas_m2.median():.1f} % / {100 * pas_m2.max():.1f} % |",
              flush=True)


if __name__ == "__main__":
    main()
