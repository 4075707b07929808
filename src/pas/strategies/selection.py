"""Selection-aware estimation: fit PAS's model for the LF population, not for the MD sample.

Beyond the paper.  MD (Eq. 16–17) spreads the HF samples uniformly over
``ln d``, so the selected pairs are tail-heavy: the ten largest of 15 000 LF
peaks are as likely to be sampled as the lowest 5 000.  The paper fits the
copula and both marginals in this "selected-sample space" (§5.4), which is
self-consistent only as far as a one-parameter copula and a Weibull marginal
can describe such a sample.  Because MD chooses events by their LF value
alone, the HF law *given* LF is the same in the sample and in the
population; what differs is how many LF peaks each pair stands for.  Here
each pair is weighted by that number and the model is fitted to the
population it represents:

* :func:`representation_weights` — the LF peaks of the conditioning set
  nearest (on ``ln d``) to each evaluated event, false positives included, so
  a true positive stands for the *impacting* part of its stratum;
* :func:`impact_probability` — ``P(impact | LF)`` from the true and false
  positives, so a draw can be "no impact" (the paper draws a positive load
  for every conditioning peak);
* :func:`population_lf_ranks` — the LF pseudo-observations from the known
  LF population itself (every conditioning peak, each counted with its impact
  probability), used both for the pairs and for the conditional draws of
  Eq. 6, so no LF marginal needs fitting;
* the HF pseudo-observations and the Weibull HF marginal use the weighted
  ranks (:func:`pas.copulas.weighted_ranks`), the copula likelihood the
  weights (pyvinecopulib's weighted MLE).
"""

from __future__ import annotations

import numpy as np

__all__ = ["representation_weights", "impact_probability", "population_lf_ranks"]


def representation_weights(ln_d_pairs, ln_d_evaluated, ln_d_pool) -> np.ndarray:
    """How many pool peaks each pair stands for: nearest-neighbour cells on ``ln d``.

    Parameters
    ----------
    ln_d_pairs : array-like, shape (m,)
        ``ln d`` of the true-positive pairs (a subset of ``ln_d_evaluated``).
    ln_d_evaluated : array-like
        ``ln d`` of every evaluated event, true and false positives.
    ln_d_pool : array-like
        ``ln d`` of the LF peaks the model stands for (the conditioning set).

    Returns
    -------
    ndarray, shape (m,)
        Counts ≥ 1 when every pair is in the pool.

    Examples
    --------
    >>> import numpy as np
    >>> pool = np.log(np.arange(1, 11) / 10)
    >>> representation_weights(pool[[0, 9]], pool[[0, 5, 9]], pool).tolist()
    [5, 2]
    """
    ev = np.unique(np.asarray(ln_d_evaluated, float))
    mids = 0.5 * (ev[1:] + ev[:-1])
    counts = np.bincount(np.searchsorted(mids, np.asarray(ln_d_pool, float)),
                         minlength=ev.size)
    return counts[np.searchsorted(ev, np.asarray(ln_d_pairs, float))]


def impact_probability(lf_true, lf_false):
    """``P(impact | LF)``: logistic regression of true (1) vs false (0) positives on LF.

    Returns a vectorised callable, or ``None`` when no false positive has been
    seen.  MD selects events by LF alone, so the regression needs no weights.
    """
    lf_false = np.asarray(lf_false, float)
    if lf_false.size == 0:
        return None
    from sklearn.linear_model import LogisticRegression

    x = np.r_[np.asarray(lf_true, float), lf_false]
    y = np.r_[np.ones(len(lf_true)), np.zeros(lf_false.size)]
    mu, sd = x.mean(), x.std() or 1.0
    model = LogisticRegression(C=1.0).fit(((x - mu) / sd)[:, None], y)
    return lambda l: model.predict_proba(((np.asarray(l, float) - mu) / sd)[:, None])[:, 1]


def population_lf_ranks(lf_pool, impact=None) -> np.ndarray:
    """LF pseudo-observations of every pool peak in the population of impacts.

    ``u_j`` is the weighted mid-rank of ``lf_pool[j]`` with weights
    ``P(impact | l_j)`` (all 1 without an impact model): the LF marginal of the
    population the copula describes, known without fitting.
    """
    from ..stats.dependence import weighted_ranks

    lf_pool = np.asarray(lf_pool, float)
    w = np.ones(lf_pool.size) if impact is None else np.maximum(impact(lf_pool), 1e-6)
    return weighted_ranks(lf_pool, w)
