"""Binding a :class:`~pas.study.study.Study` to its :mod:`study store <pas.study.store>` by replay.

The store is a *log*, not a snapshot.  The model state of a
:class:`~pas.study.study.Study` (selected copula, stopping windows, adaptive
threshold) is never serialised: :func:`attach` rebuilds it by replaying the
stored asks and tells through :meth:`Study.ask` / :meth:`Study.tell` in their
stored order.  Each fit draws from ``default_rng([seed, len(rows)])``, so the
replay is exact and a resumed study makes the decisions an uninterrupted one
would have made.  The stopping settings and budgets
(:data:`~pas.study.schema.RESUMABLE`) may differ from the stored ones: they
decide when a study stops asking, never which events it asks for, so the
stored asks are replayed whatever they say now, and the continued study asks
for what an uninterrupted one with the new settings would have asked for
(unless those settings would have stopped it before the stored asks).
Replacements of told results (``tell --replace``) are steps of the log too,
replayed where the study applied them; a retry of failed events rewinds the
log (:mod:`pas.study.amend`).  :func:`pas.study.resume.open_study` builds the
study from the stored settings first.  A resumed study logs
``resuming STORE: N results reused`` at INFO level on the ``pas`` logger.
"""

from __future__ import annotations

import json
import logging
import math
import warnings

from .loads import adopt_target
from .schema import StoreError, dumps
from .store import Ask, Replace, StudyStore

__all__ = ["attach", "study_settings"]


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


def attach(study, store) -> list[dict]:
    """Bind ``study`` to ``store``: initialise a new store, or check it and replay it.

    Raises :class:`StoreError` when the stored settings or LF pool differ from
    ``study``'s, or when the replay does not reproduce the stored asks.
    Returns the changes of resumable settings recorded now
    (:meth:`StudyStore.bind <pas.study.store.StudyStore.bind>`).
    """
    if not isinstance(store, StudyStore):
        store = StudyStore(store)
    settings = study_settings(study)
    with store.transaction() as c:
        if store.is_new and store.existed and not c.execute(
                "SELECT 1 FROM meta WHERE key = 'settings'").fetchone():
            warnings.warn(f"{store.path} exists but holds no study: a new study starts in it (a "
                          "copy of a study's .sqlite file made while its -wal file still held "
                          "the results is empty; copy a study with 'pas study backup')",
                          stacklevel=3)
        adopted = None if store.is_new else adopt_target(store, settings)
        changes = store.bind(settings, study.lfset) + ([adopted] if adopted else [])
    study.replaying = True
    # the model bands a precision study computed in its loop, reused rather than refitted
    study.stored_bands = {r["row"]: r for r in store.history() if r.get("model_low") is not None}
    try:
        for n, op in enumerate(store.ops()):
            if isinstance(op, Ask):
                got = tuple(ev.index for ev in study.ask(len(op.indices)))
                if got != op.indices:
                    raise StoreError(
                        f"study store {store.path} does not replay: ask #{n} gives events {got} "
                        f"but the store holds {op.indices} (written by another pas version?)")
            else:
                study.tell(op.idx, op.hf, error=op.error, replace=isinstance(op, Replace))
    finally:
        study.replaying, study.stored_bands = False, {}
    stored = store.history()
    if stored and study.rows and stored[-1].get("mpm") is not None:
        replayed = study.rows[len(stored) - 1].get("mpm")
        if replayed is None or not math.isclose(replayed, stored[-1]["mpm"], rel_tol=1e-9):
            warnings.warn(f"replaying {store.path} gives MPM {replayed} where the store recorded "
                          f"{stored[-1]['mpm']}: library versions changed?", stacklevel=3)
    study.store = store
    if study.rows:
        logging.getLogger("pas").info("resuming %s: %d results reused", store.path, study.n_told)
    return changes
