"""Reading an OpenFOAM run: force histories, wave gauges, and the event's loads from them."""

from __future__ import annotations

import os
import re

import numpy as np

__all__ = ["read_forces", "read_gauge", "event_loads", "FILTER_SECONDS"]

FILTER_SECONDS = 0.25
"""Width of the centred moving average of the filtered peak (s)."""

_NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _time_dirs(folder):
    """Start-time folders of a function object's output (a restart adds one), oldest first."""
    names = [n for n in os.listdir(folder) if _NUM.fullmatch(n)]
    return [os.path.join(folder, n) for n in sorted(names, key=float)]


def read_forces(case, name):
    """``t, total force (n, 3)`` of the ``forces`` function object ``name`` (N per metre of a
    one-cell-thick 2D case), restarts joined; raises FileNotFoundError if it wrote nothing."""
    folder = os.path.join(case, "postProcessing", name)
    rows = []
    for d in _time_dirs(folder) if os.path.isdir(folder) else []:
        path = os.path.join(d, "force.dat")
        if not os.path.isfile(path):
            continue
        with open(path) as f:
            for line in f:
                if line.startswith("#"):
                    continue
                vals = _NUM.findall(line)
                if len(vals) >= 4:
                    rows.append([float(v) for v in vals[:4]])
    if not rows:
        raise FileNotFoundError(f"no force history of {name!r} under {folder}")
    a = np.array(rows)
    _, keep = np.unique(a[:, 0], return_index=True)    # a restart repeats its first time
    a = a[keep]
    return a[:, 0], a[:, 1:4]


def read_gauge(case, name, *, field="alpha.water"):
    """``t, eta``: the surface elevation of a vertical column of ``probes`` (``gauge_<name>``),
    the water fraction integrated up the column from its lowest probe."""
    folder = os.path.join(case, "postProcessing", f"gauge_{name}")
    ts, cols, z = [], [], None
    for d in _time_dirs(folder) if os.path.isdir(folder) else []:
        path = os.path.join(d, field)
        if not os.path.isfile(path):
            continue
        zs = []
        with open(path) as f:
            for line in f:
                if line.startswith("# Probe"):
                    zs.append(float(_NUM.findall(line.split("(", 1)[1])[2]))
                elif not line.startswith("#") and line.strip():
                    v = line.split()
                    ts.append(float(v[0]))
                    cols.append([float(x) for x in v[1:]])
        z = np.array(zs) if zs else z
    if not ts:
        raise FileNotFoundError(f"no wave gauge {name!r} under {folder}")
    alpha = np.clip(np.array(cols), 0.0, 1.0)
    dz = np.gradient(z)
    return np.array(ts), z[0] - 0.5 * dz[0] + alpha @ dz


def _moving_average(t, y, width, step=0.005):
    """Centred moving average of width ``width`` on a uniform resampling of ``(t, y)``."""
    grid = np.arange(t[0], t[-1] + 0.5 * step, step)
    yy = np.interp(grid, t, y)
    n = max(1, int(round(width / step)))
    kernel = np.ones(n) / n
    return grid, np.convolve(yy, kernel, mode="same")


def event_loads(case, t_event, *, window=(-1.0, 3.5), wall="wallForce", deck="deckForce",
                filter_seconds=FILTER_SECONDS):
    """The event's loads from a finished run, within its own wave's window.

    Parameters
    ----------
    case : path
        The run's case folder.
    t_event : float
        Run time at which the event's linear crest reaches the structure (s).
    window : (float, float), default (-1, 3.5)
        The event's window relative to ``t_event`` (s): a green-water load of
        an earlier wave falls before it, and the event's own load (0-4 s after
        its crest reaches the bow, 1.0-2.4 s for 90 % of the example case's events) inside it.
    wall, deck : str
        Names of the ``forces`` function objects on the deckhouse wall and the deck.

    Returns
    -------
    dict
        ``wall_peak`` (raw peak of the horizontal wall force, N/m),
        ``wall_peak_filtered`` (its peak after a centred ``filter_seconds``
        moving average), ``wall_impulse`` (N s/m of the positive force) and
        ``deck_peak`` (peak downward deck force, N/m), each with the force at
        run time 0 (the air-pressure offset) subtracted; ``run_wall_peak`` and
        ``run_wall_peak_time`` over the whole run, to see an earlier wave's load.
    """
    lo, hi = t_event + window[0], t_event + window[1]
    t, f = read_forces(case, wall)
    fx = f[:, 0] - f[0, 0]
    if t[-1] < hi - 0.05:
        raise ValueError(f"the run ended at {t[-1]:.3g} s, before the event's window ends "
                         f"({hi:.3g} s)")
    inside = (t >= lo) & (t <= hi)
    g, smooth = _moving_average(t, fx, filter_seconds)
    ginside = (g >= lo) & (g <= hi)
    pos = np.clip(fx, 0.0, None)
    seg = inside.nonzero()[0]
    ps, ts = pos[seg], t[seg]
    impulse = float(np.sum(0.5 * (ps[1:] + ps[:-1]) * np.diff(ts)))
    td, fd = read_forces(case, deck)
    down = -(fd[:, 2] - fd[0, 2])
    dinside = (td >= lo) & (td <= hi)
    out = {"wall_peak": max(float(fx[inside].max()), 0.0),
           "wall_peak_filtered": max(float(smooth[ginside].max()), 0.0),
           "wall_impulse": impulse,
           "deck_peak": max(float(down[dinside].max()), 0.0) if dinside.any() else 0.0,
           "run_wall_peak": max(float(fx.max()), 0.0),
           "run_wall_peak_time": float(t[np.argmax(fx)])}
    return out
