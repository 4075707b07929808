"""A design-wave episode: what an episode oracle (CFD, basin, an HF model) receives.

:func:`design_episode` conditions the sea of a
:class:`~pas.waves.surrogate.ResponseSurrogate` on a target response at ``t0``
(MLER or FORM-RCW) and returns an :class:`Episode`: the components
(amplitudes and phases at the reference point), the surface and surrogate
response at the structure point as time series, and CSV files of both for an
external program.  Times are ship-fixed (encounter) times; the record is
periodic with the episode's duration.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass, field

import numpy as np

from .design import FormResult, form_rcw, mler
from .surrogate import ResponseSurrogate, synthesise_on

__all__ = ["Episode", "design_episode", "METHODS"]

METHODS = ("form", "mler")
"""``"form"``: FORM-RCW on the surrogate; ``"mler"``: the closed-form linear episode."""


@dataclass(frozen=True)
class Episode:
    """One conditioned wave episode.

    Attributes
    ----------
    surrogate : ResponseSurrogate
        Grid, structure point, transfer function and conditioning time.
    u : ndarray, shape (2N,)
        Standard-normal coordinates of the episode (module docs of
        :mod:`pas.waves.surrogate`); ``beta = |u|``.
    target : float
        Surrogate response reached at ``t0``.
    level : float or None
        Exceedance probability per wave encounter the target stands for.
    method : str
        ``"form"`` or ``"mler"``.
    form : FormResult
        Iterations, residual and convergence of the conditioning.
    index : int
        Position in a ladder of levels.

    An episode also answers to ``id``, ``index``, ``lf`` (the target), ``d``
    (the level) and ``meta``, so :class:`~pas.study.command_oracle.CommandOracle`
    can run one; it then writes :meth:`write_csv` into the run's folder and
    fills in ``{episode}`` and ``{components}``.
    """

    surrogate: ResponseSurrogate = field(repr=False)
    u: np.ndarray = field(repr=False)
    target: float
    level: float | None
    method: str
    form: FormResult = field(repr=False)
    index: int = 0

    @property
    def t0(self) -> float:
        return self.surrogate.t0

    @property
    def beta(self) -> float:
        return self.form.beta

    @property
    def sea(self):
        """The linear components as a :class:`~pas.waves.realisation.LinearSea`."""
        return self.surrogate.sea(self.u)

    @property
    def id(self) -> str:
        """``rcw<index>-<hash>``: a new episode never reuses an old run's folder."""
        h = hashlib.sha1(np.ascontiguousarray(self.u).tobytes())
        h.update(np.ascontiguousarray(self.surrogate.transfer).tobytes())
        h.update(repr((self.t0, self.surrogate.template.df, self.surrogate.x)).encode())
        return f"rcw{self.index:02d}-{h.hexdigest()[:10]}"

    @property
    def lf(self) -> float:
        return self.target

    @property
    def d(self) -> float:
        return float("nan") if self.level is None else float(self.level)

    @property
    def meta(self) -> dict:
        return {"level": self.d, "target": self.target, "t0": self.t0, "beta": self.beta,
                "method": self.method, "duration": self.surrogate.template.duration}

    def time_series(self, dt=0.1):
        """``t``, ``eta`` (surface at the structure point, with the second order when the
        surrogate has it), ``eta_linear`` and ``response`` (surrogate) as a DataFrame."""
        import pandas as pd

        s, sea = self.surrogate, self.sea
        lin = sea.amplitude_at(s.x)
        t, eta_lin = synthesise_on(s, lin, dt)
        eta = synthesise_on(s, s.surface_coefficients(sea), dt)[1]
        resp = synthesise_on(s, s.response_coefficients(sea), dt)[1]
        return pd.DataFrame({"t": t, "eta": eta, "eta_linear": eta_lin, "response": resp})

    def components(self):
        """One row per linear component: encounter frequency (Hz), ``omega_e``, absolute
        ``omega`` (rad/s), wave number, amplitude (m) and phase (rad) of
        ``a cos(omega_e t + phase)`` at the reference point."""
        import pandas as pd

        sea = self.sea
        keep = np.abs(sea.amplitude) > 0
        return pd.DataFrame({"frequency_hz": sea.freq[keep], "omega_e": sea.omega_e[keep],
                             "omega": sea.omega[keep], "wave_number": sea.wave_number[keep],
                             "amplitude": np.abs(sea.amplitude[keep]),
                             "phase": np.angle(sea.amplitude[keep])})

    def write_csv(self, directory, dt=0.1) -> dict:
        """Write ``episode.csv`` (:meth:`time_series`) and ``components.csv``
        (:meth:`components`) into ``directory``; returns ``{"episode": path,
        "components": path}``."""
        os.makedirs(directory, exist_ok=True)
        paths = {"episode": os.path.join(directory, "episode.csv"),
                 "components": os.path.join(directory, "components.csv")}
        self.time_series(dt).to_csv(paths["episode"], index=False)
        self.components().to_csv(paths["components"], index=False)
        return paths


def design_episode(surrogate: ResponseSurrogate, target: float, *, method="form", level=None,
                   index=0, tol=1e-6, max_iter=50) -> Episode:
    """The episode whose surrogate response equals ``target`` at ``t0``.

    Parameters
    ----------
    surrogate : ResponseSurrogate
    target : float
        Response at ``t0`` (e.g. from :func:`~pas.waves.design.rayleigh_target`).
    method : {"form", "mler"}, default "form"
        FORM-RCW on the surrogate (started from MLER), or MLER itself (which
        reaches the target of the *linear* part of the surrogate only).
    level : float, optional
        Exceedance probability the target stands for (bookkeeping).
    index : int, default 0
    tol, max_iter
        Passed to :func:`~pas.waves.design.form_rcw`.

    Returns
    -------
    Episode

    Examples
    --------
    >>> from pas.waves import jonswap
    >>> from pas.waves import response_surrogate
    >>> s = response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: 1.0 + 0 * w,
    ...                        depth=30.0, omega_max=2.0)
    >>> ep = design_episode(s, 10.0)
    >>> ep.form.converged, round(ep.form.value, 6)
    (True, 10.0)
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if method == "form":
        res = form_rcw(surrogate, target, tol=tol, max_iter=max_iter)
    else:
        u = mler(surrogate, target)
        lin = float(surrogate.b @ u)
        res = FormResult(u=u, beta=float(np.linalg.norm(u)), value=lin,
                         residual=abs(lin - target) / abs(target), alignment=0.0,
                         iterations=0, converged=True)
    return Episode(surrogate=surrogate, u=res.u, target=float(target),
                   level=None if level is None else float(level), method=method, form=res,
                   index=int(index))
