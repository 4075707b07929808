"""Extreme values of Monte-Carlo records: MPM from pooled peaks, seed maxima and fits.

A *record* is M seeds (basin runs or simulations) of a stationary sea state,
each given as the peaks of the variable in that seed (one crest per
zero-up-crossing wave, or one value per impact for loads that do not peak
every wave), together with the number of wave encounters ``n_e`` in the whole
record. Following van Essen, Scharnke & Seyffert (2023) and the PAS paper
(§2.1, Eq. 3 and 11–12) three estimates of the most probable maximum (MPM)
over an exposure duration are offered:

* **Pooled peaks** — the peaks of all seeds sorted descending; the k-th
  largest has exceedance probability per encounter ``d = k / n_e`` (largest
  ``1/n_e``; :func:`pas.stats.exceedance_probabilities`). The MPM is the
  value at ``P_t = 1 / n_e,t`` with ``n_e,t`` the encounters per exposure
  duration, read by linear interpolation on ``ln d``
  (:func:`pas.stats.value_at_exceedance`). Any quantile ``q`` of the
  exposure maximum is read at ``P_q = 1 − q^{M_t/n_e}``
  (:func:`pas.stats.quantile_exceedance`; DNV-RP-C205 via the PAS paper §5),
  where ``M_t = n_e / n_e,t`` is the number of exposure durations in the
  record — in the worked example of van Essen et al. (2023) ``M_t = 35``
  one-hour seeds and ``n_e = 16 113`` encounters: ``P_0.368 = 2.169e-3``,
  ``P_0.9 = 2.289e-4``. ``q = 0.368`` gives ``P_q ≈ 1/n_e,t``.
* **Seed maxima** — the maximum of each of the N seeds (each seed one
  exposure duration), sorted descending; the k-th largest gets exceedance
  ``k / N`` (largest ``1/N``; the same rank convention as Eq. 3, so both
  curves share one axis). The MPM is the q = 0.368 quantile of the maxima,
  i.e. the value at exceedance ``0.632``, by linear interpolation in
  probability. A seed without any peak (no impact) has maximum ``empty``.
* **Weibull fit** — a 3-parameter Weibull least-squares fit
  (:func:`pas.stats.fit_weibull3_ls`) to the top fraction of the pooled peaks
  (top 30 % for crests — the PAS validation truths use this — top 90 % for
  impact forces). The fit is the distribution of a *peak*; with ``n_p``
  peaks in ``n_e`` encounters the exceedance per encounter is
  ``(n_p/n_e) · P_W(X > x)``, so the MPM is ``isf(P_t · n_e / n_p)``.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .._validation import check_open_unit, check_peaks, check_positive
from .exceedance import exceedance_probabilities, quantile_exceedance, value_at_exceedance
from .weibull import Weibull3, fit_weibull3_ls

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
    "RecordAnalysis",
    "analyse_record",
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
def pooled_peaks_distribution(peaks, n_encounters):
    """Exceedance distribution of the pooled peaks of all seeds (Eq. 3).

    Parameters
    ----------
    peaks : array_like or sequence of array_like
        Peaks per seed (see :func:`seed_peaks`).
    n_encounters : int or sequence of int
        Wave encounters in the whole record, or one count per seed (summed).
        For impact loads this is larger than the number of peaks.

    Returns
    -------
    d : ndarray
        Exceedance probability per encounter, ``k / n_e``, ascending.
    values : ndarray
        Pooled peaks sorted descending.

    Examples
    --------
    >>> d, v = pooled_peaks_distribution([[1.0, 3.0], [2.0]], n_encounters=[5, 5])
    >>> d.tolist(), v.tolist()
    ([0.1, 0.2, 0.3], [3.0, 2.0, 1.0])
    """
    seeds = seed_peaks(peaks)
    n_total = _total_encounters(n_encounters, len(seeds))
    pooled = np.concatenate(seeds)
    if pooled.size > n_total:
        # Happens with spectral estimates such as n_w = T / Tp (van Essen &
        # Seyffert 2026, Table 2), which undercount zero up-crossings; flagged.
        warnings.warn(f"{pooled.size} peaks in {n_total} encounters: the smallest peaks get "
                      "exceedance probabilities above 1; use counted encounters or check for "
                      "double peaks per wave", stacklevel=2)
    return exceedance_probabilities(pooled, n_total)


def seed_maxima(peaks, *, empty=0.0):
    """Largest peak of each seed; ``empty`` for a seed without peaks (no impact)."""
    seeds = seed_peaks(peaks)
    return np.array([s.max() if s.size else float(empty) for s in seeds])


def seed_maxima_distribution(maxima):
    """Exceedance distribution of N seed maxima: k-th largest gets ``k / N``.

    Returns
    -------
    p : ndarray, shape (N,)
        ``1/N, 2/N, …, 1`` (ascending).
    values : ndarray, shape (N,)
        The maxima sorted descending.
    """
    m = check_peaks(maxima, "maxima")
    return np.arange(1, m.size + 1) / m.size, np.sort(m)[::-1]


# --------------------------------------------------------------- read-outs
def _read_pooled(d, values, p, *, below=0.0, warn=True):
    """Value at exceedance ``p`` on ``ln d`` with the record's range policies."""
    if p < d[0]:
        if warn:
            warnings.warn(f"target exceedance {p:.3g} is below the record's smallest "
                          f"{d[0]:.3g}: the record is shorter than the exposure; returning the "
                          "largest peak (use more seeds)", stacklevel=3)
        return float(values[0])
    if p > d[-1]:
        # Fewer peaks than the target rank: the MPM lies below every recorded
        # peak (e.g. no impact expected in the exposure duration).
        return float(below)
    return float(value_at_exceedance(d, values, p))


def quantile_pooled(peaks, n_encounters, q=MPM_QUANTILE, *, exposure_encounters=None,
                    below=0.0):
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

    Returns
    -------
    float
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    d, v = pooled_peaks_distribution(seeds, n_encounters)
    p = quantile_exceedance(q, n_total / n_t, n_total)
    return _read_pooled(d, v, p, below=below)


def mpm_pooled(peaks, n_encounters, *, exposure_encounters=None, below=0.0):
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
    d, v = pooled_peaks_distribution(seeds, n_encounters)
    return _read_pooled(d, v, 1.0 / n_t, below=below)


def _seed_maxima_quantile_rows(sorted_desc, q):
    """Rows of maxima sorted descending -> value at exceedance ``1 − q`` (linear in p).

    The k-th largest of N has exceedance ``k/N``; ``x = (1 − q) N`` falls
    between ranks ``floor(x)`` and ``floor(x) + 1``. NaN where ``x < 1``.
    """
    s = np.atleast_2d(sorted_desc)
    n = s.shape[1]
    x = (1.0 - q) * n
    k = int(np.floor(x + 1e-12))
    if k < 1:
        return np.full(s.shape[0], np.nan)
    if k >= n:
        return s[:, n - 1].copy()
    frac = x - k
    return s[:, k - 1] + frac * (s[:, k] - s[:, k - 1])


def mpm_seed_maxima(maxima, q=MPM_QUANTILE):
    """MPM as the q = 0.368 quantile of the seed maxima (exceedance ``1 − q = 0.632``).

    Parameters
    ----------
    maxima : array_like, shape (N,)
        Maximum of each seed (:func:`seed_maxima`); each seed one exposure
        duration.
    q : float, default 0.368
        Quantile; other values give other quantiles of the exposure maximum.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``1 − q < 1/N``: too few seeds to read that quantile.

    Examples
    --------
    >>> mpm_seed_maxima([1.0, 2.0, 3.0, 4.0, 5.0])   # 0.632 * 5 = 3.16 -> between ranks 3 and 4
    2.84
    """
    _, s = seed_maxima_distribution(maxima)
    q = check_open_unit(q, "q")
    if (1.0 - q) * s.size < 1.0 - 1e-12:
        raise ValueError(f"{s.size} seed maxima cannot resolve exceedance {1 - q:.3g} "
                         f"(needs at least {int(np.ceil(1 / (1 - q)))} seeds)")
    return float(np.round(_seed_maxima_quantile_rows(s, q)[0], 12))


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
    return _weibull_mpm(fit, pooled.size, n_total, 1.0 / n_t), fit


def _weibull_mpm(fit, n_peaks, n_total, p_target):
    p_peak = p_target * n_total / n_peaks
    if p_peak >= 1.0:
        return float(fit.theta)
    return float(fit.isf(p_peak))


# ------------------------------------------------------------ result object
@dataclass(frozen=True)
class RecordAnalysis:
    """Extreme-value summary of one record; build with :func:`analyse_record`.

    Attributes
    ----------
    d, values : ndarray
        Pooled-peaks exceedance distribution (``k/n_e``, peaks descending).
    p_maxima, maxima : ndarray
        Seed-maxima distribution (``k/N``, maxima descending).
    n_encounters : int
        Encounters in the record.
    exposure_encounters : float
        Encounters per exposure duration ``n_e,t``.
    p_target : float
        ``1 / n_e,t``.
    mpm_pooled, mpm_seed_maxima, mpm_fit : float
        The three MPM estimates (``mpm_seed_maxima`` NaN with fewer than 2 seeds).
    fit : Weibull3
        Weibull fit of the top ``top_fraction`` of the peaks.
    top_fraction : float
    """

    d: np.ndarray
    values: np.ndarray
    p_maxima: np.ndarray
    maxima: np.ndarray
    n_encounters: int
    exposure_encounters: float
    p_target: float
    mpm_pooled: float
    mpm_seed_maxima: float
    mpm_fit: float
    fit: Weibull3
    top_fraction: float

    @property
    def n_seeds(self) -> int:
        """Number of seeds N."""
        return int(self.maxima.size)

    @property
    def fit_scale(self) -> float:
        """``n_p / n_e``: converts the fit's per-peak exceedance to per-encounter."""
        return self.values.size / self.n_encounters

    def plot(self, ax=None, *, units="m", variable="crest"):
        """Exceedance plot; see :func:`pas.plotting.records.plot_record_exceedance`."""
        from ..plotting.records import plot_record_exceedance

        return plot_record_exceedance(
            self.d, self.values, maxima=(self.p_maxima, self.maxima), fit=self.fit,
            fit_scale=self.fit_scale, fit_from=self.values[int(np.ceil(self.top_fraction * self.values.size)) - 1],
            mpm={"pooled peaks": self.mpm_pooled, "seed maxima": self.mpm_seed_maxima,
                 f"Weibull fit (top {self.top_fraction:.0%})": self.mpm_fit},
            p_target=self.p_target, units=units, variable=variable, ax=ax)


def analyse_record(peaks, n_encounters, *, exposure_encounters=None, top_fraction=0.3,
                   empty=0.0):
    """All three MPM estimates of a record (module docs) in one object.

    Parameters
    ----------
    peaks : sequence of array_like
        Peaks per seed.
    n_encounters : int or sequence of int
        Encounters in the record, or per seed.
    exposure_encounters : float, optional
        Encounters per exposure duration; default the mean per seed.
    top_fraction : float, default 0.3
        Fraction of the peaks in the Weibull fit (0.9 for impact forces).
    empty : float, default 0.0
        Seed maximum of a seed without peaks.

    Returns
    -------
    RecordAnalysis
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    d, v = pooled_peaks_distribution(seeds, n_encounters)
    p_t = 1.0 / n_t
    maxima = seed_maxima(seeds, empty=empty)
    p_m, m_sorted = seed_maxima_distribution(maxima)
    mpm_sm = mpm_seed_maxima(maxima) if maxima.size >= 2 else float("nan")
    fit = fit_weibull3_ls(v, top_fraction=top_fraction)
    return RecordAnalysis(
        d=d, values=v, p_maxima=p_m, maxima=m_sorted, n_encounters=n_total,
        exposure_encounters=float(n_t), p_target=p_t, mpm_pooled=_read_pooled(d, v, p_t),
        mpm_seed_maxima=mpm_sm, mpm_fit=_weibull_mpm(fit, v.size, n_total, p_t), fit=fit,
        top_fraction=float(top_fraction))
