"""The main window's side of the change road: pending changes, writing, history.

Kept apart from :mod:`main_window`: the Pending changes and History docks, the Write to
prosthesis and Discard actions, Undo/Redo that turn a written change into a transaction
(:mod:`pdcp_studio.app.window.transaction_flow`), and the patient reference of the connected
prosthesis (:mod:`pdcp_studio.app.documents.fitting`).
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QCoreApplication, Qt, QTimer
from PySide6.QtGui import QAction, QKeySequence

from pdcp_studio.app.docks.history_panel import HistoryPanel
from pdcp_studio.app.docks.pending_panel import PendingPanel
from pdcp_studio.app.documents import commands, fitting, pending
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.transaction_flow import TransactionFlow
from pdcp_studio.app.words.plural import count

#: A new window reads the fitting history this long after it is live.
HISTORY_AFTER_MS = 100


def _tr(text: str) -> str:
    return QCoreApplication.translate("MainWindow", text)


class TransactionsMixin:
    """Builds ``flow``, ``pending_panel``/``pending_dock``, ``history_panel``/``history_dock``,
    ``act_write_pending``, ``act_discard_pending``, ``act_history``."""

    def _build_transactions(self) -> None:
        self.flow = TransactionFlow(self)
        self.pending_panel = PendingPanel(self.doc)
        self.pending_dock = self._dock(translate("MainWindow", "Pending changes"), "PendingDock",
                                       self.pending_panel,
                                       Qt.DockWidgetArea.BottomDockWidgetArea)
        self.tabifyDockWidget(self.plan_dock, self.pending_dock)
        self.history_panel = HistoryPanel(self)
        self.history_dock = self._dock(translate("MainWindow", "Fitting history"), "HistoryDock",
                                       self.history_panel,
                                       Qt.DockWidgetArea.BottomDockWidgetArea)
        self.tabifyDockWidget(self.plan_dock, self.history_dock)
        self.plan_dock.raise_()
        self.pending_panel.writeRequested.connect(self.write_pending)
        self.pending_panel.discardRequested.connect(self.discard_pending)
        self.pending_panel.patientChanged.connect(self.set_patient_reference)
        self.flow.finished.connect(lambda _r: self.history_panel.refresh())
        self.live.sessionStarted.connect(lambda _b: self._load_patient_reference())

        self.act_write_pending = QAction(translate("MainWindow", "&Write to prosthesis…"), self)
        self.act_write_pending.setShortcut(QKeySequence("Ctrl+Shift+W"))
        self.act_write_pending.setStatusTip(
            translate(
                "MainWindow",
                "Show the pending changes' difference and write them in one transaction",
            )
        )
        self.act_write_pending.triggered.connect(lambda _c=False: self.write_pending())
        self.act_discard_pending = QAction(
            translate("MainWindow", "&Discard pending changes"), self
        )
        self.act_discard_pending.triggered.connect(lambda _c=False: self.discard_pending())
        self.act_disconnect.triggered.disconnect()
        self.act_disconnect.triggered.connect(lambda _c=False: self.disconnect_asking())
        self.act_history = self.history_dock.toggleViewAction()
        self.act_history.setText(translate("MainWindow", "Fitting &history"))
        first = self.bus_menu.actions()[0] if self.bus_menu.actions() else None
        self.bus_menu.insertAction(first, self.act_write_pending)
        self.bus_menu.insertAction(first, self.act_discard_pending)
        self.bus_menu.insertSeparator(first)
        self.view_menu.addAction(self.pending_dock.toggleViewAction())
        self.view_menu.addAction(self.act_history)
        # Undo and Redo: a written change is undone on the prosthesis by a transaction.
        for action, slot in ((self.act_undo, self.flow.undo), (self.act_redo, self.flow.redo)):
            action.triggered.disconnect()
            action.triggered.connect(lambda _c=False, s=slot: s())
        self.pending_panel.changed.connect(self._update_write_actions)
        self.live.sessionStarted.connect(lambda _b: self._note_session_start())
        self._session_start = ""
        self._update_write_actions()

    def _update_write_actions(self) -> None:
        """Follows the Pending changes panel (it lists them again after every change)."""
        has = bool(self.pending_panel.changes) and self.doc.bus_system is not None
        self.act_write_pending.setEnabled(has)
        self.act_discard_pending.setEnabled(has)

    # -- writing -------------------------------------------------------------------------
    def write_pending(self) -> bool:
        """Write every pending change to the prosthesis (preview, confirm, one transaction)."""
        self.pending_dock.show()
        self.pending_dock.raise_()
        return self.flow.write_pending()

    def discard_pending(self) -> int:
        """Put the project back as the prosthesis is (one undo step); how many changes."""
        doc = self.doc
        changes = pending.pending_changes(doc.bus_system, doc.system, doc.link_reasons)
        if not changes:
            return 0
        stack = doc.undo_stack
        stack.beginMacro(
            count("MainWindow", "Discard %n pending change(s)", len(changes))
        )
        try:
            links = [c for c in changes if c.link is not None]
            if links:
                stack.push(commands.LinksCommand(
                    doc, [commands._action(pending.ADD if c.kind == pending.REMOVE
                                           else pending.REMOVE, c.link,
                                           "as on the prosthesis") for c in links],
                    translate("MainWindow", "Links as on the prosthesis")))
            for c in changes:
                if c.kind != pending.PARAMETER or c.key is None:
                    continue
                if c.index:
                    stack.push(commands.SetChannelFieldCommand(doc, c.ref, c.field, c.old))
                else:
                    stack.push(commands.SetDeviceFieldCommand(doc, c.key, c.field, c.old))
        finally:
            stack.endMacro()
        self.show_message(
            count(
                "MainWindow",
                "Discarded %n pending change(s): the project is as the "
                "prosthesis (Undo brings them back)",
                len(changes),
            )
        )
        return len(changes)

    def confirm_unwritten(self) -> bool:
        """Before leaving a live prosthesis (closing, disconnecting): True when no pending
        change would be lost unwritten, or the user chose to leave them."""
        n = len(self.pending_panel.changes) if self.doc.bus_system is not None else 0
        if not n or getattr(self, "quiet", False):
            return True
        return self.ask_unwritten(n)

    def ask_unwritten(self, n: int) -> bool:
        """Leave with ``n`` pending changes not written? (tests replace this method)"""
        from PySide6.QtWidgets import QMessageBox

        SB = QMessageBox.StandardButton
        answer = QMessageBox.warning(
            self,
            translate("MainWindow", "Pending changes"),
            count(
                "MainWindow",
                "%n change(s) not written to the prosthesis. Leave it without them?\n"
                "(Write to prosthesis writes them; the document keeps them either way.)",
                n,
            ),
            SB.Discard | SB.Cancel,
            SB.Cancel,
        )
        return answer == SB.Discard

    def disconnect_asking(self) -> None:
        """Bus ▸ Disconnect: asks first when pending changes were not written."""
        if self.confirm_unwritten():
            self.live.disconnect_bus()

    # -- the fitting report ---------------------------------------------------------------
    def _note_session_start(self) -> None:
        from pdcp_studio.storage.history import utc_now

        self._session_start = utc_now()

    def session_changes(self) -> list[dict]:
        """The history entries of this session: this prosthesis, since it was connected."""
        from pdcp_studio.app.docks.history_panel import for_prosthesis

        if not self._session_start:
            return []
        entries = for_prosthesis(self.history_panel.all_entries(),
                                 set(self._prosthesis_devices()))
        return [e for e in entries if str(e.get("time", "")) >= self._session_start]

    def fitting_info(self, entry: dict | None = None) -> Any:
        """Who, for whom, when and what, for the report (of one history entry, or of this
        session)."""
        import datetime as dt

        from pdcp_studio.app.report import FittingInfo

        if entry is not None:
            try:
                when = dt.datetime.fromisoformat(str(entry.get("time", "")).replace("Z",
                                                                                   "+00:00"))
            except ValueError:
                when = None
            return FittingInfo(entry.get("patient") or "", entry.get("operator") or "", when,
                               entry.get("bus") or "", [entry], policy_of_entry(entry))
        return FittingInfo(self.patient_reference(), fitting.stored_operator(),
                           dt.datetime.now(dt.UTC), self.live.url if self.live.is_live else "",
                           self.session_changes(),
                           self.doc.policy if self.live.is_live else None)

    def write_fitting_report(self, path: Any, entry: dict | None = None) -> bool:
        """Write the fitting report PDF (GUI thread: text layout); False on an error."""
        from pdcp_studio.app import report
        from pdcp_studio.errors import PdcpError

        try:
            report.write_report(path, self.doc.system, self.doc.tree, self.graph_image(),
                                fitting=self.fitting_info(entry),
                                collection=self.doc.config if self.live.is_live else None)
        except (PdcpError, OSError) as err:
            self.error_box(translate("MainWindow", "Cannot write the report"), str(err))
            return False
        self.show_message(translate("MainWindow", "Wrote the fitting report {0}").format(path))
        return True

    # -- who and for whom ----------------------------------------------------------------
    def _prosthesis_devices(self) -> list[Any]:
        bus = self.doc.bus_system
        return sorted(bus.devices) if bus is not None else []

    def patient_reference(self) -> str:
        """The connected prosthesis's patient reference ("" offline or none)."""
        if self.doc.bus_system is None:
            return ""
        return self.pending_panel.patient.text().strip()

    def set_patient_reference(self, text: str) -> None:
        devices = self._prosthesis_devices()
        if devices:
            fitting.set_patient_reference(devices, text)
            self.pending_panel.set_patient(text)

    def _load_patient_reference(self) -> None:
        devices = self._prosthesis_devices()
        entries = self.history_panel.all_entries() if devices else []
        text = fitting.patient_reference(devices, history_entries=entries) if devices else ""
        self.pending_panel.set_patient(text)
        if getattr(self, "is_ready", True):
            self.history_panel.refresh()
        elif not getattr(self, "_history_when_live", False):
            # A hidden tab: read once the window is live (the archive's read and check of
            # its chain took ~25 ms of start-up on a worker, for one entry).
            self._history_when_live = True
            self.ready.connect(lambda: QTimer.singleShot(HISTORY_AFTER_MS, self,
                                                         self.history_panel.refresh))


def policy_of_entry(entry: dict) -> Any:
    """The policy a history entry left on the prosthesis (None when it does not say)."""
    from pdcp_studio.bus.transaction import Policy

    doc = entry.get("policy_after")
    if not isinstance(doc, dict):
        return None
    try:
        return Policy.from_json(doc)
    except ValueError:
        return None
