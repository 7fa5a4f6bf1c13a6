"""The main window's side of the change road: pending changes, writing, history.

Write to prosthesis and Discard pending changes, the question before leaving unwritten
changes behind, and what the fitting report says of this session (who, for whom, which
changes); the transactions themselves run in
:class:`~pdcp_studio.app.window.controllers.transaction_flow.TransactionFlow`, the patient reference
is kept by :mod:`pdcp_studio.app.documents.fitting`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, QTimer, SignalInstance
from PySide6.QtGui import QAction, QImage
from PySide6.QtWidgets import QDockWidget

from pdcp_studio.app.docks.pending_panel import PendingPanel
from pdcp_studio.app.documents import commands, fitting, pending
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window.controllers.transaction_flow import TransactionFlow
from pdcp_studio.app.window.deferred_panel import DeferredPanel
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.app.words.plural import count

if TYPE_CHECKING:
    from pdcp_studio.app.docks.history_panel import HistoryPanel

#: A new window reads the fitting history this long after it is live.
HISTORY_AFTER_MS = 100


class Transactions(QObject):
    """Pending changes, writing them, and this session's record (see the module docstring).

    ``write_actions`` (Write to prosthesis, Discard) follow the Pending changes panel;
    ``ask_unwritten(n)`` and ``quiet()`` are the window's; ``graph_image()`` draws the
    graph for the report; ``is_ready()``/``ready`` say whether the window is live yet."""

    def __init__(self, doc: Document, live: LiveController, status: StatusLine,
                 flow: TransactionFlow, pending_panel: PendingPanel,
                 pending_dock: QDockWidget, history: DeferredPanel[HistoryPanel], *,
                 write_actions: tuple[QAction, QAction],
                 ask_unwritten: Callable[[int], bool], quiet: Callable[[], bool],
                 graph_image: Callable[[], QImage], is_ready: Callable[[], bool],
                 ready: SignalInstance) -> None:
        super().__init__(flow)
        self.doc = doc
        self.live = live
        self.status = status
        self.flow = flow
        self.pending_panel = pending_panel
        self.pending_dock = pending_dock
        self._history = history
        self.write_actions = write_actions
        self._ask_unwritten = ask_unwritten
        self._quiet = quiet
        self._graph_image = graph_image
        self._is_ready = is_ready
        self._ready = ready
        self._history_when_live = False
        self._session_start = ""
        pending_panel.writeRequested.connect(self.write_pending)
        pending_panel.discardRequested.connect(self.discard_pending)
        pending_panel.patientChanged.connect(self.set_patient_reference)
        pending_panel.changed.connect(self._update_write_actions)
        flow.finished.connect(lambda _r: history.panel().refresh())
        live.sessionStarted.connect(lambda _b: self.load_patient_reference())
        live.sessionStarted.connect(lambda _b: self._note_session_start())
        self._update_write_actions()

    def _update_write_actions(self) -> None:
        """Follows the Pending changes panel (it lists them again after every change)."""
        has = bool(self.pending_panel.changes) and self.doc.bus_system is not None
        for action in self.write_actions:
            action.setEnabled(has)

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
            links = [(c.kind, c.link) for c in changes if c.link is not None]
            if links:
                stack.push(commands.LinksCommand(
                    doc, [commands._action(pending.ADD if kind == pending.REMOVE
                                           else pending.REMOVE, link,
                                           "as on the prosthesis") for kind, link in links],
                    translate("MainWindow", "Links as on the prosthesis")))
            for c in changes:
                if c.kind != pending.PARAMETER or c.key is None:
                    continue
                if c.index and c.ref is not None:
                    stack.push(commands.SetChannelFieldCommand(doc, c.ref, c.field, c.old))
                else:
                    stack.push(commands.SetDeviceFieldCommand(doc, c.key, c.field, c.old))
        finally:
            stack.endMacro()
        self.status.say(
            count(
                "MainWindow",
                "Discarded %n pending change(s): the project is as the "
                "prosthesis (Undo brings them back)",
                len(changes),
            )
        )
        return len(changes)

    def unwritten(self) -> int:
        """How many pending changes are not written to the connected prosthesis."""
        return len(self.pending_panel.changes) if self.doc.bus_system is not None else 0

    def confirm_unwritten(self) -> bool:
        """Before leaving a live prosthesis (closing, disconnecting): True when no pending
        change would be lost unwritten, or the user chose to leave them."""
        n = self.unwritten()
        if not n or self._quiet():
            return True
        return self._ask_unwritten(n)

    def disconnect_asking(self) -> None:
        """Bus ▸ Disconnect: asks first when pending changes were not written."""
        if self.confirm_unwritten():
            self.live.disconnect_bus()

    # -- the fitting report ---------------------------------------------------------------
    def _note_session_start(self) -> None:
        from pdcp_studio.storage.history import utc_now

        self._session_start = utc_now()

    def session_changes(self) -> list[dict[str, Any]]:
        """The history entries of this session: this prosthesis, since it was connected."""
        from pdcp_studio.app.docks.history_panel import for_prosthesis

        if not self._session_start:
            return []
        entries = for_prosthesis(self._history_entries(),
                                 set(self._prosthesis_devices()))
        return [e for e in entries if str(e.get("time", "")) >= self._session_start]

    def fitting_info(self, entry: dict[str, Any] | None = None) -> Any:
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

    def write_fitting_report(self, path: Any, entry: dict[str, Any] | None = None) -> bool:
        """Write the fitting report PDF (GUI thread: text layout); False on an error."""
        from pdcp_studio.app import report
        from pdcp_studio.errors import PdcpError

        try:
            report.write_report(path, self.doc.system, self.doc.tree, self._graph_image(),
                                fitting=self.fitting_info(entry),
                                collection=self.doc.config if self.live.is_live else None)
        except (PdcpError, OSError) as err:
            self.status.error(translate("MainWindow", "Cannot write the report"), str(err))
            return False
        self.status.say(translate("MainWindow", "Wrote the fitting report {0}").format(path))
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

    def load_patient_reference(self) -> None:
        devices = self._prosthesis_devices()
        entries = self._history_entries() if devices else []
        text = fitting.patient_reference(devices, history_entries=entries) if devices else ""
        self.pending_panel.set_patient(text)
        if self._is_ready():
            self._history.panel().refresh()
        elif not self._history_when_live:
            # A hidden tab: read once the window is live (the archive's read and check of
            # its chain took ~25 ms of start-up on a worker, for one entry).
            self._history_when_live = True
            self._ready.connect(lambda: QTimer.singleShot(
                HISTORY_AFTER_MS, self, lambda: self._history.panel().refresh()))

    def _history_entries(self) -> list[dict[str, Any]]:
        """The fitting history as last read (none while its panel was never made: the
        archive is read only by the panel)."""
        panel = self._history.made
        return panel.all_entries() if panel is not None else []


def policy_of_entry(entry: dict[str, Any]) -> Any:
    """The policy a history entry left on the prosthesis (None when it does not say)."""
    from pdcp_studio.bus.transaction import Policy

    doc = entry.get("policy_after")
    if not isinstance(doc, dict):
        return None
    try:
        return Policy.from_json(doc)
    except ValueError:
        return None
