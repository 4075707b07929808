"""Rebuilding a :class:`~pas.study.study.Study` from its :mod:`study store <pas.study.store>`.

The store is a *log*, not a snapshot.  The model state of a
:class:`~pas.study.study.Study` (selected copula, stopping windows, adaptive
threshold) is never serialised: :func:`attach` rebuilds it by replaying the
stored asks and tells through :meth:`Study.ask` / :meth:`Study.tell` in their
stored order.  Each fit draws from ``default_rng([seed, len(rows)])``, so the
replay is exact and a resumed study makes the decisions an uninterrupted one
would have made.
"""

from __future__ import annotations

import json
import math
import warnings

import numpy as np

from .schema import StoreError, dumps

__all__ = ["attach", "open_study", "study_settings"]


def study_settings(study) -> dict:
    """The JSON settings that define ``study`` (checked when a store is reopened)."""
    try:
        out = study.settings()
    except AttributeError as exc:
        raise StoreError(f"{exc}, so the store cannot record it") from None
    try:
        return json.loads(dumps(out))
    except TypeError as exc:
        raise StoreError(f"study settings must be JSON-serialisable for the store: {exc}") from None


def attach(study, store) -> None:
    """Bind ``study`` to ``store``: initialise a new store, or check it and replay it.

    Raises :class:`StoreError` when the stored settings or LF pool differ from
    ``study``'s, or when the replay does not reproduce the stored asks.
    """
    from .store import StudyStore
    from .study import OracleFailureLimit

    if not isinstance(store, StudyStore):
        store = StudyStore(store)
    settings = study_settings(study)
    with store.transaction():
        if store.is_new:
            store.initialize(settings, study.lfset)
        else:
            store.check(settings, study.lfset)
    for n, op in enumerate(store.ops()):
        if op[0] == "ask":
            got = [ev.index for ev in study.ask(len(op[1]))]
            if got != op[1]:
                raise StoreError(
                    f"study store {store.path} does not replay: ask #{n} gives events {got} but "
                    f"the store holds {op[1]} (written by another pas version?)")
        else:
            try:
                study.tell(op[1], op[2], error=op[3])
            except OracleFailureLimit:
                pass
    stored = store.history()
    if stored and study.rows and stored[-1].get("mpm") is not None:
        replayed = study.rows[len(stored) - 1].get("mpm")
        if replayed is None or not math.isclose(replayed, stored[-1]["mpm"], rel_tol=1e-9):
            warnings.warn(f"replaying {store.path} gives MPM {replayed} where the store recorded "
                          f"{stored[-1]['mpm']}: library versions changed?", stacklevel=3)
    study.store = store


def open_study(store, *, consume: bool = True):
    """Rebuild the :class:`~pas.study.study.Study` held by ``store`` (a path or a StudyStore).

    With ``consume`` the results told by other processes and not used yet are
    told to the study in arrival order (written to the store only when the
    caller holds its write transaction; see ``pas study ask``).
    """
    from ..api import make_study
    from ..strategies import AS, PAS
    from .store import StudyStore
    from .study import OracleFailureLimit

    if not isinstance(store, StudyStore):
        store = StudyStore(store, create=False)
    s = store.settings()
    if not s:
        raise StoreError(f"study store {store.path} holds no study")
    strategies = {"pas": PAS, "as": AS}
    if s["strategy"] not in strategies:
        raise StoreError(f"strategy {s['strategy']!r} in {store.path} is unknown to this pas")
    idx, ids, lf, meta = store.pool()
    n = int(idx[-1]) + 1
    lf_all = np.full(n, np.nan if s["threshold"] is None else s["threshold"])
    lf_all[idx] = lf
    if s["threshold"] is None and idx.size != n:
        raise StoreError(f"study store {store.path}: LF pool has gaps but no threshold")
    plain = all(i == j for i, j in zip(ids, idx.tolist()))
    all_ids = None
    if not plain:
        all_ids = [f"\x00below-threshold-{i}" for i in range(n)]
        for i, e in zip(idx, ids):
            all_ids[i] = e
    all_meta = None
    if any(meta):
        all_meta = [{} for _ in range(n)]
        for i, m in zip(idx, meta):
            all_meta[i] = m
    keys = ("k1", "k2", "max_failures", "stop_on_convergence", "adaptive_threshold",
            "threshold_step", "fp_run")
    study = make_study(strategies[s["strategy"]], lf_all, n_waves=s["n_waves"], p_exp=s["p_exp"],
                       eps1=s["eps1"], eps2=s["eps2"], threshold=s["threshold"], seed=s["seed"],
                       max_hf=s["max_hf"], ids=all_ids, meta=all_meta, store=store,
                       **{k: s[k] for k in keys}, **s["strategy_settings"])
    if consume:
        for i, hf, err in store.unconsumed():
            try:
                study.tell(int(i), hf, error=err)
            except OracleFailureLimit:
                pass
    return study
