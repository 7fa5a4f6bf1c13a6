"""Reading stored rows defensively: whatever an editor left in the archive, a reader gets an
entry of the shape every command expects, or :class:`DamagedEntry` naming the entry and what
is wrong — never a traceback (issue 28: a row whose JSON is not an object, missing keys, wrong
types, huge integers, bad JSON).

:func:`entry_of` turns a stored row into an entry; :func:`check_entry` checks the fields that
``history list``, ``show`` and ``restore`` read; :func:`entry_id` bounds an ID a person typed.
"""

from __future__ import annotations

import json
from typing import Any

from pdcp_studio.storage.archive.base import Entry, HistoryError

#: The largest entry ID an archive can hold (SQLite's and PostgreSQL's signed 64-bit integer).
MAX_ID = (1 << 63) - 1
#: Integers in an entry beyond this are damage, not data (a VID, PID, serial, index or CRC).
MAX_INT = 1 << 32


class DamagedEntry(HistoryError):
    """A stored entry cannot be read as an entry; the text names it and says why."""

    def __init__(self, entry_id: object, why: str) -> None:
        self.entry_id = entry_id
        super().__init__(f"fitting history: entry {entry_id} is damaged: {why}; "
                         "check the archive with `pdcp-studio history verify`")


def entry_id(value: object) -> int | None:
    """``value`` as a stored entry ID, or None when it is not one (out of range, not an int)."""
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            value = int(str(value))
        except ValueError:
            return None
    return value if 1 <= value <= MAX_ID else None


def entry_of(row: Any) -> Entry:
    """A stored row ``(id, previous hash, hash, body)`` as an entry; DamagedEntry when the
    body is not a JSON object or a chain field is not what it should be."""
    try:
        raw_id, previous, digest, body = row
    except (TypeError, ValueError):
        raise DamagedEntry("?", "the row does not have its four columns") from None
    number = entry_id(raw_id)
    if number is None:
        raise DamagedEntry(repr(raw_id)[:40], "its id is not an entry number")
    if not isinstance(previous, str) or not isinstance(digest, str):
        raise DamagedEntry(number, "its hashes are not text")
    if isinstance(body, bytes | bytearray | memoryview):
        try:
            body = bytes(body).decode("utf-8")
        except UnicodeDecodeError:
            raise DamagedEntry(number, "its body is not UTF-8 text") from None
    if isinstance(body, str):
        try:
            doc = json.loads(body)
        except (ValueError, RecursionError):
            raise DamagedEntry(number, "its body is not valid JSON") from None
    else:
        doc = body  # a driver that decodes JSON columns itself
    if not isinstance(doc, dict):
        raise DamagedEntry(number, f"its body is {_kind(doc)}, not a record")
    return {"id": number, **doc, "previous_hash": previous, "hash": digest}


def _kind(value: object) -> str:
    return {list: "a list", str: "text", int: "a number", float: "a number",
            bool: "true/false", type(None): "null"}.get(type(value), type(value).__name__)


def _int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and abs(value) <= MAX_INT


def _ref_problem(ref: object, with_index: bool) -> str | None:
    if not isinstance(ref, dict):
        return "is not a record"
    keys = ("vid", "pid", "serial", "index") if with_index else ("vid", "pid", "serial")
    for key in keys:
        if key not in ref:
            return f"lacks {key}"
        if not _int(ref[key]):
            return f"has a {key} that is not a small whole number"
    return None


def _links_problem(name: str, links: object) -> str | None:
    if not isinstance(links, list):
        return f"{name} is {_kind(links)}, not a list"
    for n, link in enumerate(links, 1):
        if not isinstance(link, dict):
            return f"link {n} of {name} is not a record"
        for end in ("output", "input"):
            problem = _ref_problem(link.get(end), True)
            if problem:
                return f"the {end} of link {n} of {name} {problem}"
    return None


#: Fields every entry has, and the types they must be (None allowed where listed).
_TEXT = ("time", "bus", "action")
_OPTIONAL_TEXT = ("operator", "interlock", "patient", "workstation", "config_crc_before",
                  "config_crc_after")
_OPTIONAL_RECORD = ("outcome", "plan", "effect", "next_power_on", "origin", "policy_before",
                    "policy_after", "configuration_after", "parameters_after")


def check_entry(entry: Entry) -> Entry:
    """``entry`` itself when every field a command reads has its type; else DamagedEntry
    naming the entry and the field."""
    number = entry.get("id", "?")

    def bad(why: str) -> DamagedEntry:
        return DamagedEntry(number, why)

    for key in _TEXT:
        if key not in entry:
            raise bad(f"it lacks its {key}")
        if not isinstance(entry[key], str):
            raise bad(f"its {key} is {_kind(entry[key])}, not text")
    for key in _OPTIONAL_TEXT:
        if entry.get(key) is not None and not isinstance(entry[key], str):
            raise bad(f"its {key} is {_kind(entry[key])}, not text")
    for key in _OPTIONAL_RECORD:
        if entry.get(key) is not None and not isinstance(entry[key], dict):
            raise bad(f"its {key} is {_kind(entry[key])}, not a record")
    if not isinstance(entry.get("verified"), bool):
        raise bad("its verified flag is missing or not true/false")
    devices = entry.get("devices")
    if not isinstance(devices, list):
        raise bad(f"its devices are {_kind(devices)}, not a list")
    for n, device in enumerate(devices, 1):
        problem = _ref_problem(device, False)
        if problem:
            raise bad(f"device {n} {problem}")
    if "links_before" not in entry:
        raise bad("it lacks its links before")
    problem = _links_problem("the links before", entry["links_before"])
    if problem is None and entry.get("links_after") is not None:
        problem = _links_problem("the links after", entry["links_after"])
    if problem:
        raise bad(problem)
    for key in ("outcome", "effect", "next_power_on", "plan"):
        _check_texts(entry.get(key), bad, key)
    return entry


def _check_texts(record: object, bad: Any, name: str) -> None:
    """The lists of text lines inside an outcome, an effect or a plan are lists of text."""
    if not isinstance(record, dict):
        return
    for key in ("text", "technical", "notes"):
        value = record.get(key)
        if value is not None and (not isinstance(value, list)
                                  or not all(isinstance(x, str) for x in value)):
            raise bad(f"its {name}'s {key} is not a list of text")
    for key in ("status", "step", "reason"):
        value = record.get(key)
        if value is not None and not isinstance(value, str):
            raise bad(f"its {name}'s {key} is not text")
    actions = record.get("actions")
    if actions is not None:
        if not isinstance(actions, list):
            raise bad(f"its {name}'s actions are not a list")
        for n, action in enumerate(actions, 1):
            if not isinstance(action, dict) or not isinstance(action.get("op"), str):
                raise bad(f"action {n} of its {name} is not a record with an op")
            for end in ("output", "input"):
                problem = _ref_problem(action.get(end), True)
                if problem:
                    raise bad(f"the {end} of action {n} of its {name} {problem}")


def pending_body(token: object, body: object) -> Entry | None:
    """The entry a pending row (an announcement whose process died) becomes, or None when
    the row is not an announcement this program wrote: its body must read as an entry
    (:func:`check_entry`) whose outcome is ``interrupted``. The entry keeps the token as its
    ``announcement``: only the change the prosthesis was told of (``Anchor.announced``)
    may follow its anchored entry, so a row injected here is caught by ``history verify
    --bus`` — it is never made to look like a finished change."""
    if not isinstance(token, str) or not isinstance(body, str):
        return None
    try:
        doc = entry_of((1, "", "", body))
        check_entry(doc)
    except HistoryError:
        return None
    outcome = doc.get("outcome") or {}
    if outcome.get("status") != "interrupted":
        return None
    for key in ("id", "previous_hash", "hash"):
        doc.pop(key, None)
    doc["announcement"] = token
    return doc
