"""The LF screening set shared by every strategy: steps 1–4 of the paper (§2.1).

An :class:`LFSet` holds the LF indicator peaks over the threshold (Eq. 2),
sorted descending with their exceedance probabilities ``d = k / n_w``
(Eq. 3), and maps each *position* in that order back to the user's event
(``index`` in the input array and ``id``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._support.checks import (
    check_finite,
    check_open_unit,
    check_option,
    check_peaks,
    check_positive_int,
)
from .._support.strict_json import json_data
from ..stats.exceedance import exceedance_probabilities

__all__ = ["Event", "LFSet", "peaks_over_threshold", "check_n_waves", "N_WAVES_CONVENTIONS"]

N_WAVES_CONVENTIONS = ("count", "spectral")
"""How ``n_waves`` was obtained: counted wave encounters (one LF peak per
encounter at most) or ``T_MCS / T_p,e`` from a spectral period (paper Table 2,
the validation cases), which may lie below the number of LF peaks."""


@dataclass(frozen=True)
class Event:
    """One wave event offered to the HF oracle.

    Attributes
    ----------
    index : int
        0-based position of the event in the user's ``lf_peaks``.
    id : object
        The user's id for the event (``index`` when none was given).
    lf : float
        Its LF indicator peak value.
    d : float
        Its LF exceedance probability ``k / n_w``.
    meta : dict
        Whatever the user attached to the event (seed, time window, ...), as plain JSON
        data — numpy scalars as numbers, NaN as None — the same before and after the
        study is stored and resumed.
    sea_state : str, optional
        The sea state the event belongs to in a long-term analysis
        (:func:`pas.run_long_term`); None for a single-sea-state study.
    """

    index: int
    id: object
    lf: float
    d: float
    meta: dict = field(default_factory=dict, compare=False, repr=False)
    sea_state: str | None = None


def peaks_over_threshold(lf, threshold=None) -> np.ndarray:
    """Steps 1–4: mask of the LF peaks strictly above ``threshold`` (Eq. 2); all if None."""
    lf = np.asarray(lf, dtype=float)
    if threshold is None:
        return np.ones(lf.shape, dtype=bool)
    return lf > threshold


def check_n_waves(lf_peaks, n_waves, threshold=None, *, convention="count",
                  names=None):
    """Refuse an ``n_waves`` that makes exceedance probabilities exceed 1 (Eq. 3).

    The k-th largest LF peak over the threshold gets ``d = k / n_w``, so
    ``n_w`` below the number of peaks over the threshold gives ``d > 1`` for
    the smallest ones: a ``ValueError``.  ``n_w`` below the number of all
    given peaks (one per wave encounter) is suspicious and returns a one-line
    warning text.  With ``convention="spectral"`` (``n_w = T_MCS / T_p,e`` on
    purpose, as the paper's Table 2 and :mod:`pas.validation` do) neither is
    checked.

    Parameters
    ----------
    lf_peaks : array-like
        All LF peaks given (below the threshold included).
    n_waves : int
        Wave encounters ``n_w`` in the LF Monte-Carlo duration.
    threshold : float, optional
        LF threshold ``l0_input`` (Eq. 2).
    convention : {"count", "spectral"}
        :data:`N_WAVES_CONVENTIONS`.
    names : dict, optional
        How the message calls ``n_waves`` and ``convention`` (the CLI gives
        its option names).

    Returns
    -------
    str or None
        The warning text, or None when ``n_waves`` is plausible.

    Examples
    --------
    >>> check_n_waves([3.0, 2.0, 1.0], 2, threshold=1.5) is None
    False
    >>> check_n_waves([3.0, 2.0, 1.0], 1, threshold=1.5)
    Traceback (most recent call last):
    ...
    ValueError: n_waves=1 is below the 2 LF peaks over the threshold: their exceedance \
probabilities k/n_w would reach 2 (above 1); give the number of wave encounters in the \
LF run (at least 2), or convention='spectral' when n_w = T_MCS/T_p,e on purpose (paper Table 2)
    """
    names = {"n_waves": "n_waves", "convention": "convention='spectral'", **(names or {})}
    convention = check_option(convention, names["convention"].split("=")[0],
                              N_WAVES_CONVENTIONS)
    n_waves = check_positive_int(n_waves, "n_waves")
    lf = check_peaks(lf_peaks, "lf_peaks")
    threshold = None if threshold is None else check_finite(threshold, "threshold")
    if convention == "spectral":
        return None
    n_over = int(peaks_over_threshold(lf, threshold).sum())
    if n_over > n_waves:
        raise ValueError(
            f"{names['n_waves']}={n_waves} is below the {n_over} LF peaks over the threshold: "
            f"their exceedance probabilities k/n_w would reach {n_over / n_waves:.3g} (above 1); "
            f"give the number of wave encounters in the LF run (at least {n_over}), or "
            f"{names['convention']} when n_w = T_MCS/T_p,e on purpose (paper Table 2)")
    if lf.size > n_waves:
        return (f"{names['n_waves']}={n_waves} is below the {lf.size} LF peaks given "
                f"({n_over} over the threshold): with one peak per wave encounter n_w is at least "
                f"{lf.size}; say {names['convention']} if n_w = T_MCS/T_p,e on purpose")
    return None


class LFSet:
    """LF peaks over threshold with exceedance probabilities (steps 1–4).

    Parameters
    ----------
    lf_peaks : array-like, shape (n_events,)
        LF indicator peak of every event.
    n_waves : int
        Number of wave encounters ``n_w`` in the LF Monte-Carlo duration.
    p_exp : float
        Target exceedance probability, used only to check that the pool reaches it.
    threshold : float, optional
        LF threshold ``l0_input``.
    ids : sequence, optional
        User ids of the events (default: their index).
    meta : sequence of dict, optional
        Per-event metadata passed to the oracle on :class:`Event`.
    min_peaks : int, default 4
        Fewest peaks above the threshold PAS can work with.
    sea_state : str, optional
        Name of the sea state, carried on every :class:`Event` (long-term analysis).
    """

    def __init__(self, lf_peaks, *, n_waves, p_exp, threshold=None, ids=None, meta=None,
                 min_peaks: int = 4, sea_state: str | None = None):
        lf_all = check_peaks(lf_peaks, "lf_peaks")
        self.n_waves = check_positive_int(n_waves, "n_waves")
        self.p_exp = check_open_unit(p_exp, "p_exp")
        self.threshold = None if threshold is None else check_finite(threshold, "threshold")
        if ids is not None:
            ids = list(ids)
            if len(ids) != lf_all.size:
                raise ValueError(f"ids has {len(ids)} entries but lf_peaks has {lf_all.size}")
            if len(set(map(str, ids))) != len(ids):
                raise ValueError("ids must be unique")
        if meta is not None and len(meta) != lf_all.size:
            raise ValueError(f"meta has {len(meta)} entries but lf_peaks has {lf_all.size}")
        keep = np.flatnonzero(peaks_over_threshold(lf_all, self.threshold))
        if keep.size < min_peaks and self.threshold is None:
            raise ValueError(f"lf_peaks: only {keep.size} LF peak(s) given; the screening "
                             f"needs at least {min_peaks}")
        if keep.size < min_peaks:
            raise ValueError(
                f"threshold: only {keep.size} LF peak(s) lie above threshold={threshold}; "
                f"the screening needs at least {min_peaks}: lower the threshold"
            )
        order = keep[np.argsort(-lf_all[keep], kind="stable")]
        self.index = order
        self.d, self.lf = exceedance_probabilities(lf_all[order], self.n_waves)
        self.ln_d = np.log(self.d)
        self.n = order.size
        if self.p_exp < self.d[0] or self.p_exp > self.d[-1]:
            raise ValueError(
                f"p_exp={self.p_exp:g} lies outside the LF exceedance range "
                f"[{self.d[0]:g}, {self.d[-1]:g}] of the {self.n} peaks over threshold: "
                "lower the threshold or use a longer LF record"
            )
        self._ids = ids
        self._meta = meta
        self.sea_state = sea_state

    def event(self, position: int) -> Event:
        """The :class:`Event` at ``position`` in the descending order."""
        i = int(self.index[position])
        return Event(
            index=i,
            id=self._ids[i] if self._ids is not None else i,
            lf=float(self.lf[position]),
            d=float(self.d[position]),
            meta=json_data(dict(self._meta[i])) if self._meta is not None else {},
            sea_state=self.sea_state,
        )

    def position_of(self, index: int) -> int:
        """Position of the user's event ``index`` (ValueError if below the threshold)."""
        hit = np.flatnonzero(self.index == index)
        if hit.size == 0:
            raise ValueError(f"event index {index} is not in the LF set (below the threshold?)")
        return int(hit[0])
