"""Several loads per HF event in the study store: the ``event_loads`` table.

One CFD run or basin test gives many signals; an oracle answering ``{name:
load}`` (:func:`pas.study.answers.check_hf_answer`) has every named load kept
here, in the transaction that stores the event's result, so nothing it gave is
lost and :func:`pas.study.refit.refit` can analyse another load on the same
events.  An answer of one bare number is the screened load only (``events.hf``)
and writes no row.

``event_loads(study, idx, name, value, error)``
    One row per named load of an event: ``value`` (NULL when the load was NaN,
    negative or not a number) and ``error`` (why, else NULL); the loads of the
    event's result, kept by event index also when a retry takes the event's
    ask out of the log (its result, and so its loads, may be reused); a retried
    failure's loads are deleted with its result.  Created when a store is opened
    (:func:`add_event_loads`), so stores written before it existed gain it and
    still open and replay as they were.
"""

from __future__ import annotations

from .answers import screened_load
from .schema import StoreError, _now

__all__ = ["add_event_loads", "put_loads", "replace_loads", "record_loads", "stored_loads",
           "load_names", "answers_from_loads", "adopt_target"]

EVENT_LOADS = """
CREATE TABLE IF NOT EXISTS event_loads (
    study TEXT NOT NULL DEFAULT '', idx INTEGER NOT NULL, name TEXT NOT NULL,
    value REAL, error TEXT,
    PRIMARY KEY (study, idx, name))
"""

LOAD_REPLACEMENTS = """
CREATE TABLE IF NOT EXISTS load_replacements (
    id INTEGER PRIMARY KEY AUTOINCREMENT, study TEXT NOT NULL DEFAULT '', idx INTEGER NOT NULL,
    name TEXT NOT NULL, old_value REAL, old_error TEXT, new_value REAL, new_error TEXT,
    source TEXT, replaced_at TEXT NOT NULL)
"""


def add_event_loads(c) -> None:
    """Create the ``event_loads`` and ``load_replacements`` tables when missing.

    Idempotent; run in the opening transaction of
    :class:`~pas.study.store.StudyStore` for new stores and older ones alike,
    so it needs no schema version of its own.
    """
    c.execute(EVENT_LOADS)
    c.execute(LOAD_REPLACEMENTS)


def put_loads(c, idx: int, loads, path, scope: str = "") -> None:
    """Store ``loads`` (``{name: (value, error)}``) of event ``idx`` of study ``scope`` in ``c``.

    Identical rows are left as they are; a different value for a stored load
    raises :class:`~pas.study.schema.StoreError` (as a second, different result does).
    """
    for name, (value, error) in (loads or {}).items():
        row = c.execute("SELECT value, error FROM event_loads WHERE study = ? AND idx = ? AND "
                        "name = ?", (scope, idx, name)).fetchone()
        if row is None:
            c.execute("INSERT INTO event_loads VALUES (?, ?, ?, ?, ?)",
                      (scope, idx, name, value, error))
        elif tuple(row) != (value, error):
            raise StoreError(f"load {name!r} of event index {idx} is already stored in {path} "
                             f"(value={row[0]}, error={row[1]!r}); refusing to overwrite it "
                             "(correct it with --replace, or replace=True)")


def replace_loads(c, idx: int, loads, scope: str = "", source: str | None = None) -> bool:
    """Replace the stored named ``loads`` of event ``idx``, each old value to ``load_replacements``.

    Loads not named in ``loads`` stay as they are; a load the event did not
    have is added (its old value NULL in the audit row).  Returns whether any
    stored load changed.
    """
    changed = False
    for name, (value, error) in (loads or {}).items():
        row = c.execute("SELECT value, error FROM event_loads WHERE study = ? AND idx = ? AND "
                        "name = ?", (scope, idx, name)).fetchone()
        if row is not None and tuple(row) == (value, error):
            continue
        old = (None, None) if row is None else tuple(row)
        c.execute("INSERT INTO load_replacements (study, idx, name, old_value, old_error, "
                  "new_value, new_error, source, replaced_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                  (scope, idx, name, *old, value, error, source, _now()))
        c.execute("INSERT OR REPLACE INTO event_loads VALUES (?, ?, ?, ?, ?)",
                  (scope, idx, name, value, error))
        changed = True
    return changed


def record_loads(store, event, loads) -> None:
    """Store the named loads of ``event`` alone, its result still to come (no target yet)."""
    with store.transaction() as c:
        put_loads(c, int(event.index), loads, store.path, store.scope)


def stored_loads(store, name=None) -> dict:
    """``{idx: {name: (value, error)}}`` of the stored loads (of load ``name`` only if given)."""
    sql, args = "SELECT idx, name, value, error FROM event_loads WHERE study = ?", (store.scope,)
    if name is not None:
        sql, args = sql + " AND name = ?", (store.scope, name)
    out: dict = {}
    with store._read() as c:
        for idx, n, value, error in c.execute(sql + " ORDER BY idx, rowid", args):
            out.setdefault(int(idx), {})[n] = (value, error)
    return out


def load_names(store) -> list[str]:
    """Names of the loads stored in ``store``, in order of first appearance."""
    with store._read() as c:
        return [r[0] for r in c.execute(
            "SELECT name FROM event_loads WHERE study = ? GROUP BY name ORDER BY MIN(rowid)",
            (store.scope,))]


def answers_from_loads(store, indices, target) -> dict:
    """``{idx: (value, error)}`` for events of ``indices`` whose loads are stored but not
    their result (a run stopped for want of a ``target``), screened on ``target``."""
    if target is None:
        return {}
    loads = stored_loads(store)
    return {idx: screened_load(loads[idx], target) for idx in indices if idx in loads}


def adopt_target(store, settings: dict) -> dict | None:
    """Let a study given a ``target`` take over a store that has no result yet.

    A run whose oracle answered several loads without a ``target`` stops at the
    first answer (its loads stored, :func:`record_loads`); the same run given
    the target must then continue that store.  While no event has a result the
    target decided nothing, so the stored one is replaced and the change
    logged in ``meta.settings_changes``.  Returns the change, or None.
    """
    with store.transaction() as c:
        stored = store._meta(c, "settings") or {}
        old, new = stored.get("target"), settings.get("target")
        if old == new or c.execute("SELECT COUNT(*) FROM events WHERE study = ? AND "
                                   "result_seq IS NOT NULL", (store.scope,)).fetchone()[0]:
            return None
        store._set_meta(c, "settings", {**stored, "target": new})
        change = {"key": "target", "old": old, "new": new, "n_told": 0, "at": _now()}
        store._set_meta(c, "settings_changes", store._meta(c, "settings_changes", []) + [change])
    return change
