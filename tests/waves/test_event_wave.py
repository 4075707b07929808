"""The event's wave for an HF tool: components referred to an inlet and a start time."""

import re

import numpy as np
import pytest

from pas.waves import jonswap, linear_sea, wave_number
from pas.waves.event_wave import event_wave


@pytest.fixture(scope="module")
def sea():
    return linear_sea(lambda w: jonswap(w, 6.0, 10.0), 600.0, seed=5, depth=40.0, omega_max=1.6)


def test_structure_sees_the_lf_record_from_t_start(sea):
    t, eta = sea.elevation(0.05)                       # FFT synthesis of the LF record
    i = int(np.argmax(eta))
    wave = event_wave(sea, t[i], upwave=50.0, lead=15.0)
    run = np.arange(0.0, 20.0, 0.05)
    rec = np.interp(wave.t_start + run, t, eta, period=sea.duration)
    np.testing.assert_allclose(wave.elevation(run), rec, atol=2e-3 * eta.max())
    crest, when = wave.crest()
    assert when == pytest.approx(15.0, abs=0.06) and crest == pytest.approx(eta[i], rel=0.01)


def test_upwave_point_leads_by_linear_dispersion(sea):
    wave = event_wave(sea, 100.0, upwave=50.0, lead=15.0)
    # one component alone: at the inlet its phase leads the structure's by k * upwave
    k = wave_number(wave.omega, 40.0)
    np.testing.assert_allclose(wave.wave_number, k)
    j = int(np.argmax(wave.amplitude))
    t = np.linspace(0, 10, 7)
    at_inlet = wave.amplitude[j] * np.cos(wave.omega[j] * t + wave.phase[j])
    at_struct = wave.amplitude[j] * np.cos(wave.omega[j] * t - k[j] * 50.0 + wave.phase[j])
    shift = k[j] * 50.0 / wave.omega[j]                 # phase-speed travel time
    np.testing.assert_allclose(at_struct, wave.amplitude[j]
                               * np.cos(wave.omega[j] * (t - shift) + wave.phase[j]), atol=1e-9)
    assert not np.allclose(at_inlet, at_struct)


def test_openfoam_dictionary_reproduces_the_record_at_the_structure(sea):
    """OpenFOAM writes (H/2) cos(k x - w t + psi): evaluate its dictionary as it would."""
    t, eta = sea.elevation(0.05)
    wave = event_wave(sea, 200.0, upwave=30.0, lead=12.0)
    text = wave.openfoam_dict()

    def block(key):
        body = re.search(key + r"\s+\d+\s+\((.*?)\n\s*\);", text, re.S).group(1)
        return np.array([float(v) for v in re.findall(r"\(([^()]+)\)", body)])

    period, height, psi = block("wavePeriods"), block("waveHeights"), block("wavePhases")
    w = 2 * np.pi / period
    k = wave_number(w, 40.0)
    run = np.arange(0.0, 15.0, 0.1)
    foam = (0.5 * height * np.cos(k * 30.0 - np.outer(run, w) + psi)).sum(axis=1)
    rec = np.interp(wave.t_start + run, t, eta, period=sea.duration)
    np.testing.assert_allclose(foam, rec, atol=2e-3 * np.abs(eta).max())
    assert "irregularMultiDirectional" in text and "shallowWaterAbsorption" in text


def test_energy_cut_keeps_the_largest_components(sea):
    wave = event_wave(sea, 300.0, upwave=40.0, lead=10.0)
    cut = wave.cut(0.95)
    assert cut.n_components < wave.n_components
    assert cut.energy >= 0.95 and np.sum(cut.amplitude ** 2) / np.sum(wave.amplitude ** 2) \
        == pytest.approx(cut.energy)
    assert cut.amplitude.min() >= np.sort(wave.amplitude)[::-1][cut.n_components - 1]
    effect = wave.cut_effect(0.95)
    assert set(effect) >= {"crest_error", "time_shift", "n_components"}


@pytest.mark.parametrize("kw, word", [({"upwave": -1.0, "lead": 5.0}, "upwave"),
                                      ({"upwave": 10.0, "lead": 0.0}, "lead")])
def test_bad_arguments_name_themselves(sea, kw, word):
    with pytest.raises(ValueError, match=word):
        event_wave(sea, 10.0, **kw)


def test_csv_and_json_writers(sea, tmp_path):
    import json

    wave = event_wave(sea, 50.0, upwave=20.0, lead=8.0)
    doc = json.loads(wave.to_json(tmp_path / "w.json"))
    assert doc["t_start"] == pytest.approx(42.0) and len(doc["components"]["omega"]) \
        == wave.n_components
    ts = wave.time_series(10.0, dt=0.5)
    assert list(ts.columns) == ["t", "eta_inlet", "eta_structure"] and len(ts) == 21
    assert len(wave.components()) == wave.n_components
