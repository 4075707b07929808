"""Read-only views of a study store's tables, and the named records they return.

Mixed into :class:`~pas.study.store.StudyStore`, which provides the
connection and its ``_read`` snapshot; the tables are those of
:mod:`pas.study.schema`.  Every view returns named records (read their
fields by name): :class:`LFInputs`, :class:`StoredResult`,
:class:`Outstanding`, and the replay log's :class:`Ask`, :class:`Tell` and
:class:`Replace` (:meth:`StudyStore.ops <pas.study.store.StudyStore.ops>`).
"""

from __future__ import annotations

import json
from typing import NamedTuple

import numpy as np

from .schema import StoreError

__all__ = ["StoreViews", "LFInputs", "StoredResult", "Outstanding", "Ask", "Tell", "Replace"]


class LFInputs(NamedTuple):
    """The LF input of a stored study, as given when it was created, as far as stored."""

    lf_peaks: np.ndarray
    ids: list | None
    meta: list | None


class StoredResult(NamedTuple):
    """A result (``hf`` or ``error``) of event ``idx`` stored but not used by the study yet."""

    idx: int
    hf: float | None
    error: str | None


class Outstanding(NamedTuple):
    """An event asked but not consumed yet; ``has_result``: its result is stored."""

    idx: int
    hf: float | None
    error: str | None
    has_result: bool


class Ask(NamedTuple):
    """An ask of the replay log: the events of ask ``batch`` (a sequence number), in order."""

    batch: int
    indices: tuple[int, ...]


class Tell(NamedTuple):
    """A consumed tell of the replay log: the result the study used for event ``idx``."""

    idx: int
    hf: float | None
    error: str | None


class Replace(NamedTuple):
    """A replacement the study applied: event ``idx``'s result became ``hf`` / ``error``."""

    idx: int
    hf: float | None
    error: str | None


class StoreViews:
    """What a :class:`~pas.study.store.StudyStore` lets you read (no writes here).

    :meth:`ops` also remembers the last op read, so that the store's later
    writes can detect another driver.
    """

    @property
    def is_new(self) -> bool:
        """True while the store holds no study (no settings written yet)."""
        with self._read() as c:
            return self._meta(c, "settings") is None

    def settings(self) -> dict:
        """The stored study settings (``{}`` for a new store)."""
        with self._read() as c:
            return self._meta(c, "settings", {})

    def get(self, key, default=None):
        """A JSON value from the ``meta`` table (e.g. ``"oracle"``, ``"batch_size"``)."""
        with self._read() as c:
            return self._meta(c, key, default)

    def _pool(self):
        """``idx, ids, lf, meta`` of the stored LF pool, ordered by ``idx``."""
        with self._read() as c:
            rows = c.execute("SELECT idx, event_id, lf, meta FROM lf_peaks WHERE study = ? "
                             "ORDER BY idx", (self.scope,)).fetchall()
        idx, ids, lf, meta = zip(*rows) if rows else ((), (), (), ())
        return (np.array(idx, dtype=int), [json.loads(i) for i in ids],
                np.array(lf, dtype=float), [json.loads(m) for m in meta])

    def lf_inputs(self) -> LFInputs:
        """The ``lf_peaks, ids, meta`` given when the study was created, as far as stored.

        Peaks below the threshold were not stored: they come back as the
        threshold value (never sampled), with placeholder ids.  ``ids`` and
        ``meta`` are None when the study had none.
        """
        idx, ids, lf, meta = self._pool()
        threshold = self.settings()["threshold"]
        n = int(idx[-1]) + 1
        if threshold is None and idx.size != n:
            raise StoreError(f"study store {self.path}: LF pool has gaps but no threshold")
        lf_all = np.full(n, np.nan if threshold is None else threshold)
        lf_all[idx] = lf
        all_ids = all_meta = None
        if any(i != j for i, j in zip(ids, idx.tolist())):
            all_ids = [f"\x00below-threshold-{i}" for i in range(n)]
            for i, e in zip(idx, ids):
                all_ids[i] = e
        if any(meta):
            all_meta = [{} for _ in range(n)]
            for i, m in zip(idx, meta):
                all_meta[i] = m
        return LFInputs(lf_all, all_ids, all_meta)

    def unconsumed(self) -> list[StoredResult]:
        """The results and replacements no study used yet, in arrival order.

        Tell them with ``replace=True`` (:meth:`Study.tell <pas.study.study.Study.tell>`):
        a replacement of a result the study used is then applied as one.
        """
        with self._read() as c:
            rows = c.execute(
                "SELECT result_seq, idx, hf, error FROM events WHERE study = ? AND "
                "result_seq IS NOT NULL AND tell_seq IS NULL",
                (self.scope,),
            ).fetchall()
            rows += c.execute("SELECT seq, idx, new_hf, new_error FROM replacements "
                              "WHERE study = ? AND consumed_seq IS NULL", (self.scope,)).fetchall()
        return [StoredResult(idx, hf, error) for _seq, idx, hf, error in sorted(rows)]

    def outstanding(self) -> list[Outstanding]:
        """The events asked but not consumed yet, in ask order."""
        with self._read() as c:
            return [Outstanding(idx, hf, error, result_seq is not None)
                    for idx, hf, error, result_seq in c.execute(
                        "SELECT idx, hf, error, result_seq FROM events WHERE study = ? AND "
                        "tell_seq IS NULL ORDER BY batch, batch_pos", (self.scope,))]

    def ops(self) -> list[Ask | Tell | Replace]:
        """The replay log in order: :class:`Ask`, :class:`Tell` and :class:`Replace` records.

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
        asked: dict[int, list[int]] = {}
        for batch, idx in asks:
            asked.setdefault(batch, []).append(idx)
        ops: dict[int, Ask | Tell | Replace] = {b: Ask(b, tuple(i)) for b, i in asked.items()}
        first_old = {}
        for seq, idx, old_hf, old_err, new_hf, new_err in replaced:
            first_old.setdefault(idx, (old_hf, old_err))
            if seq is not None:
                ops[seq] = Replace(idx, new_hf, new_err)
        for seq, idx, hf, err in tells:
            ops[seq] = Tell(idx, *first_old.get(idx, (hf, err)))
        return [ops[k] for k in sorted(ops)]

    def events(self):
        """All events sent to the HF tool as a :class:`pandas.DataFrame`, in ask order.

        Columns as in the ``events`` table; ``state`` as stored (:data:`~pas.study.schema.STORED`).
        """
        import pandas as pd

        with self._read() as c:
            cur = c.execute("SELECT e.*, p.meta FROM events e JOIN lf_peaks p USING (study, idx) "
                            "WHERE study = ? ORDER BY batch, batch_pos", (self.scope,))
            cols = [d[0] for d in cur.description]
            df = pd.DataFrame(cur.fetchall(), columns=cols).drop(columns="study")
        df["event_id"] = [json.loads(x) for x in df["event_id"]]
        df["meta"] = [json.loads(x) for x in df["meta"]]
        return df

    def history(self) -> list[dict]:
        """The stored history rows, in order."""
        with self._read() as c:
            return [json.loads(r[0]) for r in c.execute(
                "SELECT data FROM history WHERE study = ? ORDER BY row", (self.scope,))]

    def replacements(self) -> list[dict]:
        """The audit trail of replaced results (``replacements`` table), oldest first."""
        return self._table("replacements")

    def load_replacements(self) -> list[dict]:
        """The audit trail of corrected named loads (``load_replacements`` table), oldest first."""
        return self._table("load_replacements")

    def dropped(self) -> list[dict]:
        """The asks a retry took out of the log, with their kept results (``dropped`` table)."""
        return self._table("dropped")

    def _table(self, name) -> list[dict]:
        with self._read() as c:
            cur = c.execute(f"SELECT * FROM {name} WHERE study = ? ORDER BY id", (self.scope,))
            cols = [d[0] for d in cur.description]
            return [{k: v for k, v in zip(cols, r) if k != "study"} for r in cur.fetchall()]
