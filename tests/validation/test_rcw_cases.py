"""Design waves on the validation analogues: episode oracles and run_rcw_case.

The episode oracle of a case must be its generator's HF model: on the
generator's own sea, with the random parts of the model switched off in both,
it returns the generator's HF value for every wave event.
"""

from types import SimpleNamespace

import numpy as np
import pytest

from pas.validation import (
    CASE_IDS,
    case_impacts,
    case_impacts_hard,
    case_vbm,
    case_waves,
    generate_case,
    get_case,
)
from pas.validation._common import DT, condition_sea
from pas.validation._impact_signals import OMEGA_MAX as IMPACT_OMEGA_MAX
from pas.validation.episodes import case_surrogate, episode_oracle, run_rcw_case
from pas.waves.episode import design_episode

DURATION = 900.0
# Random parts off.  Hard variants: no deflection margin (mean 1e-9 m), no log-normal
# scatter; paper-like: never deflected, no impulsive part, no scatter.
NO_SCATTER = {"hard": {"delta_mean": 1e-9, "gw_scatter": 0.0, "slam_scatter": 0.0},
              "paper-like": {"gw_deflected": 0.0, "gw_impulse": 0.0, "gw_scatter": 0.0,
                             "slam_impulse": 0.0, "slam_scatter": 0.0}}


def _generated(case):
    spec = get_case(case)
    fam = spec.family
    if fam == "1":
        ev, _ = case_waves.generate_case1(spec, 4, 1, DURATION, 100, noise=False)
        return ev, case_waves.OMEGA_MAX, None
    if fam == "2":
        ev, _ = case_vbm.generate_case2(spec, 4, 1, DURATION, mode="hog" if case == "2a" else "sag")
        return ev, case_vbm.OMEGA_MAX, None
    mod = case_impacts_hard if spec.variant == "hard" else case_impacts
    gen = mod.generate_green_water if fam == "3" else mod.generate_slamming
    ev, _ = gen(spec, 4, 1, DURATION, coeffs=NO_SCATTER[spec.variant])
    return ev, IMPACT_OMEGA_MAX, NO_SCATTER[spec.variant]


@pytest.mark.parametrize("case", ["1a", "2a", "2b", "3b", "4b", "3b-hard", "4b-hard"])
def test_episode_oracle_is_the_generator_model(case):
    ev, omega_max, coeffs = _generated(case)
    sea = condition_sea(get_case(case).condition, DURATION, 4, 0, omega_max=omega_max)
    oracle = episode_oracle(case, coeffs)
    ours = np.array([oracle(SimpleNamespace(sea=sea, t0=t + DT)) for t in ev["t_start"]])
    assert ev["hf"].size > 50 and np.count_nonzero(ev["hf"]) >= 3
    assert np.allclose(ours, ev["hf"], rtol=1e-9, atol=1e-9 * ev["hf"].max())


def test_episode_oracle_rejects_t0_outside_a_wave():
    sea = condition_sea(get_case("2a").condition, 300.0, 0, 0, omega_max=3.0)
    with pytest.raises(ValueError, match="not inside a complete wave"):
        episode_oracle("2a")(SimpleNamespace(sea=sea, t0=0.0))


@pytest.mark.parametrize("case", CASE_IDS)
def test_case_surrogate_conditions_the_lf_response(case):
    """The surrogate's linear part is the case's LF response: its spectrum gives the
    LF-indicator scale (cases 1-3: the LF peaks are peaks of that response)."""
    s = case_surrogate(case, second_order=False)
    spec = get_case(case)
    if spec.family == "1":
        assert 4 * np.sqrt(s.m0) == pytest.approx(spec.condition.hs, rel=2e-3)
    assert s.second_order is False and s.m0 > 0 and s.m2 > 0


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    path = tmp_path_factory.mktemp("pas-cache")
    return {c: generate_case(c, scale=0.15, path=path) for c in ("2b", "3a", "4a")}


@pytest.mark.parametrize("case", ["2b", "3a", "4a"])
def test_run_rcw_case(small, case):
    data = small[case]
    res = run_rcw_case(data)
    h = res.history
    assert res.strategy == "rcw" and res.n_hf == 5 and res.n_failed == 0
    assert h["form_converged"].all() and (h["iterations"] <= 50).all()
    assert (h["residual"] <= 1e-6).all()
    at_p = h[np.isclose(h["level"], data.p_exp)]
    assert len(at_p) == 1 and res.mpm == at_p["hf"].iloc[0]
    if case != "4a":  # LF Monte-Carlo target: the LF peak read at the level
        v = np.sort(data.lf)[::-1]
        expected = np.interp(np.log(data.p_exp), np.log(np.arange(1, v.size + 1) / data.n_waves), v)
        assert at_p["target"].iloc[0] == pytest.approx(expected, rel=1e-12)
    # higher levels, higher loads (the HF models are monotone in the conditioned response)
    dist = res.distribution
    assert np.all(np.diff(dist["h_mean"].to_numpy()) <= 0)
    mler = run_rcw_case(data, method="mler")
    assert mler.strategy == "mler" and (mler.history["iterations"] == 0).all()


@pytest.mark.slow
def test_cli_reproduce_design_waves(tmp_path, monkeypatch, capsys):
    import pandas as pd

    from pas.cli import main

    monkeypatch.setenv("PAS_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "out"
    assert main(["reproduce", "2a", "--scale", "0.1", "--strategies", "rcw,mler",
                 "--replications", "3", "--out", str(out), "--quiet"]) == 0
    assert "RCW" in capsys.readouterr().out
    t = pd.read_csv(out / "table.csv")
    assert t["strategy"].tolist() == ["RCW", "MLER"]
    assert (t["hf_samples"] == 5).all() and (t["replications"] == 1).all()  # deterministic
    assert t["paper_mpm"].isna().all() and abs(t["M2"]).max() < 0.1
    assert (out / "design_2a.png").stat().st_size > 0
    assert main(["reproduce", "2a", "--strategies", "pas,rcx"]) == 2
    assert "unknown rcx" in capsys.readouterr().err


def test_case1_rcw_holds_the_hf_crest_at_the_linear_target():
    """Why FORM-RCW misses case 1 (README): its surrogate *is* the HF crest, so the
    episode's second-order crest equals the linear target; MLER's exceeds it."""
    oracle = episode_oracle("1a")
    s = case_surrogate("1a", duration=300.0)
    rcw = oracle(design_episode(s, 9.0))
    assert rcw == pytest.approx(9.0, rel=1e-6)
    mler = oracle(design_episode(case_surrogate("1a", duration=300.0, second_order=False), 9.0,
                                 method="mler"))
    assert mler > 1.1 * 9.0
