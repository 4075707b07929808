"""The SQLite file of a study store: connection, write transactions, checkpoint, backup.

One file (standard-library :mod:`sqlite3`), WAL journal, ``synchronous=FULL``,
every write in a ``BEGIN IMMEDIATE`` transaction with a busy time-out, so a
driver process and any number of ``pas study tell`` processes can write at the
same time without losing a result.  While a study runs, SQLite keeps the
newest writes in a ``-wal`` file beside the store; :meth:`StoreFile.checkpoint`
(called when a run ends, also at Ctrl-C or SIGTERM) moves them into the main
file, so the ``.sqlite`` file alone then holds the whole study.
:meth:`StoreFile.backup` (``pas study backup``) writes a consistent one-file
copy at any time, also of a study that is running.
"""

from __future__ import annotations

import os
import sqlite3
from contextlib import contextmanager

from .schema import StoreError, named_errors

__all__ = ["StoreFile"]

_CREATED_HERE: set[str] = set()
"""Store files this process created (their later handles did not find them there)."""


class StoreFile:
    """The connection to one store file (:class:`~pas.study.store.StudyStore` is one).

    Parameters
    ----------
    path : str or os.PathLike
        The ``.db`` file.
    create : bool, default True
        Create the file when missing; False raises ``FileNotFoundError``.
    timeout : float, default 120
        Seconds to wait for another process's write transaction.
    """

    def __init__(self, path, *, create: bool = True, timeout: float = 120.0):
        self.path = os.fspath(path)
        if not create and not os.path.exists(self.path):
            raise FileNotFoundError(f"study store {self.path} does not exist "
                                    "(create it with 'pas study create')")
        #: whether the file was there (not empty) before this process opened it: a long-term
        #: analysis opens one file per sea state after its own handle created it
        key = os.path.realpath(self.path)
        self.existed = (os.path.exists(self.path) and os.path.getsize(self.path) > 0
                        and key not in _CREATED_HERE)
        if not os.path.exists(self.path):
            _CREATED_HERE.add(key)
        with named_errors(self.path):
            self._conn = sqlite3.connect(self.path, timeout=timeout, isolation_level=None)
            self._conn.execute("PRAGMA journal_mode=WAL")
            self._conn.execute("PRAGMA synchronous=FULL")
            self._conn.execute("PRAGMA foreign_keys=ON")
        self._depth = 0

    def close(self) -> None:
        """Checkpoint (:meth:`checkpoint`) and close the connection; closing twice is harmless."""
        try:
            self.checkpoint()
        except StoreError:
            pass  # another process still reads: its connection's close checkpoints
        self._conn.close()

    def checkpoint(self) -> bool:
        """Move the writes waiting in the ``-wal`` file into the ``.sqlite`` file.

        Afterwards the ``.sqlite`` file alone holds the whole study (a copy of
        it is complete).  Returns False when another process was reading or
        writing and part of the log stayed in the ``-wal`` file (their next
        checkpoint moves it); the study is complete either way.
        """
        try:
            self._conn.execute("SELECT 1")
        except sqlite3.ProgrammingError:  # closed
            return True
        if self._depth:
            return False
        with named_errors(self.path):
            busy, _log, _moved = self._conn.execute("PRAGMA wal_checkpoint(TRUNCATE)").fetchone()
        return not busy

    def backup(self, target) -> str:
        """Write a consistent one-file copy of the store to ``target`` (a new file); its path.

        Safe while another process runs or tells the study (SQLite's online
        backup, :meth:`sqlite3.Connection.backup`): the copy is the study as
        of one moment, every result up to then included, and opens as a study
        on its own (no ``-wal`` file needed).
        """
        target = os.fspath(target)
        if os.path.exists(target):
            raise FileExistsError(f"{target} exists; give a new file for the copy")
        with named_errors(self.path):
            dest = sqlite3.connect(target)
            try:
                self._conn.backup(dest)
                dest.execute("PRAGMA journal_mode=DELETE")  # one file, no -wal beside it
            finally:
                dest.close()
        return target

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

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
