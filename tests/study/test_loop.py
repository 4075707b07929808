"""The one study loop: failure limit, and tell that only records."""

import numpy as np
import pytest
from conftest import no_band

import pas
from pas import Budget

LF = np.random.default_rng(0).rayleigh(1.0, 500)
KW = dict(n_waves=500, p_exp=0.01, eps1=0.01, seed=0)


def test_no_oracle_call_after_the_failure_limit_in_process():
    calls = []

    def oracle(ev):
        calls.append(ev.index)
        raise RuntimeError("no licence")

    with pytest.raises(pas.OracleFailureLimit, match="max_failures=1.*no licence") as info:
        pas.run_pas(LF, oracle, strategy=no_band(), budget=Budget(max_failures=1), **KW)
    # the 4 initial events form one batch; the limit is passed at the 2nd failure
    assert len(calls) == 2 and info.value.result.n_failed == 2


def test_failure_limit_result_skips_the_model_band():
    """The partial result at the limit comes at once: no bootstrap refits, as after Ctrl-C."""
    lf = np.random.default_rng(4).rayleigh(1.0, 600)

    calls = []

    def oracle(ev):   # loads for the first 12 events, then a broken licence server
        calls.append(ev.index)
        if len(calls) > 12:
            raise RuntimeError("no licence")
        return 2.0 * ev.lf ** 1.2

    with pytest.raises(pas.OracleFailureLimit) as info:
        pas.make_study(pas.PAS(), lf, n_waves=600, p_exp=1e-2, eps1=1e-4, seed=3,
                       budget=Budget(max_hf=40, max_failures=2),
                       stop_on_convergence=False).optimize(oracle)
    res = info.value.result
    assert np.isfinite(res.mpm) and res.mpm_band_model is None
    assert tuple(res.mpm_band) == tuple(res.mpm_band_sampling)


def test_failure_limit_also_with_a_store(tmp_path):
    calls = []

    def oracle(ev):
        calls.append(ev.index)
        return float("nan")

    db = tmp_path / "s.db"
    with pytest.raises(pas.OracleFailureLimit):
        pas.run_pas(LF, oracle, strategy=no_band(), budget=Budget(max_failures=1), study=db,
                    **KW)
    assert len(calls) == 2
    # resumed with the same limit: the loop stops before resubmitting or asking anything
    with pytest.raises(pas.OracleFailureLimit):
        pas.run_pas(LF, lambda ev: pytest.fail("oracle called"), strategy=no_band(),
                    budget=Budget(max_failures=1), study=db, **KW)
    # a raised limit (a budget, changeable on resume) lets the study go on
    res = pas.run_pas(LF, lambda ev: 2.0 * ev.lf, strategy=no_band(),
                      budget=Budget(max_hf=8, max_failures=5), study=db, **KW)
    assert res.n_failed == 2 and res.n_hf == 8


def test_tell_records_failures_beyond_the_limit_without_raising():
    study = pas.make_study(no_band(), LF, budget=Budget(max_failures=0), **KW)
    events = study.ask()
    for ev in events:
        study.tell(ev, error="crashed")
    assert study.n_failed == 4
    assert [r["status"] for r in study.rows] == ["failed"] * 4
    assert all(s.is_finished() for s in study.state.values())
