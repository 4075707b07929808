"""The study does not refit a family far behind on AIC (estimators.PRUNE_AIC)."""

import functools

import numpy as np
import pytest

import pas
import pas.strategies.estimators as estimators
from pas.validation.timing_problem import scenario


@functools.cache
def _every_family_refitted():
    saved = estimators.PRUNE_AIC
    estimators.PRUNE_AIC = None
    try:
        return _run()
    finally:
        estimators.PRUNE_AIC = saved


def _study(prune, monkeypatch):
    monkeypatch.setattr(estimators, "PRUNE_AIC", prune)
    return _run()


def _run():
    lf, hf = scenario(3000)
    return pas.run_pas(lf, lambda e: float(hf[e.index]), n_waves=3300, p_exp=2.55e-3, seed=0,
                       eps1=1e-12, max_hf=36,
                       strategy=pas.PAS(band=pas.ModelBand(n_bootstrap=0)))


def test_a_family_far_behind_is_not_refitted_and_changes_no_selection(monkeypatch):
    unrefitted = []
    original = estimators.unrefitted

    def counting(fit, *args, **kwargs):
        unrefitted.append(fit.copula.name)
        return original(fit, *args, **kwargs)

    every = _every_family_refitted()
    monkeypatch.setattr(estimators, "unrefitted", counting)
    pruned = _study(15.0, monkeypatch)
    assert unrefitted  # some family was far enough behind not to be refitted
    assert list(pruned.history["family"]) == list(every.history["family"])
    assert pruned.mpm == pytest.approx(every.mpm, rel=1e-9)
    for column in [c for c in every.history.columns if c.startswith("aic_")]:
        # not refitted, a family's AIC is that of its old values: at least the refitted one
        stale, fresh = pruned.history[column].to_numpy(), every.history[column].to_numpy()
        assert np.all((stale >= fresh - 1e-6) | np.isnan(fresh))


def test_a_family_that_may_have_caught_up_is_refitted_before_it_is_selected(monkeypatch):
    import dataclasses

    every = _every_family_refitted()
    original = estimators.unrefitted

    def flattering(fit, *args, **kwargs):  # an unrefitted AIC better than every refitted one
        old = original(fit, *args, **kwargs)
        return dataclasses.replace(old, copula=dataclasses.replace(old.copula, aic=-1e9))

    monkeypatch.setattr(estimators, "unrefitted", flattering)
    pruned = _study(15.0, monkeypatch)
    assert list(pruned.history["family"]) == list(every.history["family"])
    assert pruned.mpm == pytest.approx(every.mpm, rel=1e-9)
    assert np.nanmin(pruned.history.filter(like="aic_").to_numpy(float)) > -1e8
