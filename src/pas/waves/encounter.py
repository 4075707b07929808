"""Encounter frequencies and periods of waves met by a ship under way (paper Eq. 1)."""

from __future__ import annotations

import numpy as np

from .spectra import GRAVITY

__all__ = ["encounter_frequency", "wave_frequency_from_encounter", "mean_encounter_period"]


def encounter_frequency(omega, speed, heading, *, g=GRAVITY):
    """Encounter frequency ``w_e = w - w^2 V cos(mu) / g`` (paper Eq. 1).

    Parameters
    ----------
    omega : array_like
        Absolute wave frequency (rad/s).
    speed : float
        Ship forward speed ``V`` (m/s).
    heading : float
        Wave heading relative to the ship, degrees (180 = head seas).
    """
    w = np.asarray(omega, dtype=float)
    return w - w**2 * speed * np.cos(np.deg2rad(heading)) / g


def wave_frequency_from_encounter(omega_e, speed, heading, *, g=GRAVITY):
    """Invert :func:`encounter_frequency` on its monotonic (lower) branch.

    ``w = 2 w_e / (1 + sqrt(1 - 4 c w_e))`` with ``c = V cos(mu) / g``; this
    form is exact for ``c = 0``, head and bow-quartering seas (``c < 0``, where
    the map is monotonic for all ``w``) and following seas below the turning
    point ``w_e < 1 / (4 c)``.

    Raises
    ------
    ValueError
        If some ``w_e`` lies beyond the following-sea turning point.
    """
    we = np.asarray(omega_e, dtype=float)
    c = speed * np.cos(np.deg2rad(heading)) / g
    disc = 1.0 - 4.0 * c * we
    if np.any(disc < 0):
        raise ValueError(
            "encounter frequency beyond the following-sea turning point "
            f"1/(4 V cos mu / g) = {1 / (4 * c):.4g} rad/s; the map w -> w_e is not "
            "invertible there. Lower omega_max or use a heading with cos(mu) <= 0."
        )
    return 2.0 * we / (1.0 + np.sqrt(disc))


def mean_encounter_period(t1, speed, heading, *, g=GRAVITY):
    """Mean encounter period ``T1,e = T1 / (1 - 2 pi V cos(mu) / (T1 g))`` (Eq. 1).

    The same map converts a peak period ``Tp`` into ``Tp,e`` (paper Table 3).

    Examples
    --------
    >>> round(float(mean_encounter_period(10.0, 5.1, 180.0)), 2)  # condition B, Tp,e
    7.54
    """
    t1 = np.asarray(t1, dtype=float)
    if np.any(t1 <= 0):
        raise ValueError("periods must be positive")
    denom = 1.0 - 2.0 * np.pi * speed * np.cos(np.deg2rad(heading)) / (t1 * g)
    if np.any(denom <= 0):
        raise ValueError("following-sea speed too high: encounter period undefined")
    return t1 / denom
