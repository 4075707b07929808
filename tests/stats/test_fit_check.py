"""The fit check of the precision stop: its false alarms on right models and what it detects."""

import numpy as np
from scipy import stats

from pas.stats.fit_check import uniform_check


def test_uniform_transforms_are_rejected_at_most_as_often_as_the_level_says():
    rng = np.random.default_rng(0)
    rejected = [uniform_check(rng.random(60)).rejects(0.05) for _ in range(600)]
    # Bonferroni over two tests: at most 5 %, and a check that never rejects fails too
    assert 0.01 <= np.mean(rejected) <= 0.06


def test_a_model_heavier_than_the_loads_leaves_the_top_decile_empty():
    t = 0.9 * np.random.default_rng(1).random(80)  # no transform above 0.9
    check = uniform_check(t)
    assert check.p_top < 1e-3 and check.rejects(0.01)
    assert check.worst() == "the count of transforms above 0.9"


def test_a_misplaced_body_fails_on_its_shape():
    body = 0.9 * stats.beta(4, 4).rvs(180, random_state=2)  # too many in the middle of the body
    top = 0.9 + 0.1 * np.random.default_rng(3).random(20)  # and the top decile as it should be
    check = uniform_check(np.r_[body, top])
    assert check.p_ks < 1e-4 and check.worst() == "the transforms' shape (KS)"


def test_too_few_transforms_cannot_show_a_misfit():
    assert uniform_check([0.999, 0.998, 0.997, 0.996]).p == 1.0
