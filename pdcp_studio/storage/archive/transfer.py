"""Moving a workstation's history into another archive: ``history export`` / ``import``.

Export is JSON lines, one entry a line, oldest first, each with its ``id``, ``previous_hash``
and ``hash``: the file verifies on its own (:func:`chain.verify_export`). Import appends each
entry to the target archive as a new entry of its chain whose body is the original body plus
``origin`` — the workstation, archive, id and hashes it had — so the original still verifies
(:func:`chain.origin_problem`, checked by ``verify`` too). An entry already imported (its
original hash is there) is skipped, so importing a file twice adds nothing; the rest are
appended in one commit, all or none.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import IO, Any

from pdcp_studio.storage.archive.base import Archive, Entry, HistoryError
from pdcp_studio.storage.archive.chain import clean_body, verify_export


def export_lines(archive: Archive) -> Iterator[str]:
    """The archive's entries as JSON lines (hashes included)."""
    for entry in archive.entries():
        yield json.dumps(entry, ensure_ascii=False, sort_keys=True)


def read_lines(stream: IO[str], name: str) -> list[Entry]:
    """An export file's entries; HistoryError naming the line that is not one."""
    out: list[Entry] = []
    for number, line in enumerate(stream, 1):
        if not line.strip():
            continue
        try:
            doc: Any = json.loads(line)
        except ValueError as err:
            raise HistoryError(f"{name}: line {number} is not JSON: {err}") from err
        if not isinstance(doc, dict):
            raise HistoryError(f"{name}: line {number} is not an entry")
        out.append(doc)
    return out


@dataclass
class ImportReport:
    imported: list[int]
    skipped: int


def import_entries(archive: Archive, entries: Iterable[Entry], *, source: str) -> ImportReport:
    """Append ``entries`` (an export, oldest first) to ``archive`` with their origin; refused
    whole (HistoryError) when the export does not verify."""
    entries = list(entries)
    problem = verify_export(entries)
    if problem:
        raise HistoryError(f"{source}: not imported, the export does not verify: {problem}")
    archive.check_can_record()
    held = archive.origin_hashes()
    bodies: list[Entry] = []
    skipped = 0
    for entry in entries:
        body = clean_body(entry)
        if isinstance(body.get("origin"), dict):
            origin = dict(body["origin"])  # imported before: it keeps its first origin
        else:
            origin = {"id": int(entry["id"]), "previous_hash": entry["previous_hash"],
                      "hash": entry["hash"], "workstation": body.get("workstation"),
                      "archive": source}
        if str(origin["hash"]) in held:
            skipped += 1
            continue
        bodies.append({**body, "origin": origin})
        held.add(str(origin["hash"]))
    return ImportReport(archive.append_many(bodies), skipped)
