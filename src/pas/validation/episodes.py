"""Design waves on the analogues: each case's surrogate and its HF model on an episode.

:func:`case_surrogate` builds the response an RCW episode is conditioned on,
:func:`episode_oracle` evaluates the case's HF model -- the same physics and
frozen coefficients as its generator (:mod:`.case_waves`, :mod:`.case_vbm`,
:mod:`.case_impacts` for the paper-like 3a–4b, :mod:`.case_impacts_hard` for
3a-hard–4b-hard) -- on an arbitrary :class:`~pas.waves.episode.Episode`,
and :func:`run_rcw_case` runs :func:`pas.run_rcw` on a generated case as a
user would.

The HF value of an episode is that of its *wave event at t0*: the generator's
zero-up-crossing window of the LF signal that holds ``t0``, with the
generator's peak rule inside it.  The random parts of the HF models are set to
their medians (a design wave is one deterministic run): for 3a-hard/3b-hard the
flare-deflection margin ``δ ~ Exponential(delta_mean)`` to ``delta_mean ln 2``,
the log-normal scatter of the hard cases 3–4 to 1; for the paper-like 3a–4b
every random input at its median (:func:`.case_impacts.green_water_load`:
not deflected, no impulsive part, no scatter).

Conditioned response and target per case
----------------------------------------
* 1a/1b: the surface elevation at the point (T = 1); LF Monte-Carlo target (the
  LF crest; 1b's noisy LF crest -- the noise belongs to the indicator, not to
  the sea, so the episode has none).
* 2a/2b: midship VBM, hogging positive (2a) or sagging positive (2b); LF
  Monte-Carlo target.
* 3a/3b: linear bow relative wave elevation ``R'`` (with the swell-up factor)
  at the forward perpendicular; LF Monte-Carlo target.
* 4a/4b: linear relative wave elevation ``R'`` at the station-19 panels.  The
  case's LF indicator (the relative rise velocity) is not the peak of a linear
  process at one instant, so its statistics cannot give a linear target: the
  target is Rayleigh on ``R'``'s spectrum, with the response peaks per wave
  encounter from its zero-crossing period (``T_MCS / T_z`` over ``n_w``).

The surrogate (FORM-RCW) is the transfer function of that response applied to
the linear + Sharma–Dean second-order surface at the structure point (second-
order band: the case's, or ``omega_max`` for case 2, whose HF model has none).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..design_waves import run_rcw
from ..stats.peaks import segment_max, segment_min, zero_upcrossings
from ..waves import (
    FERRY_190M,
    jonswap,
    second_order_elevation,
    second_order_kernel,
    ship_rao,
    wave_number,
)
from ..waves.surrogate import response_surrogate
from . import case_impacts, case_impacts_hard, case_vbm, case_waves
from ._common import DT
from ._impact_signals import OMEGA_MAX as IMPACT_OMEGA_MAX
from ._impact_signals import OMEGA_MAX_2 as IMPACT_OMEGA_MAX_2
from ._impact_signals import crossing_values, relative_elevations, time_derivative
from .registry import get_case

__all__ = [
    "case_surrogate",
    "episode_oracle",
    "EpisodeOracle",
    "run_rcw_case",
    "RCW_LADDER",
    "EPISODE_DURATION",
]

RCW_LADDER = (10.0, 5.0, 2.0, 1.0, 0.5)
"""Exceedance levels of :func:`run_rcw_case`, in multiples of ``P_exp``."""
EPISODE_DURATION = 600.0
"""Episode length (s); ``t0`` in its middle."""


def _ship_point(case_id):
    """x of the structure point along the ship, and x of the wave it sees (``x + y tan mu``)."""
    if case_id[0] == "3":
        return FERRY_190M.length / 2.0, FERRY_190M.length / 2.0
    x19 = FERRY_190M.station_x(19)
    heading = get_case(case_id).condition.heading
    return x19, x19 + case_impacts.COEFFICIENTS["y_station19"] * np.tan(np.deg2rad(heading))


def case_surrogate(case_id, *, second_order=True, duration=EPISODE_DURATION):
    """The :class:`~pas.waves.surrogate.ResponseSurrogate` of a case (module docs)."""
    spec = get_case(case_id)
    cond, fam = spec.condition, spec.family
    heading = 180.0 if cond.heading is None else cond.heading
    common = dict(duration=duration, depth=cond.depth, speed=cond.speed, heading=heading,
                  second_order=second_order)

    def spectrum(w):
        return jonswap(w, cond.hs, cond.tp, cond.gamma)

    if fam == "1":
        return response_surrogate(spectrum, np.ones_like, omega_max=case_waves.OMEGA_MAX, **common)
    if fam == "2":
        ship = replace(FERRY_190M, vbm_factor=case_vbm.COEFFICIENTS["vbm_factor"])
        sign = 1.0 if spec.id == "2a" else -1.0

        def vbm(w):
            return sign * ship_rao(ship, w, speed=cond.speed, heading=heading).vbm

        return response_surrogate(spectrum, vbm, omega_max=case_vbm.OMEGA_MAX, **common)
    x, xe = _ship_point(spec.id)
    c_sw = case_impacts.COEFFICIENTS["c_sw"]
    mu = np.deg2rad(heading)

    def rwe(w):
        r = ship_rao(FERRY_190M, w, speed=cond.speed, heading=heading)
        e = np.exp(-1j * wave_number(w, cond.depth) * xe * np.cos(mu))
        return c_sw - (r.heave - x * r.pitch) / e

    return response_surrogate(spectrum, rwe, omega_max=IMPACT_OMEGA_MAX, x=xe,
                              omega_max_2=IMPACT_OMEGA_MAX_2, **common)


def _window(signal, t0):
    """Sample slice of the zero-up-crossing wave of ``signal`` that holds ``t0``."""
    u = zero_upcrossings(signal)
    i0 = int(round(t0 / DT))
    k = int(np.searchsorted(u, i0, side="right")) - 1
    if k < 0 or k + 1 >= u.size:
        raise ValueError(f"t0 = {t0:g} s is not inside a complete wave of the episode")
    return u[k:k + 2]


def _crest(episode, coeffs=None):
    """Case 1: crest of the second-order surface in the linear surface's wave at t0."""
    sea = episode.sea
    _, eta1 = sea.elevation(DT)
    kern = second_order_kernel(sea, omega_max=case_waves.OMEGA_MAX)  # cached per grid
    _, eta2 = second_order_elevation(sea, DT, kernel=kern)
    win = _window(eta1, episode.t0)
    return max(float(segment_max(eta1 + eta2, win)[0][0]), 0.0)


def _vbm(episode, coeffs=None, *, mode):
    m_lin, m_nl = case_vbm._signals(episode.sea, dict(case_vbm.COEFFICIENTS, **(coeffs or {})))
    win = _window(-m_lin, episode.t0)  # waves of the sagging-positive LF signal
    v = segment_max(-m_nl, win)[0][0] if mode == "sag" else -segment_min(-m_nl, win)[0][0]
    return max(float(v), 0.0)


def _green_water_hard(episode, coeffs=None):
    """Case 3-hard at the medians: deflection margin ``delta_mean ln 2``, scatter 1."""
    c, sea = dict(case_impacts_hard.COEFFICIENTS, **(coeffs or {})), episode.sea
    _, _, _, r_lf, r_hf = relative_elevations(sea, c, bow=True)
    r_hf = r_hf + c["bow_wave"] * sea.speed**2 / (2.0 * 9.81)
    peak = segment_max(r_hf, _window(r_lf, episode.t0))[0]
    return float(case_impacts_hard.green_water_force(peak, c["delta_mean"] * np.log(2.0), 1.0,
                                                     c)[0])


def _slamming_hard(episode, coeffs=None):
    """Case 4-hard at the median scatter: largest Wagner impact in the wave at t0."""
    c, sea = dict(case_impacts_hard.COEFFICIENTS, **(coeffs or {})), episode.sea
    nl, slope, _, r_lf, r_hf = relative_elevations(sea, c, bow=False)
    v_hf = sea.synthesise(time_derivative(sea, nl), DT)[1]
    s_hf = sea.synthesise(slope, DT)[1]
    win = _window(r_lf, episode.t0)
    idx, (v, s) = crossing_values(r_hf, c["panel_height"], v_hf, s_hf)
    inside = (idx >= win[0]) & (idx < win[1])
    if not inside.any():
        return 0.0
    force = float(np.max(case_impacts_hard.slamming_forces(v[inside], s[inside], 1.0, c)))
    return force if force >= c["noise_kN"] else 0.0


def _green_water(episode, coeffs=None):
    """Case 3 (paper-like) at the medians: :func:`.case_impacts.green_water_load`."""
    c, sea = dict(case_impacts.COEFFICIENTS, **(coeffs or {})), episode.sea
    _, _, _, r_lf, r_hf = relative_elevations(sea, c, bow=True)
    return case_impacts.green_water_load(r_hf, speed=sea.speed, window=_window(r_lf, episode.t0),
                                         coefficients=c)


def _slamming(episode, coeffs=None):
    """Case 4 (paper-like) at the medians: the generator's rise rule in the wave at t0."""
    c, sea = dict(case_impacts.COEFFICIENTS, **(coeffs or {})), episode.sea
    _, _, _, r_lf, r_hf = relative_elevations(sea, c, bow=False)
    return case_impacts.slamming_load(r_hf, DT, window=_window(r_lf, episode.t0), coefficients=c)


class EpisodeOracle:
    """The HF model of a case as ``oracle(episode) -> float`` (module docs).

    ``episode`` needs only ``sea`` (a :class:`~pas.waves.realisation.LinearSea`
    on the case's grid) and ``t0``.  ``coeffs`` overrides the frozen model
    coefficients, as the generators' ``coeffs`` do (for tests and calibration).
    Plain data: it pickles for process pools.
    """

    def __init__(self, case_id, coeffs=None):
        self.case = get_case(case_id).id
        self.coeffs = dict(coeffs or {})

    def __call__(self, episode) -> float:
        fam = self.case[0]
        if fam == "1":
            return _crest(episode, self.coeffs)
        if fam == "2":
            return _vbm(episode, self.coeffs, mode="hog" if self.case == "2a" else "sag")
        if get_case(self.case).variant == "hard":
            return (_green_water_hard if fam == "3" else _slamming_hard)(episode, self.coeffs)
        return (_green_water if fam == "3" else _slamming)(episode, self.coeffs)

    def __repr__(self) -> str:
        return f"EpisodeOracle({self.case!r})"


def episode_oracle(case_id, coeffs=None) -> EpisodeOracle:
    """:class:`EpisodeOracle` of ``case_id``."""
    return EpisodeOracle(case_id, coeffs)


def _target(spec, surrogate, data):
    if spec.family != "4":
        return {"linear_target": "lf", "lf_peaks": data.lf}
    tz = 2.0 * np.pi * np.sqrt(surrogate.m0 / surrogate.m2)
    return {
        "linear_target": "rayleigh",
        "peaks_per_wave": data.scale * spec.t_mcs / tz / data.n_waves,
    }


def run_rcw_case(data, *, method="form", ladder=RCW_LADDER, study=None):
    """:func:`pas.run_rcw` on a generated case (:class:`~pas.validation.data.CaseData`).

    ``method="form"`` conditions the second-order surrogate, ``"mler"`` the
    linear one; the levels are ``ladder × P_exp``; ``study`` a study store
    (:func:`pas.run_rcw`).
    """
    spec = get_case(data.case)
    surrogate = case_surrogate(spec.id, second_order=method == "form")
    return run_rcw(surrogate, episode_oracle(spec.id), p_exp=data.p_exp,
                   levels=[f * data.p_exp for f in ladder], n_waves=data.n_waves,
                   method=method, study=study, **_target(spec, surrogate, data))
