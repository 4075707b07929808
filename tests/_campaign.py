"""A small HF campaign driven through a command oracle, for the kill/resume tests.

Importable by worker processes (forkserver), so it holds only module-level code.
"""

import signal
import sys
from pathlib import Path

import numpy as np

ORACLE_SCRIPT = r'''
import math, os, sys, time
event, index, lf, out, log = sys.argv[1:6]
time.sleep(0.02)
value = 1.2 * float(lf) ** 1.1 * math.exp(0.1 * math.sin(7.0 * int(index)))
with open(out + ".tmp", "w") as f:
    f.write(repr(value))
os.replace(out + ".tmp", out)
with open(log, "a") as f:
    f.write(event + "\n")
'''

SETTINGS = dict(n_waves=2000, p_exp=1e-2, eps1=1e-4, seed=7, max_hf=25)


def lf_peaks():
    return np.random.default_rng(0).rayleigh(1.0, 2000)


def oracle_value(lf, index):
    return 1.2 * lf ** 1.1 * np.exp(0.1 * np.sin(7.0 * index))


def write_script(folder) -> str:
    path = Path(folder) / "oracle.py"
    path.write_text(ORACLE_SCRIPT)
    return str(path)


def campaign(db, root, log, script, batch_size=1):
    """Run (or resume) the campaign stored in ``db``; returns the result."""
    import pas
    from pas.study.command_oracle import CommandOracle

    oracle = CommandOracle([sys.executable, script, "{id}", "{index}", "{lf}", "{result}", log],
                           root=root, timeout=60)
    import pandas as pd

    table = pd.DataFrame({"lf": lf_peaks()}, index=[f"ev{i}" for i in range(2000)])
    return pas.run_pas(table, oracle, study=db, batch_size=batch_size,
                       strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)), **SETTINGS)


def sigint_as_in_a_shell():
    """In the child before exec: SIGINT at its default action, as a shell starts a command.

    A child inherits an ignored SIGINT, and Python then leaves it ignored (no
    KeyboardInterrupt).  The tests would inherit one whenever pytest itself
    runs as a background job of a script (``pytest ... &`` ignores SIGINT):
    ``pas run`` ignored the Ctrl-C, ran to its end (exit 0) or slept on.
    """
    signal.signal(signal.SIGINT, signal.SIG_DFL)
