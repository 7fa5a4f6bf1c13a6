"""Changes to the connected prosthesis from the app: preview → confirm → one transaction.

Every change the app makes to a prosthesis — Write to prosthesis (the pending changes),
undoing or redoing a written change, restoring a history entry — is a
:class:`~pdcp_studio.bus.transaction.Change` carried out by the session's one road
(``session.transact``: interlock, write, read back, restore on mismatch, release, record in
the fitting history). The preview is computed on the bridge's worker from the prosthesis as
it is now, shown in :class:`ConfirmDialog`, and only a confirmed change is written; the
transaction then runs on the worker with progress and Cancel. If the prosthesis changed
between the preview and the write, the transaction is declined (nothing written).

Undo: a successful write pushes :class:`WrittenCommand` on the document's undo stack. Undoing
it is a new transaction (previewed, confirmed) that writes the prosthesis back as it was
before that write, then steps the project back over the edits it wrote; redoing it writes
them again. Bus I/O never runs on the GUI thread.
"""

from __future__ import annotations

import copy
import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, Qt, Signal
from PySide6.QtGui import QUndoCommand
from PySide6.QtWidgets import QProgressDialog, QWidget

from pdcp_studio.app.dialogs.confirm_change import ConfirmDialog
from pdcp_studio.app.documents import fitting, pending
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.app.words.outcome_words import outcome_words
from pdcp_studio.app.words.plural import count
from pdcp_studio.model.system import System

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

log = logging.getLogger(__name__)


class WrittenCommand(QUndoCommand):
    """A marker on the undo stack: the edits from ``first_index`` up to here were written
    to the prosthesis (``bus_before`` is the prosthesis before the write). It changes nothing
    in the document itself; the flow turns its undo and redo into transactions."""

    def __init__(self, first_index: int, bus_before: System, result: Any, text: str) -> None:
        super().__init__(text)
        self.first_index = first_index
        self.bus_before = bus_before
        self.result = result

    def redo(self) -> None:  # the transaction did the work: nothing to do in the project
        pass

    def undo(self) -> None:
        pass


def with_store(change: Any, on: bool) -> Any:
    """``change`` storing (or not) the links after it as the prosthesis's configuration."""
    chosen = copy.copy(change)
    chosen.store = on
    return chosen


def preview_in_words(session: Any, change: Any) -> Any:
    """The preview of ``change``, its effect naming parts and channels in the user's
    language (runs on the bridge's worker)."""
    from pdcp_studio.app.words.effect_words import app_names
    from pdcp_studio.bus.session.api import preview_change

    return preview_change(session, change, names=app_names(session.system()))


class TransactionFlow(QObject):
    """Runs the app's changes to the prosthesis (see the module docstring).

    It gets the document, the live connection, the status line, a parent for its dialogs,
    ``reread_configuration()`` (after a transaction) and ``patient_reference()`` (recorded
    with it). Signals: ``previewed(ChangePreview)``, ``finished(TransactionResult)`` (any
    outcome), ``busyChanged(bool)``.
    """

    previewed = Signal(object)
    finished = Signal(object)
    busyChanged = Signal(bool)

    def __init__(self, doc: Document, live: LiveController, status: StatusLine,
                 parent: QWidget, *, reread_configuration: Callable[[], None],
                 patient_reference: Callable[[], str]) -> None:
        super().__init__(parent)
        self.doc = doc
        self.live = live
        self.status = status
        self.parent_widget = parent
        self._reread_configuration = reread_configuration
        self._patient_reference = patient_reference
        self.busy = False
        self.last_result: Any = None
        self.progress_dialog: QProgressDialog | None = None
        #: Set to cancel the running transaction (the progress dialog's Cancel does).
        self.cancel_event: threading.Event | None = None
        #: ``confirm(title, preview) -> bool`` replaces the dialog (tests).
        self.confirm: Callable[[str, Any], bool] | None = None
        #: The confirmation on screen (None when none is).
        self.dialog: ConfirmDialog | None = None

    # -- entry points --------------------------------------------------------------------
    def write_pending(self) -> bool:
        """Write every pending change in one transaction (after the preview); False if
        there is nothing to write or no prosthesis."""
        doc = self.doc
        changes = pending.pending_changes(doc.bus_system, doc.system, doc.link_reasons)
        if not changes or self._bridge() is None:
            self.status.say(self.tr("Nothing to write: the project and the "
                                             "prosthesis agree"))
            return False
        change = pending.change_for(changes, doc.system)
        first = self._first_unwritten_index()
        bus_before = doc.bus_system.copy() if doc.bus_system is not None else System()

        def done(result: Any) -> None:
            if result.written:
                text = count("TransactionFlow", "Write to prosthesis (%n change(s))",
                             len(changes))
                doc.undo_stack.push(WrittenCommand(first, bus_before, result, text))
        return self.run(change, self.tr("Write to prosthesis"), done, store=True)

    def undo(self) -> None:
        """Undo; a written change is undone on the prosthesis by a new transaction."""
        stack = self.doc.undo_stack
        cmd = stack.command(stack.index() - 1) if stack.canUndo() else None
        if not isinstance(cmd, WrittenCommand) or self._bridge() is None:
            stack.undo()
            return
        bus_now = self.doc.bus_system or System()
        back = pending.pending_changes(bus_now, cmd.bus_before)
        if not back:
            stack.setIndex(cmd.first_index)
            return
        change = pending.change_for(back, cmd.bus_before, action=f"undo {cmd.text().lower()}",
                                    reason=f"undo: as before “{cmd.text()}”")

        def done(result: Any) -> None:
            if result.ok and stack.index() > cmd.first_index:
                stack.setIndex(cmd.first_index)  # the project steps back over those edits
        self.run(change, self.tr("Undo on the prosthesis: {0}").format(cmd.text()), done,
                 store=True)

    def redo(self) -> None:
        """Redo; redoing a written change writes it again (a new transaction)."""
        stack = self.doc.undo_stack
        cmd = stack.command(stack.index()) if stack.canRedo() else None
        if not isinstance(cmd, WrittenCommand) or self._bridge() is None:
            stack.redo()
            return
        doc = self.doc
        changes = pending.pending_changes(doc.bus_system, doc.system, doc.link_reasons)
        if not changes:
            stack.redo()
            return
        cmd.bus_before = doc.bus_system.copy() if doc.bus_system is not None else System()
        change = pending.change_for(changes, doc.system, action="redo write to prosthesis")

        def done(result: Any) -> None:
            if result.written and stack.command(stack.index()) is cmd:
                cmd.result = result
                stack.redo()
        self.run(change, self.tr("Redo on the prosthesis: {0}").format(cmd.text()), done,
                 store=True)

    # -- the road ------------------------------------------------------------------------
    def run(self, change: Any, title: str,
            on_result: Callable[[Any], None] | None = None, *, store: bool | None = None,
            choose: Callable[[Any, bool], Any] = with_store) -> bool:
        """Preview ``change`` on the worker, ask, then carry it out as one transaction.

        ``store`` None offers no store box (a policy, a configuration written whole);
        True/False offers it, checked or not, and ``choose(change, on)`` is the change the
        box asks for (default: :func:`with_store`; a restore keeps or leaves the stored
        configuration it recorded)."""
        bridge = self._bridge()
        if bridge is None:
            self.status.error(title, self.tr("not connected to a prosthesis"))
            return False
        if self.busy:
            self.status.say(self.tr("A change to the prosthesis is still running"))
            return False
        original = change
        if store is not None:
            change = choose(original, store)
        session = bridge.session
        self._set_busy(True)
        worker = bridge.run(lambda _p, _c: preview_in_words(session, change),
                            self.tr("Preview the change"))
        if worker is None:
            self._set_busy(False)
            return False
        worker.finished.connect(lambda preview: self._previewed(
            bridge, change, title, preview, on_result, store,
            lambda on: choose(original, on)))
        worker.failed.connect(lambda msg: self._failed(title, msg))
        worker.cancelled.connect(lambda: self._set_busy(False))
        return True

    def _previewed(self, bridge: SessionBridge, change: Any, title: str, preview: Any,
                   on_result: Callable[[Any], None] | None, store: bool | None,
                   choose: Callable[[bool], Any]) -> None:
        self.previewed.emit(preview)
        if bridge is not self._bridge():
            self._set_busy(False)
            return
        if preview.empty and store is None:
            self._set_busy(False)
            self.status.say(self.tr("{0}: nothing to change on the prosthesis")
                                     .format(title))
            self.live.refresh()
            return
        if self.confirm is not None:  # tests answer without the dialog
            if self.confirm(title, preview):
                self._transact(bridge, change, title, preview, on_result)
            else:
                self._declined(title)
            return
        self._ask(bridge, change, title, preview, on_result, store, choose)

    def _ask(self, bridge: SessionBridge, change: Any, title: str, preview: Any,
             on_result: Callable[[Any], None] | None, store: bool | None,
             choose: Callable[[bool], Any]) -> None:
        """The confirmation (window-modal, not a nested event loop): the store box
        previews the change again; Write carries out the change last previewed."""
        dialog = ConfirmDialog(title, preview, self.parent_widget, store=store)
        self.dialog = dialog
        shown = {"change": change}
        session = bridge.session

        def store_toggled(on: bool) -> None:
            variant = choose(on)
            worker = bridge.run(lambda _p, _c: preview_in_words(session, variant),
                                self.tr("Preview the change"))
            if worker is None:
                dialog.preview_failed(self.tr("not connected to a prosthesis"))
                return

            def got(new: Any) -> None:
                if self.dialog is dialog:
                    shown["change"] = variant
                    dialog.set_preview(new)
                    self.previewed.emit(new)
            worker.finished.connect(got)
            worker.failed.connect(dialog.preview_failed)

        def finished(code: int) -> None:
            self.dialog = None
            dialog.deleteLater()
            if code != ConfirmDialog.DialogCode.Accepted:
                self._declined(title)
            elif dialog.preview.empty:
                self._set_busy(False)
                self.status.say(self.tr("{0}: nothing to change on the prosthesis")
                                .format(title))
            else:
                self._transact(bridge, shown["change"], title, dialog.preview, on_result)

        dialog.storeToggled.connect(store_toggled)
        dialog.finished.connect(finished)
        dialog.setWindowModality(Qt.WindowModality.WindowModal)
        dialog.show()

    def _declined(self, title: str) -> None:
        self._set_busy(False)
        self.status.say(self.tr("{0}: not confirmed, nothing written").format(title))

    def _transact(self, bridge: SessionBridge, change: Any, title: str, preview: Any,
                  on_result: Callable[[Any], None] | None) -> None:
        """Carry out the confirmed ``change`` (the one ``preview`` showed) on the worker."""
        if bridge is not self._bridge():
            self._set_busy(False)
            return
        operator = fitting.operator_name(self.parent_widget)
        patient = self._patient_reference()
        shown = set(preview.links_before)

        def same_bus(p: Any) -> bool:  # the prosthesis must still be as previewed
            return set(p.links_before) == shown

        session = bridge.session
        # Its own cancel event: a cancelled transaction still reports what it did (rolled
        # back…), which a cancelled worker would drop.
        stop = threading.Event()
        worker = bridge.run(
            lambda prog, _cancel: session.transact(
                change, operator=operator or None, patient=patient or None,
                confirm=same_bus, progress=prog, cancel=stop),
            title)
        if worker is None:
            self._set_busy(False)
            return
        self.cancel_event = stop
        self._show_progress(title, worker, stop)
        worker.finished.connect(lambda result: self._done(title, result, on_result))
        worker.failed.connect(lambda msg: self._failed(title, msg))
        worker.cancelled.connect(lambda: self._cancelled(title))

    def _show_progress(self, title: str, worker: Any, stop: threading.Event) -> None:
        dialog = QProgressDialog(self.tr("Writing to the prosthesis…"), self.tr("Cancel"), 0, 0,
                                 self.parent_widget)
        dialog.setWindowTitle(title)
        dialog.setWindowModality(Qt.WindowModality.WindowModal)
        dialog.setMinimumDuration(300)
        dialog.setAutoClose(False)
        dialog.setAutoReset(False)

        def on_progress(done: int, total: int, text: str) -> None:
            if total > 0:
                dialog.setMaximum(total)
                dialog.setValue(min(done, total))
            if text:
                dialog.setLabelText(text)

        def on_cancel() -> None:
            dialog.setLabelText(self.tr("Cancelling… (the prosthesis is put back as it was)"))
            stop.set()

        worker.progress.connect(on_progress)
        dialog.canceled.connect(on_cancel)
        worker.done.connect(dialog.close)
        worker.done.connect(dialog.deleteLater)
        self.progress_dialog = dialog

    def _close_progress(self) -> None:
        """Close the progress dialog before anything is said: an error shown under it would
        be hidden (the worker's ``done``, which also closes it, comes after the outcome)."""
        dialog, self.progress_dialog = self.progress_dialog, None
        if dialog is not None:
            dialog.close()

    def _done(self, title: str, result: Any, on_result: Callable[[Any], None] | None) -> None:
        self._close_progress()
        self._set_busy(False)
        self.last_result = result
        if on_result is not None:
            on_result(result)
        status = getattr(result.status, "value", str(result.status))
        if result.ok:
            self.status.say(outcome_words(result, title))
        elif status == "declined":
            self.status.error(title, self.tr(
                "The prosthesis changed after the preview, so nothing was written. "
                "Look at the pending changes again and write them."))
        else:
            self.status.error(title, self.tr("{0}\nThe prosthesis is as it was before.")
                                  .format(outcome_words(result, title)))
        for note in getattr(result, "notes", ()):
            log.info("%s: %s", title, note)
        # The prosthesis and its stored configuration as they are now (previews use them).
        self.live.refresh()
        self._reread_configuration()
        self.finished.emit(result)

    def _failed(self, title: str, message: str) -> None:
        self._close_progress()
        self._set_busy(False)
        self.status.error(title, message)
        self.live.refresh()

    def _cancelled(self, title: str) -> None:
        self._close_progress()
        self._set_busy(False)
        self.status.say(self.tr("{0}: cancelled").format(title))
        self.live.refresh()

    # -- helpers -------------------------------------------------------------------------
    def _set_busy(self, busy: bool) -> None:
        if busy != self.busy:
            self.busy = busy
            self.busyChanged.emit(busy)

    def _bridge(self) -> Any:
        bridge = self.live.bridge
        return bridge if bridge is not None and self.doc.session is bridge else None

    def _first_unwritten_index(self) -> int:
        """The undo-stack index just after the last write (where this write's edits start)."""
        stack = self.doc.undo_stack
        for i in range(stack.index() - 1, -1, -1):
            if isinstance(stack.command(i), WrittenCommand):
                return i + 1
        return 0
