"""The one-off calibration scans of the case analogues (kept for the record).

Not part of the package or the tests.  Each scan generates the full-scale
data set for data seed 0 with trial coefficients and prints the data
properties the coefficients were set against — never a PAS or AS result; the
chosen values are frozen in ``src/pas/validation/case_vbm.py``,
``case_impacts.py`` (paper-like 3a–4b) and ``case_impacts_hard.py`` (the
``-hard`` variants).

Run: ``python cases/calibrate.py {2,3,4,4-gate,4-kinematics,4-angle,3-hard,4-hard}``.

Case 2 (issue 11): the first calibration gave hogging < sagging, the paper
hogging 1.10e9 > sagging 9.00e8 N m; a Froude–Krylov term of a side flare
along the midbody (stations 5–15) gives extra buoyancy amidships, i.e. a
hogging moment, and fixes the order; its ``tan_flare_mid`` is scanned here.

Paper-like cases (issue 11), targets fixed before the scan:

* case 3 (``gw_margin``, ``gw_deflected``, ``gw_impulse``; ``C_gw`` is set in
  each trial so that the 3a truth MPM is 1850 kN, then 3b is a check):
  truths of 3a and 3b within ±10 % of Table 4; green-water rates within
  ±25 % of 3 % / 8 % of encounters; miss share of the ln-d-uniform sample of
  50 on 3a within 35–55 %; λ_L ≥ λ_U on 3a and 3b.  Among the trials that
  meet all of these, the one whose 3a miss share is closest to 45 % (Fig. 9:
  23 of 51); on a tie (the scan gave three), the one whose two rates are
  closest to 3 % / 8 % (sum of relative deviations) — this tie-break was
  added after the scan showed the tie.
* case 4 (``slam_impulse``; ``C0`` set per trial so that the 4a truth is
  1710 kN, 4b a check): truths within ±10 %; then the largest λ_L − λ_U.
"""

import sys
import time

import numpy as np

from pas.stats.dependence import empirical_tail_dependence, kendall_tau
from pas.validation import case_impacts
from pas.validation._common import seed_plan
from pas.validation.case_impacts_hard import generate_green_water as hard_green_water
from pas.validation.case_impacts_hard import generate_slamming as hard_slamming
from pas.validation.case_vbm import generate_case2
from pas.validation.data import CaseData, dependence, ground_truth
from pas.validation.properties import data_properties
from pas.validation.registry import get_case


def _events(cid, fn, coeffs, **kw):
    spec = get_case(cid)
    n, dur = seed_plan(spec.t_mcs, 1.0)
    ev, info = fn(spec, 0, n, dur, coeffs=coeffs, **kw)
    m = ground_truth(ev["hf"], spec.n_waves, spec.p_exp, spec.truth_method)[0]
    return spec, ev, m


def _properties(cid, fn, coeffs):
    """data_properties of a trial data set (full scale, data seed 0)."""
    spec = get_case(cid)
    n, dur = seed_plan(spec.t_mcs, 1.0)
    ev, info = fn(spec, 0, n, dur, coeffs=coeffs)
    mpm, d, h, extra = ground_truth(ev["hf"], spec.n_waves, spec.p_exp, spec.truth_method)
    tau, lu, ll = dependence(ev["lf"], ev["hf"], spec.threshold)
    data = CaseData(case=cid, lf=ev["lf"], hf=ev["hf"], ids=np.array([]), seed_no=ev["seed_no"],
                    t_start=ev["t_start"], t_end=ev["t_end"], n_waves=spec.n_waves,
                    p_exp=spec.p_exp, threshold=spec.threshold, eps1=spec.eps1, unit=spec.unit,
                    truth_mpm=mpm, truth_d=d, truth_h=h, tau=tau, lambda_u=lu, lambda_l=ll,
                    seed=0, scale=1.0, info=extra)
    return data_properties(data)


def _line(p):
    return (f"{p['case']} truth {p['truth_mpm']:.0f} ({100 * p['truth_vs_paper']:+.0f}%) "
            f"rate {100 * p['impact_rate']:.1f}% miss {100 * p['miss_all']:.0f}% "
            f"ln-d50 {100 * p['miss_lnu50']:.0f}% tau {p['tau']:.2f} "
            f"lU/lL {p['lambda_u']:.2f}/{p['lambda_l']:.2f} beta {p['weibull_beta']:.2f} "
            f"{p['family']}")


def _scale_to_truth(cid, fn, coeffs, key, start):
    """``coeffs[key]`` such that the truth MPM of ``cid`` is the paper's (two rescalings)."""
    value = start
    for _ in range(2):
        _, _, m = _events(cid, fn, dict(coeffs, **{key: value}))
        value *= get_case(cid).paper_truth / m
    return value


def case2():
    # first calibration (VERSION 2): hog 1.10e9, sag 9.00e8 each within +-25 %
    for vf, tf in [(1.0, 0.0), (0.75, 0.1), (0.69, 0.08)]:
        out = []
        for cid, mode in (("2a", "hog"), ("2b", "sag")):
            spec, _, m = _events(cid, generate_case2, {"vbm_factor": vf, "tan_flare": tf,
                                                        "tan_flare_mid": 0.0}, mode=mode)
            out.append(f"{cid} {m:.3g} ({m / spec.paper_truth - 1:+.0%})")
        print(f"vbm_factor {vf} tan_flare {tf}:", ", ".join(out))
    # issue 11 (VERSION 3): the paper's order hogging > sagging by a midbody side flare, with
    # vbm_factor and the bow flare kept; rule fixed before the scan: among the trials with
    # hog > sag and both truths within +-25 %, the smallest sum of |truth/paper - 1|
    for tm in (0.05, 0.1, 0.15, 0.2, 0.25, 0.3):
        out = []
        for cid, mode in (("2a", "hog"), ("2b", "sag")):
            spec, _, m = _events(cid, generate_case2, {"tan_flare_mid": tm}, mode=mode)
            out.append(f"{cid} {m:.4g} ({m / spec.paper_truth - 1:+.1%})")
        print(f"vbm_factor 0.69 tan_flare 0.08 tan_flare_mid {tm}:", ", ".join(out), flush=True)


def case3():
    """Paper-like green water (module docs of pas.validation.case_impacts)."""
    fn = case_impacts.generate_green_water
    for margin, deflected, impulse in [(m, q, k) for m in (0.0, 0.25, 0.5)
                                       for q in (0.35, 0.4, 0.45) for k in (0.3, 0.5)]:
        trial = {"gw_margin": margin, "gw_deflected": deflected, "gw_impulse": impulse}
        c_gw = _scale_to_truth("3a", fn, trial, "C_gw", 0.2)
        trial["C_gw"] = round(c_gw, 4)
        print(trial, flush=True)
        for cid in ("3a", "3b"):
            print("   ", _line(_properties(cid, fn, trial)), flush=True)


def case4():
    """Paper-like slamming (module docs of pas.validation.case_impacts)."""
    fn = case_impacts.generate_slamming
    for impulse in (0.0, 0.25, 0.5, 1.0):
        trial = {"slam_impulse": impulse}
        trial["C0"] = round(_scale_to_truth("4a", fn, trial, "C0", 0.2), 4)
        print(trial, flush=True)
        for cid in ("4a", "4b"):
            print("   ", _line(_properties(cid, fn, trial)), flush=True)
            # the same impacts without the 100 kN noise threshold: every panel contact a pair
            p = _properties(cid, fn, dict(trial, noise_kN=0.0))
            print(f"      without the 100 kN threshold: lU/lL {p['lambda_u']:.2f}/"
                  f"{p['lambda_l']:.2f}", flush=True)


def case4_gate():
    """Tested and not adopted (stop 17): an impulsive part only above a velocity gate.

    Hypothesis: the low-RRV positives owe their load to an impulsive part (module docs of
    case_impacts), so allowing it only for violent impacts, ``v > gate · v_Ochi``, would tie
    small loads to small RRV and give λ_L ≥ λ_U.  Same rule as :func:`case4`.  Also an
    impulsive part in every contact (``slam_impulse_p`` 1.0 / 0.6).
    """
    fn = case_impacts.generate_slamming
    trials = ([{"slam_impulse_gate": g, "slam_impulse": i} for g in (1.0, 2.0, 2.5, 3.0)
               for i in (0.5, 1.0, 2.0)]
              + [{"slam_impulse_p": p, "slam_impulse": i}
                 for p, i in ((1.0, 0.1), (1.0, 0.25), (1.0, 0.5), (0.6, 0.5))])
    for trial in trials:
        trial["C0"] = round(_scale_to_truth("4a", fn, trial, "C0", 0.05), 4)
        print(trial, flush=True)
        for cid in ("4a", "4b"):
            print("   ", _line(_properties(cid, fn, trial)), flush=True)


def case4_kinematics():
    """Tested after the gate (stop 18): is λ_L < λ_U set by the kinematics, before any load model?

    A load that grows with the panel-level speed ``v`` and nothing else (no impulsive
    part, no scatter, no noise threshold: ``F ∝ v²``) has the ranks of ``v``; any other
    increasing function of ``v`` has the same ranks and so the same τ and λ.  Keep
    the share of events the frozen model has as impacts (the largest loads) and
    measure the LF–HF dependence on those pairs.  Had λ_L ≥ λ_U held here, a load
    model monotone in ``v`` with a suitable threshold could reach the paper's
    property; it does not.
    """
    fn = case_impacts.generate_slamming
    for cid in ("4a", "4b"):
        spec = get_case(cid)
        n, dur = seed_plan(spec.t_mcs, 1.0)
        frozen, _ = fn(spec, 0, n, dur)
        rate = float(np.mean(frozen["hf"] > 0))
        ev, _ = fn(spec, 0, n, dur, coeffs={"slam_impulse": 0.0, "slam_scatter": 0.0,
                                              "noise_kN": 0.0})
        for share in (0.5, rate, 0.05):
            top = ev["hf"] > np.quantile(ev["hf"], 1.0 - share)
            tau = kendall_tau(ev["lf"][top], ev["hf"][top])
            lu, ll = empirical_tail_dependence(ev["lf"][top], ev["hf"][top])
            print(f"{cid} F ∝ v², largest {100 * share:.1f} % of events "
                  f"({'the frozen impact share' if share == rate else 'for comparison'}): "
                  f"tau {tau:.2f} lU/lL {lu:.2f}/{ll:.2f}", flush=True)


def _slope_scattered_force(v, d, c):
    """Slamming force with the flare's angle to the water scattered by the local wave slope.

    Wagner's load grows with ``cot β`` of the relative deadrise; the water surface
    at the contact tilts it by ``α = angle0 · (v / v_Ochi)^power · s``, ``s`` standard
    normal (drawn from the uniform the frozen model uses for its impulsive part, which
    is off here): steeper, faster contacts meet the flare at a more random angle.
    """
    from scipy import special

    v = np.asarray(v, float)
    k, v_ochi = case_impacts.slam_scales(c)
    s = special.ndtri(np.clip(d["u_impulse"], 1e-12, 1 - 1e-12))
    alpha = c["angle0"] * (v / v_ochi) ** c["angle_power"] * s
    beta = np.deg2rad(np.clip(c["beta_flare_deg"] - alpha, 5.0, 85.0))
    force = k / np.tan(beta) * v**2 * np.exp(c["slam_scatter"] * d["z_scatter"])
    return np.where((v > 0) & (force >= c["noise_kN"]), force, 0.0)


def case4_angle():
    """Tested and not adopted (stop 18): the relative deadrise scattered by the wave slope.

    The issue's "flare angle at the contact": a scatter of the load that grows with the
    impact velocity, up and down, instead of the impulsive part (which only adds).  Same
    rule as :func:`case4`.  The model function is swapped in for the scan only.
    """
    frozen = case_impacts._slamming_force
    case_impacts._slamming_force = _slope_scattered_force
    try:
        fn = case_impacts.generate_slamming
        for power in (1.0, 2.0):
            for angle0 in (2.0, 4.0, 6.0, 8.0):
                trial = {"slam_impulse": 0.0, "angle0": angle0, "angle_power": power}
                trial["C0"] = round(_scale_to_truth("4a", fn, trial, "C0", 0.2), 4)
                print(trial, flush=True)
                for cid in ("4a", "4b"):
                    print("   ", _line(_properties(cid, fn, trial)), flush=True)
    finally:
        case_impacts._slamming_force = frozen


def case3_hard():
    # targets: green-water rate ~3 % / ~8 % of encounters, MPM 1850 / 4920 kN (+-25 %)
    for csw, dm, cgw in [(1.5, 1.0, 0.5), (1.6, 1.5, 0.45), (1.7, 2.5, 0.35), (1.7, 2.5, 0.37)]:
        out = []
        for cid in ("3a", "3b"):
            spec, ev, m = _events(cid, hard_green_water,
                                  {"c_sw": csw, "delta_mean": dm, "C_gw": cgw})
            rate = (ev["hf"] > 0).sum() / spec.n_waves
            out.append(f"{cid} rate {rate:.3f} MPM {m:.0f} ({m / spec.paper_truth - 1:+.0%})")
        print(f"c_sw {csw} delta_mean {dm} C_gw {cgw}:", ", ".join(out))


def case4_hard():
    # targets: MPM 1710 / 2440 kN (+-25 %), with c_sw frozen by case 3
    for c0, bf in [(0.1, 40.0), (0.1, 50.0), (0.095, 50.0)]:
        out = []
        for cid in ("4a", "4b"):
            spec, ev, m = _events(cid, hard_slamming, {"C0": c0, "beta_flare_deg": bf})
            out.append(f"{cid} MPM {m:.0f} ({m / spec.paper_truth - 1:+.0%})")
        print(f"C0 {c0} beta_flare {bf}:", ", ".join(out))


if __name__ == "__main__":
    t0 = time.perf_counter()
    {"2": case2, "3": case3, "4": case4, "4-gate": case4_gate,
     "4-kinematics": case4_kinematics, "4-angle": case4_angle, "3-hard": case3_hard,
     "4-hard": case4_hard}[sys.argv[1] if len(sys.argv) > 1 else "2"]()
    print(f"[{time.perf_counter() - t0:.0f} s]")
