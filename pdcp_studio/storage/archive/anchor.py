"""The archive against the prosthesis's memory: is the archive's last entry for this
prosthesis the one the prosthesis remembers (reference §5 Decision, issue 28)?

A chain alone can be re-hashed by whoever can write the archive; the anchor cannot, since it is
in the arbitrator's memory. :func:`anchor_problem` is the pure comparison; :func:`check` walks
the chain first (``Archive.verify``), then compares. Both answer None (all is well) or the
difference in words, naming the entries.
"""

from __future__ import annotations

from collections.abc import Iterable

from pdcp_studio.storage.archive.base import Archive, Entry, HistoryError
from pdcp_studio.storage.archive.chain import Anchor

Part = tuple[int, int, int]


def names_part(entry: Entry, parts: set[Part]) -> bool:
    """Does ``entry`` record a change to a prosthesis with one of ``parts``?"""
    for d in entry.get("devices") or ():
        if isinstance(d, dict) and (d.get("vid"), d.get("pid"), d.get("serial")) in parts:
            return True
    return False


def anchor_problem(entries: list[Entry], anchor: Anchor | None,
                   parts: Iterable[Part]) -> str | None:
    """None when ``entries`` (the whole archive, oldest first) end, for the prosthesis with
    ``parts``, at the entry ``anchor`` names; else what differs.

    After the anchored entry one entry may name the prosthesis: the one whose
    ``announcement`` is the change the prosthesis was told of before it was written
    (``anchor.announced``) — a change whose anchor the PC could not write any more.
    """
    wanted = set(parts)
    count = len(entries)
    if anchor is None:
        return None  # an arbitrator that keeps no anchor (a memory written before it had one)
    after = 0
    if anchor.entry:
        by_id = {e.get("id"): e for e in entries}
        anchored = by_id.get(anchor.entry)
        if anchored is None:
            held = "no entries (an empty archive)" if not count else \
                f"{count} entr{'y' if count == 1 else 'ies'}"
            return (f"the prosthesis remembers entry {anchor.entry} (hash {anchor.hash}), "
                    f"but the archive holds {held}: entries were deleted, or this is not the "
                    "archive that recorded its changes")
        if anchored.get("hash") != anchor.hash:
            return (f"entry {anchor.entry} has hash {anchored.get('hash')} in the archive, but "
                    f"the prosthesis remembers {anchor.hash}: the archive was edited and "
                    "re-hashed, or it is not the archive that recorded its changes")
        wanted |= {(d["vid"], d["pid"], d["serial"]) for d in anchored.get("devices") or ()
                   if isinstance(d, dict) and {"vid", "pid", "serial"} <= d.keys()}
        after = anchor.entry
    later = [e for e in entries if isinstance(e.get("id"), int) and e["id"] > after
             and names_part(e, wanted)]
    if anchor.announced and len(later) == 1 and later[0].get("announcement") == anchor.announced:
        return None
    if later:
        ids = ", ".join(str(e["id"]) for e in later[:5]) + (" …" if len(later) > 5 else "")
        since = f"entry {anchor.entry}" if anchor.entry else "its first change"
        return (f"entr{'y' if len(later) == 1 else 'ies'} {ids} name this prosthesis but "
                f"were recorded after {since}, the last the prosthesis remembers: "
                "it does not know of them (entries added to the archive, or an anchor that "
                "was never written)")
    return None


def check(archive: Archive, anchor: Anchor | None, parts: Iterable[Part]) -> str | None:
    """None when ``archive``'s chain is intact and its last entry for this prosthesis is the
    anchored one; else why not, in words (a damaged row is named, never raised)."""
    report = archive.verify()
    if not report.ok:
        return f"entry {report.first_bad} is not intact: {report.reason}"
    try:
        entries = archive.entries()
    except HistoryError as err:
        return str(err)
    return anchor_problem(entries, anchor, parts)
