"""Amending a study's log: retrying failed events and replacing told results.

Both run inside one write transaction of the :class:`~pas.study.store.StudyStore`
(the ``c`` argument), so a process killed during either leaves the store as
it was before or as it is after, never in between.

Retry (:func:`rewind_failed`)
    The *cut* is the first consumed tell of a retried failed event (sequence
    number ``cut``).  Everything before it stays in the log: an uninterrupted
    run with the fixed oracle made the same asks and tells up to there.  After it:

    - every ask with a sequence number above ``cut`` (the substitutes the
      failure caused and everything asked after) is moved to the ``dropped``
      table with its result, if any;
    - every tell at or after ``cut`` is no longer consumed (``tell_seq``
      cleared): its result stays on the event and is told again, in ask
      order, when the study is driven next;
    - the history rows of those tells, derived from the log, are deleted
      (replay rebuilds them);
    - each retried failed event still in the log becomes pending again (its
      failure is copied to ``dropped`` first), so the next run calls the
      oracle for it.

    When the replayed study asks a dropped event again, its stored result is
    reused (:func:`reuse_dropped`), not recomputed: a load or 0 always, a
    failure only when that event was not among those retried.  Results of
    dropped events the study does not ask again stay in ``dropped`` and are
    not used.  A result told later for a dropped pending event is kept there
    (:func:`tell_dropped`).  Failures not retried that lie before the cut
    stay as they are.

Replace (:func:`replace_result`)
    The new value goes on the event, the old one with the time, the source and
    a note to the ``replacements`` table.  A study that had already used the
    old value applies the replacement as a new step of its log (a history row
    and a refit; :meth:`Study.tell <pas.study.study.Study.tell>` with
    ``replace=True``); the asks it made meanwhile stay as they were.
"""

from __future__ import annotations

from .schema import STORED, StoreError, _now
from .state import EventState

__all__ = ["rewind_failed", "dropped_index", "reuse_dropped", "tell_dropped", "replace_result",
           "stage_replacement", "apply_replacement", "REPLACED_AFTER_USE", "REPLACED_BEFORE_USE"]

_EVENT_COLUMNS = ("idx", "key", "state", "hf", "error", "batch", "batch_pos", "result_seq",
                  "tell_seq", "attempts", "asked_at", "submitted_at", "result_at", "source")
REPLACED_AFTER_USE = ("the study had used the old value: the asks it made since stay as they "
                      "were (MD gaps and threshold raises after it may differ from what the new "
                      "value would have caused); later fits use the new value")
REPLACED_BEFORE_USE = "the study had not used the old value yet: nothing it decided depended on it"


def _archive(store, c, rows, retry_seq, reason_of, reusable_of) -> None:
    now = _now()
    c.executemany(
        f"INSERT INTO dropped (study, {', '.join(_EVENT_COLUMNS)}, retry_seq, reason, reusable, "
        f"dropped_at) VALUES ({', '.join('?' * (len(_EVENT_COLUMNS) + 5))})",
        [(store.scope, *r, retry_seq, reason_of(r), int(reusable_of(r)), now) for r in rows])


def rewind_failed(store, c, keys=None) -> dict:
    """Rewind the log so the failed events (all, or those whose id is in ``keys``) run again.

    Returns ``{"retried": [ids], "dropped": n asks taken out of the log,
    "kept": n of those holding a result kept for reuse, "cut": seq or None}``.
    """
    scope = store.scope
    failed = c.execute("SELECT idx, key, tell_seq FROM events WHERE study = ? AND state = ?",
                       (scope, STORED[EventState.FAILED])).fetchall()
    if keys is not None:
        wanted = [str(k) for k in keys]
        have = {k for _, k, _ in failed}
        for k in wanted:
            if k not in have:
                row = c.execute("SELECT state FROM events WHERE study = ? AND key = ?",
                                (scope, k)).fetchone()
                why = "was never asked for" if row is None else f"is {row[0]}, not failed"
                raise StoreError(f"event {k} {why} in {store.path}: only failed events can be "
                                 "retried")
        failed = [f for f in failed if f[1] in set(wanted)]
    report = {"retried": [k for _, k, _ in failed], "dropped": 0, "kept": 0, "cut": None}
    if not failed:
        return report
    retry_idx = {i for i, _, _ in failed}
    retry_seq = store._next_seq(c)
    store._set_meta(c, "op_seq", retry_seq)  # a driver holding the old log must reopen
    told = [t for _, _, t in failed if t is not None]
    cols = ", ".join(_EVENT_COLUMNS)
    if told:
        cut = report["cut"] = min(told)
        later = c.execute(f"SELECT {cols} FROM events WHERE study = ? AND batch > ?",
                          (scope, cut)).fetchall()

        def reusable(r):
            return r[7] is not None and r[0] not in retry_idx

        _archive(store, c, later, retry_seq, lambda r: "retried failure" if r[0] in retry_idx
                 else "asked after a retried failure", reusable)
        report["dropped"], report["kept"] = len(later), sum(map(reusable, later))
        c.execute("DELETE FROM events WHERE study = ? AND batch > ?", (scope, cut))
        c.execute("UPDATE events SET tell_seq = NULL WHERE study = ? AND tell_seq >= ?",
                  (scope, cut))
        c.execute("UPDATE replacements SET consumed_seq = NULL WHERE study = ? AND "
                  "consumed_seq > ?", (scope, cut))
        c.execute("UPDATE replacements SET consumed_seq = 0 WHERE study = ? AND idx NOT IN "
                  "(SELECT idx FROM events WHERE study = ? AND tell_seq IS NOT NULL)",
                  (scope, scope))
        n_ops = (c.execute("SELECT COUNT(*) FROM events WHERE study = ? AND tell_seq IS NOT NULL",
                           (scope,)).fetchone()[0]
                 + c.execute("SELECT COUNT(*) FROM replacements WHERE study = ? AND "
                             "consumed_seq > 0", (scope,)).fetchone()[0])
        c.execute("DELETE FROM history WHERE study = ? AND row >= ?", (scope, n_ops))
    marks = ", ".join("?" * len(retry_idx))
    still = c.execute(f"SELECT {cols} FROM events WHERE study = ? AND idx IN ({marks})",
                      (scope, *retry_idx)).fetchall()
    _archive(store, c, still, retry_seq, lambda r: "retried failure", lambda r: False)
    c.execute(f"DELETE FROM event_loads WHERE study = ? AND idx IN ({marks})",
              (scope, *retry_idx))
    c.execute(f"UPDATE events SET state = ?, hf = NULL, error = NULL, result_seq = NULL, "
              f"tell_seq = NULL, result_at = NULL, source = NULL WHERE study = ? AND "
              f"idx IN ({marks})", (STORED[EventState.PENDING], scope, *retry_idx))
    return report


def dropped_index(store, c, key: str) -> int:
    """The event index of the latest ask of ``key`` a retry took out of the log."""
    return c.execute("SELECT idx FROM dropped WHERE study = ? AND key = ? ORDER BY id DESC "
                     "LIMIT 1", (store.scope, key)).fetchone()[0]


def reuse_dropped(store, c, idx: int, seq: int) -> None:
    """Give the newly asked event ``idx`` the result a retry dropped, when there is one to reuse."""
    row = c.execute("SELECT id, state, hf, error, attempts, result_at, source FROM dropped "
                    "WHERE study = ? AND idx = ? AND reusable = 1 AND reused_seq IS NULL "
                    "ORDER BY id DESC LIMIT 1", (store.scope, idx)).fetchone()
    if row is None:
        return
    c.execute("UPDATE events SET state = ?, hf = ?, error = ?, attempts = ?, result_at = ?, "
              "source = ?, result_seq = ? WHERE study = ? AND idx = ?",
              (*row[1:], store._next_seq(c), store.scope, idx))
    c.execute("UPDATE dropped SET reused_seq = ? WHERE id = ?", (seq, row[0]))


def tell_dropped(store, c, key: str, value, error, source) -> bool:
    """Keep a result told for an event a retry took out of the log; False when none is waiting."""
    row = c.execute("SELECT id FROM dropped WHERE study = ? AND key = ? AND result_seq IS NULL "
                    "AND reused_seq IS NULL ORDER BY id DESC LIMIT 1",
                    (store.scope, key)).fetchone()
    if row is None:
        return False
    state = STORED[EventState.of_result(value, error)]
    c.execute("UPDATE dropped SET state = ?, hf = ?, error = ?, result_seq = ?, result_at = ?, "
              "source = ?, reusable = 1 WHERE id = ?",
              (state, value, error, store._next_seq(c), _now(), source, row[0]))
    return True


def replace_result(store, c, idx: int, value, error, source) -> bool:
    """Replace the stored result of event ``idx`` (audited); False when it is identical."""
    key, hf, err, old_source, result_at, tell_seq = c.execute(
        "SELECT key, hf, error, source, result_at, tell_seq FROM events WHERE study = ? AND "
        "idx = ?", (store.scope, idx)).fetchone()
    if (hf, err) == (value, error):
        return False
    used = tell_seq is not None
    c.execute(
        "INSERT INTO replacements (study, idx, key, old_hf, old_error, old_source, "
        "old_result_at, new_hf, new_error, source, seq, consumed_seq, replaced_at, note) "
        "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
        (
            store.scope,
            idx,
            key,
            hf,
            err,
            old_source,
            result_at,
            value,
            error,
            source,
            store._next_seq(c),
            None if used else 0,
            _now(),
            REPLACED_AFTER_USE if used else REPLACED_BEFORE_USE,
        ),
    )
    c.execute("UPDATE events SET state = ?, hf = ?, error = ?, source = ?, result_at = ? "
              "WHERE study = ? AND idx = ?",
              (STORED[EventState.of_result(value, error)], value, error, source, _now(),
               store.scope, idx))
    return True


def _waiting_replacement(store, c, idx: int, value, error):
    """The id of the oldest stored replacement of ``idx`` by ``(value, error)`` no study applied."""
    row = c.execute("SELECT id FROM replacements WHERE study = ? AND idx = ? AND "
                    "consumed_seq IS NULL AND new_hf IS ? AND new_error IS ? ORDER BY id LIMIT 1",
                    (store.scope, idx, value, error)).fetchone()
    return None if row is None else row[0]


def stage_replacement(store, c, idx: int, value, error, source) -> None:
    """Store ``(value, error)`` as the replacement of ``idx``'s used result, unless it waits
    already.

    A study applying a correction it was told in Python stores it here first
    (:func:`replace_result`), the way ``pas study tell --replace`` does;
    :func:`apply_replacement` then marks it applied.
    """
    if _waiting_replacement(store, c, idx, value, error) is None and \
            not replace_result(store, c, idx, value, error, source):
        raise StoreError(f"event index {idx} already holds this result in {store.path}")


def apply_replacement(store, c, idx: int, value, error) -> None:
    """Mark that the study applied the stored replacement of ``idx`` by ``(value, error)`` now."""
    waiting = _waiting_replacement(store, c, idx, value, error)
    if waiting is None:
        raise StoreError(f"no replacement of event index {idx} by hf={value}, error={error!r} "
                         f"waits in {store.path}; store it first (record_result with "
                         "replace=True)")
    c.execute(
        "UPDATE replacements SET consumed_seq = ? WHERE id = ?", (store._claim_op(c), waiting)
    )
