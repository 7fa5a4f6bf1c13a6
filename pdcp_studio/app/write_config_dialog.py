"""Write a stored configuration to the arbitrator — only after showing what it changes.

Public API
    ``WriteConfigDialog(bridge, collection, *, system=None, parent=None)`` — ``bridge`` is a
    ``SessionBridge``; ``collection`` the ``ConfigCollection`` to write (for the on-screen
    system: ``WriteConfigDialog.for_system(bridge, system)``); ``system`` only names devices.
    Opening it reads the arbitrator's current configuration (``start()``, called by the
    constructor) and lists, per configuration, the links the write adds, removes and keeps.
    The Write button is never the default button (Enter does not write) and is enabled only
    once the current configuration was read. ``write()`` writes, then reads back and compares.
    Properties: ``state`` (one of ``READING``, ``READY``, ``WRITING``, ``VERIFYING``,
    ``VERIFIED``, ``MISMATCH``, ``FAILED``), ``diffs`` (``list[ConfigDiff]``), ``stored``.
    Signals: ``stateChanged(str)``, ``verified(bool ok, str message)``.

Pure helpers: ``diff_collections(stored, new) -> list[ConfigDiff]`` and
``verify_collection(written, read_back) -> (ok, message)`` (links, their indices, and the
type and profile of both ends must match, configuration by configuration in index order;
the indices themselves and the order of links may differ).
"""

from __future__ import annotations

from typing import Any, NamedTuple

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

from pdcp_studio.app.compare_dialog import links_of_configuration, ref_label
from pdcp_studio.app.workers import Worker
from pdcp_studio.model.configuration import ConfigCollection, StoredChannel
from pdcp_studio.model.system import Link, System

READING, READY, WRITING, VERIFYING = "reading", "ready", "writing", "verifying"
VERIFIED, MISMATCH, FAILED = "verified", "mismatch", "failed"
ADDED, REMOVED, KEPT = "add", "remove", "keep"
_COLOURS = {ADDED: QColor(205, 240, 205), REMOVED: QColor(250, 210, 210)}


class ConfigDiff(NamedTuple):
    """What writing changes in one configuration (by index)."""

    index: int
    added: tuple[Link, ...]
    removed: tuple[Link, ...]
    kept: tuple[Link, ...]

    @property
    def changed(self) -> bool:
        """True when writing adds or removes a link here."""
        return bool(self.added or self.removed)


def _by_index(collection: ConfigCollection | None) -> dict[int, frozenset[Link]]:
    if collection is None:
        return {}
    return {c.index: links_of_configuration(c) for c in collection.configurations}


def diff_collections(stored: ConfigCollection | None, new: ConfigCollection) -> list[ConfigDiff]:
    """Per configuration index (of either side), the links added, removed and kept."""
    old, fresh = _by_index(stored), _by_index(new)
    out = []
    for index in sorted(old.keys() | fresh.keys()):
        a, b = old.get(index, frozenset()), fresh.get(index, frozenset())
        out.append(ConfigDiff(index, tuple(sorted(b - a)), tuple(sorted(a - b)),
                              tuple(sorted(a & b))))
    return out


def _ends(ch: StoredChannel) -> tuple[int, int, int, int, int, int]:
    return (ch.vid, ch.pid, ch.serial, ch.index, ch.type, ch.profile)


def verify_collection(written: ConfigCollection,
                      read_back: ConfigCollection | None) -> tuple[bool, str]:
    """Does the arbitrator now hold what was written? Returns (ok, a message saying why)."""
    if read_back is None:
        return False, "the arbitrator reports no stored configuration after the write"

    def summary(c: ConfigCollection) -> list[frozenset[tuple[Any, ...]]]:
        # By contents, in index order: the codec may renumber indices that are not 1…n.
        return [frozenset((_ends(sl.output), _ends(sl.input)) for sl in cfg.links)
                for cfg in sorted(c.configurations, key=lambda cfg: cfg.index)]

    want, got = summary(written), summary(read_back)
    if len(want) != len(got):
        return False, f"{len(want)} configuration(s) written, {len(got)} read back"
    for n, (w, g) in enumerate(zip(want, got, strict=True), 1):
        missing, extra = w - g, g - w
        if missing or extra:
            return False, (f"configuration {n}: {len(missing)} link(s) missing and "
                           f"{len(extra)} unexpected after reading back")
    total = sum(len(w) for w in want)
    return True, f"read back {total} link(s) in {len(want)} configuration(s): identical"


class WriteConfigDialog(QDialog):
    """Confirm, write, verify (see the module docstring)."""

    stateChanged = Signal(str)
    verified = Signal(bool, str)

    def __init__(self, bridge: Any, collection: ConfigCollection, *,
                 system: System | None = None, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Write configuration to the arbitrator")
        self.resize(820, 460)
        self.bridge = bridge
        self.collection = collection
        self.system = system
        self.stored: ConfigCollection | None = None
        self.diffs: list[ConfigDiff] = []
        self.state = ""
        self._worker: Worker | None = None

        self.message = QLabel()
        self.message.setWordWrap(True)
        self.table = QTableWidget(0, 4)
        self.table.setHorizontalHeaderLabels(["Configuration", "Change", "Output", "Input"])
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
        self.write_button = QPushButton("Write to arbitrator")
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
    def for_system(cls, bridge: Any, system: System,
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
        self.close_button.setText("Close" if done else "Cancel")
        self.stateChanged.emit(state)

    def start(self) -> None:
        """Read the arbitrator's current configuration to show the diff."""
        self._set_state(READING)
        self.message.setText("Reading the arbitrator's stored configuration…")
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
        self.diffs = diff_collections(stored, self.collection)
        self._show_diff()
        added = sum(len(d.added) for d in self.diffs)
        removed = sum(len(d.removed) for d in self.diffs)
        kept = sum(len(d.kept) for d in self.diffs)
        if stored is None or not stored.configurations:
            head = "The arbitrator stores no configuration yet."
        else:
            head = f"The arbitrator stores {len(stored.configurations)} configuration(s)."
        change = (f"Writing adds {added} link(s), removes {removed} and keeps {kept}."
                  if added or removed else f"Writing changes nothing ({kept} link(s) kept).")
        self.message.setText(f"{head} {change} The stored configuration decides the links "
                             "the prosthesis makes at its next start-up.")
        self._set_state(READY)

    def _show_diff(self) -> None:
        rows = [(d.index, kind, link) for d in self.diffs
                for kind, links in ((REMOVED, d.removed), (ADDED, d.added), (KEPT, d.kept))
                for link in links]
        self.table.setRowCount(len(rows))
        words = {ADDED: "+ add", REMOVED: "− remove", KEPT: "keep"}
        for i, (index, kind, link) in enumerate(rows):
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
        """Write the configuration (only once the diff is shown), then verify it."""
        if self.state != READY:
            return None
        self._set_state(WRITING)
        self.result.setText("Writing…")
        worker = self.bridge.write_configuration(self.collection)
        if worker is None:
            self._fail("the bus connection is closed")
            return None
        self._worker = worker
        worker.finished.connect(self._read_back)
        worker.failed.connect(self._write_failed)
        worker.cancelled.connect(self._cancelled)
        return worker

    def _read_failed(self, message: str) -> None:
        self._fail(f"reading the arbitrator failed: {message}")

    def _write_failed(self, message: str) -> None:
        self._fail(f"writing failed: {message}")

    def _read_back_failed(self, message: str) -> None:
        self._fail(f"reading back failed: {message}")

    def _cancelled(self) -> None:
        self._fail(f"cancelled while {self.state}")

    def _read_back(self, _session_result: Any = None) -> None:
        """The session verified its own read-back already; read once more, independently."""
        self._set_state(VERIFYING)
        self.result.setText("Written. Reading back to verify…")
        worker = self.bridge.read_configuration()
        if worker is None:
            self._fail("the bus connection closed before the read-back")
            return
        self._worker = worker
        worker.finished.connect(self._on_read_back)
        worker.failed.connect(self._read_back_failed)
        worker.cancelled.connect(self._cancelled)  # else stuck in VERIFYING: no Close

    def _on_read_back(self, read_back: ConfigCollection | None) -> None:
        ok, message = verify_collection(self.collection, read_back)
        self._set_state(VERIFIED if ok else MISMATCH)
        if ok:
            self.result.setText(f"<b>Verified:</b> {message}.")
        else:
            self.result.setText(f"<b style='color:#b00000'>Verification failed:</b> {message}. "
                                "Do not rely on the stored configuration; write it again.")
        self.verified.emit(ok, message)

    def _fail(self, message: str) -> None:
        self._set_state(FAILED)
        self.result.setText(f"<b style='color:#b00000'>Failed:</b> {message}")
        self.verified.emit(False, message)

    def reject(self) -> None:
        if self.state in (WRITING, VERIFYING):
            return  # the write is under way: closing now would hide its outcome
        if self._worker is not None and self.state == READING:
            self._worker.cancel()
        super().reject()
