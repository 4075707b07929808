"""Read-only views of a study store's tables: the LF pool, events, history and audit trails.

Mixed into :class:`~pas.study.store.StudyStore`, which provides the
connection and its ``_read`` snapshot; the tables are those of
:mod:`pas.study.schema`.
"""

from __future__ import annotations

import json

import numpy as np

from .schema import StoreError

__all__ = ["StoreViews"]


class StoreViews:
    """What a :class:`~pas.study.store.StudyStore` lets you read (no writes here)."""

    def pool(self):
        """``(idx, ids, lf, meta)`` of the stored LF pool, ordered by ``idx``."""
        with self._read() as c:
            rows = c.execute("SELECT idx, event_id, lf, meta FROM lf_peaks WHERE study = ? "
                             "ORDER BY idx", (self.scope,)).fetchall()
        return (np.array([r[0] for r in rows], dtype=int), [json.loads(r[1]) for r in rows],
                np.array([r[2] for r in rows], dtype=float), [json.loads(r[3]) for r in rows])

    def lf_inputs(self):
        """``(lf_peaks, ids, meta)`` as given when the study was created, as far as stored.

        Peaks below the threshold were not stored: they come back as the
        threshold value (never sampled), with placeholder ids.  ``ids`` and
        ``meta`` are None when the study had none.
        """
        idx, ids, lf, meta = self.pool()
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
        return lf_all, all_ids, all_meta

    def unconsumed(self) -> list[tuple]:
        """``(idx, hf, error)`` of results and replacements no study used yet, in arrival order.

        Tell them with ``replace=True`` (:meth:`Study.tell <pas.study.study.Study.tell>`):
        a replacement of a result the study used is then applied as one.
        """
        with self._read() as c:
            rows = c.execute("SELECT result_seq, idx, hf, error FROM events WHERE study = ? AND "
                             "result_seq IS NOT NULL AND tell_seq IS NULL", (self.scope,)).fetchall()
            rows += c.execute("SELECT seq, idx, new_hf, new_error FROM replacements "
                              "WHERE study = ? AND consumed_seq IS NULL", (self.scope,)).fetchall()
        return [r[1:] for r in sorted(rows)]

    def outstanding(self) -> list[tuple]:
        """``(idx, hf, error, has_result)`` of events not consumed yet, in ask order."""
        with self._read() as c:
            return [(r[0], r[1], r[2], r[3] is not None) for r in c.execute(
                "SELECT idx, hf, error, result_seq FROM events WHERE study = ? AND tell_seq IS NULL "
                "ORDER BY batch, batch_pos", (self.scope,))]

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

    def dropped(self) -> list[dict]:
        """The asks a retry took out of the log, with their kept results (``dropped`` table)."""
        return self._table("dropped")

    def _table(self, name) -> list[dict]:
        with self._read() as c:
            cur = c.execute(f"SELECT * FROM {name} WHERE study = ? ORDER BY id", (self.scope,))
            cols = [d[0] for d in cur.description]
            return [{k: v for k, v in zip(cols, r) if k != "study"} for r in cur.fetchall()]
