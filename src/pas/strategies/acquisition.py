"""Sample selection on the LF exceedance axis: initial samples and MD.

Paper §2.4–2.5, Eq. 4, 16, 17.  Everything works on ``ln d``, the logarithm of
the LF exceedance probability, so samples spread over the tail.

MD as printed (Eq. 16–17) targets the midpoint of the largest gap between
selected samples and takes the nearest unselected pool peak.  Near the top of
the LF distribution the pool is discrete (``d = 1/n_w, 2/n_w, …``): once both
neighbours of a gap such as ``[1/n_w, 2/n_w]`` are selected, no peak can ever
split it, the nearest peak lies *outside* the gap, and the paper's rule keeps
returning to the same gap, walking down the ranks one by one.  The default
(``skip_unsplittable=True``) therefore only considers gaps that contain at
least one available peak; ``skip_unsplittable=False`` is Eq. 16–17 verbatim.
"""

from __future__ import annotations

import numpy as np

__all__ = ["initial_targets", "nearest_available", "md_select"]


def initial_targets(ln_d: np.ndarray, m: int) -> np.ndarray:
    """Step 5: ``m`` targets spaced uniformly over ``ln d``, largest to smallest peak (§2.5)."""
    return np.linspace(ln_d[0], ln_d[-1], m)


def nearest_available(ln_d: np.ndarray, available: np.ndarray, target: float) -> int:
    """Position of the available pool peak closest to ``target`` on ``ln d`` (Eq. 4, 17).

    ``ln_d`` is ascending; ties go to the rarer (larger) peak.  Returns -1 when
    nothing is available.
    """
    idx = np.flatnonzero(available)
    if idx.size == 0:
        return -1
    j = np.searchsorted(ln_d[idx], target)
    cand = idx[max(j - 1, 0): j + 1]
    return int(cand[np.argmin(np.abs(ln_d[cand] - target))])


def md_select(ln_d: np.ndarray, available: np.ndarray, ln_d_selected, q: int = 1, *,
              skip_unsplittable: bool = True) -> list[int]:
    """Maximum-distance acquisition (Eq. 16–17), generalised to a batch of ``q``.

    Parameters
    ----------
    ln_d : ndarray
        ``ln d`` of the whole pool, ascending.
    available : ndarray of bool
        Pool positions that may be chosen.
    ln_d_selected : array-like
        ``ln d`` of the selected samples (the study passes every evaluated or
        pending event, false positives included), at least two.
    q : int
        Batch size; the batch is filled sequentially, each chosen peak joining
        the selected set before the next gap is sought.
    skip_unsplittable : bool, default True
        Ignore gaps with no available peak inside (module docs); when no gap
        can be split, fall back to the paper's rule.

    Returns
    -------
    list of int
        Chosen positions (fewer than ``q`` when the pool runs out).
    """
    sel = np.sort(np.asarray(ln_d_selected, dtype=float))
    if sel.size < 2:
        raise ValueError("MD acquisition needs at least two selected samples")
    available = available.copy()
    out = []
    for _ in range(q):
        lo, hi = sel[:-1], sel[1:]
        width = hi - lo
        if skip_unsplittable:
            cum = np.concatenate([[0], np.cumsum(available)])
            inside = (
                cum[np.searchsorted(ln_d, hi, "left")] - cum[np.searchsorted(ln_d, lo, "right")]
            )
            if (inside > 0).any():
                width = np.where(inside > 0, width, -np.inf)
        k = int(np.argmax(width))
        p = nearest_available(ln_d, available, lo[k] + (hi[k] - lo[k]) / 2.0)
        if p < 0:
            break
        out.append(p)
        available[p] = False
        sel = np.sort(np.append(sel, ln_d[p]))
    return out
