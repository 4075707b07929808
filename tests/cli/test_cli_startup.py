"""The command line starts without the numerical stack: ``pas --help`` and ``pas study tell``.

Timing is a benchmark's business (``benchmarks/timing/cli_startup.py``); here the
cause of a slow start is checked: which libraries a fresh process imports.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pas
from pas.cli.run import STRATEGY_NAMES
from pas.study.factory import STRATEGIES

HEAVY = ("matplotlib", "sklearn", "pyvinecopulib", "scipy", "pandas")


def _python(code, *args):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(Path(pas.__file__).parents[1]), os.environ.get("PYTHONPATH", "")])}
    return subprocess.run([sys.executable, *args, "-c", code], capture_output=True, text=True,
                          env=env, check=True)


def _loaded(code):
    out = _python(code + "\nimport sys\nprint(sorted({m.split('.')[0] for m in sys.modules} & "
                  f"{set(HEAVY)!r}))").stdout
    return out.strip().splitlines()[-1]


def test_import_pas_cli_loads_no_plotting_or_model_library():
    # the check of the issue: python -X importtime -c "import pas.cli"
    timing = _python("import pas.cli", "-X", "importtime").stderr
    names = {ln.split("|")[-1].strip().split(".")[0] for ln in timing.splitlines() if "|" in ln}
    assert "pas" in names
    assert not names & {"matplotlib", "sklearn", "pyvinecopulib"}, names & set(HEAVY)


def test_help_and_study_tell_import_nothing_heavy(tmp_path):
    assert _loaded("from pas.cli import build_parser\nbuild_parser().format_help()") == "[]"
    db = tmp_path / "s.db"
    study = pas.make_study("pas", np.random.default_rng(0).rayleigh(1.0, 500), n_waves=500,
                           p_exp=0.01, eps1=0.1, seed=1, store=db)
    (ev, *_) = study.ask()
    study.store.close()
    assert _loaded(f"from pas.cli import main\nassert main(['study', 'tell', {str(db)!r}, "
                   f"'{ev.id}', '2.5']) == 0") == "[]"


@pytest.mark.slow
def test_lazy_package_keeps_its_public_names():
    code = ("import pas\nnames = [n for n in pas.__all__ if getattr(pas, n) is None]\n"
            "from pas import *\nassert callable(run_pas) and callable(pas.metrics)\n"
            "from pas.stats.metrics import m1\nassert callable(pas.metrics) and m1 is pas.m1\n"
            "from pas.study import StudyStore, open_study\nfrom pas.records import analyse_record\n"
            "print(names)")
    assert _python(code).stdout.strip() == "[]"


def test_cli_strategy_names_are_the_registry():
    assert STRATEGY_NAMES == tuple(STRATEGIES)
