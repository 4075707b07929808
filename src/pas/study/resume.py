"""Reopen a stored study: :func:`open_study` rebuilds it from its store and replays it."""

from __future__ import annotations

from ..strategies.design_waves import DESIGN_WAVE_METHODS
from .factory import STRATEGIES
from .schema import RESUMABLE, StoreError, with_legacy_settings
from .store import StudyStore
from .study import Study

__all__ = ["open_study"]


def open_study(store, *, consume: bool = True, changes: dict | None = None) -> Study:
    """Rebuild the :class:`Study` held by ``store`` (a path or a :class:`StudyStore`).

    The stored settings and LF pool build the study (:meth:`Study.from_settings`),
    which then replays the stored asks and tells (:func:`pas.study.replay.attach`).
    With ``consume`` the results told by other processes and not used yet are
    told to the study in arrival order (replacements of used
    results applied as such) (written to the store only when the
    caller holds its write transaction; see ``pas study ask``).  ``changes``
    sets new stopping settings or budgets (:data:`~pas.study.schema.RESUMABLE`,
    e.g. ``{"eps1": 10.0}``), recorded in the store (``pas study set``).
    """
    if not isinstance(store, StudyStore):
        store = StudyStore(store, create=False)
    s = store.settings()
    if not s:
        what = (" but a long-term analysis (pas.run_long_term)" if store.get("longterm") else
                " (a copy of a study's file made while its -wal file held the results? copy a "
                "study with 'pas study backup')" if store.existed else "")
        raise StoreError(f"study store {store.path} holds no single study{what}")
    s = with_legacy_settings(s)
    for key in changes or {}:
        if key not in RESUMABLE:
            raise ValueError(f"{key} cannot change on a resumed study; these can: "
                             f"{', '.join(RESUMABLE)}")
    s = {**s, **(changes or {})}
    if s["strategy"] in DESIGN_WAVE_METHODS.values():
        raise StoreError(f"{store.path} holds design waves ({s['strategy']}); its episodes are "
                         "rebuilt from the surrogate: continue it with pas.run_rcw(..., "
                         f"study={str(store.path)!r}) (pas study tell also stores its results)")
    if not isinstance(s["strategy"], str) or s["strategy"] not in STRATEGIES:
        raise StoreError(f"strategy {s['strategy']!r} in {store.path} is unknown to this pas")
    lf_all, all_ids, all_meta = store.lf_inputs()
    study = Study.from_settings(s, lf_all, ids=all_ids, meta=all_meta, store=store)
    if consume:
        for waiting in store.unconsumed():
            study.tell(int(waiting.idx), waiting.hf, error=waiting.error, replace=True)
    return study
