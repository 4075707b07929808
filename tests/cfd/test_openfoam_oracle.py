"""One event through the OpenFOAM oracle on a tiny mesh, end to end, and its failures.

OpenFOAM must be installed (``apt-get install openfoam``; ``.ci/run`` does it):
these tests are not skipped without it, they fail.
"""

import json
import os
import shutil

import numpy as np
import pandas as pd
import pytest

from pas.cfd import GreenWaterTank, openfoam_oracle, read_forces, read_gauge
from pas.study.oracles import OracleError

SEA = {"hs": 3.0, "tp": 7.0, "gamma": 3.3, "depth": 15.0, "duration": 300.0, "omega_max": 1.8}
TINY = GreenWaterTank(depth=15.0, freeboard=1.5, upwave=20.0, deck=6.0, top=8.0, cell=0.6,
                      band=5.0, air=4.0)


def _events():
    from pas.cfd.event import sea_from_recipe
    from pas.stats.peaks import wave_crests, zero_upcrossings

    t, x = sea_from_recipe(SEA, 3).elevation(0.05)
    peaks, idx = wave_crests(x, zero_upcrossings(x))
    k = int(np.argmax(peaks))
    return pd.DataFrame({"lf": [peaks[k]], "seed": [3], "t_peak": [t[idx[k]]]},
                        index=pd.Index(["w0"], name="event"))


@pytest.fixture(scope="module")
def ran(tmp_path_factory):
    assert shutil.which("interFoam"), "OpenFOAM is not installed: apt-get install openfoam"
    root = tmp_path_factory.mktemp("cfd")
    oracle = openfoam_oracle(SEA, root / "runs", case=TINY, lead=5.0, after=2.0, cwd=root)
    return root, oracle, _events()


def _call(oracle, ev):
    from types import SimpleNamespace

    row = ev.iloc[0]
    event = SimpleNamespace(id="w0", index=0, lf=float(row.lf), d=1.0,
                            meta={"seed": int(row.seed), "t_peak": float(row.t_peak)})
    return oracle(event)


def test_one_event_runs_and_answers_named_loads(ran):
    root, oracle, ev = ran
    answer = _call(oracle, ev)
    assert set(answer) >= {"wall_peak_filtered", "wall_peak", "wall_impulse", "deck_peak"}
    assert all(np.isfinite(v) and v >= 0 for v in answer.values())
    assert answer["wall_peak"] >= answer["wall_peak_filtered"]
    folder = root / "runs" / "w0"
    info = json.loads((folder / "event.json").read_text())
    assert info["openfoam"].startswith("OPENFOAM=") and info["n_cells"] == TINY.n_cells
    assert info["t_event"] == pytest.approx(5.0)
    # the run's own outputs are kept and readable
    t, f = read_forces(folder / "case", "wallForce")
    assert t[-1] == pytest.approx(7.0, abs=0.05) and f.shape == (t.size, 3)
    tg, eta = read_gauge(folder / "case", "bow")
    assert np.isfinite(eta).all() and eta.max() > 0.5 * ev.lf.iloc[0]


def test_a_result_is_reused_not_run_again(ran):
    root, oracle, ev = ran
    log = root / "runs" / "w0" / "case" / "log.interFoam"
    if not log.exists():
        _call(oracle, ev)
    stamp = os.path.getmtime(log)
    first = json.loads((root / "runs" / "w0" / "result.json").read_text())
    with pytest.warns(RuntimeWarning, match="earlier run"):
        again = _call(oracle, ev)
    assert again == first and os.path.getmtime(log) == stamp


def test_a_broken_case_fails_the_event_never_zero(tmp_path):
    bad = TINY.write(tmp_path / "bad")
    with open(os.path.join(bad, "system", "fvSolution"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n")
    oracle = openfoam_oracle(SEA, tmp_path / "runs", case=bad, upwave=TINY.upwave, lead=5.0,
                             after=2.0, cwd=tmp_path)
    with pytest.raises(OracleError, match="exit"):
        _call(oracle, _events())
    assert not (tmp_path / "runs" / "w0" / "result.json").exists()


def test_bad_arguments(tmp_path):
    with pytest.raises(ValueError, match="sea"):
        openfoam_oracle({"hs": 3.0}, tmp_path)
    with pytest.raises(ValueError, match="case"):
        openfoam_oracle(SEA, tmp_path, case=tmp_path, upwave=10.0)
    with pytest.raises(ValueError, match="positive"):
        GreenWaterTank(cell=0.0)
