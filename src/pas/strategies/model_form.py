"""Model-form uncertainty in the model band: the semi-empirical distribution (beyond the paper).

The bootstrap of :mod:`pas.strategies.band` resamples the evaluated events and
refits the same family of models, so it carries the sampling uncertainty of
the fit but not a bias that every refit shares: a conditional law the
candidates do not contain (``docs/explanation/known-truth.md``, held-out types).  Where
HF values were measured the model is not needed.  The *semi-empirical*
distribution of a fitted model puts every evaluated event at its observed HF
value (0 for a false positive) in each of the ``z`` realisations and lets the
model draw only the events not evaluated — the top of the LF pool, which
screening evaluates first, then rests on data (a design-based estimator in
the spirit of Horvitz & Thompson 1952, with the model as the imputation of
the events not sampled).  With ``ModelBand(model_form="semi-empirical")``
each bootstrap replicate reads the MPM of both distributions from its model,
and the band spans the 2.5–97.5 % ranges of both sets of replicate MPMs:
where the model and the data disagree about the evaluated events, the band
holds both answers.  The point estimate (the MPM) is not changed.

The observed values are those of the study's pairs, not of the replicate's
resample: a measured load is a fact about its event, not a sample of a law.
"""

from __future__ import annotations

import numpy as np

from ..stats.exceedance import mpm_of_realisations

__all__ = ["MODEL_FORMS", "semi_empirical", "replicate_values", "band_ends"]

MODEL_FORMS = ("none", "semi-empirical")
"""The choices of ``ModelBand.model_form``."""


def semi_empirical(draws, pairs) -> np.ndarray:
    """``draws`` (shape ``(z, n0)``, the top ``n0`` events in LF order) with every
    evaluated event of ``pairs`` at its observed HF value (0 for a false positive).

    A true positive below the draws' conditioning set (a replicate's set ends at
    its own lowest LF) is added as a column of its observed value.
    """
    draws = np.array(draws, dtype=float)
    n0 = draws.shape[1]
    positions = np.concatenate([pairs.position, pairs.fp_position]).astype(int)
    values = np.concatenate([np.asarray(pairs.hf, float), np.zeros(len(pairs.fp_position))])
    inside = positions < n0
    draws[:, positions[inside]] = values[inside]
    below = values[~inside & (values > 0)]
    if below.size:
        draws = np.hstack([draws, np.broadcast_to(below, (draws.shape[0], below.size))])
    return draws


def replicate_values(draws, pairs, lfset, model_form: str) -> tuple:
    """A replicate's MPMs: ``(model,)``, or ``(model, semi-empirical)`` with
    ``model_form="semi-empirical"``; ``pairs`` the study's evaluated events."""
    model = mpm_of_realisations(draws, lfset.n_waves, lfset.p_exp)
    if model_form == "none":
        return (model,)
    return model, mpm_of_realisations(semi_empirical(draws, pairs), lfset.n_waves, lfset.p_exp)


def band_ends(values) -> tuple | None:
    """``(low, high, model MPMs)`` of the replicates' :func:`replicate_values` (None where a
    replicate failed): each form's 2.5–97.5 % range, the union of them; None when fewer
    than 10 replicates could be fitted."""
    values = np.asarray([v for v in values if v is not None], dtype=float)
    if len(values) < 10:
        return None
    low = float(np.min(np.percentile(values, 2.5, axis=0)))
    high = float(np.max(np.percentile(values, 97.5, axis=0)))
    return low, high, values[:, 0]
