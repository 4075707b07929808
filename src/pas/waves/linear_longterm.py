"""Linear short-term and long-term statistics of a response over a table of sea states.

Per sea state ``s`` (JONSWAP of ``hs``, ``tp``, ``gamma``; a heading and the
transfer function's speed) the response spectrum on the wave frequency is
``|H(w)|^2 S(w)``; its moments in the ship-fixed (encounter) frame are
``m_n = integral w_e^n |H(w)|^2 S(w) dw`` (the Jacobian of ``w -> w_e``
cancels), the mean up-crossing rate ``nu_s = sqrt(m2 / m0) / (2 pi)`` (1/s)
and the response peak per cycle is Rayleigh: ``P(A > x) = exp(-x^2 / (2 m0))``
(narrow band). The long-term exceedance per response cycle ("per
encounter") is the cycle-weighted mixture

``Q(x) = sum_s p_s nu_s exp(-x^2 / (2 m0_s)) / sum_s p_s nu_s``

(e.g. DNV-CG-0130 Sec. 2; the all-cycles-independent form of Snoopy's
``LongTermSpectral``), whose value at ``p_exceed`` is the long-term value; a
return period of ``N`` years is ``p_exceed = 1 / (N * 3600 * hours_per_year *
sum_s p_s nu_s)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import optimize, special

from .encounter import encounter_frequency
from .spectra import jonswap

__all__ = ["HOURS_PER_YEAR", "short_term_linear", "LinearLongTerm", "linear_long_term",
           "rayleigh_extreme", "sea_state_spectrum", "response_spectrum"]

HOURS_PER_YEAR = 365.25 * 24
"""Hours in a year (Julian), for return periods."""

_OMEGA = np.linspace(0.02, 4.0, 2000)
_NEEDED = ("name", "probability", "hs", "tp")


def sea_state_spectrum(row):
    """``S(omega)`` of a sea-state row: JONSWAP of ``hs``, ``tp``, ``gamma`` (default 3.3)."""
    gamma = float(row.get("gamma", 3.3)) if hasattr(row, "get") else 3.3
    hs, tp = float(row["hs"]), float(row["tp"])
    return lambda w: jonswap(w, hs, tp, gamma)


def response_spectrum(transfer, response, sea_state, *, omega=None):
    """Response spectrum of one sea state on the encounter frequency.

    ``S_R(w_e) = |H(w)|^2 S(w) / |dw_e / dw|`` on the wave-frequency grid
    ``omega`` (default as :func:`short_term_linear`), so that
    ``integral S_R dw_e = m0``.

    Returns
    -------
    omega_e, s_r : ndarray
        Encounter frequencies (rad/s, increasing for head and beam seas) and
        the spectral density (response unit^2 s / rad).
    """
    w = _OMEGA if omega is None else np.asarray(omega, dtype=float)
    heading = float(sea_state.get("heading", 180.0))
    h = transfer.response(response, w, heading)
    jacobian = np.abs(1.0 - 2.0 * w * transfer.speed * np.cos(np.deg2rad(heading)) / transfer._g)
    return encounter_frequency(w, transfer.speed, heading), np.abs(h) ** 2 * sea_state_spectrum(
        sea_state)(w) / jacobian


def _check_table(sea_states, transfer):
    if not isinstance(sea_states, pd.DataFrame):
        raise TypeError("sea_states must be a pandas DataFrame (e.g. ScatterDiagram.sea_states())")
    missing = [c for c in _NEEDED if c not in sea_states.columns]
    if missing:
        raise ValueError(f"sea_states lacks columns {missing}; it needs {list(_NEEDED)}")
    if sea_states["name"].duplicated().any():
        raise ValueError("sea_states: names must be unique")
    p = sea_states["probability"].to_numpy(dtype=float)
    if np.any(~np.isfinite(p)) or np.any(p < 0) or not p.sum() > 0:
        raise ValueError("sea_states: probability must be non-negative with a positive sum")
    if "speed" in sea_states.columns:
        speeds = sea_states["speed"].to_numpy(dtype=float)
        if np.any(np.abs(speeds - transfer.speed) > 1e-9):
            raise ValueError(f"sea_states: speed {sorted(set(speeds))} differs from the transfer "
                             f"function's speed {transfer.speed:g} m/s; build one transfer "
                             "function per speed and split the table")


def short_term_linear(transfer, response, sea_states, *, omega=None):
    """Response moments per sea state.

    Parameters
    ----------
    transfer : TransferFunction
    response : str or tuple
        As :meth:`TransferFunction.response`, e.g. ``('rwe', 85.0)`` or ``'vbm'``.
    sea_states : pandas.DataFrame
        ``name``, ``probability``, ``hs``, ``tp`` and optionally ``gamma``,
        ``heading`` (default 180), ``speed`` (must equal ``transfer.speed``).
    omega : array_like, optional
        Integration grid (rad/s); default 2000 points on [0.02, 4]. The
        spectral tail above it is left out (for a response that does not
        decay, such as the RWE, ``m2`` of a Tz = 6.5 s sea is then ~3 % short).

    Returns
    -------
    pandas.DataFrame
        The table with ``m0``, ``m2`` (encounter frame), ``nu`` (up-crossings
        per s), ``sigma`` (``sqrt(m0)``) and ``coverage`` (share of the wave
        variance inside the transfer function's frequency range) added.
    """
    _check_table(sea_states, transfer)
    w = _OMEGA if omega is None else np.asarray(omega, dtype=float)
    inside = (w >= transfer.omega[0]) & (w <= transfer.omega[-1])
    out = sea_states.copy().reset_index(drop=True)
    heading = out["heading"] if "heading" in out.columns else pd.Series(180.0, index=out.index)
    cache = {}
    m0, m2, cover = [], [], []
    for i, row in out.iterrows():
        mu = float(heading[i])
        if mu not in cache:
            h = transfer.response(response, w, mu)
            cache[mu] = (np.abs(h) ** 2, encounter_frequency(w, transfer.speed, mu))
        h2, we = cache[mu]
        s = sea_state_spectrum(row)(w)
        rs = h2 * s
        m0.append(np.trapezoid(rs, w))
        m2.append(np.trapezoid(we**2 * rs, w))
        cover.append(np.trapezoid(np.where(inside, s, 0.0), w) / (float(row["hs"]) ** 2 / 16.0))
    out["m0"], out["m2"] = np.array(m0), np.array(m2)
    out["nu"] = np.sqrt(out["m2"] / out["m0"]) / (2.0 * np.pi)
    out["sigma"] = np.sqrt(out["m0"])
    out["coverage"] = np.array(cover)
    return out


def rayleigh_extreme(m0, nu, duration, *, fractile=None):
    """Short-term extreme of a Rayleigh response over ``duration`` seconds.

    The most probable maximum ``sqrt(2 m0 ln(nu T))`` when ``fractile`` is
    None, otherwise the ``fractile`` quantile of the maximum of ``n = nu T``
    independent cycles, ``sqrt(-2 m0 ln(1 - fractile^(1/n)))``.
    """
    m0, nu = np.asarray(m0, dtype=float), np.asarray(nu, dtype=float)
    n = nu * float(duration)
    if np.any(n <= 1):
        raise ValueError("duration must hold more than one response cycle")
    if fractile is None:
        return np.sqrt(2.0 * m0 * np.log(n))
    if not 0.0 < fractile < 1.0:
        raise ValueError(f"fractile must lie in (0, 1), got {fractile!r}")
    return np.sqrt(-2.0 * m0 * np.log(-np.expm1(np.log(fractile) / n)))


@dataclass(frozen=True)
class LinearLongTerm:
    """Long-term Rayleigh mixture over sea states (module docstring).

    Attributes
    ----------
    table : pandas.DataFrame
        :func:`short_term_linear` output (``name``, ``probability``, ``m0``, ``nu``...).
    """

    table: pd.DataFrame

    def __post_init__(self):
        t = self.table
        keep = (t["probability"] > 0) & (t["m0"] > 0)
        w = (t["probability"] * t["nu"]).to_numpy(dtype=float)
        object.__setattr__(self, "_w", w[keep] / w[keep].sum())
        object.__setattr__(self, "_m0", t["m0"].to_numpy(dtype=float)[keep])
        object.__setattr__(self, "_keep", keep.to_numpy())

    @property
    def cycles_per_second(self):
        """Mean response cycles per second over the diagram, ``sum_s p_s nu_s``."""
        t = self.table
        return float((t["probability"] * t["nu"]).sum() / t["probability"].sum())

    def cycles_per_year(self, hours_per_year=HOURS_PER_YEAR):
        """Response cycles ("encounters") in a year."""
        return self.cycles_per_second * 3600.0 * hours_per_year

    def log_exceedance(self, x):
        """``ln Q(x)`` (log-sum-exp, finite far in the tail)."""
        x = np.asarray(x, dtype=float)
        terms = np.log(self._w) - x[..., None] ** 2 / (2.0 * self._m0)
        return special.logsumexp(terms, axis=-1)

    def exceedance(self, x):
        """Long-term exceedance probability per response cycle ``Q(x)``."""
        return np.exp(self.log_exceedance(x))

    def p_exceed_of(self, return_period, hours_per_year=HOURS_PER_YEAR):
        """Per-cycle exceedance of the value with the given return period (years)."""
        if not return_period > 0:
            raise ValueError(f"return_period must be positive (years), got {return_period!r}")
        return 1.0 / (return_period * self.cycles_per_year(hours_per_year))

    def value(self, p_exceed=None, *, return_period=None, hours_per_year=HOURS_PER_YEAR):
        """Response level ``x`` with ``Q(x) = p_exceed`` (or that of ``return_period`` years)."""
        if (p_exceed is None) == (return_period is None):
            raise ValueError("give exactly one of p_exceed and return_period")
        p = self.p_exceed_of(return_period, hours_per_year) if p_exceed is None else p_exceed
        if not 0.0 < p < 1.0:
            raise ValueError(f"p_exceed must lie in (0, 1), got {p!r}")
        hi = np.sqrt(2.0 * self._m0.max() * -np.log(p)) * 1.001
        return float(optimize.brentq(lambda x: self.log_exceedance(x) - np.log(p), 0.0, hi,
                                     xtol=1e-12 * hi, rtol=1e-13))

    def contributions(self, x):
        """Each sea state's share of ``Q(x)`` (sums to 1), as a DataFrame ``name``, ``share``."""
        t = self.table
        share = np.zeros(len(t))
        terms = np.log(self._w) - float(x) ** 2 / (2.0 * self._m0)
        share[self._keep] = np.exp(terms - special.logsumexp(terms))
        return pd.DataFrame({"name": t["name"].to_numpy(), "share": share})


def linear_long_term(transfer, response, sea_states, *, omega=None):
    """:class:`LinearLongTerm` of ``response`` over ``sea_states`` (see :func:`short_term_linear`).

    Examples
    --------
    >>> from pas.waves import FERRY_190M, TransferFunction, north_atlantic
    >>> import numpy as np
    >>> tf = TransferFunction.from_ship(FERRY_190M, np.linspace(0.05, 2.5, 120))
    >>> lt = linear_long_term(tf, "heave", north_atlantic().sea_states())
    >>> bool(lt.value(1e-8) > lt.value(1e-4))
    True
    """
    return LinearLongTerm(short_term_linear(transfer, response, sea_states, omega=omega))
