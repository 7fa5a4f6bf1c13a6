"""The hash chain of the fitting history, pure: hashing an entry and walking a chain.

Both engines (:mod:`.sqlite`, :mod:`.postgres`) and an exported file (``history import``) are
checked here, so there is one definition of "intact" (reference §5). Each entry stores the
SHA-256 of the previous entry (``previous_hash``) and its own ``hash`` = SHA-256 over its id,
its previous hash and its canonical JSON body; the first entry's previous hash is
:data:`GENESIS`. An entry imported from another archive keeps, in its ``origin``, the id and
hashes it had there: its body without ``origin`` still hashes to them (:func:`origin_problem`).

Tamper-evidence beyond the chain builds on these functions: the head anchored in the
arbitrator's memory (:class:`Anchor`, compared in :mod:`.anchor`) and defensive reading of rows
(:mod:`.rows`); nothing here reads a database.
"""

from __future__ import annotations

import hashlib
import json
import struct
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
    except (ValueError, RecursionError):
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
    except (KeyError, TypeError, ValueError, OverflowError):
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
    for row in rows:
        count += 1
        checked = _row_problem(row, expected_id)
        if isinstance(checked, VerifyReport):
            return VerifyReport(False, count, checked.first_bad, checked.reason)
        entry_id, prev, digest, body = checked
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
    if head is not None and (not _small_int(head[0]) or not isinstance(head[1], str)):
        return VerifyReport(False, count, last_id, "the archive's head record is damaged")
    if head is not None and (head[0], head[1]) != (last_id, previous):
        if head[0] > last_id:
            return VerifyReport(False, count, last_id + 1,
                                f"entries {last_id + 1}…{head[0]} are missing (deleted)")
        return VerifyReport(False, count, head[0],
                            f"entry {head[0]}: does not match the archive's head record")
    if head is None and count and head_kept:
        return VerifyReport(False, count, 1, "the archive's head record is missing")
    return VerifyReport(True, count)


def _small_int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value < 1 << 63


def _row_problem(row: object, expected_id: int) -> Row | VerifyReport:
    """``row`` as (id, previous hash, hash, body text), or why it cannot be walked (a row an
    editor broke: wrong column types, a huge id), naming the entry."""
    try:
        columns: tuple[Any, ...] = tuple(row)  # type: ignore[arg-type]
    except TypeError:
        columns = ()
    if len(columns) != 4:
        return VerifyReport(False, 0, expected_id, f"entry {expected_id}: the row is damaged")
    entry_id, prev, digest, body = columns
    if not _small_int(entry_id):
        return VerifyReport(False, 0, expected_id,
                            f"entry {expected_id}: the next row's id {str(entry_id)[:30]!r} "
                            "is not an entry number")
    if isinstance(body, bytes | bytearray | memoryview):
        body = bytes(body).decode("utf-8", "replace")
    if not isinstance(prev, str) or not isinstance(digest, str) or not isinstance(body, str):
        return VerifyReport(False, 0, entry_id,
                            f"entry {entry_id} is damaged: its hashes or body are not text")
    return entry_id, prev, digest, body


def verify_export(lines: Iterable[dict[str, Any]]) -> str | None:
    """None when exported entries (``history export``'s lines, oldest first) form an intact
    stretch of a chain — each hashes to its ``hash`` and names the one before it — else the
    first problem, naming the entry."""
    previous: str | None = None
    for entry in lines:
        try:
            entry_id, prev, digest = int(entry["id"]), str(entry["previous_hash"]), entry["hash"]
        except (KeyError, TypeError, ValueError, OverflowError):
            return "an exported line lacks its id or hashes"
        if not isinstance(digest, str) or not _small_int(entry_id):
            return f"entry {str(entry_id)[:30]}: its id or hash is damaged"
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


@dataclass(frozen=True)
class Anchor:
    """What a prosthesis remembers of its fitting history (reference §5 Decision): the id of
    the entry that recorded its last change — ids run 1, 2, 3…, so it is also the number of
    entries the archive held then — and that entry's hash; ``announced`` is the token of a
    change announced (``Archive.begin``) and carried out but whose entry was not anchored yet
    (the PC stopped between the write and the record): the one entry after the anchored one
    that may name this prosthesis. ``entry`` 0 is a prosthesis with no recorded change."""

    entry: int
    hash: str
    announced: str = ""

    def to_json(self) -> dict[str, Any]:
        return {"entry": self.entry, "hash": self.hash, "announced": self.announced or None}

    def text(self) -> str:
        """The anchor for a person: ``entry 12, hash 3f…`` (+ the announcement)."""
        if not self.entry and not self.announced:
            return "no change recorded yet"
        out = f"entry {self.entry}, hash {self.hash}" if self.entry else "no entry yet"
        return out + (f", change {self.announced} announced" if self.announced else "")


#: The anchor as the arbitrator's memory and the host link carry it: the entry id (u64 LE),
#: its SHA-256 (32 bytes), the announced change's token (32 ASCII bytes, NUL-padded).
ANCHOR_STRUCT = struct.Struct("<Q32s32s")
ANCHOR_SIZE = ANCHOR_STRUCT.size


def pack_anchor(anchor: Anchor) -> bytes:
    """``anchor`` as its 72 bytes; ValueError for one that cannot be (a hash that is not 64
    hex digits, a token longer than 32 ASCII characters, an id out of range)."""
    if not 0 <= anchor.entry < 1 << 63:
        raise ValueError(f"anchor entry {anchor.entry} is out of range")
    digest = bytes.fromhex(anchor.hash) if anchor.entry else bytes(32)
    if len(digest) != 32:
        raise ValueError("an anchor's hash is 64 hex digits")
    token = anchor.announced.encode("ascii")
    if len(token) > 32:
        raise ValueError("an anchor's announcement token is at most 32 characters")
    return ANCHOR_STRUCT.pack(anchor.entry, digest, token)


def unpack_anchor(data: bytes) -> Anchor:
    """The anchor in ``data`` (:func:`pack_anchor`'s bytes); ValueError when it is not one."""
    if len(data) != ANCHOR_SIZE:
        raise ValueError(f"an anchor is {ANCHOR_SIZE} bytes, not {len(data)}")
    entry, digest, token = ANCHOR_STRUCT.unpack(data)
    if entry >= 1 << 63:
        raise ValueError(f"anchor entry {entry} is out of range")
    try:
        announced = token.rstrip(b"\0").decode("ascii")
    except UnicodeDecodeError:
        raise ValueError("an anchor's announcement token is not ASCII") from None
    return Anchor(entry, digest.hex() if entry else "", announced)
