"""The hash chain of the fitting history, pure: hashing an entry and walking a chain.

Both engines (:mod:`.sqlite`, :mod:`.postgres`) and an exported file (``history import``) are
checked here, so there is one definition of "intact" (reference §5). Each entry stores the
SHA-256 of the previous entry (``previous_hash``) and its own ``hash`` = SHA-256 over its id,
its previous hash and its canonical JSON body; the first entry's previous hash is
:data:`GENESIS`. An entry imported from another archive keeps, in its ``origin``, the id and
hashes it had there: its body without ``origin`` still hashes to them (:func:`origin_problem`).

Tamper-evidence beyond the chain (the head anchored in the arbitrator's memory, defensive
reading of rows) builds on these functions; nothing here reads a database.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

GENESIS = "0" * 64

#: One stored row: id, previous hash, hash, the body as stored (JSON text).
Row = tuple[int, str, str, str]


def canonical(body: dict[str, Any]) -> str:
    """The JSON the hash covers: sorted keys, no spaces, UTF-8 kept."""
    return json.dumps(body, sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def entry_hash(entry_id: int, previous_hash: str, body_json: str) -> str:
    """SHA-256 over the id, the previous entry's hash and the canonical JSON body."""
    data = f"{entry_id}\n{previous_hash}\n{body_json}".encode()
    return hashlib.sha256(data).hexdigest()


def clean_body(body: dict[str, Any]) -> dict[str, Any]:
    """An entry's body: its fields without the chain's own (``id``, ``hash``,
    ``previous_hash``)."""
    return {k: v for k, v in body.items() if k not in ("id", "hash", "previous_hash")}


def next_link(last: tuple[int, str] | None, body: dict[str, Any]) -> tuple[int, str, str, str]:
    """The row that follows ``last`` (its id and hash; None for an empty archive):
    (new id, previous hash, hash, body text)."""
    last_id, last_hash = last if last else (0, GENESIS)
    body = clean_body(body)
    new_id = last_id + 1
    return (new_id, last_hash, entry_hash(new_id, last_hash, canonical(body)),
            json.dumps(body, ensure_ascii=False))


@dataclass(frozen=True)
class VerifyReport:
    """``ok`` when every entry is intact; else ``first_bad`` names the first entry that is
    not (an id, or the id after which entries are missing) and ``reason`` says why."""

    ok: bool
    entries: int
    first_bad: int | None = None
    reason: str = ""


def _content(body: str) -> tuple[str, dict[str, Any] | None]:
    try:
        doc = json.loads(body)
    except ValueError:
        return body, None
    if not isinstance(doc, dict):
        return body, None
    return canonical(doc), doc


def origin_problem(body: dict[str, Any]) -> str | None:
    """None when an imported entry's body (without ``origin``) still hashes to the id and
    hashes it had in the archive it came from, or when it has no origin; else why not."""
    origin = body.get("origin")
    if origin is None:
        return None
    if not isinstance(origin, dict):
        return "its origin is not a record"
    own = {k: v for k, v in body.items() if k != "origin"}
    try:
        digest = entry_hash(int(origin["id"]), str(origin["previous_hash"]), canonical(own))
    except (KeyError, TypeError, ValueError):
        return "its origin lacks the original id or hashes"
    if digest != origin.get("hash"):
        return (f"it no longer matches entry {origin['id']} of the archive it was imported "
                f"from (workstation {origin.get('workstation') or 'unknown'})")
    return None


def verify_rows(rows: Iterable[Row], head: tuple[int, str] | None, *,
                head_kept: bool = True) -> VerifyReport:
    """Walk ``rows`` (in id order) from :data:`GENESIS`; the first entry that is not intact,
    and why. ``head`` is the archive's head record (last id, last hash), which catches the
    deletion of the newest entries; ``head_kept`` False for an archive that keeps none."""
    count = 0
    previous, expected_id = GENESIS, 1
    for entry_id, prev, digest, body in rows:
        count += 1
        if entry_id != expected_id:
            return VerifyReport(False, count, expected_id,
                                f"entry {expected_id} is missing (deleted): the next "
                                f"entry is {entry_id}")
        if prev != previous:
            return VerifyReport(False, count, entry_id,
                                f"entry {entry_id}: its previous hash does not match "
                                f"entry {entry_id - 1} (an entry was deleted or edited)")
        content, doc = _content(body)
        if entry_hash(entry_id, prev, content) != digest:
            return VerifyReport(False, count, entry_id,
                                f"entry {entry_id} was edited: its hash does not match "
                                "its content")
        problem = origin_problem(doc) if doc is not None else None
        if problem:
            return VerifyReport(False, count, entry_id, f"entry {entry_id} (imported): {problem}")
        previous, expected_id = digest, entry_id + 1
    last_id = expected_id - 1
    if head is not None and (head[0], head[1]) != (last_id, previous):
        if head[0] > last_id:
            return VerifyReport(False, count, last_id + 1,
                                f"entries {last_id + 1}…{head[0]} are missing (deleted)")
        return VerifyReport(False, count, head[0],
                            f"entry {head[0]}: does not match the archive's head record")
    if head is None and count and head_kept:
        return VerifyReport(False, count, 1, "the archive's head record is missing")
    return VerifyReport(True, count)


def verify_export(lines: Iterable[dict[str, Any]]) -> str | None:
    """None when exported entries (``history export``'s lines, oldest first) form an intact
    stretch of a chain — each hashes to its ``hash`` and names the one before it — else the
    first problem, naming the entry."""
    previous: str | None = None
    for entry in lines:
        try:
            entry_id, prev, digest = int(entry["id"]), str(entry["previous_hash"]), entry["hash"]
        except (KeyError, TypeError, ValueError):
            return "an exported line lacks its id or hashes"
        if previous is not None and prev != previous:
            return f"entry {entry_id}: its previous hash does not match the entry before it"
        body = clean_body(entry)
        if entry_hash(entry_id, prev, canonical(body)) != digest:
            return f"entry {entry_id} was edited: its hash does not match its content"
        problem = origin_problem(body)
        if problem:
            return f"entry {entry_id} (imported): {problem}"
        previous = digest
    return None
