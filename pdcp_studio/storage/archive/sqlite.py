"""The fitting history in one SQLite file: the embedded default, one workstation's archive.

Stdlib ``sqlite3`` in WAL mode with ``synchronous=FULL``: a commit is whole or absent after a
kill or a power cut, readers never block the writer, and two processes (two app windows, the
app and the CLI) may append at once — each append takes SQLite's write lock (``BEGIN
IMMEDIATE``), reads the last entry and writes the next inside it, so there is one writer at a
time and the chain never forks. A new archive may be opened by several connections at once
(the History view's reader and a change's recorder): its switch into WAL is retried while
another one holds the lock (see :func:`_switch_into_wal`), and its tables are made in one
transaction. A ``head`` row updated in the same commit as each entry catches the deletion of
the newest entries.

A change announces itself before it writes (a row in ``pending``, outside the chain) and
``finish`` turns it into its entry in the same commit that removes it. A PC killed between the
write and the record leaves the pending row; the next ``recover`` appends it as an entry whose
outcome is ``interrupted``. Rows of a process still running are left alone.
"""

from __future__ import annotations

import json
import os
import sqlite3
import time
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from pdcp_studio.storage.archive.base import Archive, Entry, EntryFilter, HistoryError, workstation
from pdcp_studio.storage.archive.chain import Row, VerifyReport, next_link, verify_rows
from pdcp_studio.storage.archive.rows import entry_id as checked_id
from pdcp_studio.storage.archive.rows import entry_of, pending_body

T = TypeVar("T")

#: Seconds an open or an append waits for another connection's write to finish.
BUSY_TIMEOUT_S = 15.0
#: Seconds between two tries of a new archive's switch into WAL (:func:`_switch_into_wal`).
WAL_RETRY_S = 0.005

#: The archive's tables, made in one write transaction on every open (each ``IF NOT EXISTS``).
_SCHEMA = (
    """CREATE TABLE IF NOT EXISTS entries (
    id INTEGER PRIMARY KEY,
    previous_hash TEXT NOT NULL,
    hash TEXT NOT NULL,
    body TEXT NOT NULL
)""",
    """CREATE TABLE IF NOT EXISTS pending (
    token TEXT PRIMARY KEY,
    pid INTEGER NOT NULL,
    host TEXT NOT NULL,
    body TEXT NOT NULL
)""",
    """CREATE TABLE IF NOT EXISTS head (
    one INTEGER PRIMARY KEY CHECK (one = 1),
    last_id INTEGER NOT NULL,
    last_hash TEXT NOT NULL
)""",
    # A clinic's view: a patient's entries without reading every body.
    "CREATE INDEX IF NOT EXISTS entries_patient ON entries (json_extract(body, '$.patient'))",
)

_PATIENT = "json_extract(body, '$.patient') = ?"
_DEVICE = ("EXISTS (SELECT 1 FROM json_each(entries.body, '$.devices') AS d "
           "WHERE json_extract(d.value, '$.vid') = ? AND json_extract(d.value, '$.pid') = ? "
           "AND json_extract(d.value, '$.serial') = ?)")


class SqliteArchive(Archive):
    """One archive file."""

    engine = "sqlite"

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._db = _connect(self.path)
        except (sqlite3.Error, OSError) as err:
            raise HistoryError(f"fitting history {self.path}: cannot open: {err}") from err

    @property
    def location(self) -> str:
        return str(self.path)

    def close(self) -> None:
        try:
            self._db.close()
        except sqlite3.Error:
            pass

    # -- writing ------------------------------------------------------------------------
    def _append_locked(self, body: Entry) -> int:
        """Append inside an open write transaction; returns the new id."""
        row = self._db.execute("SELECT id, hash FROM entries ORDER BY id DESC LIMIT 1").fetchone()
        new_id, previous, digest, text = next_link(row, body)
        self._db.execute("INSERT INTO entries (id, previous_hash, hash, body) VALUES (?, ?, ?, ?)",
                         (new_id, previous, digest, text))
        self._db.execute("INSERT OR REPLACE INTO head (one, last_id, last_hash) VALUES (1, ?, ?)",
                         (new_id, digest))
        return new_id

    def _write(self, fn: Callable[[], T]) -> T:
        try:
            self._db.execute("BEGIN IMMEDIATE")
            try:
                value = fn()
                self._db.execute("COMMIT")
            except BaseException:
                self._db.execute("ROLLBACK")
                raise
        except sqlite3.Error as err:
            raise HistoryError(f"fitting history {self.path}: cannot write: {err}") from err
        return value

    def begin(self, body: Entry) -> str:
        token = uuid.uuid4().hex
        text = json.dumps(self.stamp(body), ensure_ascii=False)
        self._write(lambda: self._db.execute(
            "INSERT INTO pending (token, pid, host, body) VALUES (?, ?, ?, ?)",
            (token, os.getpid(), workstation(), text)))
        return token

    def finish(self, token: str, body: Entry) -> int:
        stamped = self.stamp(body)

        def run() -> int:
            self._db.execute("DELETE FROM pending WHERE token = ?", (token,))
            return self._append_locked(stamped)

        return self._write(run)

    def recover(self) -> list[int]:
        host = workstation()

        def run() -> list[int]:
            ids = []
            rows = self._db.execute(
                "SELECT token, pid, host, body FROM pending ORDER BY rowid").fetchall()
            for token, pid, where, body in rows:
                if where == host and isinstance(pid, int) and alive(pid):
                    continue
                recovered = pending_body(token, body)
                if recovered is None:
                    continue  # damaged or not an announcement: never chained in (issue 28)
                self._db.execute("DELETE FROM pending WHERE token = ?", (token,))
                ids.append(self._append_locked(recovered))
            return ids

        return self._write(run)

    # -- reading ------------------------------------------------------------------------
    def _read(self, sql: str, params: tuple[Any, ...] = ()) -> list[Any]:
        try:
            return self._db.execute(sql, params).fetchall()
        except sqlite3.Error as err:
            raise HistoryError(f"fitting history {self.path}: cannot read: {err}") from err

    @staticmethod
    def _entry(row: Row) -> Entry:
        return entry_of(row)  # damage is DamagedEntry naming the entry, never a traceback

    def entries(self, where: EntryFilter | None = None) -> list[Entry]:
        clauses: list[str] = []
        params: list[Any] = []
        if where is not None and where.patient is not None:
            clauses.append(_PATIENT)
            params.append(where.patient)
        if where is not None and where.device is not None:
            clauses.append(_DEVICE)
            params.extend(where.device)
        sql = "SELECT id, previous_hash, hash, body FROM entries"
        if clauses:
            sql += " WHERE " + " AND ".join(clauses)
        return [self._entry(r) for r in self._read(sql + " ORDER BY id", tuple(params))]

    def get(self, entry_id: int) -> Entry | None:
        if checked_id(entry_id) is None:
            return None  # no row can have it (beyond SQLite's 64-bit integer)
        rows = self._read("SELECT id, previous_hash, hash, body FROM entries WHERE id = ?",
                          (entry_id,))
        return self._entry(rows[0]) if rows else None

    def verify(self) -> VerifyReport:
        rows = self._read("SELECT id, previous_hash, hash, body FROM entries ORDER BY id")
        head = self._read("SELECT last_id, last_hash FROM head")
        return verify_rows(rows, (head[0][0], head[0][1]) if head else None)


def _connect(path: Path) -> sqlite3.Connection:
    """A connection to the archive at ``path``, in WAL mode with its tables made; safe when
    several connections open a new archive at once. The busy timeout is set before the first
    statement (``connect``'s ``timeout``)."""
    db = sqlite3.connect(str(path), timeout=BUSY_TIMEOUT_S, isolation_level=None,
                         check_same_thread=False)
    try:
        _switch_into_wal(db)
        db.execute("PRAGMA synchronous=FULL")
        _make_tables(db)
    except BaseException:
        db.close()
        raise
    return db


def _switch_into_wal(db: sqlite3.Connection) -> None:
    """WAL mode, tried again while another connection writes, until the busy timeout.

    The switch cannot wait on the busy timeout as other statements do: SQLite reads the
    file's header, then upgrades to the write lock, and an upgrade that finds another
    connection writing fails at once (``SQLITE_BUSY`` without the busy handler, which could
    deadlock) — as when two connections open a new archive at once. Once the archive is in
    WAL (the mode is kept in the file) the switch is only a read and cannot fail this way.
    """
    deadline = time.monotonic() + BUSY_TIMEOUT_S
    while True:
        try:
            db.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as err:
            busy = err.sqlite_errorcode & 0xFF == sqlite3.SQLITE_BUSY  # or an extended BUSY_*
            if not busy or time.monotonic() > deadline:
                raise
            time.sleep(WAL_RETRY_S)


def _make_tables(db: sqlite3.Connection) -> None:
    """The archive's tables, all or none, under the write lock (waiting for another
    connection's on the busy timeout)."""
    db.execute("BEGIN IMMEDIATE")
    try:
        for statement in _SCHEMA:
            try:
                db.execute(statement)
            except sqlite3.OperationalError as err:
                if "JSON" not in str(err) or "INDEX" not in statement:
                    raise
                # a body an editor left malformed: no index, and each reader names the entry
                # (storage/archive/rows.py) instead of the archive failing to open
        db.execute("COMMIT")
    except BaseException:
        if db.in_transaction:
            db.execute("ROLLBACK")
        raise


def alive(pid: int) -> bool:
    """Is process ``pid`` running on this machine?"""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True
