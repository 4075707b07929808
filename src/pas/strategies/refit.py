"""A saved PAS result's final model, fitted again (:func:`refit`)."""

from __future__ import annotations

import numpy as np

from .base import Pairs
from .pas import PAS
from .screening import LFSet

__all__ = ["refit"]


def refit(result):
    """The final model of a PAS result (a :class:`~pas.strategies.steps.FittedModel`),
    fitted again from what the result holds.

    Uses the result's settings, pairs, false positives (history), selected
    family and the LF peaks it conditioned on (``distribution["lf"]``), so a
    saved result can be redrawn (:func:`pas.plotting.conditional_quantile_curves`)
    without the LF Monte-Carlo run.
    """
    dist = result.distribution
    if "lf" not in dist or not result.family:
        raise ValueError("the result holds no fitted PAS model (no 'lf' column in its "
                         "distribution, or no copula family)")
    settings = dict((result.settings or {}).get("strategy_settings", {}))
    strategy = PAS.from_flat(settings, strict=False)  # stored: pas 0.1 kept every option
    strategy.reset(result.seed)
    lfset = LFSet(dist["lf"].to_numpy(float), n_waves=result.n_waves, p_exp=result.p_exp,
                  threshold=(result.settings or {}).get("threshold"))
    lf = result.pairs["lf"].to_numpy(float)
    pos = np.clip(lfset.n - np.searchsorted(lfset.lf[::-1], lf, side="right"), 0, lfset.n - 1)
    hist = result.history
    fp_lf = hist.loc[hist["status"] == "false_positive", "lf"].to_numpy(float)
    pairs = Pairs(pos, lf, result.pairs["hf"].to_numpy(float), lfset.d[pos], fp_lf,
                  np.zeros(fp_lf.size, dtype=int))
    return strategy.fit(pairs, lfset, family=result.family)
