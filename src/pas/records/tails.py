"""Named tail models that extrapolate a record beyond its largest peak.

A record of ``n_e`` encounters can only resolve exceedance probabilities down
to about ``1/n_e``; a target beyond that (a long exposure, a high quantile) is
a NaN or an error in :mod:`pas.records.records` unless one of these models is
asked for by name:

* ``"weibull"`` — 3-parameter Weibull by least squares on Weibull paper
  (:func:`pas.stats.fit_weibull3_ls`) to the top ``top_fraction`` of the
  peaks (PAS paper Eq. 15; 0.3 for crests, the validation truths use it);
  per-encounter exceedance ``(n_p/n_e) · P_W(X > x)``.
* ``"gpd"`` — generalised Pareto by maximum likelihood
  (``scipy.stats.genpareto.fit``, location fixed at the threshold) to the
  peaks above the ``ceil(top_fraction · n_p)``-th largest (peaks over
  threshold, as pyextremes' POT model); per-encounter exceedance
  ``(n_u/n_e) · P_GPD(X − u > x − u)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

from ..stats.weibull import fit_weibull3_ls

__all__ = ["TAIL_MODELS", "TailModel", "fit_tail"]

TAIL_MODELS = {"weibull": 0.3, "gpd": 0.1}  # name -> default top fraction


@dataclass(frozen=True)
class TailModel:
    """A fitted tail: ``exceedance(x) = rate · dist.sf(x)`` per encounter.

    Attributes
    ----------
    name : str
        ``"weibull"`` or ``"gpd"``.
    dist : object
        Distribution of a peak (``Weibull3`` or a frozen ``scipy.stats`` GPD)
        with ``sf`` and ``isf``.
    rate : float
        Probability per encounter of a peak in the fitted population.
    threshold : float
        Smallest value the model describes (the GPD threshold, the smallest
        fitted Weibull value).
    """

    name: str
    dist: object
    rate: float
    threshold: float

    def exceedance(self, x):
        """Exceedance probability per encounter of ``x`` (valid for ``x ≥ threshold``)."""
        return self.rate * self.dist.sf(np.asarray(x, dtype=float))

    def value_at_exceedance(self, p):
        """The value exceeded with probability ``p`` per encounter; NaN where ``p ≥ rate``."""
        ratio = np.asarray(p, dtype=float) / self.rate
        out = np.where(ratio < 1.0, self.dist.isf(np.minimum(ratio, 1.0 - 1e-16)), np.nan)
        return float(out) if out.ndim == 0 else out


def fit_tail(pooled, n_encounters, model, *, top_fraction=None):
    """Fit the named tail model (module docs) to pooled peaks.

    Parameters
    ----------
    pooled : array_like
        All peaks of the record.
    n_encounters : int
        Encounters in the record.
    model : {"weibull", "gpd"}
    top_fraction : float, optional
        Fraction of the largest peaks fitted; default 0.3 (Weibull), 0.1 (GPD).

    Returns
    -------
    TailModel

    Examples
    --------
    >>> import numpy as np
    >>> x = np.random.default_rng(0).exponential(1.0, 20000)
    >>> t = fit_tail(x, 20000, "gpd")
    >>> round(float(t.value_at_exceedance(1e-6)), 1)   # exact: ln(1e6) = 13.8
    13.5
    """
    if model not in TAIL_MODELS:
        raise ValueError(f"extrapolate must be one of {sorted(TAIL_MODELS)} (a named tail "
                         f"model), got {model!r}")
    x = np.sort(np.asarray(pooled, dtype=float))[::-1]
    frac = TAIL_MODELS[model] if top_fraction is None else float(top_fraction)
    if not 0.0 < frac <= 1.0:
        raise ValueError(f"top_fraction must be in (0, 1], got {top_fraction!r}")
    if model == "weibull":
        fit = fit_weibull3_ls(x, top_fraction=frac)
        k = max(3, int(np.ceil(frac * x.size)))
        return TailModel("weibull", fit, x.size / n_encounters, float(x[k - 1]))
    k = int(np.ceil(frac * x.size))
    if k < 10 or k >= x.size:
        raise ValueError(f"a GPD tail needs at least 10 peaks above its threshold and one "
                         f"below; top_fraction={frac:g} of {x.size} peaks gives {k}")
    u = float(x[k])
    exc = x[:k] - u
    c, _, scale = stats.genpareto.fit(exc, floc=0.0)
    return TailModel("gpd", stats.genpareto(c, loc=u, scale=scale), k / n_encounters, u)
