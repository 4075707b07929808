"""Parallel HF batches: a Dask LocalCluster and a local process pool give the serial answer."""

import time

import numpy as np
import pytest
from conftest import no_band

import pas
from pas.study.store import StudyStore

distributed = pytest.importorskip("distributed")
pytestmark = pytest.mark.slow  # a cluster and a process pool start

LF = np.random.default_rng(1).rayleigh(1.0, 2000)
KW = dict(n_waves=2000, p_exp=1e-2, eps1=1e-4, seed=11, max_hf=16)


def slow_hf(ev):
    """HF load; later events of a batch often finish first."""
    time.sleep(0.002 * ((ev.index * 7) % 5))
    return 1.2 * ev.lf ** 1.1


def _study(store=None):
    return pas.make_study(no_band(), LF, store=store, **KW)


def test_dask_local_cluster_batch_study(tmp_path):
    serial = pas.run_pas(LF, slow_hf, strategy=no_band(), batch_size=4, **KW)
    db = str(tmp_path / "s.db")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = pas.run_pas(LF, slow_hf, strategy=no_band(), batch_size=4, study=db,
                          executor=client.get_executor(), **KW)
    assert res.n_hf == 16
    assert res.mpm == serial.mpm  # told in ask order, whatever finished first
    assert list(res.history["event_index"]) == list(serial.history["event_index"])
    with StudyStore(db, create=False) as store:
        ev = store.events()
    assert len(ev) == 16 and set(ev["state"]) == {"done"} and set(ev["batch_pos"]) == {0, 1, 2, 3}


def test_process_pool_workers(tmp_path):
    serial = _study().optimize(slow_hf, batch_size=4)
    res = _study().optimize(slow_hf, batch_size=4, n_workers=2)
    assert res.mpm == serial.mpm and res.n_hf == 16
    with pytest.raises(ValueError, match="oracle must be picklable"):
        _study().optimize(lambda ev: 1.0, batch_size=4, n_workers=2)
    with pytest.raises(ValueError, match="pending"):
        _study(str(tmp_path / "p.db")).optimize(slow_hf, batch_size=4, pending="later")
