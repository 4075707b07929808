"""Crash-safe study store: every HF result is on disk the moment it arrives.

One SQLite file per study — or per long-term analysis, one study per sea
state, each in its own ``scope`` (schema 3) — (standard-library
:mod:`sqlite3`), WAL journal,
``synchronous=FULL``, every write in a ``BEGIN IMMEDIATE`` transaction with a
busy time-out, so a driver process and any number of ``pas study tell``
processes can write at the same time without losing a result.  Everything is
stored as JSON or plain columns; nothing is pickled.

The file itself — its connection, transactions, checkpoint and backup — is
:class:`~pas.study.store_file.StoreFile`'s.

The tables are described in :mod:`pas.study.schema`; rebuilding a study from
them is :mod:`pas.study.replay` (:func:`~pas.study.replay.attach`) and
:func:`~pas.study.resume.open_study`.

Examples
--------
One process asks, any process tells, the next ask continues the same study::

    study = pas.make_study(pas.PAS, lf, n_waves=n_w, p_exp=p, eps1=0.05, seed=1,
                           store="campaign.db")
    events = study.ask()                    # stored as pending
    ...                                     # days later, elsewhere:
    StudyStore("campaign.db").tell_by_key(events[0].id, 4.2)
    study = open_study("campaign.db")       # replayed, the new result used
    study.ask()
"""

from __future__ import annotations

import json
import os

import numpy as np

from .._version import __version__
from . import amend
from .loads import add_event_loads, put_loads, replace_loads
from .schema import (
    RESUMABLE,
    SCHEMA_VERSION,
    STATES,
    STORED,
    StoreConflict,
    StoreError,
    _now,
    _pool_hash,
    _pool_records,
    create_or_upgrade,
    dumps,
    with_legacy_settings,
)
from .state import EventState
from .store_file import StoreFile
from .store_views import Ask, LFInputs, Outstanding, Replace, StoredResult, StoreViews, Tell
from .stored_results import add_results_table

__all__ = ["StudyStore", "StoreError", "StoreConflict", "SCHEMA_VERSION", "read_settings", "STATES",
           "LFInputs", "StoredResult", "Outstanding", "Ask", "Tell", "Replace"]


class StudyStore(StoreFile, StoreViews):
    """One study's SQLite file (:mod:`pas.study.schema` for the tables).

    Parameters
    ----------
    path : str or os.PathLike
        The ``.db`` file.
    create : bool, default True
        Create the file when missing; False raises ``FileNotFoundError``.
    timeout : float, default 120
        Seconds to wait for another process's write transaction.
    scope : str, default ""
        The study in the file (schema 3): ``""`` for a single study, a
        sea-state name for one study of a long-term analysis
        (:mod:`pas.longterm`).  Every read and write stays inside it.
    """

    def __init__(self, path, *, create: bool = True, timeout: float = 120.0, scope: str = ""):
        super().__init__(path, create=create, timeout=timeout)
        self.scope = str(scope)
        self._op_seq = 0
        with self.transaction() as c:
            version = c.execute("PRAGMA user_version").fetchone()[0]
            if version > SCHEMA_VERSION:
                raise StoreError(
                    f"study store {self.path} has schema version {version}; this pas reads "
                    f"up to version {SCHEMA_VERSION}: upgrade pas to open it")
            if version < SCHEMA_VERSION:
                create_or_upgrade(c, version)
            add_event_loads(c)
            add_results_table(c)
            c.executemany("INSERT OR IGNORE INTO meta VALUES (?, ?, ?)",
                          [(self.scope, k, dumps(0)) for k in ("seq", "op_seq")])

    def __repr__(self) -> str:
        return f"StudyStore({self.path!r})" if not self.scope else \
            f"StudyStore({self.path!r}, scope={self.scope!r})"

    def _meta(self, c, key, default=None):
        row = c.execute("SELECT value FROM meta WHERE study = ? AND key = ?",
                        (self.scope, key)).fetchone()
        return default if row is None else json.loads(row[0])

    def _set_meta(self, c, key, value) -> None:
        c.execute("INSERT OR REPLACE INTO meta VALUES (?, ?, ?)", (self.scope, key, dumps(value)))

    def _next_seq(self, c) -> int:
        seq = self._meta(c, "seq") + 1
        self._set_meta(c, "seq", seq)
        return seq

    def _claim_op(self, c) -> int:
        """Next op sequence number, refusing when another process consumed or asked meanwhile."""
        current = self._meta(c, "op_seq")
        if current != self._op_seq:
            raise StoreConflict(
                f"study store {self.path} was changed by another process driving the same study "
                "(asks or consumed tells); reopen the study to continue")
        seq = self._next_seq(c)
        self._set_meta(c, "op_seq", seq)
        self._op_seq = seq
        return seq

    # -- creation and meta -------------------------------------------------
    def bind(self, settings: dict, lfset) -> list[dict]:
        """Write the settings and LF pool of a new study, or check them against the stored ones.

        On a store holding a study, raise :class:`StoreError` naming the first
        setting that differs.  The stopping settings and budgets
        (:data:`~pas.study.schema.RESUMABLE`) may change: the new values are
        stored and each change is appended to ``meta.settings_changes``, which
        is returned (the changes made now; ``[]`` for a new study).
        """
        with self.transaction() as c:
            if self._meta(c, "settings") is None:
                self._initialize(c, settings, lfset)
                return []
            return self._check(c, settings, lfset)

    def _initialize(self, c, settings: dict, lfset) -> None:
        records = _pool_records(lfset)
        c.executemany("INSERT INTO lf_peaks VALUES (?, ?, ?, ?, ?, ?, ?)",
                      [(self.scope, *r) for r in records])
        for k, v in (("settings", settings), ("lf_sha256", _pool_hash(records)),
                     ("created_at", _now()), ("pas_version", __version__)):
            self._set_meta(c, k, v)

    def _check(self, c, settings: dict, lfset) -> list[dict]:
        changes = []
        stored = with_legacy_settings(self._meta(c, "settings"))
        for key in sorted(set(stored) | set(settings)):
            old, new = stored.get(key), settings.get(key)
            if key == "strategy_settings":
                for k in sorted(set(old or {}) | set(new or {})):
                    if (old or {}).get(k) != (new or {}).get(k):
                        raise StoreError(self._differs(k, (old or {}).get(k), (new or {}).get(k)))
            elif old != new and key not in RESUMABLE:
                raise StoreError(self._differs(key, old, new))
            elif old != new:
                changes.append({"key": key, "old": old, "new": new})
        if _pool_hash(_pool_records(lfset)) != self._meta(c, "lf_sha256"):
            n = c.execute("SELECT COUNT(*) FROM lf_peaks WHERE study = ?",
                          (self.scope,)).fetchone()[0]
            raise StoreError(
                f"lf_peaks differ from those the study store {self.path} was created with "
                f"({n} peaks over threshold stored, {lfset.n} given; values, ids or meta "
                "changed)")
        if stored != settings:
            self._set_meta(c, "settings", settings)
        if changes:
            n_told = c.execute("SELECT COUNT(*) FROM events WHERE study = ? AND "
                               "tell_seq IS NOT NULL", (self.scope,)).fetchone()[0]
            now = _now()
            for ch in changes:
                ch.update(n_told=n_told, at=now)
            self._set_meta(c, "settings_changes", self._meta(c, "settings_changes", []) + changes)
        return changes

    def _differs(self, key, old, new) -> str:
        return (f"{key} differs from the study store {self.path}: it was created with "
                f"{key}={old!r}, this call has {key}={new!r}")

    def put(self, key, value) -> None:
        """Store a JSON value in the ``meta`` table (not the reserved keys)."""
        if key in ("settings", "lf_sha256", "seq", "op_seq", "created_at", "pas_version",
                   "settings_changes"):
            raise StoreError(f"meta key {key!r} is reserved")
        with self.transaction() as c:
            self._set_meta(c, key, value)

    # -- the log -----------------------------------------------------------
    def record_ask(self, events) -> int:
        """Store a study's ask: ``events`` become pending, in this order.

        An event a retry took out of the log gets its kept result back
        (:func:`pas.study.amend.reuse_dropped`), so it is not run again.
        """
        with self.transaction() as c:
            seq = self._claim_op(c)
            now = _now()
            c.executemany(
                "INSERT INTO events (study, idx, key, event_id, lf, d, state, batch, batch_pos, "
                "asked_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                [
                    (
                        self.scope,
                        ev.index,
                        str(ev.id),
                        dumps(ev.id),
                        ev.lf,
                        ev.d,
                        STORED[EventState.PENDING],
                        seq,
                        i,
                        now,
                    )
                    for i, ev in enumerate(events)
                ],
            )
            for ev in events:
                amend.reuse_dropped(self, c, ev.index, seq)
        return seq

    def mark_submitted(self, events) -> None:
        """Count a hand-over of ``events`` to an HF tool (``attempts`` + 1)."""
        with self.transaction() as c:
            c.executemany("UPDATE events SET attempts = attempts + 1, submitted_at = ? "
                          "WHERE study = ? AND idx = ?",
                          [(_now(), self.scope, ev.index) for ev in events])

    def record_result(self, event, value, error=None, *, source=None, loads=None,
                      replace: bool = False) -> None:
        """Store the HF result (``value``) or failure (``error``) of an asked event, and ``loads``.

        The one place a result this process got is written (:meth:`record_tell`
        then marks it used).  Idempotent for an identical result; refuses to
        overwrite a different one.  With ``replace`` the event's result was
        used already: the new one is stored as its replacement (audited,
        :func:`pas.study.amend.stage_replacement`), unless that replacement
        already waits, and named ``loads`` replace the stored ones
        (:func:`pas.study.loads.replace_loads`; with the screened load
        unchanged, they are all that changes).
        """
        idx = int(event if isinstance(event, (int, np.integer)) else event.index)
        value = _as_result(value, error)
        with self.transaction() as c:
            if replace:
                loads_changed = replace_loads(c, idx, loads, self.scope, source or "python")
                if not (loads_changed and self._holds(c, idx, value, error)):
                    amend.stage_replacement(self, c, idx, value, error, source or "python")
                return
            self._put_result(c, idx, value, error, source)
            put_loads(c, idx, loads, self.path, self.scope)

    def _holds(self, c, idx, value, error) -> bool:
        """Whether event ``idx``'s stored result is ``(value, error)``."""
        row = c.execute("SELECT hf, error FROM events WHERE study = ? AND idx = ?",
                        (self.scope, idx)).fetchone()
        return row is not None and tuple(row) == (value, error)

    def _put_result(self, c, idx, value, error, source):
        row = c.execute("SELECT key, state, hf, error, result_seq FROM events "
                        "WHERE study = ? AND idx = ?", (self.scope, idx)).fetchone()
        if row is None:
            raise StoreError(f"event index {idx} was never asked for in {self.path}")
        key, state, hf, err, result_seq = row
        if result_seq is not None:
            if (hf, err) == (value, error):
                return
            raise StoreError(f"event {key} already has a result in {self.path} ({state}, "
                             f"hf={hf}, error={err!r}); refusing to overwrite it")
        state = STORED[EventState.of_result(value, error)]
        c.execute("UPDATE events SET state = ?, hf = ?, error = ?, result_seq = ?, result_at = ?, "
                  "source = ? WHERE study = ? AND idx = ?",
                  (state, value, error, self._next_seq(c), _now(), source, self.scope, idx))

    def record_tell(self, event, row: dict, *, replace: bool = False) -> None:
        """Store that the study used ``event``'s stored result, with its history row.

        With ``replace`` the row applies a stored replacement of a used result
        (:meth:`record_result` with ``replace``).  Nothing of the result is
        written here: it must be stored already and be the row's ``hf`` /
        ``error``, else :class:`StoreError`.
        """
        value = _as_result(row.get("hf"), row.get("error"))
        with self.transaction() as c:
            if replace:
                amend.apply_replacement(self, c, event.index, value, row.get("error"))
            else:
                self._mark_told(c, event.index, value, row.get("error"))
            self._put_history(c, event, row)

    def _mark_told(self, c, idx, value, error) -> None:
        found = c.execute("SELECT key, hf, error, result_seq FROM events WHERE study = ? AND "
                          "idx = ?", (self.scope, idx)).fetchone()
        if found is None:
            raise StoreError(f"event index {idx} was never asked for in {self.path}")
        key, hf, err, result_seq = found
        if result_seq is None or (hf, err) != (value, error):
            held = "no result" if result_seq is None else f"hf={hf}, error={err!r}"
            raise StoreError(f"event {key}: the study used hf={value}, error={error!r} but "
                             f"{self.path} holds {held}; store the result first "
                             "(record_result), a stored one is never overwritten")
        c.execute("UPDATE events SET tell_seq = ? WHERE study = ? AND idx = ?",
                  (self._claim_op(c), self.scope, idx))

    def tell_by_key(self, key, value=None, *, error=None, source=None, loads=None,
                    replace: bool = False) -> bool:
        """Record a result (and named ``loads``) for the pending event with id ``key``, any process.

        Returns False when the identical result is already stored; a different
        one raises :class:`StoreError` unless ``replace``: then the new result
        replaces the old one, which is kept with the time and the source in
        the audit trail (:meth:`replacements`); a study that used the old
        value applies the new one when it is next driven
        (:mod:`pas.study.amend`).  A result for an event a retry took out of
        the log is kept there and used if the study asks for it again.
        """
        key = str(key)
        value = _as_result(value, error)
        with self.transaction() as c:
            found = c.execute("SELECT idx, state, result_seq, hf, error FROM events "
                              "WHERE study = ? AND key = ?", (self.scope, key)).fetchone()
            if found is None:
                if amend.tell_dropped(self, c, key, value, error, source):
                    put_loads(c, amend.dropped_index(self, c, key), loads, self.path, self.scope)
                    return True
                raise StoreError(f"event {key} was not asked for in {self.path}")
            idx, state, result_seq, hf, err = found
            if result_seq is not None:
                if replace:
                    loads_changed = replace_loads(c, idx, loads, self.scope, source)
                    return amend.replace_result(self, c, idx, value, error, source) or \
                        loads_changed
                if (hf, err) == (value, error):
                    put_loads(c, idx, loads, self.path, self.scope)  # a different load: refused
                    return False
                raise StoreError(f"event {key} is already told ({state}, hf={hf}, "
                                 f"error={err!r}); to correct it, tell it again with "
                                 "--replace (replace=True)")
            self._put_result(c, idx, value, error, source)
            put_loads(c, idx, loads, self.path, self.scope)
            return True

    def _put_history(self, c, event, row: dict) -> None:
        c.execute("INSERT INTO history VALUES (?, ?, ?, ?, ?)",
                  (self.scope, row["row"], event.index, dumps(row), _now()))

    def retry_failed(self, keys=None) -> dict:
        """Rewind the log so failed events run again (:func:`pas.study.amend.rewind_failed`)."""
        with self.transaction() as c:
            return amend.rewind_failed(self, c, keys)


def _as_result(value, error):
    """The stored form of a result: ``value`` as a float, None for a failure."""
    return None if error is not None else float(value)


def read_settings(path) -> dict:
    """Stored settings of the study at ``path`` or in an open :class:`StudyStore` (``{}``
    when there is no store yet)."""
    if isinstance(path, StudyStore):
        return path.settings()
    if not os.path.exists(os.fspath(path)):
        return {}
    with StudyStore(path, create=False) as store:
        return store.settings()
