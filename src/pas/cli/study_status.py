"""``pas study status``: where a stored study stands, and with ``--events`` every event it asked.

``--events`` adds the events table, the audit trail of replaced results and
named loads (``pas study tell --replace``) and the asks a retry took out of the log
(``pas study retry``), whose results are kept.  The result shown is the one
stored for the current state of the log (:mod:`pas.study.stored_results`);
``--refresh`` replays the log instead.
"""

from __future__ import annotations

import math

__all__ = ["status"]


def status(args) -> int:
    """``pas study status``: counts, the MPM so far, convergence, pending events (and all events).

    Reads the result stored for the current state of the log
    (:mod:`pas.study.stored_results`); only when there is none, or with
    ``--refresh``, replays the log and computes it (and stores it when no told
    result is waiting).
    """
    from ..study.store import StudyStore
    from ..study.stored_results import stored_result
    from .study_programs import store_path

    path = store_path(args.study)
    with StudyStore(path, create=False) as store:
        waiting = store.unconsumed()
        shown, n_told, key = stored_result(store)
        if getattr(args, "refresh", False):
            shown = None
        from_store = shown is not None
        if not from_store:
            shown, n_told = _replayed(store, waiting, key)
        events = store.events()
        changes = store.get("settings_changes", [])
        audit = {"replacements": store.replacements(), "dropped": store.dropped(),
                 "load_replacements": store.load_replacements()}
    pend = events[events["state"] == "pending"]
    failed = events[events["state"] == "failed"]
    # a stored result covers the results the study used; waiting ones are left out of it
    left_out = len(waiting) if from_store else 0
    included = len(waiting) - left_out
    used_converged = shown.pop("used_converged", shown["converged"])
    counts_text, band_text = shown.pop("counts_text"), shown.pop("band_text")
    shown.setdefault("precision", None)  # a result stored before precision targets
    stop_state = shown.pop("stop_text", None)
    fitted = shown.pop("fitted")
    info = {"study": path, **shown, "n_pending": len(pend),
            "results_not_yet_used": len(waiting),
            "converged": None if waiting else used_converged,
            "converged_with_waiting": shown["converged"] if included else None,
            "finished": shown["finished"] if not waiting else None,
            "settings_changes": changes, "result_n_told": n_told, "result_stored": from_store,
            "pending": [{"id": r.event_id, "index": int(r.idx), "lf": r.lf, "d": r.d,
                         "asked_at": r.asked_at} for r in pend.itertuples()],
            "failed": [{"id": r.event_id, "index": int(r.idx), "error": r.error}
                       for r in failed.itertuples()]}
    if args.events:
        info["events"] = events.drop(columns=["meta"]).to_dict(orient="records")
        info.update(audit)
    if args.json:
        from .._support.strict_json import dumps
        print(dumps(info))
        return 0
    _print_status(info, counts_text, band_text, fitted, included, left_out, stop_state)
    if not from_store:
        why = "--refresh" if getattr(args, "refresh", False) else "no result stored for it"
        print(f"(computed by replaying the log of {n_told} used results: {why})")
    if args.events:
        _print_events(events, audit)
    return 0


def _replayed(store, waiting, key) -> tuple[dict, int]:
    """``(summary, n_told)`` of the study replayed from ``store``, the ``waiting`` results told.

    Stored for the next status when no result is waiting (with them it is the
    result of no state of the log) and the log is still the one of ``key``.
    """
    from ..study.resume import open_study
    from ..study.stored_results import save_result, summary

    study = open_study(store, consume=False)
    study.store = None
    used_converged = bool(study.converged)
    n_told = study.n_told
    for result in waiting:
        study.tell(int(result.idx), result.hf, error=result.error, replace=True)
    res = study.result()
    shown = summary(study, res)
    if not waiting and shown["fitted"]:
        save_result(store, study, res, expected_key=key)
    return {**shown, "used_converged": used_converged}, n_told


def _print_status(info, counts_text, band_text, fitted, included, left_out,
                  stop_state=None) -> None:
    print(f"{info['study']}: {info['strategy'].upper()}, seed {info['seed']}")
    print(f"{counts_text}, pending {info['n_pending']}"
          + (f", budget {info['max_hf']}" if info["max_hf"] else ""))
    if included:
        print(f"{included} result(s) told since the last ask: "
              + ("included below" if fitted else "counted above, too few for a model yet")
              + ", not yet used by the study ('pas study ask' or 'pas study run' uses them)")
    if left_out:
        print(f"{left_out} result(s) told since the last ask are not included below: this is "
              f"the stored result of the {info['result_n_told']} results the study has used "
              f"('pas study status --refresh' includes them, 'pas study ask' or 'pas study "
              f"run' uses them)")
    at = info["converged_at_n_hf"]
    if fitted:
        fam = f", copula {info['family']}" if info["family"] else ""
        print(f"MPM so far {info['mpm']:.5g}, {band_text}{fam}")
        verdict = ("converged" + (f" (at {at} HF evaluations)" if at is not None else "")
                   if info["converged"] else "not converged")
        if included:
            verdict = ("undecided until the study uses the waiting results (with them it "
                       "would be " + ("converged" if info["converged_with_waiting"]
                                     else "not converged") + ")")
        elif left_out:
            verdict = "undecided until the study uses the waiting results"
        if info["eps1"] is not None:
            print(f"convergence: E_bar {_fmt(info['E_bar'])} (limit eps1 {info['eps1']:g}), COV "
                  f"{_fmt(info['COV'])} (limit eps2 {info['eps2']:g}): {verdict}")
        if info["precision"] is not None:
            detail = (stop_state or "").split(": ", 1)[-1]
            print(f"precision target ±{100 * info['precision']:g} %: {verdict}; {detail}")
    else:
        print("no model fitted yet")
    for ch in info["settings_changes"]:
        print(f"setting changed: {ch['key']} {ch['old']} -> {ch['new']} "
              f"(after {ch['n_told']} results, {ch['at']})")
    if info["failed"]:
        shown = [f"{f['id']} ({str(f['error'])[:80]})" for f in info["failed"][:5]]
        more = len(info["failed"]) - len(shown)
        print(f"failed: {'; '.join(shown)}" + (f"; and {more} more" if more > 0 else "")
              + f" - left out of the fit; 'pas study retry {info['study']}' asks them again")
    if info["pending"]:
        print("pending:")
        for p in info["pending"]:
            print(f"  {p['id']}  (index {p['index']}, lf {p['lf']:.5g}, asked {p['asked_at']})")


def _result_text(hf, error) -> str:
    if error is not None:
        return f"error {error!r}"
    return "none" if hf is None else f"{hf:.6g}"


def _print_events(events, audit) -> None:
    cols = ["event_id", "idx", "lf", "state", "hf", "error", "attempts", "asked_at", "result_at",
            "source"]
    print("events (in ask order):")
    print(events[cols].to_string(index=False))
    for r in audit["replacements"]:
        print(f"replaced: event {r['key']} {_result_text(r['old_hf'], r['old_error'])} -> "
              f"{_result_text(r['new_hf'], r['new_error'])} at {r['replaced_at']} "
              f"(source {r['source']}, old from {r['old_source'] or 'the study'}); {r['note']}")
    keys = dict(zip(events["idx"], events["event_id"]))
    for r in audit["load_replacements"]:
        print(f"replaced load {r['name']!r} of event {keys.get(r['idx'], r['idx'])}: "
              f"{_result_text(r['old_value'], r['old_error'])} -> "
              f"{_result_text(r['new_value'], r['new_error'])} at {r['replaced_at']} "
              f"(source {r['source']})")
    for r in audit["dropped"]:
        kept = ("no result" if r["result_seq"] is None else
                _result_text(r["hf"], r["error"]) + (" (reused)" if r["reused_seq"] else
                                                     " kept, not used" if r["reusable"] else
                                                     " not reused"))
        print(f"dropped by a retry: event {r['key']} ({r['reason']}): {kept}")


def _fmt(x) -> str:
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.3g}"
