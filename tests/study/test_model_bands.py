"""Several studies' model bands at once, one a process (pas.study.precision.model_bands)."""

import copy
import os

import _longterm_problem as problem
import numpy as np
import pytest
from harness.timing_problem import scenario

import pas
import pas.strategies.band as band_module
from pas.study import precision


def _studies(sizes=(600, 2500, 1200), max_hf=14):
    """Fitted studies of different sizes (a Gumbel problem each), their bands not computed."""
    out = []
    for k, n in enumerate(sizes):
        lf, hf = scenario(n, seed=10 + k)
        seen = []
        pas.run_pas(lf, lambda e, hf=hf: float(hf[e.index]), n_waves=int(1.1 * n), p_exp=0.01,
                    eps1=1e-12, seed=k, max_hf=max_hf,
                    strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)),
                    callback=lambda study, row: seen.append(study))
        study = seen[-1]
        study.strategy.band = pas.ModelBand(n_bootstrap=12)
        study.kept_band = None  # run_pas's result kept the band of no replicates
        out.append(study)
    return out


def test_bands_in_processes_are_each_studys_own_band_and_are_kept():
    studies = _studies()
    alone = copy.deepcopy(studies)
    seconds = precision.model_bands([None, *studies], n_jobs=2)
    assert sorted(seconds) == [1, 2, 3] and all(s > 0 for s in seconds.values())
    for study, other in zip(studies, alone):
        expected = precision.model_band(other, other.pairs(), n_jobs=1)
        assert expected is not None and np.all(np.isfinite(expected))
        # kept: reading it again computes nothing and gives the band to the bit
        assert precision.model_band(study, study.pairs()) == expected
    assert precision.model_bands(studies, n_jobs=2) == {}  # nothing left to compute


def test_only_the_bands_not_kept_are_computed():
    studies = _studies(sizes=(800, 900), max_hf=10)
    first = precision.model_band(studies[0], studies[0].pairs())
    assert first is not None
    assert sorted(precision.model_bands(studies, n_jobs=2)) == [1]
    assert precision.model_band(studies[0], studies[0].pairs()) == first


class _Broken(ValueError):
    """An error that cannot be rebuilt from its pickle (a keyword-only argument)."""

    def __init__(self, *, why):
        super().__init__(why)


def test_a_band_that_raises_in_a_worker_raises_its_own_error_here():
    studies = _studies(sizes=(700, 800), max_hf=10)
    real = studies[1].strategy.model_band

    def broken(pairs, lfset, rng, *, n_jobs=None):  # takes n_jobs: run in a worker
        raise _Broken(why="no band")

    studies[1].strategy.model_band = broken  # an override as a user's strategy might have
    with pytest.raises(_Broken, match="no band"):
        precision.model_bands(studies, n_jobs=2)
    studies[1].strategy.model_band = real
    assert sorted(precision.model_bands(studies, n_jobs=2)) == [1]  # study 0 was kept


def test_a_worker_that_dies_leaves_its_band_to_this_process():
    studies = _studies(sizes=(700, 800), max_hf=10)
    parent = os.getpid()

    def dies_in_a_worker(pairs, lfset, rng, *, n_jobs=None):
        if os.getpid() != parent:
            os._exit(1)  # as the out-of-memory killer would end it
        return 1.0, 2.0

    studies[0].strategy.model_band = dies_in_a_worker
    precision.model_bands(studies, n_jobs=2)  # no hang: both bands computed here instead
    assert precision.model_band(studies[0], studies[0].pairs()) == (1.0, 2.0)
    assert precision.model_band(studies[1], studies[1].pairs()) is not None


def test_a_strategys_own_model_band_without_n_jobs_is_still_called():
    studies = _studies(sizes=(700, 800), max_hf=10)
    calls = []

    def own(pairs, lfset, rng):  # no n_jobs: called in this process, as before
        calls.append(len(pairs))
        return 1.0, 2.0

    studies[0].strategy.model_band = own
    precision.model_bands(studies, n_jobs=2)
    assert calls == [len(studies[0].pairs())]
    assert precision.model_band(studies[0], studies[0].pairs()) == (1.0, 2.0)
    assert precision.model_band(studies[1], studies[1].pairs()) is not None


def _process_count(parallel):
    """band.process_count with None meaning two processes (parallel) or one."""
    real = band_module.process_count

    def count(n_jobs, n_tasks):
        if n_jobs is None:
            n_jobs = 2 if parallel else 1
        return real(n_jobs, n_tasks)

    return count


@pytest.mark.slow
def test_a_long_term_analysis_is_the_same_with_its_bands_in_processes(monkeypatch):
    # the sea states' bands during the allocation (a precision target) and in the result,
    # one study a process against one after another: the same events, value and bands
    results, computed, forks = {}, [], []
    real, real_fork = precision.model_bands, os.fork

    def counted(studies, n_jobs=None):
        out = real(studies, n_jobs)
        computed.append(len(out))
        return out

    def fork():
        forks.append(1)
        return real_fork()

    monkeypatch.setattr(precision, "model_bands", counted)
    monkeypatch.setattr(os, "fork", fork)
    for parallel in (False, True):
        monkeypatch.setattr(band_module, "process_count", _process_count(parallel))
        computed.clear()
        forks.clear()
        results[parallel] = pas.run_long_term(
            problem.table(n_waves=2000), problem.lf_peaks(1, n_waves=2000), problem.Oracle(),
            p_exceed=1e-3, max_hf=40, precision=0.10, seed=4,
            strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=10)))
        # several states' bands at once, in worker processes only when parallel
        assert max(computed) >= 2 and (len(forks) >= 2) == parallel
    one, many = results[False], results[True]
    assert many.history["halfwidth"].notna().sum() >= 1  # bands during the allocation too
    assert (one.value, one.band, one.n_hf) == (many.value, many.band, many.n_hf)
    assert one.history.drop(columns="seconds", errors="ignore").equals(
        many.history.drop(columns="seconds", errors="ignore"))
    cols = [c for c in one.contributions.columns if "seconds" not in c]
    assert one.contributions[cols].equals(many.contributions[cols])
