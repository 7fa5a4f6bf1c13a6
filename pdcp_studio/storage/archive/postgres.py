"""The fitting history on the clinic's PostgreSQL server, shared by every workstation.

Signed-in operators: the recorded operator is the role the workstation signed in as (its full
name from ``pdcp.operators`` where the clinic gave one), never free text — the server's insert
trigger refuses any other (:mod:`.schema_pg`). A reader (``pdcp_reader``) is refused before a
change is announced, so nothing reaches the prosthesis. Appends are serialised by the
archive's advisory lock, taken before the last entry is read: several workstations at once
never fork the chain.

Faults: a server that cannot be reached or refuses the announcement stops the change before
any frame (``run_transaction``). A connection lost after the announcement keeps the outcome in
this workstation's journal (:mod:`.journal`); :meth:`PostgresArchive.recover` (every open of a
read command, and the next change) records it once the server is back. An announcement of
another workstation is recorded as interrupted only once its connection is gone and it is
older than :data:`OTHER_HOST_GRACE_S` (that workstation may still record its outcome).

The password comes from libpq's own sources (the URL, ``$PGPASSWORD``, ``~/.pgpass``) or, in
the app, from a dialog kept in memory for the session (:func:`remember_password`); PDCP Studio
never writes one down.
"""

from __future__ import annotations

import json
import os
import uuid
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar, cast

from pdcp_studio.storage.archive import journal
from pdcp_studio.storage.archive.base import (
    Archive,
    Entry,
    EntryFilter,
    HistoryError,
    NotAllowedError,
    workstation,
)
from pdcp_studio.storage.archive.chain import VerifyReport, next_link, verify_rows
from pdcp_studio.storage.archive.rows import entry_id as checked_id
from pdcp_studio.storage.archive.rows import entry_of, pending_body
from pdcp_studio.storage.archive.schema_pg import APPEND_LOCK, INIT_SQL, SCHEMA

if TYPE_CHECKING:
    import psycopg

T = TypeVar("T")

#: Seconds a connection attempt waits for the server.
CONNECT_TIMEOUT_S = 5
#: Seconds after which another workstation's announcement whose connection is gone is recorded
#: as interrupted (before that, that workstation may still record its outcome).
OTHER_HOST_GRACE_S = 3600

_passwords: dict[str, str] = {}


def remember_password(location: str, password: str) -> None:
    """The password typed into the app's sign-in dialog, for this process only."""
    _passwords[location] = password


def forget_passwords() -> None:
    _passwords.clear()


def _psycopg() -> Any:
    try:
        import psycopg
    except ImportError as err:
        raise HistoryError("a PostgreSQL archive needs psycopg (pip install psycopg): "
                           f"{err}") from err
    return psycopg


def location_of(url: str) -> str:
    """``postgresql://USER@HOST:PORT/DB`` without its password or options, for a person."""
    psycopg = _psycopg()
    try:
        info = psycopg.conninfo.conninfo_to_dict(url)
    except psycopg.Error as err:
        raise HistoryError(f"fitting history: not a PostgreSQL URL: {err}") from err
    user = info.get("user") or os.environ.get("PGUSER") or ""
    host = info.get("host") or os.environ.get("PGHOST") or "localhost"
    port = info.get("port") or os.environ.get("PGPORT") or "5432"
    db = info.get("dbname") or os.environ.get("PGDATABASE") or user
    if str(host).startswith("/"):
        host = f"[{host}]"
    return f"postgresql://{user + '@' if user else ''}{host}:{port}/{db}"


def connect(url: str, *, password: str | None = None) -> psycopg.Connection[Any]:
    """A connection to the clinic's server; HistoryError in words when there is none."""
    pg = _psycopg()
    where = location_of(url)
    extra: dict[str, Any] = {}
    secret = password if password is not None else _passwords.get(where)
    if secret is not None:
        extra["password"] = secret
    try:
        db = pg.connect(url, autocommit=True, connect_timeout=CONNECT_TIMEOUT_S,
                        application_name="pdcp-studio", **extra)
    except pg.OperationalError as err:
        raise ServerUnreachable(where, _first_line(err)) from err
    except pg.Error as err:
        raise HistoryError(f"the fitting history at {where} cannot be opened: "
                           f"{_first_line(err)}") from err
    return cast("psycopg.Connection[Any]", db)


class ServerUnreachable(HistoryError):
    """The server is down, unreachable, or refuses the sign-in."""

    def __init__(self, where: str, why: str) -> None:
        self.where, self.why = where, why
        self.needs_password = "password" in why.lower()
        super().__init__(f"the clinic's fitting history at {where} cannot be reached: {why}")


def _first_line(err: BaseException) -> str:
    text = str(err).strip().splitlines()
    return text[0] if text else type(err).__name__


def init_schema(url: str) -> str:
    """``archive init``: the schema, group roles and grants, in one transaction; returns
    the archive's location. Run by the clinic's administrator (a role that may create roles
    and a schema in the database)."""
    psycopg = _psycopg()
    with connect(url) as db:
        try:
            with db.transaction():
                for statement in INIT_SQL:
                    db.execute(statement)
        except psycopg.Error as err:
            raise HistoryError(f"archive init {location_of(url)}: {_first_line(err)}") from err
    return location_of(url)


class PostgresArchive(Archive):
    """The clinic's shared archive, signed in as one role."""

    engine = "postgresql"

    def __init__(self, url: str, *, password: str | None = None) -> None:
        self._psycopg = _psycopg()
        self._url = url
        self._where = location_of(url)
        self._db = connect(url, password=password)
        try:
            row = self._db.execute(
                f"SELECT session_user::text, to_regnamespace('{SCHEMA}') IS NOT NULL"
            ).fetchone()
            role, ready = (str(row[0]), bool(row[1])) if row else ("", False)
            if not ready:
                raise HistoryError(f"{self._where} holds no fitting history yet: the clinic's "
                                   f"administrator runs: pdcp-studio archive init URL")
            allowed = self._db.execute(
                f"SELECT has_schema_privilege('{SCHEMA}', 'USAGE')").fetchone()
            if not (allowed and allowed[0]):
                raise NotAllowedError(f"signed in as {role}, who may neither read nor record "
                                      f"the fitting history at {self._where}: the clinic's "
                                      "administrator makes the login a member of pdcp_fitter "
                                      "or pdcp_reader")
            named = self._db.execute(f"SELECT full_name FROM {SCHEMA}.operators WHERE role = %s",
                                     (role,)).fetchone()
        except self._psycopg.Error as err:
            self._db.close()
            raise HistoryError(f"the fitting history at {self._where} cannot be read: "
                               f"{_first_line(err)}") from err
        except BaseException:
            self._db.close()
            raise
        self._role = role
        self._full_name = str(named[0]) if named and named[0] else None

    @property
    def location(self) -> str:
        return self._where

    def signed_in(self) -> str:
        return self._role

    def operator(self) -> str:
        """The signed-in role's full name from the clinic's operator table, else the role
        (``$PDCP_STUDIO_OPERATOR`` is not asked)."""
        return self._full_name or self._role

    def may_record(self) -> bool:
        row = self._run(lambda: self._db.execute(
            f"SELECT has_table_privilege('{SCHEMA}.entries', 'INSERT') "
            f"AND has_table_privilege('{SCHEMA}.pending', 'INSERT')").fetchone(), "read")
        return bool(row and row[0])

    def check_can_record(self) -> None:
        if not self.may_record():
            raise NotAllowedError(f"signed in as {self._role}, who may read the fitting "
                                  "history but not record changes")

    def stamp(self, body: Entry) -> Entry:
        if isinstance(body.get("origin"), dict):
            return super().stamp(body)
        out = dict(body)
        out.setdefault("workstation", workstation())
        out["operator"] = self.operator()
        out["signed_in"] = self._role
        return out

    def close(self) -> None:
        try:
            self._db.close()
        except self._psycopg.Error:
            pass

    # -- the connection -----------------------------------------------------------------
    def _run(self, fn: Callable[[], T], what: str) -> T:
        psycopg = self._psycopg
        try:
            return fn()
        except psycopg.errors.InsufficientPrivilege as err:
            raise NotAllowedError(f"signed in as {self._role}: the fitting history at "
                                  f"{self._where} refused it: {_first_line(err)}") from err
        except psycopg.OperationalError as err:
            raise ServerUnreachable(self._where, _first_line(err)) from err
        except psycopg.Error as err:
            raise HistoryError(f"the fitting history at {self._where}: cannot {what}: "
                               f"{_first_line(err)}") from err

    def _append_locked(self, body: Entry) -> int:
        """Append inside an open transaction, under the archive's advisory lock."""
        self._db.execute("SELECT pg_advisory_xact_lock(%s)", (APPEND_LOCK,))
        row = self._db.execute(
            f"SELECT id, hash FROM {SCHEMA}.entries ORDER BY id DESC LIMIT 1").fetchone()
        new_id, previous, digest, text = next_link((int(row[0]), str(row[1])) if row else None,
                                                   body)
        self._db.execute(f"INSERT INTO {SCHEMA}.entries (id, previous_hash, hash, body) "
                         "VALUES (%s, %s, %s, %s)", (new_id, previous, digest, text))
        return new_id

    def _write(self, fn: Callable[[], T]) -> T:
        def run() -> T:
            with self._db.transaction():
                return fn()

        return self._run(run, "write")

    # -- writing ------------------------------------------------------------------------
    def begin(self, body: Entry) -> str:
        self.check_can_record()
        try:
            self._flush_journal()
        except ServerUnreachable:
            raise
        except HistoryError:  # a kept outcome the server refuses stays kept; this change
            pass              # is announced as usual
        token = uuid.uuid4().hex
        text = json.dumps(self.stamp(body), ensure_ascii=False)
        self._write(lambda: self._db.execute(
            f"INSERT INTO {SCHEMA}.pending (token, pid, host, body) VALUES (%s, %s, %s, %s)",
            (token, os.getpid(), workstation(), text)))
        return token

    def finish(self, token: str, body: Entry) -> int:
        stamped = self.stamp(body)

        def run() -> int:
            self._db.execute(f"DELETE FROM {SCHEMA}.pending WHERE token = %s", (token,))
            return self._append_locked(stamped)

        try:
            return self._write(run)
        except ServerUnreachable as lost:
            err = lost
        try:  # the server may be back already (a restart): once, on a new connection
            self._db.close()
            self._db = connect(self._url)
            return self._write(run)
        except ServerUnreachable as again:
            err = again
        kept = journal.keep(self._where, token, stamped)
        raise HistoryError(
            f"not recorded yet: the connection to the clinic's fitting history was lost "
            f"({err.why}); the outcome is kept on this workstation ({kept}) and recorded "
            "when the archive can be reached again") from err

    def _flush_journal(self) -> list[int]:
        """Record the outcomes this workstation kept while the server was away — those of
        the role signed in now (another person's wait for them to sign in: an outcome is
        never recorded under someone else's name)."""
        ids: list[int] = []
        for path, token, body in journal.waiting(self._where):
            if body.get("signed_in") not in (None, self._role):
                continue
            late = {**self.stamp(body), "recorded_late": True}  # the full name as it is now

            def run(token: str = token, late: Entry = late) -> int:
                self._db.execute(f"DELETE FROM {SCHEMA}.pending WHERE token = %s", (token,))
                return self._append_locked(late)

            ids.append(self._write(run))
            journal.done(path)
        return ids

    def recover(self) -> list[int]:
        if not self.may_record():
            return []  # a reader records nothing, not even another's interrupted change
        ids = self._flush_journal()
        host = workstation()
        from pdcp_studio.storage.archive.sqlite import alive

        rows = self._run(lambda: self._db.execute(
            f"SELECT p.token, p.pid, p.host, p.body, "
            f"EXISTS (SELECT 1 FROM pg_stat_activity a WHERE a.pid = p.backend), "
            f"extract(epoch FROM now() - p.created) FROM {SCHEMA}.pending p "
            "ORDER BY p.created").fetchall(), "read")
        for token, pid, where, body, connected, age in rows:
            if where == host:
                if alive(int(pid)):
                    continue
            elif connected or float(age) < OTHER_HOST_GRACE_S:
                continue

            recovered = pending_body(token, body)
            if recovered is None:
                continue  # damaged or not an announcement: never chained in (issue 28)

            def run(token: str = token, recovered: Entry = recovered) -> int | None:
                gone = self._db.execute(f"DELETE FROM {SCHEMA}.pending WHERE token = %s",
                                        (token,))
                if gone.rowcount != 1:  # another workstation recovered it just now
                    return None
                return self._append_locked(self.stamp(recovered))

            new = self._write(run)
            if new is not None:
                ids.append(new)
        return ids

    # -- reading ------------------------------------------------------------------------
    def _select(self, where: str = "", params: tuple[Any, ...] = ()) -> list[Any]:
        sql = f"SELECT id, previous_hash, hash, body FROM {SCHEMA}.entries {where} ORDER BY id"
        return self._run(lambda: self._db.execute(sql, params).fetchall(), "read")

    @staticmethod
    def _entry(row: Any) -> Entry:
        return entry_of(row)  # damage is DamagedEntry naming the entry, never a traceback

    def entries(self, where: EntryFilter | None = None) -> list[Entry]:
        clauses: list[str] = []
        params: list[Any] = []
        if where is not None and where.patient is not None:
            clauses.append("patient = %s")
            params.append(where.patient)
        if where is not None and where.device is not None:
            vid, pid, serial = where.device
            clauses.append("devices @> %s::jsonb")
            params.append(json.dumps([{"vid": vid, "pid": pid, "serial": serial}]))
        sql = ("WHERE " + " AND ".join(clauses)) if clauses else ""
        return [self._entry(r) for r in self._select(sql, tuple(params))]

    def get(self, entry_id: int) -> Entry | None:
        if checked_id(entry_id) is None:
            return None  # no row can have it (beyond a bigint)
        rows = self._select("WHERE id = %s", (entry_id,))
        return self._entry(rows[0]) if rows else None

    def verify(self) -> VerifyReport:
        rows = [tuple(r) for r in self._select()]
        head = self._run(lambda: self._db.execute(
            f"SELECT last_id, last_hash FROM {SCHEMA}.head").fetchone(), "read")
        return verify_rows(rows, (head[0], head[1]) if head else None)

    def origin_hashes(self) -> set[str]:
        rows = self._run(lambda: self._db.execute(
            f"SELECT origin_hash FROM {SCHEMA}.entries WHERE origin_hash IS NOT NULL"
        ).fetchall(), "read")
        return {str(r[0]) for r in rows}
