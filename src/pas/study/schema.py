"""The study store's schema and encoding: SQL tables, version, states, errors and JSON.

:class:`~pas.study.store.StudyStore` writes and reads these tables;
:mod:`pas.study.replay` rebuilds a study from them.

Schema (version 3)
------------------
Version 3 scopes every study table by a ``study`` key (first column): one
file holds one study (key ``""``, what a single study always uses) or the
studies of a long-term analysis, one per sea state (key: the sea-state name,
:mod:`pas.longterm`), each with its own settings, sequence numbers and log;
the keys and unique columns below hold within one study.  A store of
version 1 or 2 is rebuilt in place when opened (:func:`upgrade_to_3`), its
rows under the key ``""``, so it opens and replays as before.

``schema_version(version)``
    One row, also ``PRAGMA user_version``.  A store written by a newer schema
    is refused with an error asking to upgrade pas; an older one is upgraded
    when opened, one step per version (:data:`UPGRADES`).
``meta(key, value)``
    JSON values: ``settings`` (strategy name and settings, ``n_waves``,
    ``p_exp``, ``threshold``, ``eps1`` …, ``seed``, ``max_hf``),
    ``lf_sha256`` (hash of the LF pool), ``created_at``, ``pas_version``,
    ``seq`` (the last sequence number handed out) and ``op_seq`` (the last
    ask or tell consumed by a study); ``oracle`` and ``batch_size`` when the
    study was created by ``pas study create`` with an ``[oracle]`` table;
    ``oracle_cwd``, ``oracle_root`` and ``oracle_command`` (the folder a
    ``pas run`` command oracle's relative paths resolve against, the folder
    of its event folders, its argument list as last run) and
    ``oracle_command_changes``, a list of ``{"old", "new", "at"}``, one per
    change of that command on a resumed run (free keys: no schema version);
    ``settings_changes``, a list of ``{"key", "old", "new", "n_told", "at"}``,
    one per change of a :data:`RESUMABLE` setting on a resumed study
    (``n_told``: results the study had consumed then).
``lf_peaks(idx, key, event_id, lf, d, meta)``
    The LF pool the study was created with: every peak over the threshold,
    keyed by ``idx``, its index in the user's ``lf_peaks``; ``key`` is
    ``str(event_id)``, ``event_id`` and ``meta`` are JSON.
``events(idx, key, event_id, lf, d, state, hf, error, batch, batch_pos,
result_seq, tell_seq, attempts, asked_at, submitted_at, result_at, source)``
    Every event sent to the HF tool.  ``state`` is ``pending``, ``done``
    (HF > 0), ``false_positive`` (HF = 0) or ``failed`` (``error`` says why):
    the :class:`~pas.study.state.EventState` written as in :data:`STORED`.
    ``batch`` is the sequence number of the ask that sent it (``batch_pos``
    its place in that ask); ``result_seq`` the sequence number at which its
    result arrived; ``tell_seq`` the one at which a study consumed it.
    ``attempts`` counts hand-overs to an HF tool (a resubmitted pending event
    has 2).
``history(row, idx, data, written_at)``
    The study's history row of each consumed tell or replacement (JSON),
    written in the same transaction.
``replacements(id, idx, key, old_hf, old_error, old_source, old_result_at, new_hf,
new_error, source, seq, consumed_seq, replaced_at, note)`` (version 2)
    The audit trail of ``tell --replace``: one row per replaced result.
    ``seq`` is when it arrived; ``consumed_seq`` when a study applied it
    (an op of the replay log), 0 when the study had not used the old value
    (no op needed), NULL until a study applies it.
``dropped(id, idx, key, state, hf, error, batch, batch_pos, result_seq, tell_seq,
attempts, asked_at, submitted_at, result_at, source, retry_seq, reason, reusable,
reused_seq, dropped_at)`` (version 2)
    Asks a retry of failed events (:mod:`pas.study.amend`) took out of the
    log, with their results: nothing told is lost.  ``reusable`` results are
    reused when the study asks that event again (``reused_seq``).
``event_loads(idx, name, value, error)``
    Every named load of an event whose oracle answered several
    (:mod:`pas.study.loads`); created on opening, also in older stores.

Replay order is the asks (grouped by ``batch``) and the consumed tells
(``tell_seq``) sorted by sequence number.  Results that arrived but were not
consumed yet (``result_seq`` set, ``tell_seq`` NULL) are consumed by whoever
drives the study next: :func:`pas.study.loop.optimize` in ask order,
``pas study ask`` in arrival order.
"""

from __future__ import annotations

import hashlib
import json
import sqlite3
from contextlib import contextmanager
from datetime import datetime, timezone

import numpy as np

from .._support.strict_json import dumps
from .settings import DEFAULT_MAX_HF, RESUMABLE
from .state import EventState

__all__ = [
    "SCHEMA_VERSION",
    "UPGRADES",
    "STATES",
    "STORED",
    "RESUMABLE",
    "LEGACY_SETTINGS",
    "DEFAULT_MAX_HF",
    "with_legacy_settings",
    "StoreError",
    "StoreConflict",
    "named_errors",
    "dumps",
]

SCHEMA_VERSION = 3
#: How each :class:`~pas.study.state.EventState` is written in ``events.state`` (schema 1).
STORED = {EventState.PENDING: "pending", EventState.TRUE_POSITIVE: "done",
          EventState.FALSE_POSITIVE: "false_positive", EventState.FAILED: "failed"}
STATES = tuple(STORED.values())
LEGACY_SETTINGS = {
    "strategy_settings": {"estimator": "selected", "copula_fit": "mle",
                          "common_random_numbers": False, "hf_location": True,
                          "hf_marginal": "weibull", "band_marginals": "fitted",
                          "band_lf_ranks": "fixed", "lf_tail": "ranks",
                          "impact_trend": "rising"},
    "stop_measure": "step",
    "legacy_md": True,
}
"""What a study store written before these settings existed (pas 0.1, schema 1) ran
with: filled in for the missing keys when such a store is opened, so it replays
and continues as it was created."""


def with_legacy_settings(stored: dict) -> dict:
    """``stored`` study settings with :data:`LEGACY_SETTINGS` for the keys they lack, and PAS
    settings as this version writes them: pas 0.1 kept every option whichever estimator
    ran, and those of the other estimator, which did not act, are dropped
    (:func:`pas.strategies.flat.pas_kwargs`)."""
    from ..strategies.pas import PAS  # here: the command line reads this module at start-up

    out = dict(stored)
    if out.get("strategy") == "pas":
        flat = {**LEGACY_SETTINGS["strategy_settings"], **(out.get("strategy_settings") or {})}
        out["strategy_settings"] = json.loads(dumps(PAS.from_flat(flat, strict=False).settings()))
    if "eps1" in out:
        for key in ("stop_measure", "legacy_md"):
            out.setdefault(key, LEGACY_SETTINGS[key])
    if out.get("precision") is not None:  # written before the fit check: none, as it ran
        out.setdefault("fit_check", None)
    return out


#: RESUMABLE (:mod:`pas.study.settings`): the stopping rule (App. C) and the budgets may
#: change when a study is resumed; every change is logged in ``meta.settings_changes``.

_SCHEMA = f"""
CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS lf_peaks (
    idx INTEGER PRIMARY KEY, key TEXT NOT NULL UNIQUE, event_id TEXT NOT NULL,
    lf REAL NOT NULL, d REAL NOT NULL, meta TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS events (
    idx INTEGER PRIMARY KEY REFERENCES lf_peaks(idx), key TEXT NOT NULL UNIQUE,
    event_id TEXT NOT NULL, lf REAL NOT NULL, d REAL NOT NULL,
    state TEXT NOT NULL CHECK (state IN {STATES!r}),
    hf REAL, error TEXT, batch INTEGER NOT NULL, batch_pos INTEGER NOT NULL,
    result_seq INTEGER, tell_seq INTEGER UNIQUE, attempts INTEGER NOT NULL DEFAULT 0,
    asked_at TEXT NOT NULL, submitted_at TEXT, result_at TEXT, source TEXT);
CREATE TABLE IF NOT EXISTS history (
    row INTEGER PRIMARY KEY, idx INTEGER NOT NULL, data TEXT NOT NULL, written_at TEXT NOT NULL);
"""


_SCHEMA_2 = """
CREATE TABLE IF NOT EXISTS replacements (
    id INTEGER PRIMARY KEY, idx INTEGER NOT NULL, key TEXT NOT NULL,
    old_hf REAL, old_error TEXT, old_source TEXT, old_result_at TEXT,
    new_hf REAL, new_error TEXT, source TEXT, seq INTEGER NOT NULL, consumed_seq INTEGER,
    replaced_at TEXT NOT NULL, note TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS dropped (
    id INTEGER PRIMARY KEY, idx INTEGER NOT NULL, key TEXT NOT NULL, state TEXT NOT NULL,
    hf REAL, error TEXT, batch INTEGER, batch_pos INTEGER, result_seq INTEGER,
    tell_seq INTEGER, attempts INTEGER, asked_at TEXT, submitted_at TEXT, result_at TEXT,
    source TEXT, retry_seq INTEGER NOT NULL, reason TEXT NOT NULL,
    reusable INTEGER NOT NULL, reused_seq INTEGER, dropped_at TEXT NOT NULL);
"""


def _run_script(c, script: str) -> None:
    for stmt in filter(str.strip, script.split(";")):
        c.execute(stmt)


def upgrade_to_2(c) -> None:
    """Schema 1 -> 2: the audit trail of replaced results and the asks a retry dropped."""
    _run_script(c, _SCHEMA_2)


#: The tables of version 3: ``(name, columns and constraints)``, each led by ``study``.
_SCHEMA_3 = (
    ("meta", "key TEXT NOT NULL, value TEXT NOT NULL, PRIMARY KEY (study, key)"),
    ("lf_peaks", "idx INTEGER NOT NULL, key TEXT NOT NULL, event_id TEXT NOT NULL, "
                 "lf REAL NOT NULL, d REAL NOT NULL, meta TEXT NOT NULL, "
                 "PRIMARY KEY (study, idx), UNIQUE (study, key)"),
    ("events", "idx INTEGER NOT NULL, key TEXT NOT NULL, event_id TEXT NOT NULL, "
               "lf REAL NOT NULL, d REAL NOT NULL, "
               f"state TEXT NOT NULL CHECK (state IN {STATES!r}), hf REAL, error TEXT, "
               "batch INTEGER NOT NULL, batch_pos INTEGER NOT NULL, result_seq INTEGER, "
               "tell_seq INTEGER, attempts INTEGER NOT NULL DEFAULT 0, asked_at TEXT NOT NULL, "
               "submitted_at TEXT, result_at TEXT, source TEXT, PRIMARY KEY (study, idx), "
               "UNIQUE (study, key), UNIQUE (study, tell_seq), "
               "FOREIGN KEY (study, idx) REFERENCES lf_peaks (study, idx)"),
    ("history", "row INTEGER NOT NULL, idx INTEGER NOT NULL, data TEXT NOT NULL, "
                "written_at TEXT NOT NULL, PRIMARY KEY (study, row)"),
    ("replacements", "id INTEGER PRIMARY KEY, idx INTEGER NOT NULL, key TEXT NOT NULL, "
                     "old_hf REAL, old_error TEXT, old_source TEXT, old_result_at TEXT, "
                     "new_hf REAL, new_error TEXT, source TEXT, seq INTEGER NOT NULL, "
                     "consumed_seq INTEGER, replaced_at TEXT NOT NULL, note TEXT NOT NULL"),
    ("dropped", "id INTEGER PRIMARY KEY, idx INTEGER NOT NULL, key TEXT NOT NULL, "
                "state TEXT NOT NULL, hf REAL, error TEXT, batch INTEGER, batch_pos INTEGER, "
                "result_seq INTEGER, tell_seq INTEGER, attempts INTEGER, asked_at TEXT, "
                "submitted_at TEXT, result_at TEXT, source TEXT, retry_seq INTEGER NOT NULL, "
                "reason TEXT NOT NULL, reusable INTEGER NOT NULL, reused_seq INTEGER, "
                "dropped_at TEXT NOT NULL"),
    ("event_loads", "idx INTEGER NOT NULL, name TEXT NOT NULL, value REAL, error TEXT, "
                    "PRIMARY KEY (study, idx, name)"),
    ("results", "log_key TEXT NOT NULL, n_told INTEGER NOT NULL, data TEXT NOT NULL, "
                "written_at TEXT NOT NULL, PRIMARY KEY (study, log_key)"),
)

#: The tables version 3 found created on opening in older stores, as they were then.
_OPENED_TABLES = """
CREATE TABLE IF NOT EXISTS event_loads (
    idx INTEGER NOT NULL, name TEXT NOT NULL, value REAL, error TEXT, PRIMARY KEY (idx, name));
CREATE TABLE IF NOT EXISTS results (
    log_key TEXT PRIMARY KEY, n_told INTEGER NOT NULL, data TEXT NOT NULL,
    written_at TEXT NOT NULL)
"""


def upgrade_to_3(c) -> None:
    """Schema 2 -> 3: every table rebuilt with a leading ``study`` key, the rows under ``""``.

    Parents before children (``lf_peaks`` before ``events``), children
    dropped first, so the foreign key holds at every step; the row order of
    each table (``rowid``) is kept.
    """
    _run_script(c, _OPENED_TABLES)
    for name, _ in _SCHEMA_3:
        c.execute(f"ALTER TABLE {name} RENAME TO _v2_{name}")
    for name, columns in _SCHEMA_3:
        c.execute(f"CREATE TABLE {name} (study TEXT NOT NULL DEFAULT '', {columns})")
        old = [r[1] for r in c.execute(f"PRAGMA table_info(_v2_{name})")]
        cols = ", ".join(old)
        c.execute(f"INSERT INTO {name} (study, {cols}) SELECT '', {cols} FROM _v2_{name} "
                  "ORDER BY rowid")
    for name, _ in reversed(_SCHEMA_3):
        c.execute(f"DROP TABLE _v2_{name}")


#: One function per schema version, taking a store from the version before to this one.
UPGRADES = {2: upgrade_to_2, 3: upgrade_to_3}


def create_or_upgrade(c, version: int) -> None:
    """Create the tables of a new store (``version`` 0) or upgrade an older one."""
    if version == 0:
        _run_script(c, _SCHEMA)
        c.execute("INSERT INTO schema_version VALUES (1)")
        version = 1
    for to in range(version + 1, SCHEMA_VERSION + 1):
        UPGRADES[to](c)
    c.execute("UPDATE schema_version SET version = ?", (SCHEMA_VERSION,))
    c.execute(f"PRAGMA user_version={SCHEMA_VERSION}")


class StoreError(ValueError):
    """The store cannot be used as asked (version, settings, state); the message says why."""


class StoreConflict(StoreError):
    """Another process consumed tells or asked events since this one read the store."""


@contextmanager
def named_errors(path):
    """An SQLite error (a corrupted or foreign file) as one :class:`StoreError` naming ``path``."""
    try:
        yield
    except sqlite3.DatabaseError as exc:
        raise StoreError(f"study store {path}: {exc} (is it an intact study store? restore it "
                         "from a copy)") from None


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def _pool_records(lfset) -> list[tuple]:
    """``(idx, key, event_id_json, lf, d, meta_json)`` of every pool event, by ``idx``."""
    out = []
    for p in np.argsort(lfset.index, kind="stable"):
        ev = lfset.event(int(p))
        out.append((ev.index, str(ev.id), dumps(ev.id), ev.lf, ev.d, dumps(ev.meta)))
    return out


def _pool_hash(records) -> str:
    h = hashlib.sha256()
    for idx, key, eid, lf, _d, meta in records:
        h.update(f"{idx}\x1f{key}\x1f{eid}\x1f{float(lf).hex()}\x1f{meta}\x1e".encode())
    return h.hexdigest()
