"""Design waves: MLER against mhkit, the second-order surrogate, FORM-RCW and run_rcw.

Independent references: mhkit's MLER coefficients (stored with the script that
made them, ``benchmarks/studies/mler_mhkit_reference.py``), the time-domain double
summation of the Sharma–Dean surface (``direct_second_order``), finite
differences, scipy's SLSQP for the constrained minimum, and closed forms.
"""

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import integrate, optimize

import pas
from pas.waves import direct_second_order, jonswap, response_surrogate
from pas.waves.design import form_rcw, mler, mler_amplitudes, rayleigh_target
from pas.waves.episode import design_episode

DATA = Path(__file__).parents[1] / "data" / "mler_mhkit.json"


def _sea_a(**kw):
    """Condition A (case 1) on a short, coarse grid: fast, still clearly non-linear."""
    opts = dict(duration=300.0, depth=30.0, omega_max=2.0)
    opts.update(kw)
    return response_surrogate(lambda w: jonswap(w, 10.0, 11.0), lambda w: np.ones_like(w), **opts)


@pytest.fixture(scope="module")
def crest():
    return _sea_a()


@pytest.fixture(scope="module")
def vbm_like():
    """A complex, frequency-dependent transfer function, at speed, off the reference point."""
    def transfer(w):
        return 2e8 * np.exp(-0.5 * w) * w**2 / (1 - (w / 0.9) ** 2 + 0.6j * w / 0.9)
    return response_surrogate(lambda w: jonswap(w, 13.2, 10.0, 3.0), transfer, duration=300.0,
                              omega_max=1.6, depth=1000.0, speed=5.1, heading=180.0, x=40.0)


# -- MLER -------------------------------------------------------------------
@pytest.mark.parametrize("name", ["pm_oscillator", "jonswap_lagged"])
def test_mler_matches_mhkit(name):
    ref = json.loads(DATA.read_text())["cases"][name]
    w = np.asarray(ref["omega"])
    d_w = ref["d_w"]
    assert np.allclose(np.diff(w), d_w)  # mhkit's step convention holds on this grid
    s_rad = np.asarray(ref["spectrum_m2_per_hz"]) / (2 * np.pi)
    rao = np.asarray(ref["rao_real"]) + 1j * np.asarray(ref["rao_imag"])
    ours = mler_amplitudes(np.sqrt(s_rad * d_w), rao, ref["target"], omega_e=w)
    theirs = np.sqrt(2 * np.asarray(ref["wave_spectrum"]) * d_w) * np.exp(
        1j * np.asarray(ref["phase"])
    )
    big = np.abs(theirs) > 1e-6 * np.abs(theirs).max()
    assert big.sum() > 50
    assert np.max(np.abs(ours - theirs)) <= 1e-6 * np.abs(theirs).max()
    assert np.allclose(ours[big], theirs[big], rtol=1e-6, atol=0)
    # and the episode's linear response reaches the target at t0 = 0
    assert np.real(np.sum(rao * ours)) == pytest.approx(ref["target"], rel=1e-12)


def test_mler_shifts_with_t0_and_flips_with_the_sign():
    w = np.array([0.5, 0.8, 1.1])
    a0 = mler_amplitudes([1.0, 2.0, 0.5], [1.0, 0.3j, -0.7], 2.0, omega_e=w)
    a5 = mler_amplitudes([1.0, 2.0, 0.5], [1.0, 0.3j, -0.7], 2.0, omega_e=w, t0=5.0)
    assert np.allclose(a5, a0 * np.exp(-5j * w))
    assert np.allclose(mler_amplitudes([1.0, 2.0, 0.5], [1.0, 0.3j, -0.7], -2.0, omega_e=w), -a0)
    with pytest.raises(ValueError, match="zero variance"):
        mler_amplitudes([1.0], [0.0], 1.0, omega_e=[1.0])


def test_surrogate_mler_is_the_closed_form(vbm_like):
    s = vbm_like
    sea = s.sea(mler(s, 3e9))
    tr = s.transfer[:s.n] * np.exp(-1j * s.template.wave_number * s.x * np.cos(np.pi))
    expected = mler_amplitudes(s.sigma, tr, 3e9, omega_e=s.template.omega_e, t0=s.t0)
    assert np.allclose(sea.amplitude, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


# -- the surrogate ----------------------------------------------------------
def test_surrogate_value_is_the_surface_at_t0(crest):
    """Linear + second-order crest at t0: against the FFT record and the direct double sum."""
    u = np.random.default_rng(3).standard_normal(2 * crest.n)
    sea = crest.sea(u)
    t, eta = sea.synthesise(crest.surface_coefficients(sea), 0.1)
    i = int(np.argmin(np.abs(t - crest.t0)))
    assert t[i] == pytest.approx(crest.t0)
    assert crest.value(u) == pytest.approx(eta[i], rel=1e-10, abs=1e-10)
    kern = crest.kernel
    band = slice(kern.j0, kern.j0 + kern.size)
    eta1 = np.real(np.sum(sea.amplitude * np.exp(1j * sea.omega_e * crest.t0)))
    eta2 = direct_second_order(sea.omega[band], sea.amplitude[band], np.array([crest.t0]),
                               depth=30.0, omega_e=sea.omega_e[band])[0]
    assert crest.value(u) == pytest.approx(eta1 + eta2, rel=1e-9)
    assert abs(eta2) > 1e-3 * abs(eta1)  # the second order is really there


def test_surrogate_gradient_by_finite_differences(vbm_like):
    s = vbm_like
    u = np.random.default_rng(5).standard_normal(2 * s.n)
    _, g = s.value_and_gradient(u)
    h = 1e-4
    for j in np.random.default_rng(6).choice(2 * s.n, 12, replace=False):
        e = np.zeros_like(u)
        e[j] = h
        fd = (s.value(u + e) - s.value(u - e)) / (2 * h)  # exact for a quadratic
        assert fd == pytest.approx(g[j], rel=1e-6, abs=1e-9 * np.abs(g).max())


def test_linear_variance_is_the_spectrum(crest):
    lin = _sea_a(second_order=False, omega_max=5.0)
    assert lin.q is None and not lin.second_order
    assert 4 * np.sqrt(lin.m0) == pytest.approx(10.0, rel=1e-3)  # Hs = 4 sqrt(m0)


# -- FORM-RCW ---------------------------------------------------------------
def test_form_on_a_linear_surrogate_returns_mler_exactly():
    lin = _sea_a(second_order=False)
    u_mler = mler(lin, 9.0)
    res = form_rcw(lin, 9.0)
    assert res.converged and res.iterations == 0 and np.array_equal(res.u, u_mler)
    start = np.random.default_rng(1).standard_normal(2 * lin.n)
    res2 = form_rcw(lin, 9.0, start=start)
    assert res2.converged and res2.iterations <= 50
    assert np.allclose(res2.u, u_mler, rtol=0, atol=1e-7 * np.linalg.norm(u_mler))


@pytest.mark.parametrize("target", [7.0, 11.0, -6.0])
def test_form_reaches_the_target_at_the_constrained_minimum(crest, target):
    res = form_rcw(crest, target)
    assert res.converged and res.iterations <= 50
    assert abs(crest.value(res.u) - target) <= 1e-6 * abs(target)
    # no feasible point nearby is closer to the origin
    rng = np.random.default_rng(2)
    for _ in range(20):
        trial = res.u + 0.05 * rng.standard_normal(res.u.size)
        v, g = crest.value_and_gradient(trial)
        for _ in range(5):  # Newton steps back onto chi = target along the gradient
            trial = trial - (v - target) / (g @ g) * g
            v, g = crest.value_and_gradient(trial)
        assert np.linalg.norm(trial) >= res.beta * (1 - 1e-9)
    # a second-order crest of the same height is more likely than a linear one
    beta_lin = np.linalg.norm(mler(crest, target))
    assert (res.beta < beta_lin) if target > 0 else (res.beta > beta_lin)


def test_form_agrees_with_scipy_slsqp(crest):
    """scipy's SLSQP on the same problem, from the same start, finds the same point."""
    from threadpoolctl import threadpool_limits

    target = 11.0
    res = form_rcw(crest, target)
    cons = {"type": "eq", "fun": lambda u: crest.value(u) - target,
            "jac": lambda u: crest.value_and_gradient(u)[1]}
    with threadpool_limits(1):  # dense small QPs: threads only contend on a busy machine
        ref = optimize.minimize(lambda u: 0.5 * u @ u, mler(crest, target), jac=lambda u: u,
                                constraints=[cons], method="SLSQP",
                                options={"ftol": 1e-14, "maxiter": 200})
    assert ref.success
    assert res.beta == pytest.approx(np.linalg.norm(ref.x), rel=1e-6)
    assert np.allclose(res.u, ref.x, atol=1e-4)


def test_form_reports_a_miss_instead_of_claiming_convergence(crest):
    res = form_rcw(crest, 11.0, start=np.full(2 * crest.n, 0.3), max_iter=1)
    assert not res.converged and res.iterations == 1


def test_form_rejects_bad_targets(crest):
    for bad in (0.0, np.nan):
        with pytest.raises(ValueError, match="target"):
            form_rcw(crest, bad)
    with pytest.raises(ValueError, match="u must have shape"):
        crest.value(np.zeros(3))


# -- episodes ---------------------------------------------------------------
def test_episode_series_components_and_csv(crest, tmp_path):
    ep = design_episode(crest, 10.0, level=1e-3, index=2)
    ts = ep.time_series(0.1)
    i = int(np.argmin(np.abs(ts["t"].to_numpy() - ep.t0)))
    assert ts["response"].iloc[i] == pytest.approx(10.0, rel=1e-6)
    assert ts["eta"].iloc[i] == pytest.approx(10.0, rel=1e-6)        # T = 1: the surface itself
    assert ts["eta_linear"].iloc[i] < 10.0                           # the linear part is lower
    assert ts["response"].idxmax() == i                              # the crest is at t0
    comp = ep.components()
    a = comp["amplitude"].to_numpy() * np.exp(1j * comp["phase"].to_numpy())
    assert np.allclose(a, ep.sea.amplitude[np.abs(ep.sea.amplitude) > 0])
    paths = ep.write_csv(tmp_path)
    assert pd.read_csv(paths["episode"]).shape == (ts.shape[0], 4)
    assert pd.read_csv(paths["components"]).shape == comp.shape
    assert ep.id.startswith("rcw02-") and ep.id != design_episode(crest, 10.5, index=2).id
    assert ep.meta["level"] == 1e-3 and ep.d == 1e-3 and ep.lf == 10.0
    m = design_episode(crest, 10.0, method="mler")
    assert m.form.iterations == 0 and m.beta > ep.beta
    with pytest.raises(ValueError, match="method"):
        design_episode(crest, 10.0, method="newwave")


def test_surrogate_rejects_bad_settings():
    with pytest.raises(ValueError, match="t0"):
        _sea_a(t0=400.0)
    with pytest.raises(ValueError, match="duration"):
        _sea_a(duration=-1.0)


# -- the strategy -----------------------------------------------------------
def test_rayleigh_target_is_the_closed_form():
    assert rayleigh_target(4.0, 1e-3) == pytest.approx(np.sqrt(2 * 4.0 * np.log(1e3)))
    assert rayleigh_target(4.0, 1e-3, peaks_per_wave=1.3) == pytest.approx(
        np.sqrt(8.0 * np.log(1.3e3)))
    with pytest.raises(ValueError, match="p must"):
        rayleigh_target(1.0, 0.0)


def test_run_rcw_ladder_targets_and_result(crest, tmp_path):
    lin = _sea_a(second_order=False)
    seen = []

    def oracle(ep):
        seen.append(ep)
        return 1.2 * ep.target

    res = pas.run_rcw(crest, oracle, p_exp=1e-3, levels=[1e-2, 5e-4, 2e-3], n_waves=20_000)
    assert isinstance(res, pas.ScreeningResult) and res.strategy == "rcw"
    assert res.n_hf == 4 and res.n_failed == 0 and res.converged
    levels = [e.level for e in seen]
    assert levels == sorted(levels, reverse=True) and 1e-3 in levels
    m0 = integrate.quad(lambda w: jonswap(w, 10.0, 11.0), 0.0, 2.0, limit=200)[0]  # band 0-2 rad/s
    expected = np.sqrt(2 * m0 * np.log(1 / np.array(levels)))
    assert np.allclose([e.target for e in seen], expected, rtol=1e-3)
    assert res.mpm == pytest.approx(1.2 * expected[levels.index(1e-3)], rel=1e-3)
    assert np.allclose(res.distribution["f_nl"], 0.2)
    assert res.distribution["exceedance_probability"].is_monotonic_increasing
    assert np.all(res.history["form_converged"]) and (res.history["iterations"] <= 50).all()
    # M2 and M3 of pas.metrics work on it (levels cover [P/2, 2P])
    truth_d = np.geomspace(1e-4, 1e-1, 50)
    truth_h = 1.2 * np.sqrt(2 * lin.m0 * np.log(1 / truth_d))
    met = pas.metrics(
        res, truth_d, truth_h, float(np.interp(np.log(1e-3), np.log(truth_d), truth_h))
    )
    assert abs(met["M2"]) < 3e-3 and abs(met["M3"]) < 0.02 and met["M1"] == 4 / 20_000
    res.save(tmp_path / "rcw")                               # same files as PAS and AS
    back = pas.ScreeningResult.load(tmp_path / "rcw")
    assert back.strategy == "rcw" and back.mpm == res.mpm and back.n_hf == 4
    assert np.allclose(back.distribution["f_nl"], 0.2)
    mres = pas.run_rcw(crest, oracle, p_exp=1e-3, method="mler")
    assert mres.strategy == "mler" and mres.n_hf == 1
    with pytest.raises(ValueError, match="n_waves"):
        pas.m1(mres)


def test_run_rcw_lf_target_failures_and_study_store(crest, tmp_path):
    lf = np.random.default_rng(0).rayleigh(2.5, 5000)
    v = np.sort(lf)[::-1]
    expected = np.interp(np.log(2e-3), np.log(np.arange(1, v.size + 1) / 6000), v)
    calls = []

    def oracle(ep):
        calls.append(ep.level)
        if ep.level > 5e-3:
            raise RuntimeError("CFD diverged")
        return 0.0 if ep.level > 2e-3 else 3.0 * ep.target

    kw = dict(p_exp=2e-3, levels=[1e-2, 4e-3], linear_target="lf", lf_peaks=lf, n_waves=6000,
              study=tmp_path / "rcw.sqlite")
    res = pas.run_rcw(crest, oracle, **kw)
    assert res.n_failed == 1 and res.n_false_positive == 1 and res.n_hf == 2
    assert not res.converged  # a failed episode is not a finished study
    h = res.history.set_index("level")
    assert h.loc[1e-2, "status"] == "failed" and "CFD diverged" in h.loc[1e-2, "error"]
    assert h.loc[2e-3, "target"] == pytest.approx(expected, rel=1e-12)
    assert res.mpm == pytest.approx(3 * expected, rel=1e-12)
    assert len(pas.StudyStore(kw["study"]).events()) == 3
    calls.clear()
    again = pas.run_rcw(crest, oracle, **kw)          # rerun: every result from the store
    assert calls == [] and again.n_failed == 1 and again.mpm == res.mpm
    retried = pas.run_rcw(crest, oracle, **kw, retry_failed=True)   # only the failed one reruns
    assert calls == [1e-2] and retried.n_failed == 1 and retried.mpm == res.mpm
    with pytest.raises(ValueError, match="lf_peaks and n_waves"):
        pas.run_rcw(crest, oracle, p_exp=2e-3, linear_target="lf")
    with pytest.raises(ValueError, match="linear_target must be"):
        pas.run_rcw(crest, oracle, p_exp=2e-3, linear_target="gauss")
    with pytest.raises(ValueError, match="ResponseSurrogate"):
        pas.run_rcw(lf, oracle, p_exp=2e-3)


def test_command_oracle_runs_an_episode_from_its_csv(crest, tmp_path):
    script = tmp_path / "hf.py"
    script.write_text(
        "import sys, pandas as pd\n"
        "ts = pd.read_csv(sys.argv[1])\n"
        "open(sys.argv[2], 'w').write(str(1.5 * ts['response'].max()))\n")
    oracle = pas.CommandOracle([sys.executable, str(script), "{episode}", "{result}"],
                               root=tmp_path / "runs", timeout=60)
    res = pas.run_rcw(crest, oracle, p_exp=1e-3)
    assert res.n_failed == 0
    assert res.mpm == pytest.approx(1.5 * res.distribution["linear"].iloc[0], rel=1e-6)
    ep_dir = tmp_path / "runs" / res.history["episode_id"].iloc[0]
    assert (ep_dir / "episode.csv").exists() and (ep_dir / "components.csv").exists()
    # the inputs were staged, then moved in; the record names the command and their digests
    assert not [p for p in ep_dir.iterdir() if p.name.startswith(".inputs-")]
    record = json.loads((ep_dir / ".pas-command.json").read_text())
    assert sorted(record["files"]) == ["components", "episode"]
    assert "{workdir}/episode.csv" in record["command"]  # as the folder sees it, movable
