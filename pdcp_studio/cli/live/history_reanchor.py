"""``pdcp-studio history re-anchor --bus URL --reason TEXT [--yes]``: a prosthesis whose
fitting history is lost for good is tied to the archive in use again, on the record.

Without it a prosthesis whose archive was lost (a dead disk without a backup) refuses every
change (reference §5 Decision: a change never appends to a history that does not verify
against the prosthesis's anchor). Re-anchoring is that refusal lifted by a person, said and
kept: the preview names what the prosthesis remembers and what the archive lacks; with
``--yes`` and a reason, a "history re-anchored" entry is recorded — operator, time, the
prosthesis, the anchor it remembered, the difference, the reason — and only then does the
prosthesis remember that entry. Nothing else of the prosthesis is written. A chain that does
not verify is never re-anchored onto: the evidence of its damage stays as it is.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from pdcp_studio.cli.main import BadInput
from pdcp_studio.model.safe_text import shown

ACTION = "history re-anchored"


def add_parser(actions: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    from pdcp_studio.cli.live.change_road import add_archive_argument

    p = actions.add_parser(
        "re-anchor", help="tie a prosthesis whose fitting history is lost to this archive, "
                          "on the record (with --yes and --reason)",
        description="For a prosthesis whose fitting history is lost for good (changes are "
                    "refused because the archive does not verify against what the prosthesis "
                    "remembers). Prints what the prosthesis remembers and what the archive "
                    "lacks; with --yes and --reason, records a 'history re-anchored' entry "
                    "(operator, time, the prosthesis, the anchor it remembered, the "
                    "difference, the reason) and then makes the prosthesis remember it. "
                    "Nothing else is written. An archive whose chain is broken is refused.")
    p.add_argument("--bus", required=True, metavar="URL", help="the prosthesis")
    p.add_argument("--memory", metavar="FILE",
                   help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
    p.add_argument("--reason", metavar="TEXT",
                   help="why the earlier history cannot be put back (recorded; needed with "
                        "--yes)")
    p.add_argument("--yes", action="store_true",
                   help="record the entry and write the anchor (without it, only the preview)")
    add_archive_argument(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.cli.live.scan import open_bus_session
    from pdcp_studio.storage.archive import HistoryError, open_archive

    check_bus_url(args.bus)
    reason = (args.reason or "").strip()
    if args.yes and not reason:
        raise BadInput("history re-anchor --yes needs --reason TEXT: why the earlier fitting "
                       "history cannot be put back (it is recorded)")
    try:
        archive = open_archive(getattr(args, "archive", None))
    except HistoryError as err:
        raise BadInput(str(err)) from err
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        with archive:
            return _re_anchor(session, archive, args.bus, reason, args.yes)
    finally:
        session.close()


def _re_anchor(session: Any, archive: Any, bus: str, reason: str, yes: bool) -> int:
    from pdcp_studio.storage.archive.anchor import anchor_problem

    archive.recover()
    where = shown(archive.location)
    report = archive.verify()
    if not report.ok:
        print(f"pdcp-studio: {where}: entry {report.first_bad} is not intact "
              f"({shown(report.reason)}): a damaged archive is never re-anchored onto; keep "
              "it as evidence and re-anchor onto another archive (--archive)", file=sys.stderr)
        return 1
    anchor = session.read_anchor()
    if anchor is None:
        print(f"the prosthesis on {shown(bus)} keeps no fitting history anchor (its "
              "arbitrator has none): nothing to re-anchor")
        return 0
    system = session.system()
    present = sorted(k for k, d in system.devices.items() if d.present)
    parts = {(k.vid, k.pid, k.serial) for k in present}
    problem = anchor_problem(archive.entries(), anchor, parts)
    if problem is None:
        print(f"{where} matches the prosthesis on {shown(bus)} (it remembers "
              f"{anchor.text()}): nothing to re-anchor")
        return 0
    print(f"The prosthesis on {shown(bus)} remembers {anchor.text()}.")
    print(f"{where} does not match: {shown(problem)}.")
    print(f"Re-anchoring records a '{ACTION}' entry in {where} naming this prosthesis, what it "
          "remembered, this difference, the operator and the reason; then the prosthesis "
          "remembers that entry. Its links, parameters and stored configuration are not "
          "touched. The changes recorded before stay unknown to this archive: keep whatever "
          "evidence of them exists.")
    if not yes:
        print("Nothing written (add --yes and --reason TEXT to re-anchor).")
        return 0
    entry_id = archive.append(_entry(session, bus, present, anchor, problem, reason))
    entry = archive.get(entry_id)
    from pdcp_studio.storage.archive.chain import Anchor

    try:
        session.write_anchor(Anchor(int(entry["id"]), str(entry["hash"])))
    except Exception as err:
        print(f"pdcp-studio: entry {entry_id} was recorded, but the prosthesis's anchor could "
              f"not be written ({shown(str(err))}); run this again once the prosthesis can "
              "be written", file=sys.stderr)
        return 1
    problem = anchor_problem(archive.entries(), session.read_anchor(), parts)
    if problem is not None:
        print(f"pdcp-studio: re-anchored, but the archive still does not verify: "
              f"{shown(problem)}", file=sys.stderr)
        return 1
    print(f"Re-anchored: entry {entry_id} recorded; the prosthesis now remembers entry "
          f"{entry_id}, hash {entry['hash']}.")
    return 0


def _entry(session: Any, bus: str, present: list[Any], anchor: Any, problem: str,
           reason: str) -> dict[str, Any]:
    """The record: a transaction that wrote nothing, with what was re-anchored and why."""
    from pdcp_studio.bus.transaction import Change, Status, TransactionResult, config_crc
    from pdcp_studio.storage.history import entry_from_result

    links = sorted(session.system().links)
    try:
        crc = config_crc(session.read_configuration())
    except Exception:  # the record still says what was re-anchored
        crc = None
    result = TransactionResult(
        Status.NOTHING, ACTION, "anchor", f"re-anchored: {reason}", links, links,
        crc, crc, devices=present, notes=[f"the prosthesis remembered {anchor.text()}",
                                          f"the archive lacked: {problem}"])
    entry = entry_from_result(result, Change(ACTION), bus=bus)
    entry["re_anchor"] = {"previous": anchor.to_json(), "difference": problem,
                          "reason": reason}
    return entry
