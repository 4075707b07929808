"""Where the joint fit of :mod:`pas.models.joint` starts its optimiser from the data.

The copula from the pairs' Kendall τ and the HF marginal from a
least-squares fit on Weibull paper (log-normal: that location and the
moments of ``ln(h − θ)``), as optimiser values; :class:`DataStarts` computes
them once for every family and marginal fitted to the same pairs.
"""

from __future__ import annotations

import numpy as np
import pyvinecopulib as pv

from ..stats.weibull import fit_weibull3_ls
from .copulas import kendall_tau

__all__ = ["DataStarts", "copula_start"]

_TINY = 1e-12


def copula_start(base: str, tau: float):
    tau = float(np.clip(tau, 0.05, 0.85))
    if base in ("gaussian", "student"):
        rho = np.sin(np.pi * tau / 2.0)
        return [np.arctanh(rho / 0.999)] + ([0.0] if base == "student" else [])
    if base == "clayton":
        return [np.log(2 * tau / (1 - tau))]
    if base == "gumbel":
        return [np.log(tau / (1 - tau))]  # θ − 1 = τ/(1−τ)
    p = pv.Bicop(family=pv.BicopFamily.frank).tau_to_parameters(tau).ravel()[0]
    return [35.0 * np.arctanh(min(p, 34.9) / 35.0)]


def _weibull_start(h, location: bool):
    """Least-squares Weibull on Weibull paper (ranks i/(n+1)) as optimiser values."""
    if location and h.size >= 3 and np.ptp(h) > 0:
        w = fit_weibull3_ls(h)
        h_min, span = h.min(), np.ptp(h)
        gap = max(h_min - w.theta, 1e-3 * span)
        return [np.log(gap / span), np.log(w.alpha), np.log(max(w.beta, 0.2))]
    x = np.log(np.sort(h))
    y = np.log(-np.log1p(-np.arange(1, h.size + 1) / (h.size + 1.0)))
    beta, c = np.polyfit(x, y, 1)
    beta = max(beta, 0.2)
    return [np.log(np.exp(-c / beta)), np.log(beta)]


def _lognormal_start(h, location: bool, weibull=None):
    """Log-normal optimiser values: the least-squares Weibull's location (``weibull``: its
    :func:`_weibull_start`, when known), moments of ln(h − θ)."""
    gap_x = (_weibull_start(h, location) if weibull is None else weibull)[0] if location else None
    span = float(np.ptp(h)) or float(h.min())
    theta = h.min() - np.exp(gap_x) * span if location else 0.0
    lw = np.log(np.maximum(h - theta, 1e-300))
    return ([gap_x] if location else []) + [float(lw.mean()), np.log(max(lw.std(), 0.05))]


class DataStarts:
    """The optimiser's starts from the data (:func:`fit_joint`'s cold start), computed once
    for every family and marginal fitted to the same pairs: their Kendall τ and the
    least-squares marginals."""

    def __init__(self, u, h, location: bool):
        self._u = np.clip(np.asarray(u, float), _TINY, 1 - _TINY)
        self._h, self._location = np.asarray(h, float), location
        self._tau, self._marginals = None, {}

    def tau(self) -> float:
        """Kendall's τ of the pairs (0.3 for fewer than 3)."""
        if self._tau is None:
            self._tau = kendall_tau(self._u, self._h) if self._u.size > 2 else 0.3
        return self._tau

    def marginal(self, marginal: str) -> list:
        """The optimiser values of the least-squares start of the HF ``marginal``."""
        if marginal not in self._marginals:
            weibull = self._marginals.get("weibull")
            if weibull is None:
                weibull = self._marginals["weibull"] = _weibull_start(self._h, self._location)
            if marginal == "lognormal":
                self._marginals[marginal] = _lognormal_start(self._h, self._location, weibull)
        return self._marginals[marginal]
