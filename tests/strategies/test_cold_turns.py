"""Cold starts of the study's joint fits: each family in its own turn, not all at once."""

import numpy as np
from test_estimator import _problem

import pas.models.joint as joint
import pas.strategies.estimators as estimators
from pas.strategies.band import ModelBand
from pas.strategies.estimators import COLD_EVERY
from pas.strategies.pas import PAS
from pas.strategies.steps import cold_turns


def test_each_family_starts_cold_once_in_cold_every_fits_and_never_two_at_once():
    families = ("gaussian", "student", "clayton", "gumbel", "frank")
    turns = [cold_turns(families, n, COLD_EVERY) for n in range(3 * COLD_EVERY)]
    assert all(len(t) <= 1 for t in turns)
    for f in families:
        assert sum(f in t for t in turns) == 3


def test_in_turn_a_study_refits_at_most_one_family_cold_per_iteration(monkeypatch):
    monkeypatch.setattr(estimators, "COLD_IN_TURN", True)
    s, pairs, _ = _problem(4, tau=0.6, m=40)
    strategy = PAS(band=ModelBand(n_bootstrap=0))
    strategy.reset(0)
    original, per_iteration = joint.fit_joint, []

    def counted(name, *args, start=None, cold=True, **kwargs):
        cold_fits.append(start is not None and cold)
        return original(name, *args, start=start, cold=cold, **kwargs)

    monkeypatch.setattr(joint, "fit_joint", counted)
    for m in range(8, 8 + 2 * COLD_EVERY):
        cold_fits = []
        strategy.predict(pairs.take(np.arange(m), np.array([], int)), s,
                         np.random.default_rng(0))
        per_iteration.append(sum(cold_fits))
    assert max(per_iteration) == 1 and sum(per_iteration) == 2 * len(strategy.families) - 1


def test_up_to_cold_up_to_pairs_every_fit_also_starts_from_the_data(monkeypatch):
    monkeypatch.setattr(estimators, "COLD_UP_TO", 12)
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
    # the first fit has no warm start; up to 12 pairs every later one also starts cold,
    # above only the COLD_EVERY-th (the study's 11th fit, at 18 pairs)
    assert per_iteration[8] == (0, n_fits)
    assert all(per_iteration[m] == (n_fits, n_fits) for m in range(9, 13))
    assert [m for m in range(13, 8 + COLD_EVERY + 2) if per_iteration[m][0]] == [8 + COLD_EVERY]
    assert all(per_iteration[m][0] in (0, n_fits) for m in per_iteration)
