"""Impact records (green water, slamming): how often, are they independent, exposure risk.

Follows the statistics of Boon (2025, PhD thesis, ch. 3–4) for basin and CFD
records of wave impacts, written for pandas tables of events:

* **How often** — the probability of an impact per wave encounter
  ``Pr(GW) = n_GW / n_w`` (thesis Eq. 3.1), and the exceedance rate ``Pr(EX)``
  of a load level the same way, with a Jeffreys or Clopper–Pearson interval
  (:func:`occurrence_probability`, :func:`impact_rates`); its dependence on
  wave height and freeboard ``Pr(GW) = exp(−(C f / Hm0)²)`` (thesis Eq. 3.4,
  the overtopping form; the thesis finds C = 1.19), fitted by binomial maximum
  likelihood with a profile-likelihood interval (:func:`fit_occurrence`); these
  live in :mod:`pas.records.occurrence` and are re-exported here.
* **Are they independent** — times between impacts within a seed against the
  exponential distribution of a Poisson process (Kolmogorov–Smirnov,
  :func:`exponential_test`); an excess of short gaps, the zero-inflation
  that wave groups cause (thesis §4.3.2–4.3.3), by a binomial test
  (:func:`clustering_test`); runs declustering with a minimum separation
  ``t_min`` (:func:`decluster`), which the thesis ties to the natural pitch
  and encounter periods: a few encounter periods joins the impacts of one
  wave group.
* **Exposure** — the probability that the largest load over ``n_w``
  encounters exceeds a limit, ``Pr(p > p_lim) = 1 − (1 − Pr(GW)(1 −
  F(p_lim)))^{n_w}`` (thesis Eq. 3.1–3.3), and its inverse
  (:func:`exposure_probability`, :func:`exposure_load`). It assumes
  independent impacts: use the declustered rate and cluster maxima when the
  record clusters. At exceedance ``1 − e⁻¹ ≈ 0.632`` the inverse is the MPM
  of :mod:`pas.records.records` and PAS for the same exposure.

The peak-load distribution ``F`` comes from :mod:`pas.records.load_fits`.

Declustering is done here, not with ``pyextremes.get_extremes(method="POT",
r=...)``, which applies the same rule (a new cluster after a gap longer than
``r``) to one continuous series with a DatetimeIndex: an impact record is many
seeds whose times restart at zero, and joining them would merge the end of one
seed with the start of the next. The two agree on a single seed
(``tests/records/test_impacts.py``).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy import stats

from .._support.checks import check_open_unit, check_positive
from .occurrence import (
    OccurrenceFit,
    _column,
    fit_occurrence,
    impact_rates,
    occurrence_model,
    occurrence_probability,
)

__all__ = [
    "occurrence_probability", "impact_rates", "occurrence_model", "OccurrenceFit",
    "fit_occurrence", "inter_arrival_times", "exponential_test", "clustering_test",
    "decluster", "exposure_probability", "exposure_load",
]


# ------------------------------------------------------- are they independent
def _impacts(events, time, seed, value):
    """Rows with an impact, sorted by seed and time (all rows without ``value``)."""
    cols = [time] + ([seed] if seed else []) + ([value] if value else [])
    for c in cols:
        _column(events, c)
    ev = events[events[value] > 0] if value else events
    return ev.sort_values(([seed] if seed else []) + [time], kind="stable")


def inter_arrival_times(events, *, time="t", seed="seed", value=None):
    """Times between consecutive impacts of the same seed.

    Parameters
    ----------
    events : pandas.DataFrame
        Impact (or per-encounter) table.
    time : str, default "t"
        Column of the impact time (s, restarting in each seed).
    seed : str or None, default "seed"
        Column of the seed (realisation); gaps never span two seeds. None for
        one continuous record.
    value : str, optional
        Load column; rows with ``value <= 0`` (no impact) are dropped first.

    Returns
    -------
    pandas.Series
        Gaps (named ``"gap"``), indexed like the later impact of each pair.

    Examples
    --------
    >>> import pandas as pd
    >>> ev = pd.DataFrame({"t": [10.0, 30.0, 35.0, 5.0, 50.0], "seed": [0, 0, 0, 1, 1]})
    >>> inter_arrival_times(ev).tolist()
    [20.0, 5.0, 45.0]
    """
    ev = _impacts(events, time, seed, value)
    t = ev[time].to_numpy(dtype=float)
    same = np.ones(len(ev) - 1, bool) if not seed else np.diff(ev[seed].to_numpy()) == 0
    gaps = np.diff(t)[same] if len(ev) > 1 else np.empty(0)
    return pd.Series(gaps, index=ev.index[1:][same] if len(ev) > 1 else ev.index[:0], name="gap")


def exponential_test(gaps, *, loc=0.0, n_mc=0, seed=0):
    """Kolmogorov–Smirnov test of inter-arrival times against the exponential.

    The exponential starts at ``loc`` and its mean is that of ``gaps − loc``.
    After declustering with ``t_min`` pass ``loc=t_min``: no declustered gap is
    shorter, and by memorylessness the gaps of a Poisson process beyond
    ``t_min`` are ``t_min`` plus an exponential (against ``loc = 0`` the
    missing short gaps alone reject the test, the more the longer ``t_min``). ``pvalue`` is scipy's
    ``kstest`` p-value, which treats that mean as known and is therefore
    conservative (rejects too rarely); ``n_mc > 0`` adds ``pvalue_mc``, the
    parametric-bootstrap p-value of ``scipy.stats.goodness_of_fit`` that
    accounts for the fitted mean (Lilliefors' test for the exponential).

    Returns
    -------
    pandas.Series
        ``n``, ``loc``, ``mean`` (of ``gaps − loc``), ``statistic``, ``pvalue``
        (and ``pvalue_mc``).

    Examples
    --------
    >>> import numpy as np
    >>> g = np.random.default_rng(1).exponential(60.0, 300)
    >>> bool(exponential_test(g)["pvalue"] > 0.05)
    True
    """
    g = np.asarray(gaps, dtype=float) - float(loc)
    if g.ndim != 1 or g.size < 3 or np.any(~np.isfinite(g)) or np.any(g < 0):
        raise ValueError("gaps must be at least 3 finite times, none shorter than loc")
    mean = g.mean()
    res = stats.kstest(g, stats.expon(scale=mean).cdf)
    out = {"n": g.size, "loc": float(loc), "mean": mean, "statistic": res.statistic,
           "pvalue": res.pvalue}
    if n_mc:
        mc = stats.goodness_of_fit(stats.expon, g, known_params={"loc": 0.0}, statistic="ks",
                                   n_mc_samples=int(n_mc), rng=np.random.default_rng(seed))
        out["pvalue_mc"] = mc.pvalue
    return pd.Series(out)


def clustering_test(gaps, t_min):
    """Excess of gaps shorter than ``t_min`` over a Poisson process: zero-inflation.

    The exponential mean is estimated from the gaps longer than ``t_min``
    (memorylessness: ``gap − t_min`` is exponential with the same mean), so the
    short gaps that clustering adds do not bias it; the expected share below
    ``t_min`` is ``F0 = 1 − exp(−t_min/mean)``. The zero-inflation
    ``π = (F_obs − F0)/(1 − F0)`` is the maximum-likelihood share of gaps from
    a short-gap component; ``pvalue`` is the one-sided binomial test of the
    short-gap count against ``F0``.

    Returns
    -------
    pandas.Series
        ``n``, ``t_min``, ``n_short``, ``expected_short``, ``zero_inflation``,
        ``pvalue``.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> g = np.r_[rng.exponential(100.0, 400), rng.uniform(5, 10, 100)]  # 100 in clusters
    >>> r = clustering_test(g, 15.0)
    >>> round(float(r["zero_inflation"]), 2), bool(r["pvalue"] < 1e-6)
    (0.2, True)
    """
    g = np.asarray(gaps, dtype=float)
    t_min = check_positive(t_min, "t_min")
    long = g[g > t_min] - t_min
    if long.size < 2:
        raise ValueError(f"fewer than 2 gaps exceed t_min={t_min:g}; lower t_min")
    f0 = -np.expm1(-t_min / long.mean())
    k = int(np.sum(g <= t_min))
    pi = max(0.0, (k / g.size - f0) / (1.0 - f0))
    p = stats.binomtest(k, g.size, f0, alternative="greater").pvalue
    return pd.Series({"n": g.size, "t_min": t_min, "n_short": k, "expected_short": f0 * g.size,
                      "zero_inflation": pi, "pvalue": p})


def decluster(events, t_min, *, time="t", seed="seed", value="load"):
    """Runs declustering: impacts less than ``t_min`` apart form one cluster; keep its maximum.

    A new cluster starts at a new seed or after a gap longer than ``t_min``
    (the rule of ``pyextremes.get_extremes(method="POT", r=t_min)``).

    Parameters
    ----------
    events : pandas.DataFrame
        Impact or per-encounter table (rows with ``value <= 0`` are dropped).
    t_min : float
        Minimum separation (s) of independent impacts.
    time, seed, value : str
        Column names (``seed=None`` for one continuous record).

    Returns
    -------
    pandas.DataFrame
        The cluster maxima (rows of ``events``) with a column ``cluster_size``.

    Examples
    --------
    >>> import pandas as pd
    >>> ev = pd.DataFrame({"t": [10.0, 14.0, 40.0, 12.0], "seed": [0, 0, 0, 1],
    ...                    "load": [3.0, 5.0, 1.0, 2.0]})
    >>> decluster(ev, 8.0)[["t", "load", "cluster_size"]].values.tolist()
    [[14.0, 5.0, 2.0], [40.0, 1.0, 1.0], [12.0, 2.0, 1.0]]
    """
    t_min = check_positive(t_min, "t_min")
    ev = _impacts(events, time, seed, value)
    t = ev[time].to_numpy(dtype=float)
    new = np.r_[True, np.diff(t) > t_min]
    if seed:
        new[1:] |= np.diff(ev[seed].to_numpy()) != 0
    cluster = np.cumsum(new)
    grouped = ev[value].groupby(cluster)
    out = ev.loc[grouped.idxmax().to_numpy()].copy()
    out["cluster_size"] = grouped.size().to_numpy()
    return out


# ------------------------------------------------------------------ exposure
def exposure_probability(limit, probability, distribution, n_encounters):
    """``Pr(max > p_lim) = 1 − (1 − Pr(GW) (1 − F(p_lim)))^{n_w}`` (Boon 2025, Eq. 3.1–3.3).

    Parameters
    ----------
    limit : float or array_like
        Load limit(s) ``p_lim``.
    probability : float
        Impact probability per encounter ``Pr(GW)``.
    distribution : scipy.stats frozen distribution (or any object with ``sf``)
        Distribution ``F`` of the peak load of an impact.
    n_encounters : float
        Encounters in the exposure ``n_w`` (e.g. hours · 3600 / T_e).

    Returns
    -------
    float, or pandas.Series indexed by ``limit``

    Examples
    --------
    >>> from scipy import stats
    >>> # 1 - (1 - 0.03 exp(-1000/300))^500 = 1 - (1 - 1.0702e-3)^500
    >>> round(exposure_probability(1000.0, 0.03, stats.expon(scale=300.0), 500), 4)
    0.4146
    """
    p = check_open_unit(probability, "probability")
    n = check_positive(n_encounters, "n_encounters")
    lim = np.asarray(limit, dtype=float)
    out = -np.expm1(n * np.log1p(-p * distribution.sf(lim)))
    if lim.ndim == 0:
        return float(out)
    return pd.Series(out, index=pd.Index(lim.ravel(), name="limit"), name="exceedance_probability")


def exposure_load(target, probability, distribution, n_encounters):
    """The load exceeded with probability ``target`` in ``n_w`` encounters (inverse of the above).

    ``sf(p) = (1 − (1 − target)^{1/n_w}) / Pr(GW)``. NaN where ``target`` is
    above ``1 − (1 − Pr(GW))^{n_w}``, the chance of any impact at all.
    ``target = 1 − e⁻¹`` gives the MPM of the exposure.

    Returns
    -------
    float, or pandas.Series indexed by ``target``

    Examples
    --------
    >>> from scipy import stats
    >>> f = stats.expon(scale=300.0)
    >>> x = exposure_load(0.41457, 0.03, f, 500)
    >>> round(x)   # back to the limit of the example above
    1000
    """
    p = check_open_unit(probability, "probability")
    n = check_positive(n_encounters, "n_encounters")
    tgt = np.asarray(target, dtype=float)
    if np.any((tgt <= 0) | (tgt >= 1)):
        raise ValueError("target exceedance probabilities must lie strictly between 0 and 1")
    sf = -np.expm1(np.log1p(-tgt) / n) / p
    out = np.where(sf < 1.0, distribution.isf(np.minimum(sf, 1.0)), np.nan)
    if tgt.ndim == 0:
        return float(out)
    return pd.Series(out, index=pd.Index(tgt.ravel(), name="target"), name="load")
