"""Exceedance probabilities normalised by the number of wave encounters.

All exceedance distributions in PAS share one basis, the number of wave
encounters ``n_w`` in the Monte-Carlo duration (paper §2.1 Step 4, Eq. 3 and
Step 10, Eq. 8): the k-th largest of ``n`` peaks gets ``d = k / n_w``.  A
quantity read at a probability is interpolated linearly on ``ln d`` (Eq. 12).
"""

from __future__ import annotations

import numpy as np

from .._support.checks import (
    check_open_unit,
    check_peaks,
    check_positive,
    check_positive_int,
)

__all__ = [
    "exceedance_probabilities",
    "value_at_exceedance",
    "mean_top_order_statistics",
    "order_statistics_read",
    "mpm_of_realisations",
    "quantile_exceedance",
    "p_exp_from_duration",
    "n_waves_from_duration",
    "mean_period_from_peak_period",
    "encounter_period",
]

G = 9.81


def exceedance_probabilities(values, n_waves: int):
    """Sort peaks descending and give each its exceedance probability (Eq. 3, 8).

    Parameters
    ----------
    values : array-like, shape (n,)
        Peak values (one per event).
    n_waves : int
        Number of wave encounters the peaks were counted over.

    Returns
    -------
    d : ndarray, shape (n,)
        Exceedance probabilities ``k / n_waves``, k = 1..n (ascending).
    sorted_values : ndarray, shape (n,)
        The values sorted descending, so ``sorted_values[k-1]`` has ``d[k-1]``.

    Examples
    --------
    >>> d, v = exceedance_probabilities([1.0, 3.0, 2.0], n_waves=10)
    >>> d.tolist(), v.tolist()
    ([0.1, 0.2, 0.3], [3.0, 2.0, 1.0])
    """
    v = check_peaks(values, "values")
    n_w = check_positive_int(n_waves, "n_waves")
    sorted_values = np.sort(v)[::-1]
    d = np.arange(1, v.size + 1) / n_w
    return d, sorted_values


def value_at_exceedance(d, values, p):
    """Interpolate a distribution ``[d, values]`` at probability ``p`` on ``ln d`` (Eq. 12).

    ``d`` must be ascending (as returned by :func:`exceedance_probabilities`);
    ``values`` may be 1-D (one distribution) or 2-D with distributions in rows.
    ``p`` outside ``[d[0], d[-1]]`` is clamped to the end value; callers
    compare ``p`` with ``d[-1]`` first where that matters (the study does, and
    refuses to converge on a clamped MPM).
    """
    ln_d = np.log(np.asarray(d, dtype=float))
    ln_p = np.log(np.asarray(p, dtype=float))
    values = np.asarray(values, dtype=float)
    if values.ndim == 1:
        return np.interp(ln_p, ln_d, values)
    return np.array([np.interp(ln_p, ln_d, row) for row in values])


def mean_top_order_statistics(realisations, k: int) -> np.ndarray:
    """The mean over realisations (rows) of each of their ``k`` largest values, descending.

    The first ``k`` entries of the mean distribution of Eq. 8–9 without sorting
    all of each row: ``np.partition`` sets the ``k`` largest apart in linear
    time and only those are sorted.  The same values, summed in the same
    order, as the full sort gives.
    """
    h = np.atleast_2d(np.asarray(realisations, dtype=float))
    n = h.shape[1]
    if k >= n:
        return np.sort(h, axis=1)[:, ::-1].mean(axis=0)
    top = np.partition(h, n - k, axis=1)[:, n - k:]
    return np.sort(top, axis=1)[:, ::-1].mean(axis=0)


def order_statistics_read(p: float, n_waves: int, n: int) -> int:
    """How many of ``n`` order statistics a read at ``p`` (Eq. 12) needs: down to
    ``d = k / n_waves ≥ p``, with one to spare.

    Examples
    --------
    >>> order_statistics_read(2.55e-3, 16364, 15000), order_statistics_read(0.5, 100, 20)
    (43, 20)
    """
    return min(int(n), int(np.ceil(p * n_waves)) + 1)


def mpm_of_realisations(realisations, n_waves: int, p: float) -> float:
    """The mean distribution of realisations read at ``p`` (Eq. 8–12), sorting only its top.

    The value :func:`value_at_exceedance` reads from the whole mean
    distribution: interpolation at ``p`` needs the order statistics down to
    ``d = k / n_waves ≥ p`` only (:func:`order_statistics_read`).
    """
    k = order_statistics_read(p, n_waves, np.atleast_2d(realisations).shape[1])
    mean = mean_top_order_statistics(realisations, k)
    return float(value_at_exceedance(np.arange(1, k + 1) / n_waves, mean, p))


def quantile_exceedance(q: float, m: float, n: float) -> float:
    """Peak exceedance probability of the q-quantile of the exposure maximum.

    A record of ``n`` wave encounters covering ``m`` exposure durations (e.g.
    ``m`` one-hour seeds) has ``n/m`` encounters per exposure, and the maximum
    over one exposure is below the level with exceedance ``P`` with probability
    ``(1 − P)^{n/m}``; setting that to ``q`` gives ``P_q = 1 − q^{m/n}``
    (van Essen, Scharnke & Seyffert 2023).  ``q = e^{-1} ≈ 0.368`` gives the MPM
    level ``≈ m/n``, one exceedance per exposure.

    Examples
    --------
    >>> round(quantile_exceedance(0.368, 35, 16113), 6)
    0.002169
    """
    qv = check_open_unit(q, "q")
    return float(-np.expm1(np.log(qv) * check_positive(m, "m") / check_positive(n, "n")))


def mean_period_from_peak_period(tp: float, gamma: float = 3.3) -> float:
    """Mean wave period ``T1`` of a JONSWAP spectrum from its peak period.

    Uses the DNV-RP-C205 relation ``T1/Tp = 0.7303 + 0.04936γ − 0.006556γ²
    + 0.0003610γ³``, which gives ``T1 = Tp / 1.198`` for γ = 3.3: the factor the
    paper's Table 2 implies (van Essen & Seyffert (2026) §2.1 Step 2 prints
    ``T_p/1.98``, which contradicts their Table 2: 11.0 s / 1.198 = 9.18 s and
    9.18 s / 3600 s = 2.55e-3).
    """
    tp = check_positive(tp, "tp")
    g = check_positive(gamma, "gamma")
    ratio = 0.7303 + 0.04936 * g - 0.006556 * g**2 + 0.0003610 * g**3
    return tp * ratio


def encounter_period(period: float, speed: float = 0.0, heading_deg: float = 180.0) -> float:
    """Encounter period for a ship at ``speed`` (m/s), heading 180° = head seas (Eq. 1).

    ``ω_e = ω − ω² V cos μ / g`` gives ``T_e = T / (1 − 2π V cos μ / (T g))``.
    """
    t = check_positive(period, "period")
    factor = 1.0 - 2.0 * np.pi * speed * np.cos(np.deg2rad(heading_deg)) / (t * G)
    if factor <= 0:
        raise ValueError(
            f"speed={speed} m/s at heading {heading_deg}° overtakes waves of period {t} s; "
            "the encounter period is undefined"
        )
    return t / factor


def p_exp_from_duration(exposure_s: float, mean_encounter_period_s: float) -> float:
    """Target exceedance probability ``P_exp = T_1,e / T_exp`` (Eq. 11)."""
    p = check_positive(mean_encounter_period_s, "mean_encounter_period_s") / check_positive(
        exposure_s, "exposure_s"
    )
    return check_open_unit(p, "P_exp (mean period / exposure)")


def n_waves_from_duration(duration_s: float, mean_encounter_period_s: float) -> int:
    """Number of encounters ``n_w ≈ T_MCS / T_e`` (paper Step 2), rounded to int.

    The paper's Table 2 uses the peak encounter period here (``50 h / 11.0 s =
    16 364``); counting zero up-crossings in the record is the alternative.
    """
    n = check_positive(duration_s, "duration_s") / check_positive(
        mean_encounter_period_s, "mean_encounter_period_s"
    )
    return max(1, int(round(n)))
