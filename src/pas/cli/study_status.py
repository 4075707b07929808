"""``pas study status``: where a stored study stands, and with ``--events`` every event it asked.

``--events`` adds the events table, the audit trail of replaced results
(``pas study tell --replace``) and the asks a retry took out of the log
(``pas study retry``), whose results are kept.
"""

from __future__ import annotations

import math

__all__ = ["status"]


def status(args) -> int:
    """``pas study status``: counts, the MPM so far, convergence, pending events (and all events)."""
    from ..study.store import StudyStore
    from ..study.resume import open_study

    with StudyStore(args.study, create=False) as store:
        study = open_study(store, consume=False)
        study.store = None
        used_converged = bool(study.converged)
        waiting = store.unconsumed()
        for idx, hf, err in waiting:
            study.tell(int(idx), hf, error=err, replace=True)
        events = store.events()
        changes = store.get("settings_changes", [])
        audit = {"replacements": store.replacements(), "dropped": store.dropped()}
    pend = events[events["state"] == "pending"]
    res = study.result()
    fitted = [r for r in study.rows if r.get("mpm") is not None]
    last = fitted[-1] if fitted else {}
    at = next((r["n_hf"] for r in fitted if r.get("stop")), None)
    info = {
        "study": args.study, "strategy": study.strategy.name, "seed": study.seed,
        "n_hf": study.n_hf, "n_false_positive": study.n_false_positive,
        "n_failed": study.n_failed, "n_evaluated": res.n_evaluated, "n_loads": res.n_loads,
        "n_no_impact": res.n_no_impact, "n_pending": len(pend), "results_not_yet_used": len(waiting),
        "max_hf": study.max_hf, "mpm": res.mpm if fitted else None,
        "mpm_band": list(res.mpm_band) if fitted else None,
        "mpm_band_sampling": list(res.mpm_band_sampling) if fitted else None,
        "mpm_band_model": None if res.mpm_band_model is None else list(res.mpm_band_model),
        "family": res.family, "E_bar": last.get("E_bar"), "COV": last.get("COV"),
        "eps1": study.stopping.eps1, "eps2": study.stopping.eps2,
        "k1": study.stopping.k1, "k2": study.stopping.k2,
        # convergence is decided on the results the study has used: with results waiting
        # it is open until an ask or run uses them ('converged_with_waiting' says how it
        # would come out, the numbers above include them)
        "converged": None if waiting else used_converged,
        "converged_with_waiting": bool(study.converged) if waiting else None,
        "converged_at_n_hf": at, "finished": bool(study.finished) if not waiting else None,
        "settings_changes": changes,
        "pending": [{"id": r.event_id, "index": int(r.idx), "lf": r.lf, "d": r.d,
                     "asked_at": r.asked_at} for r in pend.itertuples()],
    }
    if args.events:
        info["events"] = events.drop(columns=["meta"]).to_dict(orient="records")
        info.update(audit)
    if args.json:
        from .._json import dumps
        print(dumps(info))
        return 0
    print(f"{args.study}: {info['strategy'].upper()}, seed {info['seed']}")
    print(f"{res.counts_text()}, pending {info['n_pending']}"
          + (f", budget {study.max_hf}" if study.max_hf else ""))
    if waiting:
        print(f"{len(waiting)} result(s) told since the last ask: included below, not yet used "
              f"by the study ('pas study ask' or 'pas study run' uses them)")
    if fitted:
        fam = f", copula {info['family']}" if info["family"] else ""
        print(f"MPM so far {res.mpm:.5g}, {res.band_text()}{fam}")
        verdict = ("converged" + (f" (at {at} HF evaluations)" if at is not None else "")
                   if used_converged else "not converged")
        if waiting:
            verdict = ("open until the waiting results are used (with them: "
                       + ("converged" if study.converged else "not converged") + ")")
        print(f"convergence: E_bar {_fmt(info['E_bar'])} (limit eps1 {info['eps1']:g}), COV "
              f"{_fmt(info['COV'])} (limit eps2 {info['eps2']:g}): {verdict}")
    else:
        print("no model fitted yet")
    for ch in changes:
        print(f"setting changed: {ch['key']} {ch['old']} -> {ch['new']} "
              f"(after {ch['n_told']} results, {ch['at']})")
    if info["pending"]:
        print("pending:")
        for p in info["pending"]:
            print(f"  {p['id']}  (index {p['index']}, lf {p['lf']:.5g}, asked {p['asked_at']})")
    if args.events:
        _print_events(events, audit)
    return 0


def _result_text(hf, error) -> str:
    return f"error {error!r}" if error is not None else f"{hf:.6g}"


def _print_events(events, audit) -> None:
    cols = ["event_id", "idx", "lf", "state", "hf", "error", "attempts", "asked_at", "result_at",
            "source"]
    print("events (in ask order):")
    print(events[cols].to_string(index=False))
    for r in audit["replacements"]:
        print(f"replaced: event {r['key']} {_result_text(r['old_hf'], r['old_error'])} -> "
              f"{_result_text(r['new_hf'], r['new_error'])} at {r['replaced_at']} "
              f"(source {r['source']}, old from {r['old_source'] or 'the study'}); {r['note']}")
    for r in audit["dropped"]:
        kept = ("no result" if r["result_seq"] is None else
                _result_text(r["hf"], r["error"]) + (" (reused)" if r["reused_seq"] else
                                                     " kept, not used" if r["reusable"] else
                                                     " not reused"))
        print(f"dropped by a retry: event {r['key']} ({r['reason']}): {kept}")


def _fmt(x) -> str:
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.3g}"
