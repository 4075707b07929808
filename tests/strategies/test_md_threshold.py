"""Faithful MD and adaptive threshold (paper §2.4, Eq. 16–17) and common random numbers.

MD's gaps must include the false positives, so it can
sample below the lowest true positive and the threshold rule can fire; and the
stopping measures must see model change, not redrawn conditional draws.
"""

import numpy as np
import pytest

import pas
from pas.strategies.band import ModelBand
from pas.strategies.base import Pairs
from pas.strategies.estimators import ConditionalLikelihood, SelectedSample
from pas.strategies.pas import PAS
from pas.strategies.screening import LFSet
from pas.strategies.stopping import distribution_change, range_grid

NO_BAND = PAS(band=ModelBand(n_bootstrap=0))


def _threshold_problem(n=300, seed=0):
    """LF over a threshold; no impact below LF 6 (a cluster of misses at the bottom)."""
    rng = np.random.default_rng(seed)
    lf = np.sort(rng.uniform(4.0, 10.0, n))[::-1]
    hf = np.where(lf > 6.0, 100.0 * np.maximum(lf - 5.0, 0) ** 1.5 * rng.lognormal(0, 0.1, n), 0.0)
    return lf, hf


def _run(study, hf, n):
    """Ask/tell ``n`` events one at a time; returns the told (position, value) list."""
    for _ in range(n):
        events = study.ask()
        if not events:
            break
        for ev in events:
            study.tell(ev, hf[ev.index])


def test_md_samples_below_the_lowest_true_positive():
    lf, hf = _threshold_problem()
    study = pas.make_study(NO_BAND, lf, n_waves=3000, p_exp=0.01, eps1=1.0, threshold=4.0,
                           seed=0, stop_on_convergence=False, adaptive_threshold=False)
    _run(study, hf, 4)
    h = study.history()
    lowest = h[h.status == "false_positive"].lf.min()
    assert lowest < 4.1  # the initial design includes the lowest pool peak: a miss
    _run(study, hf, 20)
    h = study.history()
    tp = h[h.status == "true_positive"]
    # with gaps over true positives only, nothing below the lowest initial true
    # positive would ever be proposed; over all evaluated events MD goes there
    lowest_initial_tp = tp.iloc[:3].lf.min()
    later = h.iloc[4:]
    assert (later.lf < lowest_initial_tp).sum() >= 2


def test_threshold_rises_after_five_misses_below_every_true_positive_and_count_restarts():
    # no threshold given and impacts only for the 30 largest of 3000 LF peaks:
    # MD "oversamples zero HF values" (§2.4) until the threshold climbs
    rng = np.random.default_rng(1)
    lf = np.sort(rng.rayleigh(1.0, 3000))[::-1]
    hf = np.where(np.arange(lf.size) < 30, 50.0 * lf, 0.0)
    study = pas.make_study(NO_BAND, lf, n_waves=3000, p_exp=0.005, eps1=1.0, seed=3,
                           stop_on_convergence=False)
    _run(study, hf, 60)
    h = study.history()
    level = h.threshold.fillna(lf.min())
    raised = h.index[level.diff() > 0]
    assert len(raised) >= 3
    step = 0.02 * lf.max()
    assert level.iloc[raised[0]] == pytest.approx(lf.min() + step)
    assert np.allclose(np.diff(level.iloc[raised]), step)
    for i in raised:
        # each raise came on a fifth consecutive miss, below every true positive so far
        assert (h.status.iloc[i - 4: i + 1] == "false_positive").all()
        assert h.lf.iloc[i] < h.lf.iloc[:i][h.status.iloc[:i] == "true_positive"].min()
    # the count starts again after a raise: raises are at least five events apart
    assert np.diff(raised).min() >= 5


def test_threshold_does_not_rise_on_misses_above_a_true_positive():
    # misses interleaved with hits high up must not raise the threshold
    rng = np.random.default_rng(2)
    lf = np.sort(rng.uniform(4.0, 10.0, 300))[::-1]
    hf = np.where(np.arange(lf.size) % 2 == 0, 30.0 * lf, 0.0)
    study = pas.make_study(NO_BAND, lf, n_waves=3000, p_exp=0.01, eps1=1.0, threshold=4.0,
                           seed=0, stop_on_convergence=False, fp_run=2)
    _run(study, hf, 30)
    h = study.history()
    tp_min = np.minimum.accumulate(np.where(h.status == "true_positive", h.lf, np.inf))
    for i in h.index[h.threshold.diff() > 0]:
        assert h.lf.iloc[i] < tp_min[i - 1]


def _pairs(s, pos, hf):
    pos = np.asarray(pos)
    return Pairs(pos, s.lf[pos], hf[pos], s.d[pos])


@pytest.mark.parametrize("estimator", [SelectedSample(), ConditionalLikelihood()])
def test_common_random_numbers_make_the_same_model_predict_the_same_distribution(estimator):
    rng = np.random.default_rng(0)
    lf = rng.rayleigh(1.0, 5000)
    s = LFSet(lf, n_waves=5000, p_exp=2e-3)
    hf = 1000 * s.lf ** 1.5 * rng.lognormal(0, 0.3, s.n)
    pairs = _pairs(s, np.unique(np.geomspace(1, s.n, 30).astype(int) - 1), hf)
    grid = range_grid(s.p_exp)

    def change(crn, seeds=(0, 1)):
        preds = []
        for k in seeds:
            st = PAS(estimator=estimator, common_random_numbers=crn,
                     band=ModelBand(n_bootstrap=0))
            st.reset(7)
            preds.append(st.predict(pairs, s, np.random.default_rng(k)))
        return distribution_change(preds[0].at(grid), preds[1].at(grid))

    assert change(True) == 0.0           # same model, same numbers: no change at all
    assert change(False) > 0.0           # redrawn every iteration: noise alone moves E
