"""``history list|show|restore|verify|export|import``: the fitting history (reference §5,
contracts §2).

The archive is ``--archive URL`` when given, else ``$PDCP_STUDIO_ARCHIVE``, else
``$PDCP_STUDIO_HISTORY`` or ``history.sqlite`` in the user's data folder; ``postgresql://…``
is the clinic's shared archive. ``list --patient REF --prosthesis VID/PID/SERIAL`` is a
clinic's view: one patient's or one part's changes, from every workstation. ``restore ID
--bus URL`` is a new, previewed transaction that puts back the links, the stored
configuration and the policy that entry ID left on the prosthesis; it is written only with
``--yes``. ``verify`` exits 0 when the hash chain is intact and 1 naming the first entry that
is not; ``verify --bus URL`` also compares the archive with the anchor the prosthesis keeps
(reference §5 Decision). A damaged entry is exit 1 naming it, an ID no entry can have exit 2.
``export`` writes the archive as JSON lines (hashes included); ``import FILE`` appends such a
file to the archive, each entry keeping its origin.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pdcp_studio.cli import options
from pdcp_studio.cli.main import BadInput
from pdcp_studio.model.safe_text import shown

if TYPE_CHECKING:
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import System
    from pdcp_studio.storage.archive import Archive

#: One fitting-history entry as the archive stores it (storage/history.py).
Entry = dict[str, Any]


def add_subparser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("history", help="the fitting history of changes to prostheses",
                              description=__doc__.split("\n\n")[0])
    actions = p.add_subparsers(dest="history_command", metavar="ACTION", required=True)
    from pdcp_studio.cli.live.change_road import add_archive_argument, add_road_arguments

    lst = actions.add_parser("list", help="every recorded change, oldest first")
    lst.add_argument("--json", action="store_true", help="print the contract's JSON document")
    lst.add_argument("--patient", metavar="REF", help="only this patient's changes")
    lst.add_argument("--prosthesis", metavar="VID/PID/SERIAL", type=_part,
                     help="only changes to the prosthesis with this part")
    add_archive_argument(lst)
    lst.set_defaults(func=run_list)
    show = actions.add_parser("show", help="one entry in full")
    show.add_argument("id", type=_entry_id, metavar="ID")
    show.add_argument("--json", action="store_true", help="print the entry as JSON")
    add_archive_argument(show)
    show.set_defaults(func=run_show)
    restore = actions.add_parser(
        "restore", help="put back the state recorded AFTER entry ID (a new previewed "
                        "transaction)",
        description="Brings the prosthesis back to the state recorded after fitting history "
                    "entry ID: its links, its parts' parameter values, the stored "
                    "configuration and the policy. The preview says in words what will "
                    "change; it is written only with --yes. Refused before anything is "
                    "written (exit 1) when a part it needs is not on the bus. By default the "
                    "stored configuration recorded with the entry is put back; --store stores "
                    "the restored links instead, --no-store leaves it as it is.")
    restore.add_argument("id", type=_entry_id, metavar="ID")
    restore.add_argument("--bus", required=True, metavar="URL", help="the prosthesis")
    restore.add_argument("--memory", metavar="FILE",
                         help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
    add_road_arguments(restore)
    restore.set_defaults(func=run_restore)
    verify = actions.add_parser(
        "verify", help="check the hash chain (exit 1 if broken); with --bus, against the "
                       "prosthesis's anchor",
        description="Walks the hash chain: exit 0 when every entry is intact, 1 naming the "
                    "first that is not. With --bus, also compares the archive with the "
                    "anchor the prosthesis keeps in its arbitrator's memory (the entry that "
                    "recorded its last change and that entry's hash): an archive whose last "
                    "entry for that prosthesis is not the anchored one fails (exit 1), "
                    "saying what differs.")
    verify.add_argument("--bus", metavar="URL", help="the prosthesis whose anchor to compare")
    verify.add_argument("--memory", metavar="FILE",
                        help="PDCP Studio's own arbitrator memory (sim: and can: buses)")
    add_archive_argument(verify)
    verify.set_defaults(func=run_verify)
    from pdcp_studio.cli.live import history_reanchor

    history_reanchor.add_parser(actions)
    export = actions.add_parser("export", help="the archive as JSON lines, hashes included")
    export.add_argument("-o", "--output", metavar="FILE", type=options.file_name,
                        help="the file to write (default: standard output)")
    add_archive_argument(export)
    export.set_defaults(func=run_export)
    imp = actions.add_parser("import", help="append an export to this archive, each entry "
                                            "keeping its origin")
    imp.add_argument("file", metavar="FILE", help="a file `history export` wrote")
    add_archive_argument(imp)
    imp.set_defaults(func=run_import)


def _entry_id(text: str) -> int:
    """An entry ID as typed: a whole number an archive can hold (1 … 2⁶³−1); else exit 2."""
    from pdcp_studio.storage.archive.rows import MAX_ID

    try:
        value = int(text, 10)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text[:40]!r}: an entry ID is a whole number, "
                                         "e.g. 12 (see `history list`)") from None
    if not 1 <= value <= MAX_ID:
        raise argparse.ArgumentTypeError(f"{text[:40]}: no entry can have this ID (IDs run "
                                         f"from 1 to {MAX_ID})")
    return value


def _part(text: str) -> tuple[int, int, int]:
    parts = text.split("/")
    try:
        vid, pid, serial = (int(p, 0) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r}: a part is VID/PID/SERIAL, e.g. 2641/769/301") from None
    return vid, pid, serial


def _open(args: argparse.Namespace) -> Archive | None:
    """The archive, with the changes of PCs that died mid-way (and outcomes this workstation
    kept while the server was away) recorded; None when there is none yet (a read command
    creates no file). An archive that cannot be opened is the user's to fix (exit 2)."""
    from pdcp_studio.storage.archive import HistoryError, open_existing

    try:
        history = open_existing(getattr(args, "archive", None))
        if history is not None:
            history.recover()
    except HistoryError as err:
        raise BadInput(str(err)) from err
    return history


def _where(args: argparse.Namespace) -> str:
    from pdcp_studio.storage.archive import HistoryError, describe

    try:
        return describe(getattr(args, "archive", None))
    except HistoryError as err:
        raise BadInput(str(err)) from err


def _entries(args: argparse.Namespace) -> list[Entry]:
    from pdcp_studio.storage.archive import EntryFilter

    history = _open(args)
    if history is None:
        return []
    where = EntryFilter(patient=getattr(args, "patient", None),
                        device=getattr(args, "prosthesis", None))
    from pdcp_studio.storage.archive.rows import check_entry

    with history:
        return [check_entry(e) for e in history.entries(where)]


def _entry(args: argparse.Namespace, entry_id: int) -> Entry:
    history = _open(args)
    if history is None:
        raise BadInput(f"history: no entry {entry_id}: there is no fitting history at "
                       f"{_where(args)} yet")
    with history:
        entry = history.get(entry_id)
    if entry is None:
        raise BadInput(f"history: no entry {entry_id} in {history.location}")
    from pdcp_studio.storage.archive.rows import check_entry

    return check_entry(entry)  # a damaged entry is exit 1 naming it, never a traceback


def _crc_text(before: str | None, after: str | None) -> str:
    """The stored configuration's CRC before → after; an entry may not have recorded them
    (a change that never read the stored configuration)."""
    if before is None and after is None:
        return "not recorded"
    return f"{before or 'not recorded'} → {after or 'not recorded'}"


def _words(e: Entry) -> str:
    """The change in words: the first lines of its effect (entries recorded before the
    effect was kept say only the action)."""
    text = [ln for ln in ((e.get("effect") or {}).get("text") or [])
            if not ln.startswith(("Stored configuration: unchanged", "While the change",
                                  "No part needs", " "))]
    if not text:
        return str(e["action"])
    more = f" (+{len(text) - 2} more)" if len(text) > 2 else ""
    return "; ".join(text[:2]) + more


def _line(e: Entry) -> str:
    outcome = (e.get("outcome") or {}).get("status", "")
    return shown(f"{e['id']:>4}  {e['time']}  {e['operator']}  {_words(e)}  on {e['bus']}  "
            f"{len(e['links_before'])}→"
            f"{'?' if e['links_after'] is None else len(e['links_after'])} link(s)  "
            f"{'verified' if e['verified'] else 'not verified'}  {outcome}  "
            f"interlock: {e['interlock'] or 'none'}"
            + (f"  patient: {e['patient']}" if e.get("patient") else "")
            + (f"  workstation: {e['workstation']}" if e.get("workstation") else "")
            + (f"  (imported: entry {e['origin'].get('id')} of {e['origin'].get('archive')})"
               if isinstance(e.get("origin"), dict) else ""))


def run_list(args: argparse.Namespace) -> int:
    from pdcp_studio.storage.history import list_json

    entries = _entries(args)
    if args.json:
        print(json.dumps({"entries": [list_json(e) for e in entries]}, indent=2))
        return 0
    if not entries:
        print("no entry matches" if args.patient or args.prosthesis
              else "the fitting history is empty")
    for e in entries:
        print(_line(e))
    return 0


def _links_text(links: list[dict[str, Any]]) -> list[str]:
    def ref(d: dict[str, Any]) -> str:
        return f"{d['vid']}/{d['pid']}/{d['serial']}#{d['index']}"

    return [f"    {ref(lk['output'])} → {ref(lk['input'])}" for lk in links] or ["    none"]


def run_show(args: argparse.Namespace) -> int:
    e = _entry(args, args.id)
    if args.json:
        print(json.dumps(e, indent=2))
        return 0
    outcome = e.get("outcome") or {}
    print(_line(e))
    effect, power_on = e.get("effect"), e.get("next_power_on")
    if effect:
        print("  what it did:")
        print("\n".join(f"    {shown(ln)}" for ln in effect.get("text", [])))
    if power_on:
        print("\n".join(f"  {shown(ln)}" for ln in power_on.get("text", [])))
    if not effect:
        print("  (recorded before PDCP Studio kept a change's effect in words)")
    print("  technical detail:")
    print(f"    action: {shown(str(e['action']))}")
    for ln in (effect or {}).get("technical", []):
        print(f"    {shown(ln)}")
    print(shown(f"  outcome: {outcome.get('status', '')}"
                + (f" at step {outcome['step']}: {outcome['reason']}" if outcome.get("reason")
                   else "")))
    print("  devices: " + ", ".join(f"{d['vid']}/{d['pid']}/{d['serial']}"
                                    for d in e["devices"]))
    print("  stored configuration CRC: "
          + _crc_text(e.get("config_crc_before"), e.get("config_crc_after")))
    print("  links before:")
    print("\n".join(_links_text(e["links_before"])))
    print("  links after:")
    print("\n".join(_links_text(e["links_after"]) if e["links_after"] is not None
                    else ["    unknown (the change was interrupted)"]))
    actions = (e.get("plan") or {}).get("actions", [])
    if actions:
        print("  plan:")
        for a in actions:
            lk = {"output": a["output"], "input": a["input"]}
            print(shown(f"    {a['op']}{_links_text([lk])[0][3:]}  ({a.get('reason', '')})"))
    print(f"  hash: {e['hash']}")
    return 0


def run_restore(args: argparse.Namespace) -> int:
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.bus.transaction import NotRestorable, restore_change
    from pdcp_studio.cli.live.change_road import carry_out
    from pdcp_studio.cli.live.scan import open_bus_session

    check_bus_url(args.bus)  # a bad --bus is the same line from every command, checked first
    entry = _entry(args, args.id)
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        system = session.system()
        try:
            change = restore_change(entry, system)
        except NotRestorable as err:
            if not err.missing:
                raise BadInput(str(err)) from err
            _refuse_missing(entry, system, err.missing, args.bus)
            return 1
        if args.store is False:  # --no-store: the stored configuration stays as it is
            change.configuration = None
        return carry_out(session, change, args, default_store=False)
    finally:
        session.close()


def _refuse_missing(entry: Entry, system: System, missing: list[DeviceKey], bus: str) -> None:
    """Say which parts a restore needs and lacks, and what a replacement would do."""
    import sys

    from pdcp_studio.bus.transaction import link_from_json
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.engine.modes import plan_replacements
    from pdcp_studio.model.names import Names

    names = Names(system)
    print(f"pdcp-studio: history restore {entry['id']}: refused, nothing was written: it needs "
          + ", ".join(f"{names.part(k)} [{k}]" for k in missing)
          + ", which " + ("is" if len(missing) == 1 else "are") + " not on the bus.",
          file=sys.stderr)
    wanted = system.copy()
    for link in list(wanted.links):
        wanted.remove_link(link)
    links = [link_from_json(d) for d in entry.get("links_after") or []]
    for link in links:
        if wanted.channel(link.output) is not None and wanted.channel(link.input) is not None:
            wanted.add_link(link, check=False)
    plan = plan_replacements(system, configuration_from_system(wanted))
    if plan.added:
        print("The replacement plan would instead make:", file=sys.stderr)
        for a in plan.added:
            print(f"  {names.link(a.link)}  ({a.reason})", file=sys.stderr)
        print(f"Carry it out with: pdcp-studio apply replacements --bus {bus}", file=sys.stderr)
    else:
        print("No part on the bus can take its place; plug it in and try again.",
              file=sys.stderr)


def run_verify(args: argparse.Namespace) -> int:
    import sys

    history = _open(args)
    anchor, parts = _prosthesis_anchor(args) if getattr(args, "bus", None) else (None, set())
    if history is None:
        if anchor is not None and (anchor.entry or anchor.announced):
            print(f"pdcp-studio: {_where(args)}: there is no fitting history, but the "
                  f"prosthesis on {shown(args.bus)} remembers {anchor.text()}: this is not "
                  "the archive that recorded its changes (or it was removed)", file=sys.stderr)
            return 1
        print(f"{_where(args)}: no fitting history yet (0 entries), nothing to check")
        return 0
    from pdcp_studio.storage.archive.anchor import anchor_problem
    from pdcp_studio.storage.archive.base import HistoryError

    with history:
        report = history.verify()
        path = history.location
        problem = None
        if report.ok and args.bus:
            try:
                problem = anchor_problem(history.entries(), anchor, parts)
            except HistoryError as err:
                problem = str(err)
    if not report.ok:
        print(f"pdcp-studio: {shown(path)}: entry {report.first_bad} is not intact: "
              f"{shown(report.reason)}", file=sys.stderr)
        return 1
    if problem:
        print(f"pdcp-studio: {shown(path)} does not match the prosthesis on "
              f"{shown(args.bus)}: {shown(problem)}", file=sys.stderr)
        return 1
    print(f"{shown(path)}: {report.entries} entr{'y' if report.entries == 1 else 'ies'}, "
          "the chain is intact")
    if args.bus:
        print(f"the prosthesis on {shown(args.bus)} remembers "
              + (anchor.text() if anchor is not None else
                 "no fitting history anchor (its arbitrator keeps none)")
              + (": it is the archive's last entry for it" if anchor and anchor.entry else ""))
    return 0


def _prosthesis_anchor(args: argparse.Namespace) -> tuple[Any, set[tuple[int, int, int]]]:
    """The anchor the prosthesis on ``--bus`` keeps, and its parts (VID, PID, serial)."""
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.cli.live.scan import open_bus_session

    check_bus_url(args.bus)
    session = open_bus_session(args.bus, memory=args.memory)
    try:
        anchor = session.read_anchor()
        parts = {(k.vid, k.pid, k.serial) for k, d in session.system().devices.items()
                 if d.present}
    finally:
        session.close()
    return anchor, parts


def run_export(args: argparse.Namespace) -> int:
    """The archive as JSON lines; a file is replaced only once it is written whole."""
    import os
    import sys

    from pdcp_studio.storage.archive.transfer import export_lines

    history = _open(args)
    lines: list[str] = []
    if history is not None:
        with history:
            lines = list(export_lines(history))
    text = "".join(f"{line}\n" for line in lines)
    if not args.output:
        sys.stdout.write(text)
        return 0
    temporary = f"{args.output}.part"
    try:
        with open(temporary, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(temporary, args.output)
    except OSError as err:
        raise BadInput(f"{args.output}: cannot write: {err.strerror or err}") from err
    print(f"{len(lines)} entr{'y' if len(lines) == 1 else 'ies'} of {_where(args)} written to "
          f"{args.output}", file=sys.stderr)
    return 0


def run_import(args: argparse.Namespace) -> int:
    """Append an export to the archive in use; refused whole when it does not verify."""
    import sys

    from pdcp_studio.storage.archive import HistoryError, open_archive
    from pdcp_studio.storage.archive.transfer import import_entries, read_lines

    try:
        with open(args.file, encoding="utf-8") as f:
            entries = read_lines(f, args.file)
    except OSError as err:
        raise BadInput(f"{args.file}: cannot read: {err.strerror or err}") from err
    except HistoryError as err:
        raise BadInput(str(err)) from err
    try:
        with open_archive(getattr(args, "archive", None)) as archive:
            report = import_entries(archive, entries, source=Path(args.file).name)
            where = archive.location
    except HistoryError as err:
        print(f"pdcp-studio: history import: {shown(str(err))}", file=sys.stderr)
        return 1
    ids = report.imported
    print(f"{len(ids)} entr{'y' if len(ids) == 1 else 'ies'} imported into {shown(where)}"
          + (f" as {ids[0]}…{ids[-1]}" if ids else "")
          + (f"; {report.skipped} already there" if report.skipped else ""))
    return 0
