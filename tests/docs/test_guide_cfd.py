"""The user guide's CFD snippets run verbatim, from the folder a user stands in.

Both command-oracle snippets under "CFD: the command oracle" (docs/guide/hf-tool.md) (the Python
``CommandOracle`` one and the ``pas run --oracle 'command:...'`` one) are
taken from the page by their section heading and run as written, in a temp
folder that is the current directory and holds the user's files: the LF
peaks and a stand-in ``cfd_event.py`` that answers with a known HF peak per
seed.  Before the fix every event failed (the script was looked for in
``root/<id>/``).
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _snippets import code_blocks

import pas

SRC = str(Path(pas.__file__).resolve().parents[1])
PAGE = "docs/guide/hf-tool.md"
HEADING = "CFD: the command oracle"

# the user's CFD driver: argparse as a real one; the HF peak of a seed from a table beside it
CFD_EVENT = """\
import argparse, json, os
here = os.path.dirname(os.path.abspath(__file__))
p = argparse.ArgumentParser()
p.add_argument("--seed", required=True)
p.add_argument("--t0", type=float, required=True)
p.add_argument("--out", required=True)
a = p.parse_args()
with open(os.path.join(here, "hf_by_seed.json")) as f:
    value = json.load(f)[a.seed]
with open(a.out, "w") as f:
    f.write(repr(value))
"""


def _hf(lf, seed):
    return 1.2 * lf ** 1.1 * math.exp(0.05 * math.sin(7.0 * seed))


def _snippet(lang, needle):
    (block,) = [b for b in code_blocks(PAGE, HEADING, lang) if needle in b]
    return block


@pytest.fixture
def user_folder(tmp_path, monkeypatch):
    """The user's folder as cwd, ``python`` and ``pas`` on the PATH as this interpreter."""
    lf = np.random.default_rng(11).rayleigh(2.0, 3000)
    seeds = np.arange(3000) * 7 + 1
    table = pd.DataFrame({"id": [f"w{i:04d}" for i in range(3000)], "lf": lf, "seed": seeds,
                          "t_start": np.arange(3000) * 600.0})
    table.to_csv(tmp_path / "lf_peaks.csv", index=False)
    hf = {str(s): _hf(x, s) for x, s in zip(lf, seeds)}
    (tmp_path / "hf_by_seed.json").write_text(json.dumps(hf))
    (tmp_path / "cfd_event.py").write_text(CFD_EVENT)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "python").symlink_to(sys.executable)
    (bin_dir / "pas").write_text(f'#!/bin/sh\nexec "{sys.executable}" -m pas "$@"\n')
    (bin_dir / "pas").chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("PYTHONPATH", SRC)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)
    return tmp_path, table


def _check_told_values(history, table):
    told = history[history["status"] == "true_positive"]
    want = table.set_index("id").loc[told["event_id"]]
    np.testing.assert_allclose(told["hf"], [_hf(x, s) for x, s in zip(want["lf"], want["seed"])],
                               rtol=1e-12)


@pytest.mark.slow
def test_readme_python_command_oracle_snippet(user_folder):
    folder, table = user_folder
    code = _snippet("python", "pas.CommandOracle(")
    names = {"pas": pas, "pd": pd}  # the snippet reads lf_peaks.csv (ids, lf, metadata) itself
    exec(compile(code, PAGE, "exec"), names)
    result = names["result"]
    assert result.n_failed == 0 and result.n_hf >= 4 and math.isfinite(result.mpm)
    assert (folder / "campaign.db").exists()
    assert {p.name for p in (folder / "cfd-runs").iterdir()} == set(result.history["event_id"])
    _check_told_values(result.history, table)


@pytest.mark.slow
def test_readme_pas_run_command_snippet(user_folder):
    folder, table = user_folder
    code = _snippet("bash", "--oracle 'command:")
    run = subprocess.run(["bash", "-e", "-c", code], cwd=folder, capture_output=True, text=True,
                         timeout=1200)
    assert run.returncode == 0, run.stderr
    summary = json.loads((folder / "cfd" / "summary.json").read_text())
    assert summary["n_failed"] == 0 and math.isfinite(summary["mpm"])
    _check_told_values(pd.read_csv(folder / "cfd" / "history.csv"), table)
