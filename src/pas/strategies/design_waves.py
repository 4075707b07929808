"""Design waves as a study strategy: the episodes of a ladder of levels, all in one ask.

A design-wave prediction (FORM-RCW or MLER, Dermatis et al. 2025) evaluates
one HF episode per exceedance level and fits no model.  Run as a
:class:`~pas.study.study.Study`, the episodes are its events
(:class:`LevelLadder`): the first ask returns all of them, the study is then
finished, and the HF results, failures, resumes and corrections go through
the study loop and store as for PAS.  The episodes themselves and the result
are built by :func:`pas.run_rcw` (:mod:`pas.design_waves`).
"""

from __future__ import annotations

import sys

import numpy as np

from .base import Strategy
from .screening import LFSet

__all__ = ["DesignWaves", "LevelLadder", "DESIGN_WAVE_METHODS"]

DESIGN_WAVE_METHODS = {"form": "rcw", "mler": "mler"}
"""Conditioning method -> the strategy name a study stores and a result carries."""


class LevelLadder(LFSet):
    """The events of a design-wave study: one per level, in ladder order.

    Position ``i`` is episode ``i``: ``lf`` its linear target, ``d`` its level,
    ``id`` the episode's id, ``meta`` ``{"level", "target"}``.

    Parameters
    ----------
    levels : array_like
        Exceedance probabilities per wave encounter, descending, ``p_exp`` among them.
    targets : array_like
        Linear target response per level (non-zero, any sign).
    ids : sequence of str
        Episode ids (:attr:`pas.waves.episode.Episode.id`).
    p_exp : float
    n_waves : int, optional
        Wave encounters of the LF Monte-Carlo, when there is one.
    """

    def __init__(self, levels, targets, *, ids, p_exp, n_waves=None):
        self.d = np.asarray(levels, dtype=float)
        self.lf = np.asarray(targets, dtype=float)
        ids = [str(i) for i in ids]
        if not (self.d.shape == self.lf.shape == (len(ids),)) or not self.d.size:
            raise ValueError("levels, targets and ids must be one per episode")
        self.n = self.d.size
        self.index = np.arange(self.n)
        self.ln_d = np.log(self.d)
        self.p_exp = float(p_exp)
        self.n_waves = None if n_waves is None else int(n_waves)
        self.threshold = None
        self.sea_state = None
        self._ids = ids
        self._meta = [{"level": float(p), "target": float(t)} for p, t in zip(self.d, self.lf)]


class DesignWaves(Strategy):
    """Every episode of the ladder in the first ask; no model, no further asks.

    Parameters
    ----------
    method : {"form", "mler"}, default "form"
        How the episodes were conditioned; the strategy's ``name`` is
        ``"rcw"`` or ``"mler"`` (:data:`DESIGN_WAVE_METHODS`).
    """

    n_initial = 1
    min_pairs = sys.maxsize  # the study never fits: a design wave has no model
    spreads_samples = False

    def __init__(self, method: str = "form"):
        if method not in DESIGN_WAVE_METHODS:
            raise ValueError(f"method must be one of {', '.join(DESIGN_WAVE_METHODS)}, "
                             f"got {method!r}")
        self.method = method

    @property
    def name(self) -> str:
        return DESIGN_WAVE_METHODS[self.method]

    def initial_positions(self, lfset, available=None) -> list[int]:
        """Every episode still available, in ladder order."""
        mask = np.ones(lfset.n, dtype=bool) if available is None else available
        return [int(p) for p in np.flatnonzero(mask)]

    def propose(self, selected_d, lfset, available, last, q=1) -> list[int]:
        """Nothing: the ladder was asked for at once."""
        return []

    def predict(self, pairs, lfset, rng):
        """Not used: a design-wave result is read off its HF values (:func:`pas.run_rcw`)."""
        raise NotImplementedError("design waves fit no model; pas.run_rcw reads the result "
                                  "off the HF values of the episodes")
