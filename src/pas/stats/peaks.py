"""Peak extraction from time series: pure functions over 1-D arrays.

A *wave* is the stretch between two consecutive zero up-crossings of a
reference signal (the LF signal, or the surface elevation). Its crest is the
maximum and its trough the minimum inside that window. Everything here is
vectorised (``np.maximum.reduceat`` and friends); nothing loops over samples.

Conventions
-----------
* :func:`zero_upcrossings` returns the index ``i + 1`` of the first sample at or
  above the level after a crossing between samples ``i`` (below the level) and
  ``i + 1``. Wave ``k`` spans samples ``[u[k], u[k+1])``; the incomplete parts
  before the first and after the last up-crossing are not waves.
* Hogging/sagging or trough-type peaks are obtained by applying the crest
  functions to ``-x``.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "zero_upcrossings",
    "upcrossing_times",
    "segment_max",
    "segment_min",
    "wave_crests",
    "wave_troughs",
    "matched_peaks",
    "rise_times",
    "rise_velocities",
    "peaks_over_threshold",
    "mask_near_joins",
]


def _signal(x, name="x", min_size=2):
    a = np.asarray(x, dtype=float)
    if a.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {a.shape}")
    if a.size < min_size:
        raise ValueError(f"{name} must hold at least {min_size} samples, got {a.size}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} contains NaN or inf; clean or interpolate the record first")
    return a


def _indices(idx, n, name):
    i = np.asarray(idx)
    if i.ndim != 1 or (i.size and not np.issubdtype(i.dtype, np.integer)):
        raise ValueError(f"{name} must be a 1-D integer array")
    if i.size and (i[0] < 0 or i[-1] > n or np.any(np.diff(i) <= 0)):
        raise ValueError(f"{name} must be strictly increasing indices within the signal")
    return i.astype(np.intp)


def zero_upcrossings(x, *, level=0.0):
    """Indices of the first sample at or above ``level`` after each up-crossing.

    Parameters
    ----------
    x : array_like, shape (n,)
    level : float, default 0

    Returns
    -------
    ndarray of int

    Examples
    --------
    >>> zero_upcrossings([-1.0, 2.0, 1.0, -1.0, 0.0, 3.0, -2.0])
    array([1, 4])
    """
    a = _signal(x)
    return np.flatnonzero((a[:-1] < level) & (a[1:] >= level)) + 1


def upcrossing_times(t, x, upcross=None, *, level=0.0):
    """Up-crossing times by linear interpolation between the bracketing samples."""
    a = _signal(x)
    tt = _signal(t, "t")
    if tt.shape != a.shape:
        raise ValueError("t and x must have the same length")
    u = (
        zero_upcrossings(a, level=level)
        if upcross is None
        else _indices(upcross, a.size - 1, "upcross")
    )
    if u.size and u[0] < 1:
        raise ValueError("an up-crossing index must be >= 1")
    x0, x1 = a[u - 1], a[u]
    return tt[u - 1] + (level - x0) / (x1 - x0) * (tt[u] - tt[u - 1])


def _segment_extreme(a, starts, fn):
    if starts.size < 2:
        return np.empty(0), np.empty(0, dtype=np.intp)
    lo, hi = starts[0], starts[-1]
    seg = a[lo:hi]
    rel = starts[:-1] - lo
    values = fn.reduceat(seg, rel)
    lengths = np.diff(starts)
    hit = np.flatnonzero(seg == np.repeat(values, lengths))
    seg_id = np.repeat(np.arange(lengths.size), lengths)[hit]
    _, first = np.unique(seg_id, return_index=True)
    return values, hit[first] + lo


def segment_max(x, starts):
    """Maximum and its (first) index in each segment ``[starts[k], starts[k+1])``.

    Parameters
    ----------
    x : array_like, shape (n,)
    starts : array_like of int, shape (m,)
        Strictly increasing segment boundaries, ``0 <= starts <= n``.

    Returns
    -------
    values : ndarray, shape (m - 1,)
    index : ndarray of int, shape (m - 1,)
    """
    a = _signal(x, min_size=1)
    return _segment_extreme(a, _indices(starts, a.size, "starts"), np.maximum)


def segment_min(x, starts):
    """Minimum and its (first) index in each segment; see :func:`segment_max`."""
    a = _signal(x, min_size=1)
    return _segment_extreme(a, _indices(starts, a.size, "starts"), np.minimum)


def wave_crests(x, upcross=None):
    """Crest (maximum) of every complete zero-up-crossing wave.

    Returns
    -------
    values, index : ndarray
        One entry per wave between consecutive up-crossings.
    """
    a = _signal(x)
    u = zero_upcrossings(a) if upcross is None else upcross
    return segment_max(a, u)


def wave_troughs(x, upcross=None):
    """Trough (minimum) of every complete zero-up-crossing wave."""
    a = _signal(x)
    u = zero_upcrossings(a) if upcross is None else upcross
    return segment_min(a, u)


def matched_peaks(lf, hf, upcross=None):
    """LF crest and HF maximum in the same wave window (LF-HF pairs).

    The windows are the zero-up-crossing waves of ``lf`` (or ``upcross``);
    the HF value of a wave is the maximum of ``hf`` inside the same window,
    so an HF peak slightly delayed with respect to the LF crest still pairs
    with it as long as it stays within the wave.

    Parameters
    ----------
    lf, hf : array_like, shape (n,)
        Signals on the same time base.
    upcross : array_like of int, optional
        Window boundaries; default the zero up-crossings of ``lf``.

    Returns
    -------
    lf_peak, hf_peak : ndarray, shape (n_waves,)
    lf_index, hf_index : ndarray of int, shape (n_waves,)
    """
    a = _signal(lf, "lf")
    b = _signal(hf, "hf")
    if a.shape != b.shape:
        raise ValueError(f"lf and hf must have the same length, got {a.size} and {b.size}")
    u = zero_upcrossings(a) if upcross is None else upcross
    lv, li = segment_max(a, u)
    hv, hi = segment_max(b, u)
    return lv, hv, li, hi


def rise_times(t, x, upcross=None):
    """Time from each wave's zero up-crossing (interpolated) to its crest.

    Returns
    -------
    rise : ndarray, shape (n_waves,)
    crest : ndarray, shape (n_waves,)
        Crest values of the same waves.
    """
    a = _signal(x)
    tt = _signal(t, "t")
    if tt.shape != a.shape:
        raise ValueError("t and x must have the same length")
    u = zero_upcrossings(a) if upcross is None else _indices(upcross, a.size, "upcross")
    crest, ci = segment_max(a, u)
    t_up = upcrossing_times(tt, a, u[:-1]) if u.size > 1 else np.empty(0)
    return tt[ci] - t_up, crest


def rise_velocities(t, x, upcross=None):
    """Relative rise velocity per wave: crest / rise time (paper §3, case 4).

    For a relative wave elevation record this is the RRV indicator: peak RWE
    divided by the time from the RWE's zero up-crossing to that peak.
    """
    rise, crest = rise_times(t, x, upcross)
    return crest / rise


def peaks_over_threshold(x, threshold, *, drop_incomplete=False):
    """One peak per excursion of ``x`` above ``threshold``.

    For impact signals that do not peak every wave: each maximal run of
    samples ``> threshold`` yields its maximum.

    Parameters
    ----------
    x : array_like, shape (n,)
    threshold : float
    drop_incomplete : bool, default False
        Drop excursions that touch the first or last sample (cut by the
        record ends).

    Returns
    -------
    values, index : ndarray

    Examples
    --------
    >>> peaks_over_threshold([0, 2, 3, 1, 0, 5, 0], 0.5)
    (array([3., 5.]), array([2, 5]))
    """
    a = _signal(x, min_size=1)
    if not np.isfinite(threshold):
        raise ValueError("threshold must be finite")
    above = np.concatenate(([False], a > threshold, [False]))
    edges = np.flatnonzero(np.diff(above.astype(np.int8)))
    starts, ends = edges[0::2], edges[1::2]
    if drop_incomplete and starts.size:
        keep = (starts > 0) & (ends < a.size)
        starts, ends = starts[keep], ends[keep]
    if starts.size == 0:
        return np.empty(0), np.empty(0, dtype=np.intp)
    bounds = np.empty(2 * starts.size, dtype=np.intp)
    bounds[0::2], bounds[1::2] = starts, ends
    if bounds[-1] == a.size:
        bounds = bounds[:-1]
    # reduceat over [start, end) pairs; the odd slots are the gaps in between.
    values = np.maximum.reduceat(a, bounds)[0::2]
    lengths = ends - starts
    seg_id = np.repeat(np.arange(starts.size), lengths)
    offsets = np.concatenate(([0], np.cumsum(lengths)[:-1]))
    idx = np.repeat(starts - offsets, lengths) + np.arange(lengths.sum())
    hit = np.flatnonzero(a[idx] == values[seg_id])
    _, first = np.unique(seg_id[hit], return_index=True)
    return values, idx[hit[first]]


def mask_near_joins(peak_times, join_times, window):
    """Keep-mask dropping peaks within ``window`` of a join of concatenated records.

    When seeds are concatenated into one record, the waves around each join
    are artificial. Use ``window`` = one (encounter) wave period.

    Parameters
    ----------
    peak_times : array_like, shape (n,)
        Times (or sample indices) of the peaks.
    join_times : array_like, shape (m,)
        Times (same unit) where records were joined.
    window : float
        Half-width of the exclusion zone around each join, ``>= 0``.

    Returns
    -------
    ndarray of bool, shape (n,)
        ``True`` for peaks to keep.
    """
    p = np.asarray(peak_times, dtype=float)
    j = np.sort(np.asarray(join_times, dtype=float).ravel())
    if p.ndim != 1:
        raise ValueError("peak_times must be 1-D")
    if not (np.isfinite(window) and window >= 0):
        raise ValueError("window must be finite and non-negative")
    if np.any(~np.isfinite(p)) or np.any(~np.isfinite(j)):
        raise ValueError("peak_times and join_times must be finite")
    if j.size == 0:
        return np.ones(p.size, dtype=bool)
    pos = np.searchsorted(j, p)
    left = np.abs(p - j[np.clip(pos - 1, 0, j.size - 1)])
    right = np.abs(j[np.clip(pos, 0, j.size - 1)] - p)
    return np.minimum(left, right) > window
