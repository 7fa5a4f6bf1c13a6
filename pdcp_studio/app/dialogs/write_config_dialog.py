"""Write a stored configuration to the arbitrator — only after showing what it changes.

Public API
    ``WriteConfigDialog(bridge, collection, *, system=None, parent=None)`` — ``bridge`` is a
    ``SessionBridge``; ``collection`` the ``ConfigCollection`` to write (for the on-screen
    system: ``WriteConfigDialog.for_system(bridge, system)``); ``system`` only names devices.
    Opening it reads the arbitrator's current configuration (``start()``, called by the
    constructor) and lists, per configuration, the links the write adds, removes, changes
    and keeps — the one configuration diff (:mod:`pdcp_studio.model.config_diff`), as the
    CLI's ``config diff`` says it. The Write button is never the default button (Enter does
    not write) and is enabled only once the current configuration was read. ``write()``
    runs one transaction (``session.transact``: write, read back, restore on mismatch,
    record in the fitting history), then reads back once more and compares.
    Properties: ``state`` (one of ``READING``, ``READY``, ``WRITING``, ``VERIFYING``,
    ``VERIFIED``, ``MISMATCH``, ``FAILED``), ``diff`` (``ConfigDiff``), ``stored``,
    ``transaction`` (the ``TransactionResult``), ``result`` (the outcome line, a ``QLabel``).
    Signals: ``stateChanged(str)``,
    ``verified(bool ok, str message)``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QHeaderView,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.dialogs.compare_dialog import ref_label
from pdcp_studio.app.words.plural import count
from pdcp_studio.app.workers import Worker
from pdcp_studio.model.config_diff import ConfigDiff, diff_configurations
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.system import Link, System

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge
    from pdcp_studio.bus.transaction import TransactionResult

_CTX = "WriteConfigDialog"  # the counts' context (the class's own)

READING, READY, WRITING, VERIFYING = "reading", "ready", "writing", "verifying"
VERIFIED, MISMATCH, FAILED = "verified", "mismatch", "failed"
ADDED, REMOVED, CHANGED, KEPT = "add", "remove", "change", "keep"
_COLOURS = {ADDED: QColor(205, 240, 205), REMOVED: QColor(250, 210, 210),
            CHANGED: QColor(255, 236, 200)}


def diff_rows(diff: ConfigDiff, new: ConfigCollection) -> list[tuple[int, str, Link]]:
    """The diff as rows (configuration index, change, link): removals, additions, changed
    records, then the links the write keeps as they are."""
    rows: list[tuple[int, str, Link]] = []
    for c in diff.configurations:
        touched = set()
        for kind, links in ((REMOVED, c.only_in_a), (ADDED, c.only_in_b)):
            for sl in links:
                rows.append((c.index, kind, Link(sl.output.ref, sl.input.ref)))
                touched.add((sl.output.ref, sl.input.ref))
        for ch in c.changed:
            rows.append((c.index, CHANGED, Link(*ch.ends)))
            touched.add(ch.ends)
        cfg = next((x for x in new.configurations if x.index == c.index), None)
        for sl in (cfg.links if cfg is not None else []):
            if (sl.output.ref, sl.input.ref) not in touched:
                rows.append((c.index, KEPT, Link(sl.output.ref, sl.input.ref)))
    return rows


@runtime_checkable
class PatientSource(Protocol):
    """A parent that knows whose prosthesis this is (the main window): the write is
    recorded in the fitting history for that patient."""

    def patient_reference(self) -> str: ...


class WriteConfigDialog(QDialog):
    """Confirm, write, verify (see the module docstring)."""

    stateChanged = Signal(str)
    verified = Signal(bool, str)
    #: The outcome line. It shadows ``QDialog.result()`` (the exec() code), which nothing
    #: asks of this dialog; the name is the one its tests read.
    result: QLabel  # type: ignore[assignment]

    def __init__(self, bridge: SessionBridge, collection: ConfigCollection, *,
                 system: System | None = None, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Write configuration to the arbitrator"))
        self.resize(820, 460)
        self.bridge = bridge
        self.collection = collection
        self.system = system
        self.stored: ConfigCollection | None = None
        self.diff = ConfigDiff()
        self.rows: list[tuple[int, str, Link]] = []
        self.transaction: TransactionResult | None = None
        self.state = ""
        self._worker: Worker | None = None

        self.message = QLabel()
        self.message.setWordWrap(True)
        self.table = QTableWidget(0, 4)
        self.table.setHorizontalHeaderLabels(
            [self.tr("Configuration"), self.tr("Change"), self.tr("Output"), self.tr("Input")]
        )
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.verticalHeader().setVisible(False)
        self.table.setWordWrap(False)
        self.table.setTextElideMode(Qt.TextElideMode.ElideMiddle)
        header = self.table.horizontalHeader()
        for col, mode in enumerate((QHeaderView.ResizeMode.ResizeToContents,) * 2
                                   + (QHeaderView.ResizeMode.Stretch,) * 2):
            header.setSectionResizeMode(col, mode)
        self.result = QLabel()
        self.result.setWordWrap(True)
        self.buttons = QDialogButtonBox()
        self.write_button = QPushButton(self.tr("Write to arbitrator"))
        self.write_button.setAutoDefault(False)
        self.write_button.setDefault(False)
        self.buttons.addButton(self.write_button, QDialogButtonBox.ButtonRole.ActionRole)
        self.close_button = self.buttons.addButton(QDialogButtonBox.StandardButton.Cancel)
        self.write_button.clicked.connect(self.write)
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.message)
        layout.addWidget(self.table)
        layout.addWidget(self.result)
        layout.addWidget(self.buttons)
        self.start()

    @classmethod
    def for_system(cls, bridge: SessionBridge, system: System,
                   parent: QWidget | None = None) -> WriteConfigDialog:
        """The dialog for writing the on-screen system's links as configuration 1."""
        from pdcp_studio.engine import configuration_from_system

        return cls(bridge, ConfigCollection([configuration_from_system(system)]),
                   system=system, parent=parent)

    # -- state machine -------------------------------------------------------------------
    def _set_state(self, state: str) -> None:
        self.state = state
        self.write_button.setEnabled(state == READY)
        done = state in (VERIFIED, MISMATCH, FAILED)
        self.close_button.setText(self.tr("Close") if done else self.tr("Cancel"))
        self.stateChanged.emit(state)

    def start(self) -> None:
        """Read the arbitrator's current configuration to show the diff."""
        self._set_state(READING)
        self.message.setText(self.tr("Reading the arbitrator's stored configuration…"))
        worker = self.bridge.read_configuration()
        if worker is None:
            self._fail("the bus connection is closed")
            return
        self._worker = worker
        # Bound slots only: Qt drops them if the dialog is deleted while the bus works.
        worker.finished.connect(self._on_read)
        worker.failed.connect(self._read_failed)
        worker.cancelled.connect(self._cancelled)

    def _on_read(self, stored: ConfigCollection | None) -> None:
        self.stored = stored
        self.diff = diff_configurations(stored or ConfigCollection(), self.collection)
        self.rows = diff_rows(self.diff, self.collection)
        self._show_diff()
        n = {k: sum(1 for _i, kind, _l in self.rows if kind == k)
             for k in (ADDED, REMOVED, CHANGED, KEPT)}
        if stored is None or not stored.configurations:
            head = self.tr("The arbitrator stores no configuration yet.")
        else:
            head = count(_CTX, "The arbitrator stores %n configuration(s).",
                         len(stored.configurations))
        if self.diff.equal:
            change = count(_CTX, "Writing changes nothing (%n link(s) kept).", n[KEPT])
        else:
            change = (count(_CTX, "Writing adds %n link(s)", n[ADDED])
                      + count(_CTX, ", removes %n", n[REMOVED])
                      + (count(_CTX, ", changes the records of %n", n[CHANGED])
                         if n[CHANGED] else "")
                      + count(_CTX, " and keeps %n.", n[KEPT]))
        self.message.setText(
            self.tr(
                "{head} {change} The stored configuration decides the links "
                "the prosthesis makes at its next start-up."
            ).format(head=head, change=change)
        )
        self._set_state(READY)

    def _show_diff(self) -> None:
        self.table.setRowCount(len(self.rows))
        words = {ADDED: "+ add", REMOVED: "− remove", CHANGED: "≠ records", KEPT: "keep"}
        for i, (index, kind, link) in enumerate(self.rows):
            cells = (str(index), words[kind], ref_label(self.system, link.output),
                     ref_label(self.system, link.input))
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                item.setToolTip(text)
                if kind in _COLOURS:
                    item.setBackground(QBrush(_COLOURS[kind]))
                    item.setForeground(QBrush(QColor(0, 0, 0)))
                self.table.setItem(i, col, item)

    def write(self) -> Worker | None:
        """Write the configuration (only once the diff is shown) as one transaction, recorded
        in the fitting history; then read back once more and compare."""
        from pdcp_studio.app.documents import fitting
        from pdcp_studio.bus.transaction import Change

        if self.state != READY:
            return None
        self._set_state(WRITING)
        self.result.setText(self.tr("Writing…"))
        change = Change("config write", configuration=self.collection)
        operator = fitting.operator_name(self)
        parent = self.parent()
        patient = parent.patient_reference() if isinstance(parent, PatientSource) else ""
        session = self.bridge.session
        worker = self.bridge.run(
            lambda p, c: session.transact(change, operator=operator or None,
                                          patient=patient or None, progress=p, cancel=c),
            "Write configuration")
        if worker is None:
            self._fail("the bus connection is closed")
            return None
        self._worker = worker
        worker.finished.connect(self._written)
        worker.failed.connect(self._write_failed)
        worker.cancelled.connect(self._cancelled)
        return worker

    def _written(self, result: TransactionResult) -> None:
        self.transaction = result
        if result.written:
            self._read_back()
        elif result.status.value == "rolled_back" and result.step == "verify":
            self._set_state(MISMATCH)
            self.result.setText(
                self.tr(
                    "<b style='color:#b00000'>Verification failed:</b> {reason}. "
                    "The arbitrator keeps its previous configuration."
                ).format(reason=result.reason)
            )
            self.verified.emit(False, result.reason)
        elif result.ok:  # nothing to change: the arbitrator holds it already
            self._read_back()
        else:
            self._fail(f"writing failed: {result.reason}")

    def _read_failed(self, message: str) -> None:
        self._fail(f"reading the arbitrator failed: {message}")

    def _write_failed(self, message: str) -> None:
        self._fail(f"writing failed: {message}")

    def _read_back_failed(self, message: str) -> None:
        self._fail(f"reading back failed: {message}")

    def _cancelled(self) -> None:
        self._fail(f"cancelled while {self.state}")

    def _read_back(self) -> None:
        """The transaction verified its own read-back already; read once more,
        independently."""
        self._set_state(VERIFYING)
        self.result.setText(self.tr("Written. Reading back to verify…"))
        worker = self.bridge.read_configuration()
        if worker is None:
            self._fail("the bus connection closed before the read-back")
            return
        self._worker = worker
        worker.finished.connect(self._on_read_back)
        worker.failed.connect(self._read_back_failed)
        worker.cancelled.connect(self._cancelled)  # else stuck in VERIFYING: no Close

    def _on_read_back(self, read_back: ConfigCollection | None) -> None:
        diff = diff_configurations(self.collection, read_back or ConfigCollection())
        ok = diff.equal and read_back is not None
        if read_back is None:
            message = self.tr("the arbitrator reports no stored configuration after the write")
        elif ok:
            n = sum(len(c.links) for c in read_back.configurations)
            message = self.tr("read back {links} in {configurations}: identical").format(
                links=count(_CTX, "%n link(s)", n),
                configurations=count(_CTX, "%n configuration(s)",
                                     len(read_back.configurations)))
        else:
            message = diff.describe("written", "read back")
        self._set_state(VERIFIED if ok else MISMATCH)
        if ok:
            self.result.setText(self.tr("<b>Verified:</b> {message}.").format(message=message))
        else:
            self.result.setText(
                self.tr(
                    "<b style='color:#b00000'>Verification failed:</b> {message}. "
                    "Do not rely on the stored configuration; write it again."
                ).format(message=message)
            )
        self.verified.emit(ok, message)

    def _fail(self, message: str) -> None:
        self._set_state(FAILED)
        self.result.setText(
            self.tr("<b style='color:#b00000'>Failed:</b> {message}").format(message=message)
        )
        self.verified.emit(False, message)

    def reject(self) -> None:
        if self.state in (WRITING, VERIFYING):
            return  # the write is under way: closing now would hide its outcome
        if self._worker is not None and self.state == READING:
            self._worker.cancel()
        super().reject()
