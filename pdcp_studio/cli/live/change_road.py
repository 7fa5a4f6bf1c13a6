"""The CLI's side of the change road (reference §5), shared by every command that changes a
prosthesis: ``apply MODE --bus``, ``config save``, ``config write``, ``policy``,
``history restore``.

The preview is printed first. Without ``--yes`` nothing is written: on a terminal (stdin and
stdout both) the user is asked ``apply? [y/N]``; with no terminal, or with ``--json``, nobody is
asked and the command exits 0 having written nothing. With ``--yes`` (or a "y") the session
carries the change out as one transaction and records it in the fitting history.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pdcp_studio.model.safe_text import shown

if TYPE_CHECKING:
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.bus.session.change_road import ChangePreview
    from pdcp_studio.bus.transaction import Change, TransactionResult

#: A command's JSON document for a preview and, once carried out, the transaction's result.
JsonDoc = Callable[["ChangePreview", "TransactionResult | None"], dict[str, Any]]

EXIT_OK = 0
EXIT_FAILED = 1


def add_archive_argument(p: argparse.ArgumentParser) -> None:
    """``--archive URL``: the fitting history a command records in or reads (contracts §2)."""
    p.add_argument("--archive", metavar="URL",
                   help="the fitting history: sqlite:///PATH or "
                        "postgresql://USER@HOST[:PORT]/DB (default: $PDCP_STUDIO_ARCHIVE, "
                        "else the file in your data folder)")


def add_road_arguments(p: argparse.ArgumentParser, *, json_flag: bool = True,
                       store: bool = True) -> None:
    """``--yes``, ``--patient``, ``--archive``, (optionally) ``--store``/``--no-store`` and
    ``--json`` for a command that changes a prosthesis."""
    add_archive_argument(p)
    p.add_argument("--yes", action="store_true",
                   help="carry the change out (without it, only the preview is printed)")
    if store:
        group = p.add_mutually_exclusive_group()
        group.add_argument("--store", dest="store", action="store_true", default=None,
                           help="also store the links after the change as the arbitrator's "
                                "configuration, in the same transaction, so the next "
                                "power-on keeps them (the default for apply, param set and "
                                "policy)")
        group.add_argument("--no-store", dest="store", action="store_false",
                           help="leave the stored configuration as it is (the preview says "
                                "what the next power-on will then undo)")
    p.add_argument("--patient", metavar="REF",
                   help="the patient reference to record with the change (free text)")
    if json_flag:
        p.add_argument("--json", action="store_true",
                       help="print one JSON document (preview and transaction result)")


def ask(question: str) -> bool:
    """Ask on the terminal; only when both stdin and stdout are terminals."""
    if not (sys.stdin.isatty() and sys.stdout.isatty()):
        return False
    try:
        answer = input(f"{question} [y/N] ")
    except EOFError:
        return False
    return answer.strip().lower() in ("y", "yes")


def carry_out(session: BusSession, change: Change, args: argparse.Namespace, *,
              json_doc: JsonDoc | None = None, default_store: bool = True) -> int:
    """Preview ``change`` on ``session``, confirm it (``--yes`` or the terminal), transact,
    print the outcome. Returns the exit status.

    ``--store``/``--no-store`` (``args.store``; ``default_store`` when neither is given)
    decides whether the links after the change become the stored configuration in the same
    transaction. The preview says what the change does and what the next power-on does, in
    words; the codes come last, under "Technical detail".
    """
    from pdcp_studio.bus.session.api import preview_change

    store = getattr(args, "store", None)
    change.store = default_store if store is None else bool(store)
    want_json = bool(getattr(args, "json", False))
    preview = preview_change(session, change)
    change = preview.change
    if not want_json:
        for line in preview.lines():
            print(shown(line))
    if preview.empty:
        if want_json:
            print(json.dumps(_doc(json_doc, preview, None), indent=2))
        else:
            print("nothing to change: nothing written")
        return EXIT_OK
    go = bool(args.yes) or (not want_json and ask("apply?"))
    if not go:
        if want_json:
            print(json.dumps(_doc(json_doc, preview, None), indent=2))
        else:
            print(f"not written to {session.url}: add --yes to carry it out", file=sys.stderr)
        return EXIT_OK
    result = _transact(session, change, args, preview)
    if want_json:
        print(json.dumps(_doc(json_doc, preview, result), indent=2))
    else:
        print(shown(result.summary(), newlines=True))
        if result.history_id is not None:
            print(f"recorded as fitting history entry {result.history_id}")
        for note in result.notes:
            print(shown(f"note: {note}"))
    if not result.ok:
        if not want_json:
            print(f"pdcp-studio: error: {shown(result.summary(), newlines=True)}",
                  file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _transact(session: BusSession, change: Change, args: argparse.Namespace,
              preview: ChangePreview) -> TransactionResult:
    """The transaction, recorded in the archive ``--archive`` names (else the default); an
    archive that cannot be opened (a server down, a wrong URL) refuses the change before
    anything is written, in words."""
    from pdcp_studio.bus.transaction import Status, TransactionResult
    from pdcp_studio.storage.archive import HistoryError, open_archive

    try:
        archive = open_archive(getattr(args, "archive", None))
    except HistoryError as err:
        return TransactionResult(Status.FAILED, change.action, "record",
                                 f"the fitting history cannot be written ({err}); nothing "
                                 "was written to the prosthesis",
                                 preview.links_before, preview.links_before,
                                 devices=preview.devices)
    with archive:
        return session.transact(change, patient=getattr(args, "patient", None),
                                history=archive)


def _doc(json_doc: JsonDoc | None, preview: ChangePreview,
         result: TransactionResult | None) -> dict[str, Any]:
    doc = json_doc(preview, result) if json_doc is not None else {}
    if preview.effect is not None:
        doc["effect"] = preview.effect.to_json()
        doc["next_power_on"] = preview.effect.power_on_json()
    doc["store"] = preview.change.store
    doc.setdefault("action", preview.change.action)
    doc.setdefault("bus", preview.url)
    doc["written"] = bool(result is not None and result.written)
    doc["transaction"] = result.to_json() if result is not None else None
    return doc
