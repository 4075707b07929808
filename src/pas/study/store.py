"""Crash-safe study store: every HF result is on disk the moment it arrives.

One SQLite file per study — or per long-term analysis, one study per sea
state, each in its own ``scope`` (schema 3) — (standard-library
:mod:`sqlite3`), WAL journal,
``synchronous=FULL``, every write in a ``BEGIN IMMEDIATE`` transaction with a
busy time-out, so a driver process and any number of ``pas study tell``
processes can write at the same time without losing a result.  Everything is
stored as JSON or plain columns; nothing is pickled.

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
import sqlite3
from contextlib import contextmanager

import numpy as np

from .._version import __version__
from . import amend
from .loads import add_event_loads, put_loads
from .stored_results import add_results_table
from .schema import (RESUMABLE, with_legacy_settings, SCHEMA_VERSION, STATES, STORED, StoreConflict, StoreError,
                     _now, named_errors, _pool_hash, _pool_records, create_or_upgrade, dumps)
from .state import EventState
from .store_views import StoreViews

__all__ = ["StudyStore", "StoreError", "StoreConflict", "SCHEMA_VERSION", "read_settings", "STATES"]


class StudyStore(StoreViews):
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
        self.path = os.fspath(path)
        self.scope = str(scope)
        if not create and not os.path.exists(self.path):
            raise FileNotFoundError(f"study store {self.path} does not exist "
                                    "(create it with 'pas study create')")
        with named_errors(self.path):
            self._conn = sqlite3.connect(self.path, timeout=timeout, isolation_level=None)
            self._conn.execute("PRAGMA journal_mode=WAL")
            self._conn.execute("PRAGMA synchronous=FULL")
            self._conn.execute("PRAGMA foreign_keys=ON")
            self._depth = 0
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

    # -- plumbing ----------------------------------------------------------
    def close(self) -> None:
        self._conn.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self) -> str:
        return f"StudyStore({self.path!r})" if not self.scope else \
            f"StudyStore({self.path!r}, scope={self.scope!r})"

    @contextmanager
    def transaction(self):
        """A ``BEGIN IMMEDIATE`` write transaction; nested calls join the outer one."""
        with named_errors(self.path):
            yield from self._transaction()

    def _transaction(self):
        if self._depth:
            self._depth += 1
            try:
                yield self._conn
            finally:
                self._depth -= 1
            return
        self._conn.execute("BEGIN IMMEDIATE")
        self._depth = 1
        try:
            yield self._conn
        except BaseException:
            self._depth = 0
            self._conn.execute("ROLLBACK")
            raise
        self._depth = 0
        self._conn.execute("COMMIT")

    @contextmanager
    def _read(self):
        """A consistent read snapshot (joins a running write transaction)."""
        with named_errors(self.path):
            if self._depth:
                yield self._conn
                return
            self._conn.execute("BEGIN")
            try:
                yield self._conn
            finally:
                self._conn.execute("COMMIT")

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

    # -- creation and identity ---------------------------------------------
    @property
    def is_new(self) -> bool:
        with self._read() as c:
            return self._meta(c, "settings") is None

    def settings(self) -> dict:
        """The stored study settings (``{}`` for a new store)."""
        with self._read() as c:
            return self._meta(c, "settings", {})

    def initialize(self, settings: dict, lfset) -> None:
        """Write the settings and LF pool of a new study."""
        records = _pool_records(lfset)
        with self.transaction() as c:
            if self._meta(c, "settings") is not None:
                raise StoreError(f"study store {self.path} already holds a study")
            c.executemany("INSERT INTO lf_peaks VALUES (?, ?, ?, ?, ?, ?, ?)",
                          [(self.scope, *r) for r in records])
            for k, v in (("settings", settings), ("lf_sha256", _pool_hash(records)),
                         ("created_at", _now()), ("pas_version", __version__)):
                self._set_meta(c, k, v)

    def check(self, settings: dict, lfset) -> list[dict]:
        """Raise :class:`StoreError` naming the first setting that differs from the store.

        The stopping settings and budgets (:data:`~pas.study.schema.RESUMABLE`)
        may change: the new values are stored and each change is appended to
        ``meta.settings_changes``, which is returned (the changes made now).
        """
        changes = []
        with self.transaction() as c:
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
                self._set_meta(c, "settings_changes",
                               self._meta(c, "settings_changes", []) + changes)
        return changes

    def _differs(self, key, old, new) -> str:
        return (f"{key} differs from the study store {self.path}: it was created with "
                f"{key}={old!r}, this call has {key}={new!r}")

    def get(self, key, default=None):
        """A JSON value from the ``meta`` table (e.g. ``"oracle"``, ``"batch_size"``)."""
        with self._read() as c:
            return self._meta(c, key, default)

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
                [(self.scope, ev.index, str(ev.id), dumps(ev.id), ev.lf, ev.d, STORED[EventState.PENDING],
                  seq, i, now)
                 for i, ev in enumerate(events)])
            for ev in events:
                amend.reuse_dropped(self, c, ev.index, seq)
        return seq

    def mark_submitted(self, events) -> None:
        """Count a hand-over of ``events`` to an HF tool (``attempts`` + 1)."""
        with self.transaction() as c:
            c.executemany("UPDATE events SET attempts = attempts + 1, submitted_at = ? "
                          "WHERE study = ? AND idx = ?",
                          [(_now(), self.scope, ev.index) for ev in events])

    def record_result(self, event, value, error=None, *, source=None, loads=None) -> None:
        """Store the HF result (``value``) or failure (``error``) of a pending event, and ``loads``.

        Idempotent for an identical result; refuses to overwrite a different one.
        """
        idx = event if isinstance(event, (int, np.integer)) else event.index
        with self.transaction() as c:
            self._put_result(c, int(idx), value, error, source)
            put_loads(c, int(idx), loads, self.path, self.scope)

    def _put_result(self, c, idx, value, error, source):
        row = c.execute("SELECT key, state, hf, error, result_seq FROM events "
                        "WHERE study = ? AND idx = ?", (self.scope, idx)).fetchone()
        if row is None:
            raise StoreError(f"event index {idx} was never asked for in {self.path}")
        key, state, hf, err, rseq = row
        value = None if error is not None else float(value)
        if rseq is not None:
            if (hf, err) == (value, error):
                return
            raise StoreError(f"event {key} already has a result in {self.path} ({state}, "
                             f"hf={hf}, error={err!r}); refusing to overwrite it")
        state = STORED[EventState.of_result(value, error)]
        c.execute("UPDATE events SET state = ?, hf = ?, error = ?, result_seq = ?, result_at = ?, "
                  "source = ? WHERE study = ? AND idx = ?",
                  (state, value, error, self._next_seq(c), _now(), source, self.scope, idx))

    def record_tell(self, event, row: dict) -> None:
        """Store that the study consumed ``event``'s result, with its history row."""
        with self.transaction() as c:
            self._put_result(c, event.index, row.get("hf"), row.get("error"), None)
            seq = self._claim_op(c)
            c.execute("UPDATE events SET tell_seq = ? WHERE study = ? AND idx = ?",
                      (seq, self.scope, event.index))
            self._put_history(c, event, row)

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
        with self.transaction() as c:
            row = c.execute("SELECT idx, state, result_seq, hf, error FROM events "
                            "WHERE study = ? AND key = ?", (self.scope, str(key))).fetchone()
            value = None if error is not None else float(value)
            if row is None:
                if amend.tell_dropped(self, c, str(key), value, error, source):
                    put_loads(c, amend.dropped_index(self, c, str(key)), loads, self.path,
                              self.scope)
                    return True
                raise StoreError(f"event {key} was not asked for in {self.path}")
            if row[2] is not None:
                if (row[3], row[4]) == (value, error):
                    return False
                if replace and loads:
                    raise StoreError(f"event {key}: --replace takes the screened load alone "
                                     "(VALUE), not --load NAME=VALUE; named loads cannot be "
                                     "corrected yet")
                if replace:
                    return amend.replace_result(self, c, row[0], value, error, source)
                raise StoreError(f"event {key} is already told ({row[1]}, hf={row[3]}, "
                                 f"error={row[4]!r}); to correct it, tell it again with "
                                 "--replace (replace=True)")
            self._put_result(c, row[0], value, error, source)
            put_loads(c, row[0], loads, self.path, self.scope)
            return True

    def record_replacement(self, event, row: dict) -> None:
        """Store that the study applied a replacement of ``event``'s result, with its history row."""
        with self.transaction() as c:
            amend.apply_replacement(self, c, event.index, row.get("hf"), row.get("error"))
            self._put_history(c, event, row)

    def _put_history(self, c, event, row: dict) -> None:
        c.execute("INSERT INTO history VALUES (?, ?, ?, ?, ?)",
                  (self.scope, row["row"], event.index, dumps(row), _now()))

    def retry_failed(self, keys=None) -> dict:
        """Rewind the log so failed events run again (:func:`pas.study.amend.rewind_failed`)."""
        with self.transaction() as c:
            return amend.rewind_failed(self, c, keys)

    def ops(self) -> list[tuple]:
        """The replay log in order: ``("ask", [idx, ...])``, ``("tell", idx, hf, error)``
        and ``("replace", idx, hf, error)``.

        A tell replays the value the study used then: the old value of the
        first replacement it applied later, if any.  Also remembers the last
        op so later writes can detect another driver.
        """
        with self._read() as c:
            asks = c.execute("SELECT batch, idx FROM events WHERE study = ? "
                             "ORDER BY batch, batch_pos", (self.scope,)).fetchall()
            tells = c.execute("SELECT tell_seq, idx, hf, error FROM events "
                              "WHERE study = ? AND tell_seq IS NOT NULL", (self.scope,)).fetchall()
            replaced = c.execute("SELECT consumed_seq, idx, old_hf, old_error, new_hf, new_error "
                                 "FROM replacements WHERE study = ? AND consumed_seq IS NOT 0 "
                                 "ORDER BY id", (self.scope,)).fetchall()
            self._op_seq = self._meta(c, "op_seq")
        ops: dict[int, tuple] = {}
        for batch, idx in asks:
            ops.setdefault(batch, ("ask", []))[1].append(idx)
        first_old = {}
        for seq, idx, old_hf, old_err, new_hf, new_err in replaced:
            first_old.setdefault(idx, (old_hf, old_err))
            if seq is not None:
                ops[seq] = ("replace", idx, new_hf, new_err)
        for seq, idx, hf, err in tells:
            ops[seq] = ("tell", idx, *first_old.get(idx, (hf, err)))
        return [ops[k] for k in sorted(ops)]

def read_settings(path) -> dict:
    """Stored settings of the study at ``path`` (``{}`` when there is no store yet)."""
    if not os.path.exists(os.fspath(path)):
        return {}
    with StudyStore(path, create=False) as store:
        return store.settings()
