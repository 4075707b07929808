"""How many seeds are enough: convergence of the MPM with the number of seeds.

Following van Essen, Scharnke & Seyffert (2023): from a record of M seeds,
draw for each N = 1 … M ``W`` random subsets of N seeds without replacement
(W = 500 in the paper), estimate the MPM of every subset and compare with the
MPM of all M seeds (the reference). The root-mean-square difference

``R(N) = sqrt(mean_w (MPM_w(N) − MPM_ref)²)``

measures the sampling error of an N-seed campaign; the number of seeds needed
is the smallest N from which ``R`` stays within a tolerance (e.g. 3 % of Hs
for crests, or an absolute load tolerance). ``bias(N) = mean_w (MPM_w − ref)``
shows systematic errors, notably of fitted MPMs.

The reference is always the pooled-peaks MPM of all seeds, for every variant,
so ``bias`` of the fitted variant is the fit's own bias.

Subsets drawn without replacement from the record share seeds with the
reference, so their spread around it is smaller than that of a fresh N-seed
campaign around the truth: by the finite-population factor ``(1 − N/M)`` in
variance (at M = 40, N = 30 the raw RMS is half the fresh one). :class:`MPMConvergence`
therefore reports

``R(N) = sqrt(var_w(MPM_w) / (1 − N/M) + bias(N)²)``

for N < M (NaN at N = M, which the record cannot judge) and keeps the raw RMS
as ``rms_subsets``. Its band is a bootstrap over seeds: R(N) recomputed on
``n_boot`` records drawn from the M seeds with replacement (percentile band).
A normal-theory band (chi-square, M − 1 degrees of freedom) would be too
narrow: R(N) varies between records far more than that, because near N = M
the subsets differ by a few seeds only ("Record statistics" in
``docs/results/investigations.md``).

Each seed is one exposure duration unless ``exposure_encounters`` says
otherwise; the target exceedance ``P_t = 1/n_e,t`` is the same for every
subset, the exceedance probabilities ``k/n_e`` use each subset's own
encounter count.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from ..stats.weibull import fit_weibull3_ls
from .positions import read_at_exceedance
from .records import (
    MPM_QUANTILE,
    _exposure,
    _total_encounters,
    seed_maxima,
    seed_peaks,
    top_peaks,
    weibull_mpm,
)

__all__ = ["random_subsets", "rms_difference", "fresh_campaign_rms", "seeds_needed",
           "MPMConvergence", "mpm_convergence"]


def random_subsets(n_seeds, n_subset, n_draws, rng):
    """``n_draws`` random subsets of ``n_subset`` of ``n_seeds`` seeds, without replacement.

    Vectorised: the first ``n_subset`` columns of ``n_draws`` independent
    random permutations (argsort of uniform keys).

    Returns
    -------
    ndarray of int, shape (n_draws, n_subset)
    """
    if not 1 <= n_subset <= n_seeds:
        raise ValueError(f"subset size must be in 1..{n_seeds}, got {n_subset}")
    keys = rng.random((n_draws, n_seeds))
    return np.argsort(keys, axis=1)[:, :n_subset]


def rms_difference(estimates, reference):
    """RMS difference and bias of estimates from a reference along the last axis.

    NaN estimates are ignored; all-NaN rows give NaN.

    Returns
    -------
    rms, bias : ndarray or float
    """
    e = np.asarray(estimates, dtype=float) - reference
    with warnings.catch_warnings():  # nanmean of an all-NaN row (N = 1 seed maxima)
        warnings.simplefilter("ignore", RuntimeWarning)
        rms = np.sqrt(np.nanmean(e**2, axis=-1))
        bias = np.nanmean(e, axis=-1)
    return rms, bias


def fresh_campaign_rms(estimates, reference, n, m):
    """R(N) of a fresh N-seed campaign from subsets of an M-seed record.

    ``R² = var / (1 − N/M) + bias²`` with ``var`` and ``bias`` of the subset
    estimates about ``reference`` along the last axis (module docs). NaN for
    ``N = M``.

    Examples
    --------
    >>> import numpy as np
    >>> e = np.random.default_rng(0).normal(0.0, 1.0, (1, 20000))
    >>> round(float(fresh_campaign_rms(e, 0.0, [30], 40)[0]), 1)   # 1 / sqrt(1 - 30/40)
    2.0
    """
    e = np.asarray(estimates, dtype=float) - reference
    n = np.asarray(n, dtype=float)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        bias = np.nanmean(e, axis=-1)
        var = np.nanvar(e, axis=-1)
        fpc = np.where(n < m, 1.0 - n / m, np.nan)
        return np.sqrt(var / fpc + bias**2)


def seeds_needed(n, rms, tolerance):
    """Smallest N from which ``rms`` stays at or below ``tolerance`` for all larger N.

    Parameters
    ----------
    n : array_like of int
        Numbers of seeds, ascending.
    rms : array_like
        R(N) for each N. NaN entries inside count as not satisfying; trailing
        NaN (N = M, which a record of M seeds cannot judge) are ignored.
    tolerance : float
        Criterion in the unit of the variable (e.g. ``0.03 * Hs``).

    Returns
    -------
    int or None
        None if even the largest judged N fails.

    Examples
    --------
    >>> seeds_needed([1, 2, 3, 4], [0.5, 0.2, 0.3, 0.1], 0.25)
    4
    >>> seeds_needed([1, 2, 3, 4], [0.5, 0.2, 0.1, float("nan")], 0.25)
    2
    """
    n = np.asarray(n)
    r = np.asarray(rms, dtype=float)
    judged = np.flatnonzero(np.isfinite(r))
    if judged.size == 0:
        return None
    n, r = n[: judged[-1] + 1], r[: judged[-1] + 1]
    ok = r <= tolerance
    if not ok[-1]:
        return None
    bad = np.flatnonzero(~ok)
    return int(n[0] if bad.size == 0 else n[bad[-1] + 1])


@dataclass(frozen=True)
class MPMConvergence:
    """R(N) and bias(N) of the subset MPMs; build with :func:`mpm_convergence`.

    Attributes
    ----------
    n : ndarray of int
        Subset sizes N.
    n_seeds : int
        Seeds M in the record.
    reference : float
        Pooled-peaks MPM of all seeds.
    rms : dict of str -> ndarray
        Per variant (``"pooled"``, ``"seed maxima"``, ``"fit"``), R(N) of a
        fresh N-seed campaign (finite-population corrected; NaN at N = M).
    rms_low, rms_high : dict of str -> ndarray
        Its bootstrap-over-seeds band (NaN for "fit" and without ``n_boot``).
    rms_subsets : dict of str -> ndarray
        Raw RMS of the subsets about the reference (0 at N = M for "pooled").
    bias : dict of str -> ndarray
        Mean subset MPM minus the reference.
    n_subsets : dict of str -> int
        Subsets drawn per N for each variant.
    """

    n: np.ndarray
    n_seeds: int
    reference: float
    rms: dict
    rms_low: dict
    rms_high: dict
    rms_subsets: dict
    bias: dict
    n_subsets: dict

    def seeds_needed(self, tolerance, variant="pooled", *, conservative=False):
        """Seeds needed for ``R(N) ≤ tolerance`` (see :func:`seeds_needed`).

        ``conservative=True`` uses the upper end of the band instead of R(N).
        """
        r = self.rms_high[variant] if conservative else self.rms[variant]
        return seeds_needed(self.n, r, tolerance)


def _subset_estimates(top, maxima, enc, n_values, n_subsets, rng, *, p_t, q, positions,
                      empty, k_max):
    """Pooled-peaks and seed-maxima MPMs of ``n_subsets`` random subsets per N."""
    m = top.shape[0]
    est = {"pooled": np.full((n_values.size, n_subsets), np.nan),
           "seed maxima": np.full((n_values.size, n_subsets), np.nan)}
    subsets = []
    for i, n in enumerate(n_values):  # loop over subset sizes only
        idx = random_subsets(m, n, n_subsets, rng)
        n_e = enc[idx].sum(axis=1)
        k_need = min(int(np.ceil(p_t * n_e.max() + 1.0)) + 2, n * k_max)
        pooled = -np.sort(-top[idx].reshape(n_subsets, -1), axis=1)[:, :k_need]  # NaN last
        est["pooled"][i] = read_at_exceedance(pooled, n_e, p_t, positions=positions,
                                              below=empty)
        est["seed maxima"][i] = read_at_exceedance(
            -np.sort(-maxima[idx], axis=1), n, 1.0 - q, positions="weibull", scale="linear")
        subsets.append(idx)
    return est, subsets


def _reference(top, n_total, p_t, positions, empty):
    return float(read_at_exceedance(-np.sort(-top.ravel()), n_total, p_t, positions=positions,
                                    below=empty))


def mpm_convergence(peaks, n_encounters, *, exposure_encounters=None, n_values=None,
                    n_subsets=500, n_subsets_fit=100, top_fraction=0.3, q=MPM_QUANTILE,
                    empty=0.0, positions="gringorten", n_boot=100, n_subsets_boot=100,
                    confidence=0.95, seed=0):
    """R(N) of pooled-peaks, seed-maxima and Weibull-fit MPMs over random N-seed subsets.

    Parameters
    ----------
    peaks : sequence of array_like
        Peaks per seed (M seeds).
    n_encounters : int or sequence of int
        Encounters in the record (split evenly over seeds) or one count per seed.
    exposure_encounters : float, optional
        Encounters per exposure duration ``n_e,t``; default the mean per seed.
    n_values : sequence of int, optional
        Subset sizes N; default ``1 … M``.
    n_subsets : int, default 500
        Subsets W per N for the pooled-peaks and seed-maxima MPMs.
    n_subsets_fit : int, default 100
        Subsets per N for the Weibull-fit MPM (one least-squares fit each, the
        costly part); 0 skips the fitted variant.
    top_fraction : float, default 0.3
        Fraction of the peaks in each Weibull fit.
    q : float, default 0.368
        Quantile of the seed maxima used as their MPM (read with ``k/(N+1)``).
    empty : float, default 0.0
        Seed maximum of a seed without peaks.
    positions : {"gringorten", "weibull", "k/n"}, default "gringorten"
        Plotting positions of the pooled peaks.
    n_boot : int, default 100
        Records resampled from the seeds (with replacement) for the R(N) band
        of the pooled-peaks and seed-maxima variants; 0 skips the band (NaN).
    n_subsets_boot : int, default 100
        Subsets per N inside each resampled record.
    confidence : float, default 0.95
        Of the R(N) band.
    seed : int, default 0
        Seed of the subset draws.

    Returns
    -------
    MPMConvergence
    """
    seeds = seed_peaks(peaks)
    m = len(seeds)
    n_arr = np.asarray(n_encounters, dtype=float)
    n_total = _total_encounters(n_encounters, m)
    enc = np.full(m, n_total / m) if n_arr.ndim == 0 else n_arr
    n_t = _exposure(exposure_encounters, n_total, m)
    p_t = 1.0 / n_t
    if n_values is None:
        n_values = np.arange(1, m + 1)
    n_values = np.asarray(n_values, dtype=int)
    if n_values.ndim != 1 or n_values.size == 0 or n_values.min() < 1 or n_values.max() > m:
        raise ValueError(f"n_values must be subset sizes in 1..{m}")
    if n_subsets < 2 or n_subsets_fit < 0:
        raise ValueError("n_subsets must be >= 2 and n_subsets_fit >= 0")
    rng = np.random.default_rng(seed)

    # A subset's MPM needs its top ~P_t n_e + 2 pooled peaks; no seed can
    # contribute more than that many, so keep that many per seed.
    k_max = int(np.ceil(p_t * n_total + 1.0)) + 2
    top = top_peaks(seeds, k_max)
    reference = _reference(top, n_total, p_t, positions, empty)
    if np.isnan(reference):
        raise ValueError("the MPM target lies beyond the largest peak of the whole record; "
                         "R(N) needs a record longer than the exposure duration")
    maxima = seed_maxima(seeds, empty=empty)
    opts = {"p_t": p_t, "q": q, "positions": positions, "empty": empty, "k_max": k_max}

    est, subsets = _subset_estimates(top, maxima, enc, n_values, n_subsets, rng, **opts)
    fits = np.full((n_values.size, n_subsets_fit), np.nan)
    for i, (n, idx) in enumerate(zip(n_values, subsets)):
        for w in range(n_subsets_fit):  # one least-squares fit per subset
            sub = idx[w] if w < n_subsets else random_subsets(m, n, 1, rng)[0]
            vals = np.concatenate([seeds[j] for j in sub])
            if vals.size < 3 or np.ptp(vals) == 0:
                continue
            fit = fit_weibull3_ls(vals, top_fraction=top_fraction)
            fits[i, w] = weibull_mpm(fit, vals.size, enc[sub].sum(), p_t)
    if n_subsets_fit:
        est["fit"] = fits

    rms, raw, bias = {}, {}, {}
    for name, e in est.items():
        raw[name], bias[name] = rms_difference(e, reference)
        rms[name] = fresh_campaign_rms(e, reference, n_values, m)
    boot = {name: np.full((max(n_boot, 1), n_values.size), np.nan) for name in est}  # fit: NaN
    for b in range(n_boot):  # loop over resampled records
        r = rng.integers(0, m, m)
        ref_b = _reference(top[r], enc[r].sum(), p_t, positions, empty)
        est_b, _ = _subset_estimates(top[r], maxima[r], enc[r], n_values, n_subsets_boot, rng,
                                     **opts)
        for name, e in est_b.items():
            boot[name][b] = fresh_campaign_rms(e, ref_b, n_values, m)
    a = (1.0 - confidence) / 2.0
    with warnings.catch_warnings():  # all-NaN columns (N = M)
        warnings.simplefilter("ignore", RuntimeWarning)
        low = {name: np.nanquantile(v, a, axis=0) for name, v in boot.items()}
        high = {name: np.nanquantile(v, 1 - a, axis=0) for name, v in boot.items()}
    drawn = {name: e.shape[1] for name, e in est.items()}
    return MPMConvergence(n=n_values, n_seeds=m, reference=reference, rms=rms, rms_low=low,
                          rms_high=high, rms_subsets=raw, bias=bias, n_subsets=drawn)
