"""Reference estimators for "what k impact loads can tell" on the impact analogues.

An oracle that knows which events are impacts and applies the truth's own
estimator (:func:`reference_errors`), and two model references told the
truth's law (:func:`known_law_errors`) and also the LF through a copula at the
data's Kendall τ (:func:`known_law_lf_errors`).  They are models, not bounds
(``docs/results/investigations.md``, "What k impact loads can tell").  Used by
``benchmarks/studies/sampling_reference.py`` and
``benchmarks/investigations/stop_movement.py``.
"""

from __future__ import annotations

import numpy as np
import pyvinecopulib as pv
from scipy import optimize, stats

from pas.models.copula_densities import copula_logpdf
from pas.stats.weibull import fit_weibull3_ls


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
    """P(HF among its top 30 % | LF among its top 10 %): how well the top LF points at the top
    HF."""
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
