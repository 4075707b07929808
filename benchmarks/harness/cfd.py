"""What the CFD scripts of ``benchmarks/cfd/`` share beside :mod:`pas.validation.case_cfd`.

:func:`write_sea_recipe` writes the case's sea as the ``--sea`` file of
:mod:`pas.cfd.event` (``green_water_runs.py``, ``live_campaign.py``);
:func:`top_n_errors` is the top-N habit's error for several ``N``
(``report.py``).
"""

from __future__ import annotations

import json
import os

import pandas as pd

from pas.validation.case_cfd import CFD_CASE, cfd_lf_record, cfd_table, cfd_truth
from pas.validation.cfd_compare import top_n_estimate


def write_sea_recipe(path, case=CFD_CASE) -> str:
    """Write ``case.recipe()`` as JSON to ``path``; returns the path as a string."""
    with open(path, "w") as f:
        json.dump(case.recipe(), f, indent=1)
    return os.fspath(path)


def top_n_errors(ns=(10, 20, 30, 40, 50, 60, 70, 80, 100, 120, 150)):
    """The top-N habit's error against the truth for several ``N``."""
    events, n_waves, p_exp = cfd_lf_record()
    ok = cfd_table().query("status == 'ok'")
    truth = cfd_truth(events, ok, n_waves, p_exp)
    return pd.DataFrame([{"N": n, "error": top_n_estimate(events, ok, n, n_waves, p_exp)[0]
                          / truth - 1.0} for n in ns])
