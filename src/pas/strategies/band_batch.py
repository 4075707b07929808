"""The model band's replicates fitted together (:func:`pas.strategies.band.replicate_mpms`).

:mod:`pas.strategies.band` prepares every replicate as one after another
would (the resampled pairs, their conditioning set and LF ranks, the joint
fits that can win them); here each candidate family and marginal is fitted
to all replicates of a chunk at once (:func:`pas.models.joint_batch.fit_joint_batch`)
and each replicate's model assembled as :meth:`pas.strategies.pas.PAS.fit`
assembles it with ``update=False``: per family the marginal of higher
likelihood, the family of lowest eligible AIC.
"""

from __future__ import annotations

import numpy as np

from ..models.joint import HF_MARGINALS, best_per_family, starts_cold
from ..models.joint_batch import fit_joint_batch
from .steps import FittedModel, joint_candidates

__all__ = ["Replicate", "batch_fits", "fits_in_order", "replicate_model"]


class Replicate(tuple):
    """A prepared replicate: ``(pairs, impact model, n0, LF ranks of the top n0 peaks,
    the joint fits it starts from by (family, marginal))``."""

    __slots__ = ()

    def __new__(cls, pairs, impact, n0, u_cond, starts):
        return super().__new__(cls, (pairs, impact, n0, u_cond, starts))


def fits_in_order(strategy, starts) -> list:
    """The ``(family, marginal)`` keys of ``starts`` in the order the estimator fits them
    (families as the strategy lists them, then the Weibull before the log-normal)."""
    return [(f, m) for f in strategy.families for m in HF_MARGINALS if (f, m) in starts]


def batch_fits(strategy, replicates: dict, cold_families, width: int) -> dict:
    """Every replicate's joint fits by ``(family, marginal)``, each candidate fitted to all
    the ``replicates`` (by index, :class:`Replicate`) that keep it at once; None for a
    replicate one of whose fits failed (its ValueError), as a fit one after another fails.

    ``cold_families`` also start from the data; ``width``: the padded number of
    distinct pairs (:func:`pas.models.joint_batch.weighted_pairs`), the same for
    every chunk so that a replicate's fit does not depend on the chunk it is in.
    """
    keys = []
    for rep in replicates.values():
        keys += [k for k in fits_in_order(strategy, rep[4]) if k not in keys]
    fits = {i: {} for i in replicates}
    memos = {}  # per replicate: what a cold start reads of its data (every family, marginal)
    for name, marginal in keys:
        rows = [i for i, rep in replicates.items() if (name, marginal) in rep[4]]
        samples = [(replicates[i][3][replicates[i][0].position], replicates[i][0].hf)
                   for i in rows]
        starts = [replicates[i][4][name, marginal].x for i in rows]
        out = fit_joint_batch(name, samples, starts,
                              location=strategy.estimator.hf_location, marginal=marginal,
                              cold=starts_cold(cold_families, name), width=width,
                              memos=[memos.setdefault(i, {}) for i in rows])
        for i, fit in zip(rows, out):
            fits[i][name, marginal] = fit
    return {i: None if any(isinstance(f, Exception) for f in f_i.values())
            else {k: f_i[k] for k in fits_in_order(strategy, f_i)} for i, f_i in fits.items()}


def replicate_model(strategy, lfset, rep, fits: dict) -> FittedModel:
    """The replicate's model from its joint fits, as :meth:`pas.strategies.pas.PAS.fit`
    with ``update=False`` makes it (:meth:`~pas.strategies.pas.PAS.model_of`)."""
    pairs, impact, n0, u_cond, _ = rep
    fitted = joint_candidates(best_per_family(fits), lfset.lf[:n0], u_cond,
                              np.ones(len(pairs), dtype=bool))
    return strategy.model_of(fitted, lfset, impact)
