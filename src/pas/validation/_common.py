"""Shared plumbing of the case generators: seeds, seas and event windows."""

from __future__ import annotations

import numpy as np

from ..stats.peaks import zero_upcrossings
from ..waves import jonswap, linear_sea

DT = 0.1
"""Time step of every synthesised record (s): crest sampling error < 0.1 %."""

SEED_LENGTH = 3600.0
"""Target length of one realisation (s); the paper's case 1 used one-hour seeds."""


def seed_plan(t_mcs, scale):
    """Split ``scale · t_mcs`` into ``n`` realisations of (almost) one hour each.

    Returns
    -------
    n_seeds : int
    duration : float
        Length of each realisation (s), ``scale · t_mcs / n_seeds``.
    """
    if not (np.isfinite(scale) and 0.0 < scale <= 1.0):
        raise ValueError(f"scale must be in (0, 1], got {scale!r}")
    total = scale * t_mcs
    n = max(1, int(np.ceil(total / SEED_LENGTH - 1e-9)))
    return n, total / n


def phase_seed(seed, k):
    """Seed of the wave phases of realisation ``k`` (shared by the cases of a condition)."""
    return 1000 * int(seed) + int(k)


def model_rng(seed, k, tag):
    """Generator for the random parts of an HF model (``tag`` separates models)."""
    return np.random.default_rng([int(seed), int(k), int(tag)])


def condition_sea(cond, duration, seed, k, *, omega_max=5.0):
    """Random-phase JONSWAP sea of ``cond`` (encounter grid when the ship moves)."""
    def spectrum(w):
        return jonswap(w, cond.hs, cond.tp, cond.gamma)

    heading = 180.0 if cond.heading is None else cond.heading
    return linear_sea(spectrum, duration, seed=phase_seed(seed, k), depth=cond.depth,
                      omega_max=omega_max, speed=cond.speed, heading=heading)


def windows(signal, dt=DT):
    """Zero-up-crossing wave windows of ``signal``: boundaries and start/end times."""
    u = zero_upcrossings(signal)
    return u, u[:-1] * dt, u[1:] * dt


def window_of(index, u):
    """Window number of each sample index (-1 outside the complete waves)."""
    w = np.searchsorted(u, index, side="right") - 1
    return np.where((w >= 0) & (w < u.size - 1), w, -1)


def generator_state(frozen, overrides):
    """A generator's coefficients (``frozen`` with ``overrides``) and empty event columns."""
    columns = {k: [] for k in ("lf", "hf", "seed_no", "t_start", "t_end")}
    return dict(frozen, **(overrides or {})), columns


def add_events(columns, k, lf, hf, t_start, t_end):
    """Append the wave events of realisation ``k`` to a generator's columns."""
    for name, v in (("lf", lf), ("hf", hf), ("t_start", t_start), ("t_end", t_end),
                    ("seed_no", np.full(lf.size, k))):
        columns[name].append(v)


def joined(columns):
    """The events of all realisations: one array per column."""
    return {k: np.concatenate(v) for k, v in columns.items()}


def coefficients_on(n, *parts):
    """Sum complex FFT coefficient arrays of different lengths on one grid of length ``n``."""
    out = np.zeros(n, dtype=complex)
    for p in parts:
        out[:p.size] += p
    return out
