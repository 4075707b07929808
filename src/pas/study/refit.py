"""Analyse another load of a stored study on the same events, with no HF run.

One CFD run or basin test gives many loads (:mod:`pas.study.loads`); the study
chose its events for one of them, its ``target``.  :func:`refit` builds the
result (MPM, band, distribution, history) of another stored load from those
events: the stored asks and tells are replayed in their order, each told the
event's value of that load instead of the target's, so every fit draws as the
study's own fit at that point did.  The sample is not adapted to that load —
its events were chosen for the target — and the result says so
(:attr:`~pas.study.result.ScreeningResult.refit`).
"""

from __future__ import annotations

from .answers import check_target, screened_load
from .loads import load_names, stored_loads
from .schema import StoreError, with_legacy_settings
from .state import EventState
from .store import Ask, Replace, StudyStore
from .study import Study

__all__ = ["refit", "refit_study"]


def refit(store, target: str, *, model_band: bool = True):
    """The result of load ``target`` on the events a stored study chose for its own target.

    Parameters
    ----------
    store : str, os.PathLike or StudyStore
        The study store (``pas run``'s ``OUT/study.sqlite`` or a ``pas study`` file).
    target : str
        A load stored for the study's events (a key of the oracle's answers),
        or the study's own target.
    model_band : bool, default True
        As for :meth:`Study.result <pas.study.study.Study.result>`.

    Returns
    -------
    ScreeningResult
        With ``refit = {"target", "chosen_for", "n_missing"}``: events whose
        ``target`` load is missing or invalid count as failed, ``n_missing``
        of them beside the events the oracle failed on (which stay failed
        unless their answer held a valid ``target`` load).  ``pas study refit
        DB --target NAME`` writes it as ``pas run`` writes its result.

    Raises
    ------
    ValueError
        When ``target`` is no stored load (the message names the stored ones).
    """
    study, info = refit_study(store, target)
    result = study.result(model_band=model_band)
    result.refit = info
    return result


def refit_study(store, target: str):
    """``(study, refit info)``: the stored study replayed with load ``target`` (:func:`refit`)."""
    check_target(target)
    if target is None:
        raise ValueError("target must name the load to analyse")
    own = store if isinstance(store, StudyStore) else StudyStore(store, create=False)
    try:
        settings = with_legacy_settings(own.settings())
        if not settings:
            raise StoreError(f"study store {own.path} holds no study")
        chosen_for = settings.get("target")
        results = _results_of(own, target, chosen_for)
        lf_all, ids, meta = own.lf_inputs()
        study = Study.from_settings({**settings, "target": target}, lf_all, ids=ids, meta=meta)
        n_missing = _replay(study, own, results, target == chosen_for)
    finally:
        if own is not store:
            own.close()
    return study, {"target": target, "chosen_for": chosen_for, "n_missing": n_missing}


def _results_of(store, target, chosen_for) -> dict:
    """``{idx: (value, error, missing)}`` of load ``target`` for every event with a result.

    ``missing``: the event gave the study's target but not a valid ``target`` load.
    """
    events = store.events()
    told = events[events["result_seq"].notna()]
    own = {int(r.idx): (None if r.error is not None else r.hf, r.error)
           for r in told.itertuples()}
    loads = stored_loads(store, target)
    if target == chosen_for:
        return {idx: (v, e, False) for idx, (v, e) in own.items()}
    if not loads:
        names = load_names(store)
        raise ValueError(f"target: {target!r} is not a load stored in {store.path} (its loads: "
                         f"{', '.join(names) if names else 'none, its oracle gave one number'})")
    out = {}
    for idx, (_value, own_error) in own.items():
        value, error = (screened_load(loads[idx], target) if idx in loads else
                        (None, own_error or f"no load {target!r} stored for this event"))
        out[idx] = (value, error, error is not None and own_error is None)
    return out


def _replay(study, store, results, own_target: bool) -> int:
    """Replay the stored asks and tells on ``study`` with ``results``; the number missing.

    The study's ``own_target`` replays the log as the study ran: each tell
    the value it used then, each replacement applied where it was.  Another
    load is told once per event: a replacement corrected the screened load
    alone, the other loads stay as the oracle gave them.
    """
    missing = 0

    def tell(idx, hf, error, replace):
        nonlocal missing
        if own_target:
            study.tell(idx, hf, error=error, replace=replace)
        elif study.state.get(study.lfset.position_of(idx)) == EventState.PENDING:
            value, error, lacks = results[idx]
            study.tell(idx, value, error=error)
            missing += lacks

    for op in store.ops():
        if isinstance(op, Ask):
            positions = [study.lfset.position_of(i) for i in op.indices]
            study.start_with(positions)
            for p in positions:
                study.state[p] = EventState.PENDING
        else:
            tell(op.idx, op.hf, op.error, isinstance(op, Replace))
    for waiting in store.unconsumed():
        tell(int(waiting.idx), waiting.hf, waiting.error, True)
    return missing
