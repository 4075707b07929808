"""Extreme values of Monte-Carlo records: MPM from pooled peaks, seed maxima and fits.

A *record* is M seeds (basin runs or simulations) of a stationary sea state,
each given as the peaks of the variable in that seed (one crest per
zero-up-crossing wave, or one value per impact for loads that do not peak
every wave), together with the number of wave encounters ``n_e`` in the whole
record. Following van Essen, Scharnke & Seyffert (2023) and the PAS paper
(§2.1, Eq. 3 and 11–12) three estimates of the most probable maximum (MPM)
over an exposure duration are offered. Here, as in that literature, "MPM" is
the ``e⁻¹ ≈ 0.368`` quantile of the exposure maximum (≈ the level exceeded
once per exposure on average), not the mode of the maximum's density: the mode
lies 0.53 % higher for the maximum of 1000 Rayleigh crests
(``tests/records/test_records.py::test_mpm_is_the_e1_quantile_not_the_mode``).

* **Pooled peaks** — the peaks of all seeds sorted descending; the k-th
  largest has exceedance probability per encounter ``d = (k − 0.44)/(n_e + 0.12)``
  (Gringorten positions, :mod:`pas.records.positions`; the paper's Eq. 3
  ``k / n_e`` with ``positions="k/n"``). The MPM is the value at
  ``P_t = 1 / n_e,t`` with ``n_e,t`` the encounters per exposure duration,
  read by linear interpolation on ``ln d`` (Eq. 12). Any quantile ``q`` of
  the exposure maximum is read at ``P_q = 1 − q^{M_t/n_e}``
  (:func:`pas.stats.quantile_exceedance`; DNV-RP-C205 via the PAS paper §5),
  where ``M_t = n_e / n_e,t`` is the number of exposure durations in the
  record — in the worked example of van Essen et al. (2023) ``M_t = 35``
  one-hour seeds and ``n_e = 16 113`` encounters: ``P_0.368 = 2.169e-3``,
  ``P_0.9 = 2.288e-4`` (2.28834e-4). ``q = 0.368`` gives ``P_q ≈ 1/n_e,t``.
  A target beyond the largest peak is not read from the record: it raises
  (or is NaN in :func:`pas.records.analyse_record`) unless a named tail model
  is asked for (``extrapolate="weibull"`` or ``"gpd"``, :mod:`pas.records.tails`).
* **Seed maxima** — the maximum of each of the N seeds (each seed one
  exposure duration), sorted descending; the k-th largest gets exceedance
  ``k / (N + 1)`` (``positions="weibull"``, unbiased for the 0.632
  exceedance; the paper-style ``k/N`` biases it high at few seeds,
  "Record statistics" in ``docs/results/investigations.md``). The MPM is
  the q = 0.368 quantile of the maxima, the value at exceedance ``0.632``, by
  linear interpolation in probability. A seed without any peak (no impact)
  has maximum ``empty``.
* **Weibull fit** — a 3-parameter Weibull least-squares fit
  (:func:`pas.stats.fit_weibull3_ls`) to the top fraction of the pooled peaks
  (top 30 % for crests — the PAS validation truths use this — top 90 % for
  impact forces). The fit is the distribution of a *peak*; with ``n_p``
  peaks in ``n_e`` encounters the exceedance per encounter is
  ``(n_p/n_e) · P_W(X > x)``, so the MPM is ``isf(P_t · n_e / n_p)``. It is
  the one of the three that can also read beyond the record.

:func:`pas.records.analyse_record` puts the three together with bootstrap
confidence intervals (:func:`pas.records.bootstrap_mpm`).
"""

from __future__ import annotations

import warnings

import numpy as np

from .._support.checks import check_open_unit, check_peaks, check_positive
from ..stats.exceedance import quantile_exceedance
from ..stats.weibull import fit_weibull3_ls
from .positions import plotting_positions, read_at_exceedance
from .tails import fit_tail

__all__ = [
    "MPM_QUANTILE",
    "seed_peaks",
    "pooled_peaks_distribution",
    "seed_maxima",
    "seed_maxima_distribution",
    "mpm_pooled",
    "quantile_pooled",
    "mpm_seed_maxima",
    "mpm_weibull",
    "top_peaks",
]

#: Quantile of the exposure maximum that the MPM corresponds to (``e^{-1}``
#: rounded as in the literature; Ochi 1990, PAS paper §5).
MPM_QUANTILE = 0.368


# ----------------------------------------------------------------- inputs
def seed_peaks(peaks) -> list[np.ndarray]:
    """Normalise a record to a list of per-seed 1-D float arrays.

    Parameters
    ----------
    peaks : array_like or sequence of array_like
        A 1-D array (one seed) or a sequence of 1-D arrays (one per seed);
        a seed may be empty (no impact in that seed).

    Returns
    -------
    list of ndarray
    """
    if isinstance(peaks, np.ndarray) and peaks.dtype != object:
        if peaks.ndim == 1:
            return [check_peaks(peaks, "peaks")]
        if peaks.ndim == 2:
            return [check_peaks(row, f"peaks[{i}]") for i, row in enumerate(peaks)]
        raise ValueError(f"peaks must be 1-D or a sequence of 1-D arrays, got shape {peaks.shape}")
    try:
        seeds = list(peaks)
    except TypeError:
        raise ValueError("peaks must be an array or a sequence of per-seed arrays") from None
    if not seeds:
        raise ValueError("peaks holds no seeds")
    if np.ndim(seeds[0]) == 0:  # a flat list of numbers: one seed
        return [check_peaks(seeds, "peaks")]
    out = []
    for i, s in enumerate(seeds):
        a = np.asarray(s, dtype=float)
        if a.size == 0:
            out.append(np.empty(0))
        else:
            out.append(check_peaks(a, f"peaks[{i}]"))
    if all(a.size == 0 for a in out):
        raise ValueError("peaks: no seed holds any peak")
    return out


def _total_encounters(n_encounters, n_seeds):
    """Total encounters from a scalar (record total) or one count per seed."""
    n = np.asarray(n_encounters, dtype=float)
    if n.ndim == 0:
        total = check_positive(float(n), "n_encounters")
    else:
        if n.shape != (n_seeds,):
            raise ValueError(f"n_encounters must be a total or one count per seed ({n_seeds}), "
                             f"got shape {n.shape}")
        if np.any(~np.isfinite(n)) or np.any(n <= 0):
            raise ValueError("n_encounters per seed must be finite and > 0")
        total = float(n.sum())
    if total != round(total):
        raise ValueError(f"n_encounters must be whole numbers, got {n_encounters!r}")
    return int(round(total))


def _exposure(exposure_encounters, n_total, n_seeds):
    if exposure_encounters is None:
        return n_total / n_seeds  # each seed is one exposure duration
    return check_positive(exposure_encounters, "exposure_encounters")


def _record(peaks, n_encounters, exposure_encounters):
    """A checked record: its seeds, total encounters and encounters per exposure duration."""
    seeds = seed_peaks(peaks)
    n_total = _total_encounters(n_encounters, len(seeds))
    return seeds, n_total, _exposure(exposure_encounters, n_total, len(seeds))


# ----------------------------------------------------------- distributions
def pooled_peaks_distribution(peaks, n_encounters, *, positions="gringorten"):
    """Exceedance distribution of the pooled peaks of all seeds (Eq. 3).

    Parameters
    ----------
    peaks : array_like or sequence of array_like
        Peaks per seed (see :func:`seed_peaks`).
    n_encounters : int or sequence of int
        Wave encounters in the whole record, or one count per seed (summed).
        For impact loads this is larger than the number of peaks.
    positions : {"gringorten", "weibull", "k/n"}, default "gringorten"
        Plotting positions (:mod:`pas.records.positions`); ``"k/n"`` is the
        paper's Eq. 3.

    Returns
    -------
    d : ndarray
        Exceedance probability per encounter, e.g. ``k / n_e``, ascending.
    values : ndarray
        Pooled peaks sorted descending.

    Examples
    --------
    >>> d, v = pooled_peaks_distribution([[1.0, 3.0], [2.0]], n_encounters=[5, 5],
    ...                                  positions="k/n")
    >>> d.tolist(), v.tolist()
    ([0.1, 0.2, 0.3], [3.0, 2.0, 1.0])
    """
    seeds = seed_peaks(peaks)
    n_total = _total_encounters(n_encounters, len(seeds))
    pooled = np.sort(np.concatenate(seeds))[::-1]
    if pooled.size > n_total:
        # Happens with spectral estimates such as n_w = T / Tp (van Essen &
        # Seyffert 2026, Table 2), which undercount zero up-crossings; flagged.
        warnings.warn(f"{pooled.size} peaks in {n_total} encounters: the smallest peaks get "
                      "exceedance probabilities above 1; use counted encounters or check for "
                      "double peaks per wave", stacklevel=2)
    return plotting_positions(pooled.size, n_total, positions), pooled


def seed_maxima(peaks, *, empty=0.0):
    """Largest peak of each seed; ``empty`` for a seed without peaks (no impact)."""
    seeds = seed_peaks(peaks)
    return np.array([s.max() if s.size else float(empty) for s in seeds])


def seed_maxima_distribution(maxima, *, positions="weibull"):
    """Exceedance distribution of N seed maxima: k-th largest gets ``k / (N + 1)``.

    Returns
    -------
    p : ndarray, shape (N,)
        ``1/(N+1), …, N/(N+1)`` (ascending) for the default positions.
    values : ndarray, shape (N,)
        The maxima sorted descending.
    """
    m = check_peaks(maxima, "maxima")
    return plotting_positions(m.size, m.size, positions), np.sort(m)[::-1]


def top_peaks(seeds, k):
    """(M, k) matrix of each seed's k largest peaks, descending, NaN-padded."""
    out = np.full((len(seeds), k), np.nan)
    for i, s in enumerate(seeds):  # loop over seeds (M ≤ a few hundred), not samples
        top = np.sort(s)[::-1][:k]
        out[i, :top.size] = top
    return out


# --------------------------------------------------------------- read-outs
def _beyond(p, what):
    return ValueError(f"{what}: target exceedance {p:.3g} per encounter lies beyond the largest "
                      "peak of the record; use more seeds, or extrapolate with a named tail "
                      "model (extrapolate='gpd' or 'weibull')")


def read_pooled(seeds, n_total, p, *, positions="gringorten", below=0.0, extrapolate=None,
                top_fraction=None, what="pooled peaks"):
    """Value at exceedance ``p`` of checked seeds (see :func:`quantile_pooled`)."""
    pooled = np.sort(np.concatenate(seeds))[::-1]
    value = read_at_exceedance(pooled, n_total, p, positions=positions, below=below)
    if np.isnan(value):
        if extrapolate is None:
            raise _beyond(p, what)
        return float(fit_tail(pooled, n_total, extrapolate,
                              top_fraction=top_fraction).value_at_exceedance(p))
    return float(value)


def quantile_pooled(peaks, n_encounters, q=MPM_QUANTILE, *, exposure_encounters=None,
                    below=0.0, positions="gringorten", extrapolate=None, top_fraction=None):
    """q-quantile of the exposure maximum from the pooled peaks, at ``P_q = 1 − q^{M_t/n_e}``.

    Parameters
    ----------
    peaks, n_encounters
        See :func:`pooled_peaks_distribution`.
    q : float, default 0.368
        Quantile of the maximum over one exposure duration.
    exposure_encounters : float, optional
        Encounters per exposure duration ``n_e,t``; default the mean per seed
        (each seed one exposure duration). ``M_t = n_e / n_e,t``.
    below : float, default 0.0
        Returned when ``P_q`` exceeds the exceedance of the smallest peak
        (fewer peaks than needed: the quantile is "no event").
    positions : {"gringorten", "weibull", "k/n"}, default "gringorten"
    extrapolate : {None, "weibull", "gpd"}, default None
        Tail model for a target beyond the largest peak; None raises there.
    top_fraction : float, optional
        Fraction of the peaks the tail model fits (its default when None).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``P_q`` lies beyond the largest peak and ``extrapolate`` is None.
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    p = quantile_exceedance(q, n_total / n_t, n_total)
    return read_pooled(seeds, n_total, p, positions=positions, below=below,
                       extrapolate=extrapolate, top_fraction=top_fraction,
                       what=f"quantile q={q:g}")


def mpm_pooled(peaks, n_encounters, *, exposure_encounters=None, below=0.0,
               positions="gringorten", extrapolate=None, top_fraction=None):
    """MPM from the pooled peaks: the value at ``P_t = 1/n_e,t`` on ``ln d`` (Eq. 11–12).

    Parameters
    ----------
    peaks : array_like or sequence of array_like
        Peaks per seed.
    n_encounters : int or sequence of int
        Encounters in the whole record, or per seed.
    exposure_encounters : float, optional
        Encounters per exposure duration ``n_e,t``; default the mean per seed.
    below : float, default 0.0
        Returned when there are fewer peaks than ``n_e / n_e,t``.
    positions, extrapolate, top_fraction
        See :func:`quantile_pooled`.

    Returns
    -------
    float

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> crests = [rng.rayleigh(2.5, 400) for _ in range(40)]   # Hs = 10 m
    >>> round(mpm_pooled(crests, 40 * 400), 1)   # theory: 10 sqrt(ln 400 / 8) = 8.65
    8.8
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    return read_pooled(seeds, n_total, 1.0 / n_t, positions=positions, below=below,
                       extrapolate=extrapolate, top_fraction=top_fraction, what="MPM")


def mpm_seed_maxima(maxima, q=MPM_QUANTILE, *, positions="weibull"):
    """MPM as the q = 0.368 quantile of the seed maxima (exceedance ``1 − q = 0.632``).

    Parameters
    ----------
    maxima : array_like, shape (N,)
        Maximum of each seed (:func:`seed_maxima`); each seed one exposure
        duration.
    q : float, default 0.368
        Quantile; other values give other quantiles of the exposure maximum.
    positions : {"weibull", "gringorten", "k/n"}, default "weibull"
        ``k/(N + 1)``; ``"k/n"`` reproduces the biased ``k/N`` reading.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``1 − q`` lies outside the positions of the N maxima: too few seeds.

    Examples
    --------
    >>> mpm_seed_maxima([1.0, 2.0, 3.0, 4.0, 5.0])   # 0.632 * 6 = 3.792 -> ranks 3 and 4
    2.208
    """
    _, s = seed_maxima_distribution(maxima)
    q = check_open_unit(q, "q")
    value = read_at_exceedance(s, s.size, 1.0 - q, positions=positions, scale="linear")
    if np.isnan(value):
        raise ValueError(f"{s.size} seed maxima cannot resolve exceedance {1 - q:.3g} with "
                         f"{positions!r} positions; use more seeds")
    return float(np.round(value, 12))


def mpm_weibull(peaks, n_encounters, *, exposure_encounters=None, top_fraction=0.3):
    """MPM from a 3-parameter Weibull LS fit to the top fraction of the pooled peaks.

    Parameters
    ----------
    peaks, n_encounters, exposure_encounters
        See :func:`mpm_pooled`.
    top_fraction : float, default 0.3
        Fraction of the largest peaks fitted (0.3 for crests — the PAS
        validation truth — 0.9 for impact forces), with the plotting positions
        of all peaks (:func:`pas.stats.fit_weibull3_ls`).

    Returns
    -------
    mpm : float
        ``fit.isf(P_t · n_e / n_p)``.
    fit : Weibull3
        The fitted distribution of a peak.
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    pooled = np.concatenate(seeds)
    fit = fit_weibull3_ls(pooled, top_fraction=top_fraction)
    return weibull_mpm(fit, pooled.size, n_total, 1.0 / n_t), fit


def weibull_mpm(fit, n_peaks, n_total, p_target):
    """Value of a per-peak Weibull fit at per-encounter exceedance ``p_target``."""
    p_peak = p_target * n_total / n_peaks
    if p_peak >= 1.0:
        return float(fit.theta)
    return float(fit.isf(p_peak))
