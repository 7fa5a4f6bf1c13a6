"""The fitting history's interface: what every archive engine offers (reference §5).

An archive appends hash-chained entries (:mod:`.chain`), announces a change before it is
written (:meth:`Archive.begin`) and turns the announcement into its entry once the change is
over (:meth:`Archive.finish`); :meth:`Archive.recover` records announcements whose process
died as interrupted. Two engines implement it: :mod:`.sqlite` (one file, one workstation: the
default) and :mod:`.postgres` (the clinic's shared server, signed-in operators); :mod:`.open`
chooses by URL.

The operator recorded with an entry is the archive's to say (:meth:`Archive.stamp`): on SQLite
``$PDCP_STUDIO_OPERATOR`` or the login name, unless the caller names one; on PostgreSQL the
signed-in role, whatever the caller or the environment says.
"""

from __future__ import annotations

import abc
import getpass
import os
import socket
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from pdcp_studio.errors import PdcpError
from pdcp_studio.storage.archive.chain import VerifyReport

T = TypeVar("T")

ENV_OPERATOR = "PDCP_STUDIO_OPERATOR"

#: One entry as the archive gives it: its JSON body with ``id``, ``previous_hash``, ``hash``.
Entry = dict[str, Any]


class HistoryError(PdcpError):
    """The archive cannot be opened, read or written."""


class NotAllowedError(HistoryError):
    """The signed-in operator may read the fitting history but not record changes."""


def default_operator() -> str:
    """``$PDCP_STUDIO_OPERATOR``, else the login name."""
    env = os.environ.get(ENV_OPERATOR)
    if env:
        return env
    try:
        return getpass.getuser()
    except Exception:  # no login name (a container without a passwd entry)
        return "unknown"


def workstation() -> str:
    """This computer's name, recorded with every entry (a clinic's archive is shared)."""
    try:
        return socket.gethostname() or "unknown"
    except OSError:
        return "unknown"


@dataclass(frozen=True)
class EntryFilter:
    """Which entries to read: a patient reference and/or one part of the prosthesis
    (VID, PID, serial); None matches all."""

    patient: str | None = None
    device: tuple[int, int, int] | None = None

    def matches(self, entry: Entry) -> bool:
        """The same question the engines ask in SQL, for entries already read."""
        if self.patient is not None and entry.get("patient") != self.patient:
            return False
        if self.device is not None:
            vid, pid, serial = self.device
            return any(isinstance(d, dict) and (d.get("vid"), d.get("pid"), d.get("serial"))
                       == (vid, pid, serial) for d in entry.get("devices") or ())
        return True


class Archive(abc.ABC):
    """One fitting-history archive, opened; close it (or use ``with``)."""

    #: ``sqlite`` or ``postgresql``.
    engine: str = ""

    @property
    @abc.abstractmethod
    def location(self) -> str:
        """Where the archive is, for a person (a path or a URL without its password)."""

    def signed_in(self) -> str | None:
        """The signed-in role, on an engine with sign-in; None on SQLite."""
        return None

    def operator(self) -> str:
        """The operator this archive records with a change made now."""
        return default_operator()

    def check_can_record(self) -> None:
        """Raise :class:`NotAllowedError`, in words, when the signed-in operator may not
        record changes (a reader); nothing on an engine without sign-in."""
        if self.signed_in() is not None:
            raise NotImplementedError("an engine with sign-in says who may record")

    def stamp(self, body: Entry) -> Entry:
        """``body`` as this archive records it: the workstation, and the operator when the
        caller named none. An imported entry (with ``origin``) keeps its body as it was,
        so it still hashes to its origin: only who imported it is added there."""
        out = dict(body)
        if isinstance(out.get("origin"), dict):
            out["origin"] = {**out["origin"], "imported_by": self.signed_in() or self.operator()}
            return out
        out.setdefault("workstation", workstation())
        if not out.get("operator"):
            out["operator"] = self.operator()
        return out

    @classmethod
    def open(cls, path: str | Path | None = None) -> Archive:
        """The SQLite file at ``path``; without one, the archive in use (``--archive`` /
        ``$PDCP_STUDIO_ARCHIVE``, else the default file), whichever engine."""
        from pdcp_studio.storage.archive.open import open_archive
        from pdcp_studio.storage.archive.sqlite import SqliteArchive

        return SqliteArchive(path) if path is not None else open_archive()

    @classmethod
    def open_existing(cls, path: str | Path | None = None) -> Archive | None:
        """The archive to read, or None when it is an SQLite file not made yet: reading
        never creates it (``history list`` on a new computer is an empty history)."""
        from pdcp_studio.storage.archive.open import open_existing
        from pdcp_studio.storage.archive.sqlite import SqliteArchive

        if path is not None:
            return SqliteArchive(path) if Path(path).exists() else None
        return open_existing()

    def __enter__(self) -> Archive:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @abc.abstractmethod
    def close(self) -> None:
        """Let the archive go."""

    # -- writing ------------------------------------------------------------------------
    def append(self, body: Entry) -> int:
        """Append one entry (its fields without ``id``); returns its id."""
        stamped = self.stamp(body)
        return self._write(lambda: self._append_locked(stamped))

    def append_many(self, bodies: list[Entry]) -> list[int]:
        """Append several entries in one commit, all or none (``history import``); returns
        their ids."""
        stamped = [self.stamp(b) for b in bodies]
        return self._write(lambda: [self._append_locked(b) for b in stamped])

    @abc.abstractmethod
    def _append_locked(self, body: Entry) -> int:
        """Append a stamped entry inside an open write transaction; returns its id."""

    @abc.abstractmethod
    def _write(self, fn: Callable[[], T]) -> T:
        """Run ``fn`` as one serialised write transaction (committed, or rolled back)."""

    @abc.abstractmethod
    def begin(self, body: Entry) -> str:
        """Announce a change before it writes; ``body`` is its entry should it never finish
        (outcome ``interrupted``). Returns the token for :meth:`finish`."""

    @abc.abstractmethod
    def finish(self, token: str, body: Entry) -> int:
        """Record the finished change and drop its announcement, in one commit."""

    @abc.abstractmethod
    def recover(self) -> list[int]:
        """Append the announcements of processes that died before they finished (their
        outcome is ``interrupted``); returns the new entries' ids."""

    # -- reading ------------------------------------------------------------------------
    @abc.abstractmethod
    def entries(self, where: EntryFilter | None = None) -> list[Entry]:
        """Every entry (or those ``where`` matches), oldest first, with ``id``,
        ``previous_hash`` and ``hash``."""

    @abc.abstractmethod
    def get(self, entry_id: int) -> Entry | None:
        """One entry, or None."""

    @abc.abstractmethod
    def verify(self) -> VerifyReport:
        """Walk the chain; the first entry that is not intact, and why."""

    def origin_hashes(self) -> set[str]:
        """The original hashes of the entries imported into this archive (``history
        import`` skips an entry it already holds)."""
        return {str(e["origin"]["hash"]) for e in self.entries()
                if isinstance(e.get("origin"), dict) and "hash" in e["origin"]}
