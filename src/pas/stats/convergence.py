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
so ``R`` of the fitted variant at ``N = M`` is the fit's own bias. Because the
subsets are drawn from the record itself, ``R(M) = 0`` for the pooled variant
by construction: R(N) is informative for ``N ≪ M`` and a record of M seeds can
only show that N < M seeds suffice, never that M does.

Each seed is one exposure duration unless ``exposure_encounters`` says
otherwise; the target exceedance ``P_t = 1/n_e,t`` is the same for every
subset, the exceedance probabilities ``k/n_e`` use each subset's own
encounter count.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .exceedance import exceedance_probabilities
from .records import (
    MPM_QUANTILE,
    _exposure,
    _read_pooled,
    _seed_maxima_quantile_rows,
    _total_encounters,
    _weibull_mpm,
    seed_maxima,
    seed_peaks,
)
from .weibull import fit_weibull3_ls

__all__ = ["random_subsets", "rms_difference", "seeds_needed", "MPMConvergence",
           "mpm_convergence"]


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


def seeds_needed(n, rms, tolerance):
    """Smallest N from which ``rms`` stays at or below ``tolerance`` for all larger N.

    Parameters
    ----------
    n : array_like of int
        Numbers of seeds, ascending.
    rms : array_like
        R(N) for each N (NaN entries count as not satisfying).
    tolerance : float
        Criterion in the unit of the variable (e.g. ``0.03 * Hs``).

    Returns
    -------
    int or None
        None if even the largest N fails.

    Examples
    --------
    >>> seeds_needed([1, 2, 3, 4], [0.5, 0.2, 0.3, 0.1], 0.25)
    4
    """
    n = np.asarray(n)
    ok = np.asarray(rms, dtype=float) <= tolerance
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
    reference : float
        Pooled-peaks MPM of all seeds.
    rms, bias : dict of str -> ndarray
        Per variant (``"pooled"``, ``"seed maxima"``, ``"fit"``), R(N) and bias(N).
    n_subsets : dict of str -> int
        Subsets drawn per N for each variant.
    """

    n: np.ndarray
    reference: float
    rms: dict
    bias: dict
    n_subsets: dict

    def seeds_needed(self, tolerance, variant="pooled"):
        """Seeds needed for ``R(N) ≤ tolerance`` (see :func:`seeds_needed`)."""
        return seeds_needed(self.n, self.rms[variant], tolerance)

    def plot(self, ax=None, *, criterion=None, units="m", variable="MPM"):
        """R(N) plot; see :func:`pas.plotting.records.plot_convergence`."""
        from ..plotting.records import plot_convergence

        return plot_convergence(self.n, self.rms, criterion=criterion, bias=self.bias,
                                units=units, variable=variable, ax=ax)


def _top_matrix(seeds, k):
    """(M, k) matrix of each seed's k largest peaks, descending, NaN-padded."""
    out = np.full((len(seeds), k), np.nan)
    for i, s in enumerate(seeds):  # loop over seeds (M ≤ a few hundred), not samples
        top = np.sort(s)[::-1][:k]
        out[i, :top.size] = top
    return out


def mpm_convergence(peaks, n_encounters, *, exposure_encounters=None, n_values=None,
                    n_subsets=500, n_subsets_fit=100, top_fraction=0.3, q=MPM_QUANTILE,
                    empty=0.0, seed=0):
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
        Subsets per N for the Weibull-fit MPM (one LS fit each, ~ms per
        thousand peaks); 0 skips the fitted variant.
    top_fraction : float, default 0.3
        Fraction of the peaks in each Weibull fit.
    q : float, default 0.368
        Quantile of the seed maxima used as their MPM.
    empty : float, default 0.0
        Seed maximum of a seed without peaks.
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
    if n_subsets < 1 or n_subsets_fit < 0:
        raise ValueError("n_subsets must be >= 1 and n_subsets_fit >= 0")
    rng = np.random.default_rng(seed)

    pooled_all = np.concatenate(seeds)
    d_all, v_all = exceedance_probabilities(pooled_all, n_total)
    reference = _read_pooled(d_all, v_all, p_t)

    # Each subset's MPM needs its top ceil(P_t n_e)+1 pooled peaks; no seed can
    # contribute more than that many, so keep that many per seed.
    k_max = int(np.ceil(p_t * n_total)) + 2
    top = _top_matrix(seeds, k_max)
    maxima = seed_maxima(seeds, empty=empty)

    rms, bias, drawn = {}, {}, {"pooled": n_subsets, "seed maxima": n_subsets}
    est_pooled = np.full((n_values.size, n_subsets), np.nan)
    est_max = np.full((n_values.size, n_subsets), np.nan)
    est_fit = np.full((n_values.size, n_subsets_fit), np.nan)
    for i, n in enumerate(n_values):  # loop over subset sizes only
        idx = random_subsets(m, n, n_subsets, rng)
        n_e = enc[idx].sum(axis=1)
        k_need = min(int(np.ceil(p_t * n_e.max())) + 2, n * k_max)
        pooled = -np.sort(-top[idx].reshape(n_subsets, -1), axis=1)[:, :k_need]  # NaN last
        for w in range(n_subsets):
            row = pooled[w][np.isfinite(pooled[w])]
            if row.size == 0:
                est_pooled[i, w] = empty
                continue
            d = np.arange(1, row.size + 1) / n_e[w]
            est_pooled[i, w] = _read_pooled(d, row, p_t, below=empty, warn=False)
        est_max[i] = _seed_maxima_quantile_rows(-np.sort(-maxima[idx], axis=1), q)
        for w in range(n_subsets_fit):
            sub = idx[w] if w < n_subsets else random_subsets(m, n, 1, rng)[0]
            vals = np.concatenate([seeds[j] for j in sub])
            if vals.size < 3 or np.ptp(vals) == 0:
                continue
            fit = fit_weibull3_ls(vals, top_fraction=top_fraction)
            est_fit[i, w] = _weibull_mpm(fit, vals.size, enc[sub].sum(), p_t)

    rms["pooled"], bias["pooled"] = rms_difference(est_pooled, reference)
    rms["seed maxima"], bias["seed maxima"] = rms_difference(est_max, reference)
    if n_subsets_fit:
        rms["fit"], bias["fit"] = rms_difference(est_fit, reference)
        drawn["fit"] = n_subsets_fit
    return MPMConvergence(n=n_values, reference=float(reference), rms=rms, bias=bias,
                          n_subsets=drawn)
