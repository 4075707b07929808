"""Which distribution do the peak loads of impacts follow: fits, ranking, Q–Q data.

Candidates are ``scipy.stats`` distributions fitted by maximum likelihood
(their own ``fit``): Fréchet (``invweibull``, Boon 2025 finds it for deck
pressures), GEV (``genextreme``), Weibull (``weibull_min``), gamma,
log-normal (``lognorm``) and exponential (``expon``); and this package's
two-component Weibull mixture (``weibull_mixture``, a narrow quasi-static
body and a wide impulsive tail, :func:`pas.stats.weibull_mixture.fit_weibull_mixture`;
beyond Boon 2025 and the PAS paper).  It is rarely picked on samples of a
single known law and then barely moves the AIC-best fit's quantile at the
MPM level, and it helps on loads that are a quasi-static body with an
impulsive tail ("Record statistics" in ``docs/results/investigations.md``).
For comparison the
thesis's binned least squares is offered (``method="binned ls"``): the pdf
fitted to the histogram density by ``scipy.optimize.least_squares``, started
from the ML fit.

:func:`compare_load_distributions` ranks the candidates by AIC (``2k − 2 ln
L``, with the log-likelihood of the data at the fitted parameters for both
methods, so they compare) and reports the KS statistic and p-value against
each fitted distribution. That p-value uses parameters fitted to the same
data, so it is optimistic: read it as a ranking aid, not a test.

Impact loads recorded above a noise threshold (100 kN in the basin) are a
truncated sample: a free location parameter (the default) absorbs most of
that; ``loc=0`` fixes it for loads that start at zero. With a free location
and a shape below 1 (Weibull, gamma) the likelihood grows without bound as the
location approaches the smallest load, so such a fit sits at that load and
its AIC flatters it; compare with ``loc`` fixed as well.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
from scipy import optimize, stats

from .._support.checks import check_peaks
from ..stats.weibull_mixture import fit_weibull_mixture

__all__ = ["CANDIDATES", "fit_load_distribution", "compare_load_distributions", "qq_points"]

#: Candidate name -> scipy.stats distribution name (the mixture is this package's).
CANDIDATES = {"frechet": "invweibull", "gev": "genextreme", "weibull": "weibull_min",
              "gamma": "gamma", "lognormal": "lognorm", "exponential": "expon",
              "weibull_mixture": "weibull_mixture"}


def _dist(name):
    if name not in CANDIDATES:
        raise ValueError(f"distribution must be one of {sorted(CANDIDATES)}, got {name!r}")
    return getattr(stats, CANDIDATES[name])


def _fit_mixture(x, loc, method):
    """The Weibull mixture's parameters ``(θ, p, α1, β1, α2, β2)`` and frozen distribution."""
    if method != "ml":
        raise ValueError("the Weibull mixture is fitted by maximum likelihood only")
    m = fit_weibull_mixture(x, loc=loc)
    return (m.theta, m.p, m.alpha1, m.beta1, m.alpha2, m.beta2), m


def _binned_ls(dist, x, start, loc, bins):
    """Least squares of the pdf against the histogram density, from ``start``."""
    density, edges = np.histogram(x, bins=bins, density=True)
    mid = 0.5 * (edges[1:] + edges[:-1])
    free = list(start) if loc is None else list(start[:-2]) + [start[-1]]

    def params(theta):
        return tuple(theta) if loc is None else tuple(theta[:-1]) + (loc, theta[-1])

    def resid(theta):
        with np.errstate(all="ignore"):
            pdf = dist.pdf(mid, *params(theta))
        return np.where(np.isfinite(pdf), pdf - density, density.max() * 10.0)

    res = optimize.least_squares(resid, free, x_scale="jac", method="trf")
    return params(res.x)


def _ml_fit(dist, x, fixed):
    """scipy's ML fit; with a free location also started from the ``loc = 0`` fit.

    scipy's default start sends the free-location Fréchet, GEV and gamma into
    degenerate optima on impact loads (e.g. Fréchet shape 0.29 on case 3a,
    log-likelihood −3851 against −3408 from the second start); the better of
    the two is kept.
    """
    best = tuple(float(v) for v in dist.fit(x, **fixed))
    if fixed:
        return best
    ll = np.sum(dist.logpdf(x, *best))
    at0 = dist.fit(x, floc=0.0)
    alt = tuple(float(v) for v in dist.fit(x, *at0[:-2], loc=at0[-2], scale=at0[-1]))
    ll_alt = np.sum(dist.logpdf(x, *alt))
    return alt if np.isfinite(ll_alt) and not ll_alt <= ll else best


def fit_load_distribution(loads, name, *, method="ml", loc=None, bins="auto"):
    """Fit one candidate distribution to peak loads.

    Parameters
    ----------
    loads : array_like
        Peak loads of the impacts (no zeros for "no impact").
    name : str
        A key of :data:`CANDIDATES`.
    method : {"ml", "binned ls"}, default "ml"
        scipy's maximum-likelihood ``fit``, or least squares on the histogram
        (not for the mixture, which is fitted by maximum likelihood only).
    loc : float, optional
        Fix the location (e.g. 0); default fitted.
    bins : int or str, default "auto"
        Histogram bins of the binned least squares (``numpy.histogram``).

    Returns
    -------
    pandas.Series
        ``distribution`` (scipy name), ``params`` (shapes, loc, scale; the
        mixture: θ, p, α₁, β₁, α₂, β₂),
        ``n_params`` (free), ``loglik``, ``aic``, ``ks_statistic``,
        ``ks_pvalue``, ``method``, ``dist`` (the frozen distribution).

    Examples
    --------
    >>> from scipy import stats
    >>> x = stats.invweibull(4.0, scale=1000.0).rvs(2000, random_state=0)
    >>> r = fit_load_distribution(x, "frechet", loc=0.0)
    >>> round(r["params"][0], 1), round(r["params"][2], -1)
    (3.9, 1000.0)
    """
    x = check_peaks(loads, "loads")
    if x.size < 10:
        raise ValueError(f"loads: {x.size} values are too few to fit a distribution (>= 10)")
    if method not in ("ml", "binned ls"):
        raise ValueError(f"method must be 'ml' or 'binned ls', got {method!r}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        if name == "weibull_mixture":
            params, frozen = _fit_mixture(x, loc, method)
            name_out = CANDIDATES[name]
        else:
            dist = _dist(name)
            params = _ml_fit(dist, x, {} if loc is None else {"floc": float(loc)})
            if method == "binned ls":
                params = tuple(float(v) for v in _binned_ls(dist, x, params, loc, bins))
            frozen, name_out = dist(*params), dist.name
        loglik = float(np.sum(frozen.logpdf(x)))
    k = len(params) - (loc is not None)
    ks = stats.kstest(x, frozen.cdf)
    return pd.Series({"distribution": name_out, "params": params, "n_params": k,
                      "loglik": loglik, "aic": 2 * k - 2 * loglik,
                      "ks_statistic": float(ks.statistic), "ks_pvalue": float(ks.pvalue),
                      "method": method, "dist": frozen})


def compare_load_distributions(loads, candidates=None, *, method="ml", loc=None, bins="auto"):
    """Fit the candidates and rank them by AIC (then KS p-value).

    Parameters
    ----------
    loads : array_like
        Peak loads of the impacts.
    candidates : sequence of str, optional
        Keys of :data:`CANDIDATES`; default all.
    method, loc, bins
        See :func:`fit_load_distribution`.

    Returns
    -------
    pandas.DataFrame
        One row per candidate (index), best first, with ``delta_aic``; a
        candidate whose fit failed has NaN scores and is last.

    Examples
    --------
    >>> from scipy import stats
    >>> x = stats.lognorm(0.5, scale=800.0).rvs(3000, random_state=2)
    >>> compare_load_distributions(x, loc=0.0).index[0]
    'lognormal'
    """
    rows = {}
    for name in candidates or CANDIDATES:
        try:
            rows[name] = fit_load_distribution(loads, name, method=method, loc=loc, bins=bins)
        except (ValueError, RuntimeError, FloatingPointError) as exc:
            if "too few" in str(exc) or "must be one of" in str(exc):
                raise
            rows[name] = pd.Series({"distribution": CANDIDATES[name], "method": method,
                                    "aic": np.nan, "error": str(exc)})
    table = pd.DataFrame(rows).T
    table["aic"] = table["aic"].astype(float)
    table = table.sort_values(["aic", "ks_pvalue"], ascending=[True, False], na_position="last")
    table["delta_aic"] = table["aic"] - table["aic"].min()
    table.index.name = "candidate"
    return table


def qq_points(loads, distribution):
    """Q–Q data: sorted loads against the fitted quantiles at ``i/(n + 1)``.

    Returns
    -------
    pandas.DataFrame
        ``theoretical``, ``empirical`` (ascending).

    Examples
    --------
    >>> from scipy import stats
    >>> qq_points([3.0, 1.0, 2.0], stats.uniform(0, 4)).values.tolist()
    [[1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]
    """
    x = np.sort(check_peaks(loads, "loads"))
    p = np.arange(1, x.size + 1) / (x.size + 1.0)
    return pd.DataFrame({"theoretical": distribution.ppf(p), "empirical": x})
