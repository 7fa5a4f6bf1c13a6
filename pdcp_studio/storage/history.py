"""The fitting history: an append-only, hash-chained archive of every change to a prosthesis.

Reference §5: every transaction is recorded — time (UTC), operator, bus URL, the prosthesis (its
devices' VID/PID/serials), the action, links and stored configuration before and after (with
their CRC), the plan with its reasons, verified or not, the interlock's outcome — plus the
patient reference the clinic chose (free text) and how the transaction ended.

Storage: one SQLite file (stdlib ``sqlite3``) in WAL mode with ``synchronous=FULL``: a commit is
whole or absent after a kill or a power cut, readers never block the writer, and two processes
(two app windows, the app and the CLI) may append at once — each append takes SQLite's write
lock (``BEGIN IMMEDIATE``), reads the last entry and writes the next inside it, so there is one
writer at a time and the chain never forks. A new archive may be opened by several connections at
once (the History view's reader and a change's recorder): its switch into WAL is retried while
another one holds the lock (see :func:`_switch_into_wal`), and its tables are made in one
transaction.

The chain: each entry stores the SHA-256 of the previous entry (``previous_hash``) and its own
``hash`` = SHA-256 over its id, its previous hash and its canonical JSON body. ``verify`` walks
the entries in order and names the first one that was edited (its hash no longer matches), or
after which one was deleted (the ids jump or the next entry's previous hash is not its hash);
a ``head`` row updated in the same commit catches the deletion of the newest entries.

A change announces itself before it writes (``begin``: a row in a ``pending`` table, outside the
chain) and ``finish`` turns it into its entry in the same commit that removes it. A PC killed
between the write and the record leaves the pending row; the next ``recover`` (run by ``list``,
``show`` and ``verify``) appends it as an entry whose outcome is ``interrupted`` — so the archive
never forgets a change that may have reached the prosthesis. Rows of a process still running
are left alone.

The path is ``$PDCP_STUDIO_HISTORY`` when set, else ``history.sqlite`` in the user's data
folder (platformdirs, ``pdcp_studio.paths.history_path``). The operator is
``$PDCP_STUDIO_OPERATOR`` when set, else the login name.
"""

from __future__ import annotations

import getpass
import hashlib
import json
import os
import re
import sqlite3
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pdcp_studio.errors import PdcpError

if TYPE_CHECKING:
    from pdcp_studio.bus.transaction import Change, TransactionResult

ENV_PATH = "PDCP_STUDIO_HISTORY"
ENV_OPERATOR = "PDCP_STUDIO_OPERATOR"
GENESIS = "0" * 64
#: Seconds an open or an append waits for another connection's write to finish.
BUSY_TIMEOUT_S = 15.0
#: Seconds between two tries of a new archive's switch into WAL (:func:`_switch_into_wal`).
WAL_RETRY_S = 0.005
#: The fields of ``history list --json`` (contracts §2), in order.
LIST_FIELDS = ("id", "time", "operator", "bus", "action", "devices", "links_before",
               "links_after", "config_crc_before", "config_crc_after", "verified", "interlock")

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
)


class HistoryError(PdcpError):
    """The archive cannot be opened, read or written."""


def default_path() -> Path:
    """``$PDCP_STUDIO_HISTORY``, else the archive in the user's data folder — the one path
    ``doctor`` shows too (``pdcp_studio.paths.history_path``)."""
    from pdcp_studio.paths import history_path

    return history_path()


def default_operator() -> str:
    """``$PDCP_STUDIO_OPERATOR``, else the login name."""
    env = os.environ.get(ENV_OPERATOR)
    if env:
        return env
    try:
        return getpass.getuser()
    except Exception:  # no login name (a container without a passwd entry)
        return "unknown"


def utc_now() -> str:
    return datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def canonical(body: dict[str, Any]) -> str:
    """The JSON the hash covers: sorted keys, no spaces, UTF-8 kept."""
    return json.dumps(body, sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def entry_hash(entry_id: int, previous_hash: str, body_json: str) -> str:
    """SHA-256 over the id, the previous entry's hash and the canonical JSON body."""
    data = f"{entry_id}\n{previous_hash}\n{body_json}".encode()
    return hashlib.sha256(data).hexdigest()


@dataclass(frozen=True)
class VerifyReport:
    """``ok`` when every entry is intact; else ``first_bad`` names the first entry that is
    not (an id, or the id after which entries are missing) and ``reason`` says why."""

    ok: bool
    entries: int
    first_bad: int | None = None
    reason: str = ""


class History:
    """One archive file. Use ``History.open()`` (the default path) and close it."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._db = _connect(self.path)
        except (sqlite3.Error, OSError) as err:
            raise HistoryError(f"fitting history {self.path}: cannot open: {err}") from err

    @classmethod
    def open(cls, path: str | Path | None = None) -> History:
        return cls(path if path is not None else default_path())

    @classmethod
    def open_existing(cls, path: str | Path | None = None) -> History | None:
        """The archive to read, or None when there is none yet: reading never creates it
        (``history list`` on a new computer is an empty history, not a new file)."""
        target = Path(path) if path is not None else default_path()
        if not target.exists():
            return None
        return cls(target)

    def __enter__(self) -> History:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        try:
            self._db.close()
        except sqlite3.Error:
            pass

    # -- writing ------------------------------------------------------------------------
    def append(self, body: dict[str, Any]) -> int:
        """Append one entry (its fields without ``id``); returns its id."""
        return int(self._write(lambda: self._append_locked(body)))

    def _append_locked(self, body: dict[str, Any]) -> int:
        """Append inside an open write transaction; returns the new id."""
        body = {k: v for k, v in body.items() if k not in ("id", "hash", "previous_hash")}
        text = json.dumps(body, ensure_ascii=False)
        row = self._db.execute("SELECT id, hash FROM entries ORDER BY id DESC LIMIT 1").fetchone()
        last_id, last_hash = row if row else (0, GENESIS)
        new_id = last_id + 1
        digest = entry_hash(new_id, last_hash, canonical(body))
        self._db.execute("INSERT INTO entries (id, previous_hash, hash, body) VALUES (?, ?, ?, ?)",
                         (new_id, last_hash, digest, text))
        self._db.execute("INSERT OR REPLACE INTO head (one, last_id, last_hash) VALUES (1, ?, ?)",
                         (new_id, digest))
        return new_id

    def _write(self, fn: Any) -> Any:
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

    def begin(self, body: dict[str, Any]) -> str:
        """Announce a change before it writes; ``body`` is its entry should it never finish
        (outcome ``interrupted``). Returns the token for ``finish``."""
        import socket
        import uuid

        token = uuid.uuid4().hex
        self._write(lambda: self._db.execute(
            "INSERT INTO pending (token, pid, host, body) VALUES (?, ?, ?, ?)",
            (token, os.getpid(), socket.gethostname(), json.dumps(body, ensure_ascii=False))))
        return token

    def finish(self, token: str, body: dict[str, Any]) -> int:
        """Record the finished change and drop its announcement, in one commit."""
        def run() -> int:
            self._db.execute("DELETE FROM pending WHERE token = ?", (token,))
            return self._append_locked(body)

        return int(self._write(run))

    def recover(self) -> list[int]:
        """Append the announcements of processes that died before they finished (their
        outcome is ``interrupted``); returns the new entries' ids."""
        import socket

        host = socket.gethostname()

        def run() -> list[int]:
            ids = []
            rows = self._db.execute(
                "SELECT token, pid, host, body FROM pending ORDER BY rowid").fetchall()
            for token, pid, where, body in rows:
                if where == host and _alive(pid):
                    continue
                self._db.execute("DELETE FROM pending WHERE token = ?", (token,))
                ids.append(self._append_locked(json.loads(body)))
            return ids

        return list(self._write(run))

    # -- reading ------------------------------------------------------------------------
    def _rows(self) -> list[tuple[int, str, str, str]]:
        try:
            return self._db.execute(
                "SELECT id, previous_hash, hash, body FROM entries ORDER BY id").fetchall()
        except sqlite3.Error as err:
            raise HistoryError(f"fitting history {self.path}: cannot read: {err}") from err

    @staticmethod
    def _entry(row: tuple[int, str, str, str]) -> dict[str, Any]:
        entry_id, previous, digest, body = row
        doc = json.loads(body)
        return {"id": entry_id, **doc, "previous_hash": previous, "hash": digest}

    def entries(self) -> list[dict[str, Any]]:
        """Every entry, oldest first, with ``id``, ``previous_hash`` and ``hash``."""
        return [self._entry(r) for r in self._rows()]

    def get(self, entry_id: int) -> dict[str, Any] | None:
        try:
            row = self._db.execute("SELECT id, previous_hash, hash, body FROM entries "
                                   "WHERE id = ?", (entry_id,)).fetchone()
        except sqlite3.Error as err:
            raise HistoryError(f"fitting history {self.path}: cannot read: {err}") from err
        return self._entry(row) if row else None

    def verify(self) -> VerifyReport:
        """Walk the chain; the first entry that is not intact, and why."""
        rows = self._rows()
        previous, expected_id = GENESIS, 1
        for entry_id, prev, digest, body in rows:
            if entry_id != expected_id:
                return VerifyReport(False, len(rows), expected_id,
                                    f"entry {expected_id} is missing (deleted): the next "
                                    f"entry is {entry_id}")
            if prev != previous:
                return VerifyReport(False, len(rows), entry_id,
                                    f"entry {entry_id}: its previous hash does not match "
                                    f"entry {entry_id - 1} (an entry was deleted or edited)")
            try:
                content = canonical(json.loads(body))
            except ValueError:
                content = body
            if entry_hash(entry_id, prev, content) != digest:
                return VerifyReport(False, len(rows), entry_id,
                                    f"entry {entry_id} was edited: its hash does not match "
                                    "its content")
            previous, expected_id = digest, entry_id + 1
        try:
            head = self._db.execute("SELECT last_id, last_hash FROM head").fetchone()
        except sqlite3.Error as err:
            raise HistoryError(f"fitting history {self.path}: cannot read: {err}") from err
        last_id = expected_id - 1
        if head is not None and (head[0], head[1]) != (last_id, previous):
            if head[0] > last_id:
                return VerifyReport(False, len(rows), last_id + 1,
                                    f"entries {last_id + 1}…{head[0]} are missing (deleted)")
            return VerifyReport(False, len(rows), head[0],
                                f"entry {head[0]}: does not match the archive's head record")
        if head is None and rows:
            return VerifyReport(False, len(rows), 1, "the archive's head record is missing")
        return VerifyReport(True, len(rows))


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
            db.execute(statement)
        db.execute("COMMIT")
    except BaseException:
        if db.in_transaction:
            db.execute("ROLLBACK")
        raise


def _alive(pid: int) -> bool:
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


def interrupted(body: dict[str, Any]) -> dict[str, Any]:
    """The entry of a change whose process stopped before it was recorded."""
    return {**body, "verified": False, "links_after": None, "config_crc_after": None,
            "outcome": {"status": "interrupted", "step": "write",
                        "reason": "the PC stopped during the change: the prosthesis holds the "
                                  "state before or after it (see the next entry or read it "
                                  "back)", "notes": []}}


def list_json(entry: dict[str, Any]) -> dict[str, Any]:
    """An entry as ``history list --json`` shows it: the contract's fields, then the patient
    reference and the outcome."""
    doc = {k: entry.get(k) for k in LIST_FIELDS}
    doc["patient"] = entry.get("patient")
    doc["outcome"] = entry.get("outcome")
    return doc


def entry_from_result(result: TransactionResult, change: Change, *, bus: str,
                      operator: str | None = None, patient: str | None = None,
                      configuration_after: Any = None, effect: Any = None,
                      parameters_after: dict[str, dict[str, str]] | None = None
                      ) -> dict[str, Any]:
    """The history entry for a finished transaction (without ``id``); ``configuration_after``
    is the stored configuration read after it and ``parameters_after`` the parts' named
    values then (what ``history restore`` writes back); ``effect`` (``engine.effect.Effect``)
    is what the change did and what the next power-on does, in words."""
    from pdcp_studio.storage import config_codec

    plan: dict[str, Any] = {"actions": change.plan_json()}
    if change.plan is not None:
        p = change.plan
        plan["mode"] = p.mode
        plan["notes"] = list(p.notes)
        plan["rejections"] = [r.to_json() for r in p.rejections]
    if change.parameters:
        plan["parameters"] = [w.to_json() for w in change.parameters]
    doc = result.to_json()
    return {
        "time": utc_now(),
        "operator": operator or default_operator(),
        "bus": bus,
        "action": change.action,
        "devices": doc["devices"],
        "links_before": doc["links_before"],
        "links_after": doc["links_after"],
        "config_crc_before": result.config_crc_before,
        "config_crc_after": result.config_crc_after,
        "verified": result.verified,
        "interlock": result.interlock,
        "patient": patient,
        "plan": plan,
        "configuration_after": (config_codec.to_json(configuration_after)
                                if configuration_after is not None else None),
        "policy_before": doc["policy_before"],
        "policy_after": doc["policy_after"],
        "outcome": {"status": result.status.value, "step": result.step,
                    "reason": result.reason, "notes": list(result.notes)},
        "effect": effect.to_json() if effect is not None else None,
        "next_power_on": effect.power_on_json() if effect is not None else None,
        "parameters_after": parameters_after,
        "replaced": replaced_from_notes(result.notes),
    }


#: How the arbitrator notes a part it forgot as replaced (the note crosses every transport,
#: the host link's result too): ``replaced 2641/769/301 by 2641/769/302``.
_REPLACED_NOTE = re.compile(r"^replaced (\d+)/(\d+)/(\d+) by (\d+)/(\d+)/(\d+)$")


def replaced_note(old: Any, new: Any) -> str:
    """The result's note for ``old`` replaced by ``new`` (device keys)."""
    return f"replaced {old.vid}/{old.pid}/{old.serial} by {new.vid}/{new.pid}/{new.serial}"


def replaced_from_notes(notes: Any) -> list[dict[str, dict[str, int]]]:
    """The entry's ``replaced`` field: ``[{"old": {vid, pid, serial}, "new": {…}}]`` — the
    parts a verified transaction left replaced (issue 26 item 6), from the result's notes."""
    out = []
    for note in notes or ():
        m = _REPLACED_NOTE.match(str(note))
        if m:
            n = [int(g) for g in m.groups()]
            out.append({"old": {"vid": n[0], "pid": n[1], "serial": n[2]},
                        "new": {"vid": n[3], "pid": n[4], "serial": n[5]}})
    return out
