"""Plotting positions of ranked peaks and a vectorised read-out at one probability.

The k-th largest of ``n`` values gets the exceedance probability
``(k − a) / (n + b)``:

==============  =====  =====  ==============================================
name            a      b      use
==============  =====  =====  ==============================================
``"gringorten"``  0.44   0.12   near-unbiased for the upper tail of
                               exponential-type peaks (Gringorten 1963); the
                               default for pooled peaks
``"weibull"``     0      1      ``k/(n + 1)``: unbiased for the seed maxima
                               read at ``1 − q`` (the default there)
``"k/n"``         0      0      the PAS paper's Eq. 3 (largest ``1/n``)
==============  =====  =====  ==============================================

For pooled impact peaks ``n`` is the number of *encounters*, not of peaks:
the encounters without an impact are the smallest values of the sample.

``k/N`` seed maxima read at 0.632 estimate the MPM high at few seeds,
``k/(N + 1)`` does not; a high quantile of the hourly maximum read from
pooled seeds is high with ``k/n`` and unbiased with Gringorten ranks
("Record statistics" in ``docs/results/investigations.md``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["POSITIONS", "plotting_positions", "read_at_exceedance"]

POSITIONS = {"gringorten": (0.44, 0.12), "weibull": (0.0, 1.0), "k/n": (0.0, 0.0)}


def _constants(positions):
    try:
        return POSITIONS[positions]
    except (KeyError, TypeError):
        raise ValueError(
            f"positions must be one of {sorted(POSITIONS)}, got {positions!r}"
        ) from None


def plotting_positions(n_values, n_total, positions="gringorten"):
    """Exceedance probabilities ``(k − a)/(n_total + b)`` of the ``n_values`` largest.

    Parameters
    ----------
    n_values : int
        How many ranked values (k = 1 … n_values).
    n_total : float
        Size of the sample they are the largest of (encounters for pooled peaks).
    positions : {"gringorten", "weibull", "k/n"}

    Returns
    -------
    ndarray, shape (n_values,), ascending

    Examples
    --------
    >>> plotting_positions(3, 10, "k/n").tolist()
    [0.1, 0.2, 0.3]
    >>> plotting_positions(2, 3, "weibull").tolist()
    [0.25, 0.5]
    """
    a, b = _constants(positions)
    return (np.arange(1, int(n_values) + 1) - a) / (float(n_total) + b)


def read_at_exceedance(values, n_total, p, *, positions="gringorten", scale="log",
                       below=np.nan):
    """Value at exceedance ``p`` of each row of ranked values, interpolated between ranks.

    Parameters
    ----------
    values : array_like, shape (n,) or (B, n)
        Largest values of each row, descending; rows may end in NaN padding
        (fewer values than the row's sample).
    n_total : float or array_like, shape (B,)
        Sample size of each row (encounters for pooled peaks).
    p : float
        Exceedance probability to read at.
    positions : {"gringorten", "weibull", "k/n"}
    scale : {"log", "linear"}
        Interpolate on ``ln d`` (pooled peaks, PAS Eq. 12) or linearly in ``d``
        (seed maxima).
    below : float, default NaN
        Returned where ``p`` is larger than the exceedance of the row's smallest
        value (the value lies below all recorded ones, e.g. "no impact").

    Returns
    -------
    ndarray, shape (B,) (a float for 1-D ``values``)
        NaN where ``p`` is smaller than the exceedance of the largest value:
        that target lies beyond the record.

    Examples
    --------
    >>> float(read_at_exceedance([5.0, 4.0, 3.0], 3, 0.5, positions="weibull", scale="linear"))
    4.0
    >>> float(read_at_exceedance([5.0, 4.0, 3.0], 3, 0.1, positions="weibull"))
    nan
    """
    a, b = _constants(positions)
    if scale not in ("log", "linear"):
        raise ValueError(f"scale must be 'log' or 'linear', got {scale!r}")
    v = np.asarray(values, dtype=float)
    one = v.ndim == 1
    v = np.atleast_2d(v)
    rows, width = v.shape
    n = np.broadcast_to(np.asarray(n_total, dtype=float), (rows,))
    count = np.isfinite(v).sum(axis=1)
    x = p * (n + b) + a                       # fractional rank, 1 = the largest
    x = np.where(np.abs(x - np.round(x)) < 1e-9, np.round(x), x)
    k = np.floor(x).astype(int)               # lower rank (1-based)
    out = np.full(rows, float(below))
    out[x < 1] = np.nan
    exact = (k >= 1) & (k <= count) & (x == k)
    inside = (k >= 1) & (k < count) & ~exact
    r = np.arange(rows)
    out[exact] = v[r[exact], k[exact] - 1]
    if np.any(inside):
        ri, ki = r[inside], k[inside]
        lo, hi = v[ri, ki - 1], v[ri, ki]
        if scale == "linear":
            w = x[inside] - ki
        else:
            d_lo, d_hi = (ki - a) / (n[inside] + b), (ki + 1 - a) / (n[inside] + b)
            w = (np.log(p) - np.log(d_lo)) / (np.log(d_hi) - np.log(d_lo))
        out[inside] = lo + w * (hi - lo)
    return float(out[0]) if one else out
