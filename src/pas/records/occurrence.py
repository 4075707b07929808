"""How often: impact probability per encounter, its interval, and Eq. 3.4 against Hm0.

Part of :mod:`pas.records.impacts` (Boon 2025, thesis Eq. 3.1 and 3.4): ``Pr(GW) =
n_GW / n_w`` and ``Pr(EX)`` with Jeffreys or Clopper–Pearson intervals, and
``Pr(GW) = exp(−(C f / Hm0)²)`` fitted by binomial maximum likelihood with a
profile-likelihood interval.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import optimize, stats

from .._support.checks import check_open_unit, check_positive

__all__ = ["occurrence_probability", "impact_rates", "occurrence_model", "OccurrenceFit",
           "fit_occurrence"]


def _column(table, name):
    if not isinstance(table, pd.DataFrame):
        raise ValueError(f"expected a pandas DataFrame with a column {name!r}")
    if name not in table.columns:
        raise ValueError(f"column {name!r} not found; the table has {list(table.columns)}")
    return table[name].to_numpy(dtype=float)


def occurrence_probability(n_events, n_encounters, *, confidence=0.95, method="jeffreys"):
    """Probability per encounter ``n_events / n_encounters`` with a binomial interval.

    Parameters
    ----------
    n_events : int or array_like of int
        Encounters with an impact (or with the load above a level).
    n_encounters : int or array_like of int
        Wave encounters ``n_w``.
    confidence : float, default 0.95
    method : {"jeffreys", "clopper-pearson"}
        Jeffreys: quantiles of Beta(k + ½, n − k + ½), near-nominal coverage
        on average; Clopper–Pearson: exact tails, conservative.

    Returns
    -------
    pandas.Series (scalar input) or DataFrame (one row per entry)
        ``n_events``, ``n_encounters``, ``probability``, ``low``, ``high``.

    Examples
    --------
    >>> r = occurrence_probability(461, 15198)
    >>> round(r["probability"], 4), round(r["low"], 4), round(r["high"], 4)
    (0.0303, 0.0277, 0.0331)
    """
    k = np.asarray(n_events, dtype=float)
    n = np.asarray(n_encounters, dtype=float)
    conf = check_open_unit(confidence, "confidence")
    if np.any(n <= 0) or np.any(k < 0) or np.any(k > n) or np.any(k != np.round(k)):
        raise ValueError("n_events must be whole numbers in 0..n_encounters and "
                         "n_encounters > 0")
    a = (1.0 - conf) / 2.0
    if method == "jeffreys":
        low = stats.beta.ppf(a, k + 0.5, n - k + 0.5)
        high = stats.beta.ppf(1 - a, k + 0.5, n - k + 0.5)
    elif method == "clopper-pearson":
        with np.errstate(invalid="ignore"):
            low = stats.beta.ppf(a, k, n - k + 1)
            high = stats.beta.ppf(1 - a, k + 1, n - k)
    else:
        raise ValueError(f"method must be 'jeffreys' or 'clopper-pearson', got {method!r}")
    low = np.where(k == 0, 0.0, low)
    high = np.where(k == n, 1.0, high)
    out = {"n_events": k.astype(int), "n_encounters": n.astype(int), "probability": k / n,
           "low": low, "high": high}
    if k.ndim == 0 and n.ndim == 0:
        return pd.Series({key: v.item() for key, v in out.items()}, dtype=object)
    return pd.DataFrame(out)


def impact_rates(events, n_encounters=None, *, value="load", levels=(), hours=None,
                 confidence=0.95, method="jeffreys"):
    """``Pr(GW)`` (load > 0) and ``Pr(EX)`` (load > each level) of an event table.

    Parameters
    ----------
    events : pandas.DataFrame
        One row per impact, or one per encounter with ``value`` 0 for none.
    n_encounters : int, optional
        Wave encounters ``n_w`` of the record; default ``len(events)`` (a
        per-encounter table).
    value : str, default "load"
        Column of the peak load.
    levels : sequence of float
        Load levels for exceedance rates ``Pr(EX)``.
    hours : float, optional
        Duration of the record; adds impacts per hour.
    confidence, method
        See :func:`occurrence_probability`.

    Returns
    -------
    pandas.DataFrame
        One row per ``"impact"`` and ``"load > level"``.
    """
    load = _column(events, value)
    n_w = len(load) if n_encounters is None else int(check_positive(n_encounters, "n_encounters"))
    names = ["impact"] + [f"{value} > {lv:g}" for lv in levels]
    counts = [int(np.sum(load > 0))] + [int(np.sum(load > lv)) for lv in levels]
    table = occurrence_probability(counts, [n_w] * len(counts), confidence=confidence,
                                   method=method)
    table.index = pd.Index(names, name="event")
    if hours is not None:
        table["per_hour"] = table["n_events"] / check_positive(hours, "hours")
    return table


def occurrence_model(hm0, freeboard, c):
    """``Pr(GW) = exp(−(C f / Hm0)²)`` (Boon 2025, Eq. 3.4).

    Examples
    --------
    >>> round(float(occurrence_model(8.0, 8.0, 1.19)), 4)   # exp(-1.19^2)
    0.2427
    """
    r = np.asarray(freeboard, dtype=float) / np.asarray(hm0, dtype=float)
    return np.exp(-(c * r) ** 2)


class OccurrenceFit:
    """``C`` of Eq. 3.4 fitted by :func:`fit_occurrence`, with its interval.

    Attributes
    ----------
    c, low, high : float
        Estimate and profile-likelihood interval of ``C``.
    confidence : float
    data : pandas.DataFrame
        The conditions fitted, with their own Jeffreys intervals.
    """

    def __init__(self, c, low, high, confidence, data):
        self.c, self.low, self.high, self.confidence, self.data = c, low, high, confidence, data

    def __repr__(self):
        return (f"OccurrenceFit(C={self.c:.4g}, {self.confidence:.0%} interval "
                f"[{self.low:.4g}, {self.high:.4g}], {len(self.data)} conditions)")

    def predict(self, hm0, freeboard):
        """``Pr(GW)`` and its band (from the interval of ``C``) as a DataFrame."""
        hm0, fb = np.broadcast_arrays(np.asarray(hm0, float), np.asarray(freeboard, float))
        return pd.DataFrame({"hm0": hm0.ravel(), "freeboard": fb.ravel(),
                             "probability": occurrence_model(hm0, fb, self.c).ravel(),
                             "low": occurrence_model(hm0, fb, self.high).ravel(),
                             "high": occurrence_model(hm0, fb, self.low).ravel()})


def _binomial_loglik(c, k, n, r2):
    z = c * c * r2
    return float(np.sum(-k * z + (n - k) * np.log(-np.expm1(-z))))


def fit_occurrence(table, *, hm0="hm0", freeboard="freeboard", n_events="n_events",
                   n_encounters="n_encounters", confidence=0.95):
    """Fit ``C`` of ``Pr(GW) = exp(−(C f/Hm0)²)`` to impact counts of several conditions.

    Binomial maximum likelihood over the conditions (each ``n_events`` of
    ``n_encounters`` encounters) with the profile-likelihood interval
    ``2 (ℓ_max − ℓ(C)) ≤ χ²₁(confidence)``.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per condition (sea state and freeboard).
    hm0, freeboard, n_events, n_encounters : str
        Column names.
    confidence : float, default 0.95

    Returns
    -------
    OccurrenceFit

    Examples
    --------
    >>> import pandas as pd
    >>> t = pd.DataFrame({"hm0": [6.0, 8.0], "freeboard": [10.5, 10.5],
    ...                   "n_events": [30, 460], "n_encounters": [15000, 15000]})
    >>> fit = fit_occurrence(t)
    >>> round(fit.c, 3), fit.low < fit.c < fit.high   # each alone: 1.4245 and 1.4222
    (1.423, True)
    """
    conf = check_open_unit(confidence, "confidence")
    k = _column(table, n_events)
    n = _column(table, n_encounters)
    r2 = (_column(table, freeboard) / _column(table, hm0)) ** 2
    if np.any(r2 <= 0) or not np.all(np.isfinite(r2)):
        raise ValueError("hm0 and freeboard must be positive and finite")
    if k.sum() == 0 or np.all(k == n):
        raise ValueError("fit_occurrence needs conditions with and without impacts "
                         "(all zero or all impacts leave C unbounded)")
    nll = lambda c: -_binomial_loglik(c, k, n, r2)  # noqa: E731
    c_max = 50.0 / np.sqrt(r2.min())
    c_hat = optimize.minimize_scalar(nll, bounds=(1e-9, c_max), method="bounded",
                                     options={"xatol": 1e-12}).x
    drop = stats.chi2.ppf(conf, 1) / 2.0
    f = lambda c: nll(c) - nll(c_hat) - drop  # noqa: E731
    low = optimize.brentq(f, 1e-12, c_hat) if f(1e-12) > 0 else 0.0
    high = optimize.brentq(f, c_hat, c_max) if f(c_max) > 0 else np.inf
    data = pd.DataFrame({"hm0": _column(table, hm0), "freeboard": _column(table, freeboard)})
    data = pd.concat([data, occurrence_probability(k, n).reset_index(drop=True)], axis=1)
    return OccurrenceFit(float(c_hat), float(low), float(high), conf, data)
