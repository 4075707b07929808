"""Case 1: linear versus second-order wave crests (condition A, no ship).

Model (paper App. D.1, E.3)
---------------------------
Per realisation: a random-phase linear JONSWAP surface ``eta1`` at one point
(``df = 1/3600`` Hz, components up to 5 rad/s, depth 30 m) and its Sharma–Dean
second-order correction ``eta2`` (sum and difference frequencies, interactions
0–5 rad/s) by :func:`pas.waves.second_order_elevation`.  The wave events are the
zero-up-crossing waves of the LF signal; LF = the LF signal's crest in the
window, HF = the crest of ``eta1 + eta2`` in the same window.

* 1a: LF signal ``eta1``.
* 1b: LF signal ``eta1 + noise`` with an independent noise wave system that
  only the LF sees: JONSWAP ``Hs = 2.0 m``, ``Tp = 11.0 s``, γ = 3.3 (4 % of the
  main sea's energy, same spectral shape so that the wave count is unchanged),
  its own random phases.  The paper does not give its noise spectrum; this is
  our choice.

A window in which the HF surface stays at or below zero (1b: a short wave of
the noisy LF sitting in a trough of the true surface; rare and tiny) has no HF
crest: HF = 0, which PAS treats as a non-event.  Their number is recorded in
``info["n_hf_nonpositive"]``.

There is no free coefficient: the HF truth is physics (Sharma–Dean) only.
"""

from __future__ import annotations

import numpy as np

from ..records.theory import forristall_parameters
from ..stats.exceedance import exceedance_probabilities, value_at_exceedance
from ..stats.peaks import segment_max
from ..waves import jonswap, linear_sea, second_order_elevation, second_order_kernel
from ._common import DT, add_events, condition_sea, joined, phase_seed, windows

__all__ = ["generate_case1", "NOISE", "VERSION"]

VERSION = "2"
NOISE = {"hs": 2.0, "tp": 11.0, "gamma": 3.3}
"""The 1b noise wave system (frozen)."""
OMEGA_MAX = 5.0  # rad/s, linear components and second-order interactions (paper E.3)


def _noise(duration, seed, k, n):
    sea = linear_sea(lambda w: jonswap(w, NOISE["hs"], NOISE["tp"], NOISE["gamma"]), duration,
                     seed=phase_seed(seed, k) + 500_000, omega_max=OMEGA_MAX)
    return sea.elevation(DT)[1][:n]


def generate_case1(spec, seed, n_seeds, duration, n_waves, *, noise=False):
    """Events of case 1a (``noise=False``) or 1b for ``n_seeds`` realisations.

    Returns
    -------
    events : dict of ndarray
        ``lf``, ``hf``, ``seed_no``, ``t_start``, ``t_end``.
    info : dict
        Physics checks: realised Hs per seed, and the linear crest at
        ``P_exp`` (``d = k / n_w``) against Rayleigh and the second-order
        one against Forristall, both with the same exceedance convention.
    """
    cond = spec.condition
    out = {k: [] for k in ("lf", "hf", "seed_no", "t_start", "t_end")}
    hs_real, m0s, lin_crests = [], [], []
    kernel, n_nonpos = None, 0
    for k in range(n_seeds):
        sea = condition_sea(cond, duration, seed, k, omega_max=OMEGA_MAX)
        if kernel is None:
            kernel = second_order_kernel(sea, omega_max=OMEGA_MAX)
        _, eta1 = sea.elevation(DT)
        _, eta2 = second_order_elevation(sea, DT, kernel=kernel)
        lf_sig = eta1 + _noise(duration, seed, k, eta1.size) if noise else eta1
        u, t0, t1 = windows(lf_sig)
        lf, _ = segment_max(lf_sig, u)
        hf = segment_max(eta1 + eta2, u)[0]
        n_nonpos += int(np.count_nonzero(hf <= 0))
        hf = np.maximum(hf, 0.0)
        add_events(out, k, lf, hf, t0, t1)
        hs_real.append(4.0 * float(np.std(eta1)))
        m0s.append(sea.m0)
        lin_crests.append(segment_max(eta1, windows(eta1)[0])[0] if noise else lf)
    events = joined(out)
    info = _physics(spec, np.concatenate(lin_crests), events["hf"], hs_real,
                    float(np.mean(m0s)), n_waves, noise)
    info["n_hf_nonpositive"] = n_nonpos
    return events, info


def _physics(spec, lin, hf, hs_real, m0, n_waves, noise):
    """Rayleigh / Forristall checks on the same ``d = k / n_w`` basis as the truth."""
    cond, p = spec.condition, spec.p_exp
    emp_lin = float(value_at_exceedance(*exceedance_probabilities(lin, n_waves), p))
    ln_n = np.log(lin.size / (n_waves * p))  # crests per wave exceeding = n_w p / n_z
    rayleigh = float(np.sqrt(2.0 * m0 * ln_n))
    # Forristall (2000), long-crested: P(C > c) = exp(-(c / (a Hs))^b), T1 = Tp / 1.198.
    a, b, _, _ = forristall_parameters(cond.hs, cond.tp / 1.198, cond.depth)
    hs = np.asarray(hs_real)
    return {
        "hs_realised": [round(h, 4) for h in hs_real],
        "hs_max_rel_error": float(np.max(np.abs(hs / cond.hs - 1))),
        "m0": m0,
        "n_crests_linear": int(lin.size),
        "linear_crest_mpm": emp_lin,
        "rayleigh_mpm": rayleigh,
        "linear_vs_rayleigh": emp_lin / rayleigh - 1,
        "forristall_mpm": float(a * cond.hs * ln_n ** (1 / b)),
        "hf_empirical_mpm": float(value_at_exceedance(*exceedance_probabilities(hf, n_waves), p)),
        "noise": NOISE if noise else None,
    }
