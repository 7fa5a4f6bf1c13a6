"""Which archive: ``--archive URL``, else ``$PDCP_STUDIO_ARCHIVE``, else the SQLite file of
``$PDCP_STUDIO_HISTORY`` or the user's data folder (contracts §2).

``sqlite:///PATH`` (or a plain path) is the embedded archive; ``postgresql://…`` (or
``postgres://…``) the clinic's server, its password from the URL, ``$PGPASSWORD``,
``~/.pgpass`` or the app's sign-in dialog, TLS as libpq offers it (``?sslmode=…``).
"""

from __future__ import annotations

import os
from pathlib import Path

from pdcp_studio.storage.archive.base import Archive, HistoryError

ENV_ARCHIVE = "PDCP_STUDIO_ARCHIVE"
ENV_PATH = "PDCP_STUDIO_HISTORY"


def default_path() -> Path:
    """``$PDCP_STUDIO_HISTORY``, else the archive in the user's data folder — the one path
    ``doctor`` shows too (``pdcp_studio.paths.history_path``)."""
    from pdcp_studio.paths import history_path

    return history_path()


def archive_url(url: str | None = None) -> str:
    """The archive in use: ``url``, else ``$PDCP_STUDIO_ARCHIVE``, else ``sqlite:///`` the
    default path."""
    chosen = url or os.environ.get(ENV_ARCHIVE)
    return chosen if chosen else f"sqlite:///{default_path()}"


def is_postgres(url: str) -> bool:
    return url.startswith(("postgresql:", "postgres:"))


def sqlite_path(url: str) -> Path:
    """The file of a ``sqlite:///PATH`` URL (or a plain path)."""
    if url.startswith("sqlite://"):
        rest = url[len("sqlite://"):]
        if not rest.startswith("/"):
            raise HistoryError(f"fitting history: {url!r}: write sqlite:///PATH (three "
                               "slashes, then the path)")
        return Path(rest[1:] if rest.startswith("//") else rest)
    if "://" in url or url.startswith(("postgres", "sqlite:")):
        raise HistoryError(f"fitting history: {url!r} is not an archive URL: use "
                           "sqlite:///PATH or postgresql://USER@HOST[:PORT]/DB")
    return Path(url)


def describe(url: str | None = None) -> str:
    """The archive in use, for a person (a path, or the server without its password)."""
    chosen = archive_url(url)
    if is_postgres(chosen):
        from pdcp_studio.storage.archive.postgres import location_of

        return location_of(chosen)
    return str(sqlite_path(chosen))


def open_archive(url: str | None = None) -> Archive:
    """The archive at ``url`` (see :func:`archive_url`), opened; an SQLite file is made when
    there is none."""
    chosen = archive_url(url)
    if is_postgres(chosen):
        from pdcp_studio.storage.archive.postgres import PostgresArchive

        return PostgresArchive(chosen)
    from pdcp_studio.storage.archive.sqlite import SqliteArchive

    return SqliteArchive(sqlite_path(chosen))


def open_existing(url: str | None = None) -> Archive | None:
    """The archive to read, or None when it is an SQLite file not made yet: reading never
    creates one (``history list`` on a new computer is an empty history, not a new file)."""
    chosen = archive_url(url)
    if not is_postgres(chosen) and not sqlite_path(chosen).exists():
        return None
    return open_archive(chosen)
