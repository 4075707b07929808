"""The study does not refit a family far behind on AIC (estimators.PRUNE_AIC)."""

import numpy as np
import pytest

import pas
import pas.strategies.estimators as estimators
from pas.validation.timing_problem import scenario


def _study(prune, monkeypatch):
    monkeypatch.setattr(estimators, "PRUNE_AIC", prune)
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

    every = _study(None, monkeypatch)
    monkeypatch.setattr(estimators, "unrefitted", counting)
    pruned = _study(15.0, monkeypatch)
    assert unrefitted  # some family was far enough behind not to be refitted
    assert list(pruned.history["family"]) == list(every.history["family"])
    assert pruned.mpm == pytest.approx(every.mpm, rel=1e-9)
    for column in [c for c in every.history.columns if c.startswith("aic_")]:
        # not refitted, a family's AIC is that of its old values: at least the refitted one
        stale, fresh = pruned.history[column].to_numpy(), every.history[column].to_numpy()
        assert np.all((stale >= fresh - 1e-6) | np.isnan(fresh))
