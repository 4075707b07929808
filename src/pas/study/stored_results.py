"""Results stored per state of the log, so ``pas study status`` need not replay it.

Replaying a study (:mod:`pas.study.replay`) refits the model once per told
result and then recomputes the model band: seconds at a hundred pairs.  Each
time a result with the model band is computed for a study bound to its store
(:meth:`Study.result <pas.study.study.Study.result>`, ``pas study status``),
its summary is kept here, keyed by a fingerprint of what decides it: the
consumed tells, the applied replacements and the settings.  A stored summary
is current only while the fingerprint is unchanged; any later tell,
replacement, retry or settings change gives another one, so a stale result is
never shown as current.

``results(study, log_key, n_told, data, written_at)``
    One row per fingerprint ``log_key`` (hex SHA-256): ``n_told`` consumed
    tells, ``data`` the JSON summary (:func:`summary`).  Created when a store
    is opened (:func:`add_results_table`), so older stores gain it empty and
    ``status`` replays them as before.
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings

from .schema import StoreError, _now, dumps

__all__ = ["add_results_table", "log_key", "save_result", "stored_result", "summary"]

RESULTS = """
CREATE TABLE IF NOT EXISTS results (
    study TEXT NOT NULL DEFAULT '', log_key TEXT NOT NULL, n_told INTEGER NOT NULL,
    data TEXT NOT NULL, written_at TEXT NOT NULL, PRIMARY KEY (study, log_key))
"""


def add_results_table(c) -> None:
    """Create the ``results`` table when missing (idempotent; run when a store opens)."""
    c.execute(RESULTS)


def log_key(c, scope: str = "") -> tuple[str, int]:
    """``(fingerprint, n_told)`` of the consumed state of study ``scope``'s log read in ``c``."""
    tells = c.execute("SELECT tell_seq, idx, hf, error FROM events WHERE study = ? AND "
                      "tell_seq IS NOT NULL ORDER BY tell_seq", (scope,)).fetchall()
    replaced = c.execute("SELECT id, idx, consumed_seq, old_hf, old_error, new_hf, new_error "
                         "FROM replacements WHERE study = ? AND consumed_seq IS NOT NULL "
                         "ORDER BY id", (scope,)).fetchall()
    settings = c.execute("SELECT value FROM meta WHERE study = ? AND key = 'settings'",
                         (scope,)).fetchone()
    text = dumps([[list(r) for r in tells], [list(r) for r in replaced],
                  None if settings is None else json.loads(settings[0])])
    return hashlib.sha256(text.encode()).hexdigest(), len(tells)


def summary(study, result) -> dict:
    """What ``pas study status`` shows of ``study`` and its ``result``, as JSON values."""
    from . import stop_text  # not at import: 'pas study tell' opens stores without it

    fitted = [r for r in study.rows if r.get("mpm") is not None]
    last = fitted[-1] if fitted else {}

    def floats(pair):
        return None if pair is None else [float(x) for x in pair]

    return {
        "strategy": study.strategy.name, "seed": study.seed, "n_hf": study.n_hf,
        "n_false_positive": study.n_false_positive, "n_failed": study.n_failed,
        "n_evaluated": result.n_evaluated, "n_loads": result.n_loads,
        "n_no_impact": result.n_no_impact, "max_hf": study.max_hf, "fitted": bool(fitted),
        "mpm": float(result.mpm) if fitted else None,
        "mpm_band": floats(result.mpm_band) if fitted else None,
        "mpm_band_sampling": floats(result.mpm_band_sampling) if fitted else None,
        "mpm_band_model": floats(result.mpm_band_model),
        "family": result.family, "E_bar": _number(last.get("E_bar")),
        "COV": _number(last.get("COV")),
        "eps1": study.rule.eps1, "eps2": study.rule.eps2,
        "precision": study.rule.precision, "forecast": result.forecast,
        "stop_text": stop_text.state(result) if fitted else None,
        "k1": study.rule.k1, "k2": study.rule.k2,
        "converged": bool(result.converged), "finished": bool(study.finished),
        "converged_at_n_hf": next((r["n_hf"] for r in fitted if r.get("stop")), None),
        "counts_text": result.counts_text(), "band_text": result.band_text() if fitted else None,
    }


def _number(x):
    return None if x is None or (isinstance(x, float) and math.isnan(x)) else float(x)


def save_result(store, study, result, expected_key=None) -> None:
    """Store the summary of ``result`` under the store's current log fingerprint.

    Skipped when the log is not the one ``study`` was built from: its settings
    are not the stored ones, the fingerprint is not ``expected_key`` (read
    before a replay), or, without one, another process changed the log since
    this store's last op.  A store that cannot be written gives a warning,
    never an error: the result is computed and the log is intact.
    """
    try:
        with store.transaction() as c:
            stored = store._meta(c, "settings")
            if stored is None or stored != json.loads(dumps(study.settings())):
                return
            key, n_told = log_key(c, store.scope)
            if key != expected_key if expected_key is not None else \
                    store._meta(c, "op_seq") != store._op_seq:
                return
            c.execute("INSERT OR REPLACE INTO results VALUES (?, ?, ?, ?, ?)",
                      (store.scope, key, n_told, dumps(summary(study, result)), _now()))
    except StoreError as exc:
        warnings.warn(f"the result was not stored for 'pas study status' ({exc})", stacklevel=3)


def stored_result(store) -> tuple[dict | None, int, str]:
    """``(summary, n_told, log_key)`` of the current log state (summary None if none stored)."""
    with store._read() as c:
        key, n_told = log_key(c, store.scope)
        row = c.execute("SELECT data FROM results WHERE study = ? AND log_key = ?",
                        (store.scope, key)).fetchone()
    return (None if row is None else json.loads(row[0])), n_told, key
