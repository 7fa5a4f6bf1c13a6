"""This workstation's journal of outcomes the shared archive could not take yet.

A change announced to the clinic's server (``Archive.begin``) whose connection is lost before
its outcome is recorded: the prosthesis ends old or new (the arbitrator's transaction is whole),
and its outcome is kept here, one small JSON file per change, until the archive can be reached
again — the next open of that archive records it (``PostgresArchive.recover``). Nothing is lost
silently: an outcome neither recorded nor journaled is said to be unrecorded by the caller.

The folder is ``archive-journal`` in the user's data folder; each file names the archive it
belongs to (its location, never a password).
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path
from typing import Any

from pdcp_studio.storage.archive.base import Entry


def journal_dir() -> Path:
    """The journal's folder (beside the user's own SQLite history)."""
    from pdcp_studio.paths import user_data_dir

    return user_data_dir() / "archive-journal"


def keep(location: str, token: str, body: Entry) -> Path:
    """Keep the outcome of the change announced as ``token``: written whole (a temporary
    file, flushed, then renamed) so a kill leaves it or nothing."""
    folder = journal_dir()
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{token}.json"
    temporary = path.with_suffix(".tmp")
    with open(temporary, "w", encoding="utf-8") as f:
        json.dump({"archive": location, "token": token, "body": body}, f, ensure_ascii=False)
        f.flush()
        os.fsync(f.fileno())
    os.replace(temporary, path)
    return path


def waiting(location: str) -> list[tuple[Path, str, Entry]]:
    """The outcomes kept for the archive at ``location``, oldest first: (file, token, body)."""
    folder = journal_dir()
    if not folder.is_dir():
        return []
    out: list[tuple[float, Path, str, Entry]] = []
    for path in folder.glob("*.json"):
        try:
            doc: Any = json.loads(path.read_text(encoding="utf-8"))
            if doc.get("archive") != location:
                continue
            out.append((path.stat().st_mtime, path, str(doc["token"]), dict(doc["body"])))
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            continue  # another archive's or a damaged file: left for a person to look at
    return [(p, t, b) for _m, p, t, b in sorted(out, key=lambda x: x[0])]


def done(path: Path) -> None:
    """The outcome in ``path`` is recorded: forget it."""
    with contextlib.suppress(FileNotFoundError):
        path.unlink()
