"""Cold starts of the study's joint fits: every COLD_EVERY-th fit, all families at once."""

import numpy as np
from test_estimator import _problem

import pas.models.joint as joint
from pas.strategies.band import ModelBand
from pas.strategies.estimators import COLD_EVERY
from pas.strategies.pas import PAS


def test_only_every_cold_every_th_fit_also_starts_from_the_data(monkeypatch):
    s, pairs, _ = _problem(4, tau=0.6, m=40)
    strategy = PAS(band=ModelBand(n_bootstrap=0))
    strategy.reset(0)
    original, per_iteration = joint.fit_joint, {}

    def counted(name, *args, start=None, cold=True, **kwargs):
        cold_fits.append(start is not None and cold)
        return original(name, *args, start=start, cold=cold, **kwargs)

    monkeypatch.setattr(joint, "fit_joint", counted)
    for m in range(8, 8 + COLD_EVERY + 2):
        cold_fits = []
        strategy.predict(pairs.take(np.arange(m), np.array([], int)), s,
                         np.random.default_rng(0))
        per_iteration[m] = (sum(cold_fits), len(cold_fits))
    n_fits = len(strategy.families)
    # the first fit has no warm start; of the later ones only the COLD_EVERY-th (the
    # study's 11th fit, at 18 pairs) also starts from the data, every family at once
    assert per_iteration[8] == (0, n_fits)
    assert [m for m in range(9, 8 + COLD_EVERY + 2) if per_iteration[m][0]] == [8 + COLD_EVERY]
    assert all(per_iteration[m][0] in (0, n_fits) for m in per_iteration)
