"""The Pending changes view: what the project would change on the connected prosthesis.

Lists :func:`pdcp_studio.app.documents.pending.pending_changes` (links to remove, links to make,
parameters to write) with their reasons; selecting a row selects the link or channel on the
graph. "Write to prosthesis…" hands the list to the window's transaction flow, "Discard"
puts the project back as the prosthesis is (one undo step). The patient reference of the
connected prosthesis and the operator are edited here too: they go into the fitting history.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QBrush
from PySide6.QtWidgets import (
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.documents import fitting, pending
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import style
from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP
from pdcp_studio.app.words.effect_words import app_names, effect_tr
from pdcp_studio.app.words.plural import count

ROLE = Qt.ItemDataRole.UserRole

#: The reasons the app gives its own staged links (a plan's reasons are the plan's).
OWN_REASONS = (
    QT_TRANSLATE_NOOP("PendingPanel", "linked by hand"),
    QT_TRANSLATE_NOOP("PendingPanel", "removed by hand"),
    QT_TRANSLATE_NOOP("PendingPanel", "as on the prosthesis"),
)


class PendingPanel(QWidget):
    """Pending changes of the document against the prosthesis (see the module docstring)."""

    #: The user asked to write the pending changes (the window runs the transaction).
    writeRequested = Signal()
    #: The user asked to drop the pending changes.
    discardRequested = Signal()
    #: The patient reference was edited (text).
    patientChanged = Signal(str)
    #: The list was computed again.
    changed = Signal()

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.changes: list[pending.PendingChange] = []
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.patient = QLineEdit()
        self.patient.setPlaceholderText(self.tr("free text, as your clinic chooses"))
        self.patient.setToolTip(self.tr("The patient reference belongs to the prosthesis: it "
                                        "is recorded with every change and printed on the "
                                        "fitting report"))
        self.patient.editingFinished.connect(
            lambda: self.patientChanged.emit(self.patient.text().strip()))
        self.operator = QLabel()
        self.view = QTreeWidget()
        self.view.setColumnCount(3)
        self.view.setHeaderLabels([self.tr("Change"), self.tr("What"), self.tr("Why")])
        self.view.setRootIsDecorated(False)
        self.view.setAlternatingRowColors(True)
        header = self.view.header()
        header.setStretchLastSection(False)
        header.setSectionResizeMode(0, QHeaderView.ResizeMode.ResizeToContents)
        header.setSectionResizeMode(1, QHeaderView.ResizeMode.Stretch)
        header.setSectionResizeMode(2, QHeaderView.ResizeMode.Interactive)
        self.view.setColumnWidth(2, 200)
        self.view.itemSelectionChanged.connect(self._on_row_selected)
        self.write_button = QPushButton(self.tr("Write to prosthesis…"))
        self.write_button.setToolTip(self.tr("Show the difference, then write every pending "
                                             "change in one transaction"))
        self.discard_button = QPushButton(self.tr("Discard pending changes"))
        self.write_button.clicked.connect(self.writeRequested)
        self.discard_button.clicked.connect(self.discardRequested)

        who = QHBoxLayout()
        who.addWidget(QLabel(self.tr("Patient reference:")))
        who.addWidget(self.patient, 1)
        who.addSpacing(12)
        who.addWidget(self.operator)
        buttons = QHBoxLayout()
        buttons.addStretch(1)
        buttons.addWidget(self.discard_button)
        buttons.addWidget(self.write_button)
        box = QVBoxLayout(self)
        box.setContentsMargins(6, 6, 6, 6)
        box.addLayout(who)
        box.addWidget(self.summary)
        box.addWidget(self.view, 1)
        box.addLayout(buttons)

        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        for sig in (doc.linksChanged, doc.systemReset, doc.busChanged, doc.sessionChanged):
            sig.connect(self._later)
        doc.channelChanged.connect(self._later)
        doc.deviceChanged.connect(self._later)
        self.refresh()

    def _later(self, *_args: object) -> None:
        self._timer.start()

    # -- contents ----------------------------------------------------------------------
    def refresh(self) -> None:
        """List the pending changes again (once per event-loop turn)."""
        self._timer.stop()
        doc = self.doc
        live = doc.session is not None and doc.bus_system is not None
        self.changes = pending.pending_changes(doc.bus_system, doc.system,
                                               getattr(doc, "link_reasons", {}))
        self.view.clear()
        bus = doc.bus_system
        names = app_names(bus if bus is not None else doc.system, doc.tree)
        for change in self.changes:
            kind = {pending.ADD: self.tr("+ link"), pending.REMOVE: self.tr("− link"),
                    pending.PARAMETER: self.tr("parameter")}[change.kind]
            what = change.describe(bus, doc.system, names, effect_tr)
            why = self.tr(change.reason) if change.reason in OWN_REASONS else change.reason
            item = QTreeWidgetItem([kind, what, why])
            colour = {pending.ADD: style.PREVIEW_ADD, pending.REMOVE: style.PREVIEW_REMOVE}.get(
                change.kind, style.PENDING)
            item.setForeground(0, QBrush(colour))
            item.setToolTip(1, what)
            item.setData(0, ROLE, change)
            self.view.addTopLevelItem(item)
        n = len(self.changes)
        if not live:
            self.summary.setText(self.tr("Offline: edits change the document only. Connect "
                                         "to a prosthesis to write to it."))
        elif n == 0:
            self.summary.setText(self.tr("No pending changes: the project and the prosthesis "
                                         "on {0} agree.").format(getattr(doc.session, "url",
                                                                         "")))
        else:
            self.summary.setText(self.tr(
                "<b>{0}</b> for the prosthesis on {1}: edits are staged here "
                "and reach the prosthesis only with Write to prosthesis.").format(
                    count("PendingPanel", "%n pending change(s)", n),
                    getattr(doc.session, "url", "")))
        self.write_button.setEnabled(live and n > 0)
        self.discard_button.setEnabled(live and n > 0)
        self.patient.setEnabled(live)
        name = fitting.stored_operator()
        self.operator.setText(self.tr("Operator: {0}").format(name) if name else
                              self.tr("Operator: (asked at the first write)"))
        self.changed.emit()

    def set_patient(self, text: str) -> None:
        if self.patient.text() != text:
            self.patient.setText(text)

    def _on_row_selected(self) -> None:
        items = self.view.selectedItems()
        change = items[0].data(0, ROLE) if items else None
        if change is None:
            return
        if change.link is not None and self.doc.system.has_link(change.link):
            self.doc.select(change.link)
        elif change.ref is not None:
            self.doc.select(change.ref)
        elif change.key is not None:
            self.doc.select(change.key)
