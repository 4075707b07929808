"""A record's three MPM estimates with bootstrap confidence intervals, in one object.

The intervals resample *seeds* with replacement (each seed an independent
realisation; peaks inside a seed are not independent, wave groups cluster
them) and read every replicate the way the estimate itself was read: the
percentile interval of ``n_boot`` replicates. A replicate whose target lies
beyond its largest peak is NaN and left out; their share is reported
(``n_valid``), since a large share means the record is too short for that
target.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .._support.checks import check_open_unit
from ..stats.exceedance import quantile_exceedance
from ..stats.weibull import Weibull3, fit_weibull3_ls
from .positions import plotting_positions, read_at_exceedance
from .records import (
    MPM_QUANTILE,
    _record,
    seed_maxima,
    top_peaks,
    weibull_mpm,
)

__all__ = ["bootstrap_mpm", "RecordAnalysis", "analyse_record"]

_METHODS = ("pooled peaks", "seed maxima", "weibull")


def _replicates(seeds, enc, p, q, method, idx, *, positions, top_fraction, empty):
    """Estimates of the resampled records ``idx`` (B, M) of seed indices."""
    b, m = idx.shape
    if method == "seed maxima":
        mx = -np.sort(-seed_maxima(seeds, empty=empty)[idx], axis=1)
        return read_at_exceedance(mx, m, 1.0 - q, positions=positions, scale="linear")
    n_e = enc[idx].sum(axis=1)
    if method == "pooled peaks":
        k = int(np.ceil(p * n_e.max() + 1.0)) + 2
        top = top_peaks(seeds, k)
        pooled = -np.sort(-top[idx].reshape(b, -1), axis=1)[:, :k]   # NaN last
        return read_at_exceedance(pooled, n_e, p, positions=positions, below=empty)
    out = np.full(b, np.nan)
    for i in range(b):  # one least-squares fit per replicate
        vals = np.concatenate([seeds[j] for j in idx[i]])
        if vals.size >= 3 and np.ptp(vals) > 0:
            fit = fit_weibull3_ls(vals, top_fraction=top_fraction)
            out[i] = weibull_mpm(fit, vals.size, n_e[i], p)
    return out


def bootstrap_mpm(peaks, n_encounters, *, method="pooled peaks", q=None,
                  exposure_encounters=None, n_boot=1000, confidence=0.95,
                  positions=None, top_fraction=0.3, empty=0.0, seed=0):
    """Bootstrap-over-seeds confidence interval of an MPM or exposure-maximum quantile.

    Parameters
    ----------
    peaks : sequence of array_like
        Peaks per seed; at least 2 seeds (split one long run into segments).
    n_encounters : int or sequence of int
        Encounters in the record, or per seed.
    method : {"pooled peaks", "seed maxima", "weibull"}
        Which estimate (see :mod:`pas.records.records`).
    q : float, optional
        Quantile of the exposure maximum; default the MPM as its estimate reads
        it (pooled peaks and fit at ``P_t = 1/n_e,t``, seed maxima at 0.368).
    exposure_encounters : float, optional
        Encounters per exposure duration; default the mean per seed.
    n_boot : int, default 1000
        Replicates (the Weibull method fits each one; use ~200 there).
    confidence : float, default 0.95
    positions : str, optional
        Plotting positions; default "gringorten" (pooled) or "weibull" (maxima).
    top_fraction : float, default 0.3
        Fraction of the peaks in each Weibull fit.
    empty : float, default 0.0
        Value of a seed (maximum) without any peak.
    seed : int, default 0

    Returns
    -------
    pandas.Series
        ``low``, ``high``, ``se`` (standard deviation of the replicates),
        ``n_valid`` (replicates inside the record), ``n_boot``, ``confidence``.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> crests = [rng.rayleigh(2.5, 400) for _ in range(40)]
    >>> ci = bootstrap_mpm(crests, 40 * 400, n_boot=400)
    >>> bool(ci["low"] < 8.65 < ci["high"]), int(ci["n_valid"])   # theory 8.65 m
    (True, 400)
    """
    if method not in _METHODS:
        raise ValueError(f"method must be one of {list(_METHODS)}, got {method!r}")
    conf = check_open_unit(confidence, "confidence")
    if int(n_boot) < 10:
        raise ValueError(f"n_boot must be >= 10, got {n_boot!r}")
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    m = len(seeds)
    if m < 2:
        raise ValueError("a bootstrap over seeds needs at least 2 seeds; split a single long "
                         "run into segments of one exposure duration")
    enc = np.asarray(n_encounters, dtype=float)
    enc = np.full(m, n_total / m) if enc.ndim == 0 else enc
    pos = positions or ("weibull" if method == "seed maxima" else "gringorten")
    p = 1.0 / n_t if q is None else quantile_exceedance(q, n_total / n_t, n_total)
    q = MPM_QUANTILE if q is None else q
    idx = np.random.default_rng(seed).integers(0, m, size=(int(n_boot), m))
    est = _replicates(seeds, enc, p, q, method, idx, positions=pos,
                      top_fraction=top_fraction, empty=empty)
    ok = est[np.isfinite(est)]
    if ok.size < 2:
        low = high = se = np.nan
    else:
        low, high = np.quantile(ok, [(1 - conf) / 2, (1 + conf) / 2])
        se = ok.std(ddof=1)
    return pd.Series({"low": float(low), "high": float(high), "se": float(se),
                      "n_valid": int(ok.size), "n_boot": int(n_boot), "confidence": conf})


# ------------------------------------------------------------ result object
@dataclass(frozen=True)
class RecordAnalysis:
    """Extreme-value summary of one record; build with :func:`analyse_record`.

    Attributes
    ----------
    d, values : ndarray
        Pooled-peaks exceedance distribution (``positions``, peaks descending).
    p_maxima, maxima : ndarray
        Seed-maxima distribution (``k/(N+1)``, maxima descending).
    n_encounters : int
        Encounters in the record.
    exposure_encounters : float
        Encounters per exposure duration ``n_e,t``.
    p_target : float
        ``1 / n_e,t``.
    mpm_pooled, mpm_seed_maxima, mpm_fit : float
        The three MPM estimates; NaN where the record cannot resolve them
        (target beyond the largest peak, fewer than 2 seeds).
    fit : Weibull3
        Weibull fit of the top ``top_fraction`` of the peaks.
    top_fraction : float
    positions : str
        Plotting positions of the pooled peaks.
    ci : pandas.DataFrame
        Bootstrap interval (``low``, ``high``, ``se``, ``n_valid``) per
        estimate, index ``"pooled peaks"``, ``"seed maxima"`` (empty when
        ``n_boot = 0``).
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
    positions: str = "gringorten"
    ci: pd.DataFrame = field(default_factory=pd.DataFrame)

    @property
    def n_seeds(self) -> int:
        """Number of seeds N."""
        return int(self.maxima.size)

    @property
    def fit_scale(self) -> float:
        """``n_p / n_e``: converts the fit's per-peak exceedance to per-encounter."""
        return self.values.size / self.n_encounters


def analyse_record(peaks, n_encounters, *, exposure_encounters=None, top_fraction=0.3,
                   empty=0.0, positions="gringorten", n_boot=1000, confidence=0.95, seed=0):
    """All three MPM estimates of a record (:mod:`pas.records.records`) in one object.

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
    positions : {"gringorten", "weibull", "k/n"}, default "gringorten"
        Plotting positions of the pooled peaks (the seed maxima use ``k/(N+1)``).
    n_boot : int, default 1000
        Bootstrap replicates over seeds for the intervals of the pooled-peaks
        and seed-maxima MPMs (:func:`bootstrap_mpm`); 0 skips them.
    confidence : float, default 0.95
    seed : int, default 0
        Seed of the bootstrap.

    Returns
    -------
    RecordAnalysis
    """
    seeds, n_total, n_t = _record(peaks, n_encounters, exposure_encounters)
    v = np.sort(np.concatenate(seeds))[::-1]
    d = plotting_positions(v.size, n_total, positions)
    p_t = 1.0 / n_t
    maxima = seed_maxima(seeds, empty=empty)
    p_m = plotting_positions(maxima.size, maxima.size, "weibull")
    m_sorted = np.sort(maxima)[::-1]
    mpm_sm = read_at_exceedance(m_sorted, m_sorted.size, 1 - MPM_QUANTILE, positions="weibull",
                                scale="linear")
    mpm_p = read_at_exceedance(v, n_total, p_t, positions=positions, below=empty)
    if np.isnan(mpm_p):
        warnings.warn(f"the MPM target {p_t:.3g} per encounter lies beyond the largest peak: "
                      "mpm_pooled is NaN; use more seeds or pas.records.mpm_pooled(..., "
                      "extrapolate='gpd')", stacklevel=2)
    fit = fit_weibull3_ls(v, top_fraction=top_fraction)
    rows = {}
    if n_boot and len(seeds) >= 2:
        for method in ("pooled peaks", "seed maxima"):
            rows[method] = bootstrap_mpm(
                seeds, n_encounters, method=method, exposure_encounters=n_t, n_boot=n_boot,
                confidence=confidence, positions=positions if method == "pooled peaks" else None,
                empty=empty, seed=seed)
    return RecordAnalysis(
        d=d, values=v, p_maxima=p_m, maxima=m_sorted, n_encounters=n_total,
        exposure_encounters=float(n_t), p_target=p_t, mpm_pooled=float(mpm_p),
        mpm_seed_maxima=float(mpm_sm), mpm_fit=weibull_mpm(fit, v.size, n_total, p_t), fit=fit,
        top_fraction=float(top_fraction), positions=positions,
        ci=pd.DataFrame(rows).T if rows else pd.DataFrame())
