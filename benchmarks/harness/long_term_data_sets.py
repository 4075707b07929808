"""The long-term analogues' data sets as ``benchmarks/studies/long_term.py`` reads them.

:func:`pool_data_sets` joins redraws of one scatter into one data set (the
"pooled truth" of ``docs/results/long-term.md``); :func:`p_exceed_of_return_period`
gives the per-encounter exceedance of a return period (its 20-year level).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pandas as pd

from pas.waves import HOURS_PER_YEAR


def pool_data_sets(datasets):
    """One data set of the union of ``datasets`` (redraws of one scatter, same sea states).

    Per sea state every event of every data set (ids prefixed ``d<seed>-``),
    ``n_waves``, ``duration`` and ``hours`` summed, so that its encounter rate
    is theirs together; its truth has about the error of one data set's
    divided by √(number of data sets).
    """
    names = list(datasets[0].hf)

    def joined(attr):
        return {s: np.concatenate([getattr(d, attr)[s] for d in datasets]) for s in names}

    table = datasets[0].sea_states.copy()
    for col in ("n_waves", "duration", "hours"):
        table[col] = sum(d.sea_states.set_index("name").loc[table["name"], col].to_numpy()
                         for d in datasets)
    ids = {s: np.concatenate([np.char.add(f"d{d.seed}-", d.ids[s].astype(str)) for d in datasets])
           for s in names}
    meta = {s: pd.concat([d.meta[s] for d in datasets], ignore_index=True) for s in names}
    return replace(datasets[0], sea_states=table, lf=joined("lf"), hf=joined("hf"), ids=ids,
                   meta=meta, info={"pooled_seeds": [d.seed for d in datasets]})


def p_exceed_of_return_period(data, years, hours_per_year=HOURS_PER_YEAR):
    """Per-encounter exceedance of the ``years`` return period of a
    :class:`~pas.validation.long_term_data.LongTermData`: ``1 / (years · N_year)`` with
    ``N_year = 3600 · hours_per_year · Σ p_s ν_s / Σ p_s`` wave encounters a year."""
    t = data.sea_states
    p = t["probability"].to_numpy(float)
    nu = t["n_waves"].to_numpy(float) / t["duration"].to_numpy(float)
    per_year = 3600.0 * float(hours_per_year) * float(np.sum(p * nu) / np.sum(p))
    return 1.0 / (float(years) * per_year)
