"""What every screening strategy provides, so one study loop runs PAS and AS alike.

A strategy turns the current LF–HF pairs into a predicted HF exceedance
distribution (:meth:`Strategy.predict`) and proposes where to sample next
(:meth:`Strategy.propose`).  Everything about *running* a campaign — the
oracle, false positives, failures, the adaptive threshold, stopping, the
store — lives in :mod:`pas.study`, not here.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field

import numpy as np

from ..stats.exceedance import value_at_exceedance
from .acquisition import initial_targets, md_select, nearest_available
from .screening import LFSet

__all__ = ["Pairs", "Prediction", "Strategy", "Z95", "band95", "read_only"]

Z95 = 1.96
"""Half-width of the U95 bands in standard deviations, as printed in the paper (Eq. 10)."""


def band95(mean, sd):
    """The U95 band ``(mean − Z95·sd, mean + Z95·sd)`` (Eq. 10)."""
    return mean - Z95 * sd, mean + Z95 * sd


@dataclass(frozen=True)
class Pairs:
    """The true-positive LF–HF pairs available to a fit.

    ``position`` indexes the :class:`~pas.strategies.screening.LFSet` order; ``lf``,
    ``hf`` and ``d`` (LF exceedance probability) are aligned with it.
    """

    position: np.ndarray
    lf: np.ndarray
    hf: np.ndarray
    d: np.ndarray
    #: LF values of the evaluated false positives (HF = 0), for impact models
    fp_lf: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: their positions in the LFSet order (for their exceedance probabilities)
    fp_position: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=int))

    def __len__(self) -> int:
        return int(self.position.size)

    def take(self, idx, fp_idx=None) -> "Pairs":
        """The pairs at ``idx`` (and the false positives at ``fp_idx``; all when None)."""
        fp = slice(None) if fp_idx is None else fp_idx
        return Pairs(self.position[idx], self.lf[idx], self.hf[idx], self.d[idx],
                     np.asarray(self.fp_lf)[fp], np.asarray(self.fp_position, dtype=int)[fp])


def read_only(values) -> np.ndarray:
    """A read-only view of the array ``values`` (the array itself stays writeable): what a
    prediction hands to the result's table, which shares it instead of copying."""
    view = np.asarray(values).view()
    view.flags.writeable = False
    return view


@dataclass
class Prediction:
    """A predicted HF exceedance distribution and its MPM (Steps 10–12).

    ``d`` ascending; ``h_mean`` the mean distribution, ``h_low``/``h_high`` its
    U95 band; ``mpm_band`` the band read at ``P_exp``; ``record`` holds the
    strategy-specific diagnostics written to the iteration history;
    ``columns`` optional per-rank arrays aligned with ``d`` (PAS: the LF peak
    conditioned on at each rank and its impact probability), written beside
    the distribution.
    """

    d: np.ndarray
    h_mean: np.ndarray
    h_low: np.ndarray
    h_high: np.ndarray
    mpm: float
    mpm_band: tuple
    record: dict = field(default_factory=dict)
    columns: dict = field(default_factory=dict)

    @classmethod
    def read_at(cls, p_exp: float, d, h_mean, h_low, h_high, record=None,
                columns=None) -> Prediction:
        """A distribution and its band, with the MPM and its band read at ``p_exp`` (Step 12)."""
        return cls(d=d, h_mean=h_mean, h_low=h_low, h_high=h_high,
                   mpm=float(value_at_exceedance(d, h_mean, p_exp)),
                   mpm_band=(float(value_at_exceedance(d, h_low, p_exp)),
                             float(value_at_exceedance(d, h_high, p_exp))),
                   record={} if record is None else record,
                   columns={} if columns is None else columns)

    def at(self, p):
        """The mean distribution interpolated at probabilities ``p`` on ``ln d``."""
        return value_at_exceedance(self.d, self.h_mean, p)


class Strategy(ABC):
    """Base class of screening strategies (PAS, AS).

    Subclasses set ``name``, ``n_initial`` and ``min_pairs`` and implement
    :meth:`predict`.  The default :meth:`initial_positions` spreads the
    initial samples uniformly over ``ln d`` (§2.5) and :meth:`propose` is MD
    (Eq. 16–17); AS overrides :meth:`propose` with MVPD.
    """

    name: str = "base"
    n_initial: int = 4
    min_pairs: int = 4
    #: samples spread over the whole LF range, so Kendall's tau of the pairs
    #: measures the indicator (False for strategies that cluster samples)
    spreads_samples: bool = True

    def reset(self, seed: int | None = None) -> None:
        """Start a study: forget state carried between iterations (e.g. the selected copula).

        ``seed`` is the study's seed, for random numbers a strategy keeps for the
        whole study (PAS's common random numbers).
        """

    @abstractmethod
    def predict(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator) -> Prediction:
        """Fit the model to ``pairs`` and predict the HF distribution."""

    def initial_positions(self, lfset: LFSet, available=None) -> list[int]:
        """Initial samples: ``n_initial`` positions uniformly spaced on ``ln d`` (§2.5).

        With ``available`` (after failed oracle calls) the nearest peaks still
        available to the same targets.
        """
        available = np.ones(lfset.n, dtype=bool) if available is None else available.copy()
        out = []
        for t in initial_targets(lfset.ln_d, min(self.n_initial, lfset.n)):
            p = nearest_available(lfset.ln_d, available, t)
            if p < 0:
                break
            available[p] = False
            out.append(p)
        return out

    def propose(self, selected_d, lfset: LFSet, available: np.ndarray,
                last: Prediction | None, q: int = 1) -> list[int]:
        """Next ``q`` positions by maximum distance on ``ln d`` (Eq. 16–17).

        ``selected_d`` are the LF exceedance probabilities of the selected
        samples — every evaluated or pending event, false positives included
        (§2.4; the study decides); ``available`` marks pool positions that may
        still be chosen.  Gaps no pool peak can split are skipped
        (:func:`~pas.strategies.acquisition.md_select`).
        """
        return md_select(lfset.ln_d, available, np.log(selected_d), q)

    def model_band(self, pairs: Pairs, lfset: LFSet, rng: np.random.Generator, *,
                   n_jobs: int | None = None):
        """Optional U95 band of the MPM including model uncertainty, or None (``n_jobs``:
        the processes it may use, :meth:`pas.strategies.pas.PAS.model_band`)."""
        return None
