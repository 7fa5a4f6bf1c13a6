"""The bus monitor dock: decoded frames in a table that stays fast under a flood.

Frames arrive in batches (``SessionBridge.frameSeen(list)``). The dock keeps every frame
in a capped ring buffer (``capacity`` rows, oldest dropped first) and the table model
shows the ones that pass the filter, appending a whole batch with one
``beginInsertRows`` and dropping overflow with one ``beginRemoveRows``. Text for the
cells is made lazily in ``data()``, only for the rows on screen.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any, NamedTuple

from PySide6.QtCore import QAbstractTableModel, QModelIndex, QPersistentModelIndex, Qt, Signal
from PySide6.QtGui import QFontDatabase
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDockWidget,
    QFileDialog,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPushButton,
    QSpinBox,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.workers import Worker
from pdcp_studio.protocol.codes import FunctionCode

DEFAULT_CAPACITY = 100_000
CHANNEL_DATA = "Channel data"
ANY = "(any)"
_ROOT = QModelIndex()  # the invisible root, shared as a default argument

COLUMNS = ("Time", "ID", "Node", "Function", "Data", "Decoded")


class Row(NamedTuple):
    """One frame as shown: the raw fields plus the node and function derived once."""

    timestamp: float
    arbitration_id: int
    data: bytes
    text: str
    node: int
    function: str


def make_row(frame: Any) -> Row:
    """A table row from a ``FrameSeen`` (or anything with its four fields)."""
    data = bytes(frame.data)
    text = str(frame.text)
    arbitration_id = int(frame.arbitration_id)
    if text.startswith(CHANNEL_DATA):
        function = CHANNEL_DATA
    elif data:
        try:
            function = FunctionCode(data[0]).title
        except ValueError:
            function = f"0x{data[0]:02X}"
    else:
        function = ""
    return Row(float(frame.timestamp), arbitration_id, data, text,
               arbitration_id & 0xFF, function)


class FrameFilter(NamedTuple):
    """Text (case-insensitive, in the decoded text or hex data), function name, node ID."""

    text: str = ""
    function: str = ""
    node: int | None = None

    def __bool__(self) -> bool:
        return bool(self.text or self.function or self.node is not None)

    def matches(self, row: Row) -> bool:
        if self.node is not None and row.node != self.node:
            return False
        if self.function and row.function != self.function:
            return False
        if self.text:
            needle = self.text.lower()
            return needle in row.text.lower() or needle in row.data.hex(" ")
        return True


class FrameTableModel(QAbstractTableModel):
    """The filtered frames, capped at ``capacity`` rows (oldest dropped first)."""

    def __init__(self, capacity: int = DEFAULT_CAPACITY, parent: Any = None) -> None:
        super().__init__(parent)
        self.capacity = capacity
        self.rows: deque[Row] = deque()
        self.t0: float | None = None

    def rowCount(self, parent: QModelIndex | QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(self.rows)

    def columnCount(self, parent: QModelIndex | QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(COLUMNS)

    def headerData(self, section: int, orientation: Qt.Orientation,
                   role: int = Qt.ItemDataRole.DisplayRole) -> Any:
        if role == Qt.ItemDataRole.DisplayRole and orientation == Qt.Orientation.Horizontal:
            return COLUMNS[section]
        return None

    def data(self, index: QModelIndex | QPersistentModelIndex,
             role: int = Qt.ItemDataRole.DisplayRole) -> Any:
        if role != Qt.ItemDataRole.DisplayRole or not index.isValid():
            return None
        row = self.rows[index.row()]
        col = index.column()
        if col == 0:
            return f"{row.timestamp - (self.t0 or 0.0):10.4f}"
        if col == 1:
            return f"0x{row.arbitration_id:03X}"
        if col == 2:
            return str(row.node)
        if col == 3:
            return row.function
        if col == 4:
            return row.data.hex(" ").upper()
        return row.text

    def append(self, rows: Sequence[Row]) -> None:
        """Add rows at the end in one insert, dropping the oldest beyond the capacity."""
        if not rows:
            return
        if self.t0 is None:
            self.t0 = rows[0].timestamp
        if len(rows) > self.capacity:
            rows = rows[-self.capacity:]
        overflow = len(self.rows) + len(rows) - self.capacity
        if overflow > 0:
            self.beginRemoveRows(QModelIndex(), 0, overflow - 1)
            for _ in range(overflow):
                self.rows.popleft()
            self.endRemoveRows()
        start = len(self.rows)
        self.beginInsertRows(QModelIndex(), start, start + len(rows) - 1)
        self.rows.extend(rows)
        self.endInsertRows()

    def replace(self, rows: Iterable[Row]) -> None:
        self.beginResetModel()
        self.rows = deque(rows, maxlen=None)
        while len(self.rows) > self.capacity:
            self.rows.popleft()
        if self.rows and self.t0 is None:
            self.t0 = self.rows[0].timestamp
        self.endResetModel()

    def clear(self) -> None:
        self.t0 = None
        self.replace(())


def save_frames(path: str | Path, rows: Sequence[Row]) -> int:
    """Write frames to ``path``: a python-can capture chosen by extension (.asc, .blf, .log,
    .csv, .trc — the bus monitor's Recorder), or decoded text for ``.txt``. Returns the count."""
    path = Path(path)
    if path.suffix.lower() == ".txt":
        t0 = rows[0].timestamp if rows else 0.0
        with open(path, "w", encoding="utf-8") as out:
            for r in rows:
                out.write(f"{r.timestamp - t0:12.6f}  0x{r.arbitration_id:03X}  "
                          f"{r.data.hex(' ').upper():23}  {r.text}\n")
        return len(rows)
    from pdcp_studio.bus.monitor import Recorder  # python-can loads only here

    with Recorder(path) as recorder:
        for r in rows:
            recorder.write(r.arbitration_id, r.data, r.timestamp)
    return len(rows)


class MonitorDock(QDockWidget):
    """Decoded frames with filter, pause, clear, save and autoscroll.

    Feed it with ``add_frames(list[FrameSeen])`` (connect ``SessionBridge.frameSeen``).
    Signals: ``saved(path)``, ``error(message)``, ``countChanged(shown, total)``.
    """

    saved = Signal(str)
    error = Signal(str)
    countChanged = Signal(int, int)

    def __init__(self, parent: QWidget | None = None, capacity: int = DEFAULT_CAPACITY) -> None:
        super().__init__("Bus monitor", parent)
        self.setObjectName("MonitorDock")
        self.capacity = capacity
        self.all_rows: deque[Row] = deque(maxlen=capacity)
        self._held: list[Row] = []  # rows that arrived while paused
        self._filter = FrameFilter()
        self._save_worker: Worker | None = None
        self.model = FrameTableModel(capacity, self)

        self.view = QTableView()
        self.view.setModel(self.model)
        self.view.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.view.verticalHeader().setVisible(False)
        self.view.verticalHeader().setDefaultSectionSize(18)
        self.view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
        self.view.setWordWrap(False)
        header = self.view.horizontalHeader()
        header.setStretchLastSection(True)
        for col, width in enumerate((90, 60, 45, 190, 170)):
            header.resizeSection(col, width)
        header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)

        self.text_filter = QLineEdit()
        self.text_filter.setPlaceholderText("Filter text or hex…")
        self.text_filter.setClearButtonEnabled(True)
        self.function_filter = QComboBox()
        self.function_filter.addItems([ANY, CHANNEL_DATA,
                                       *sorted({c.title for c in FunctionCode})])
        self.node_filter = QSpinBox()
        self.node_filter.setRange(-1, 254)
        self.node_filter.setSpecialValueText("any node")
        self.node_filter.setValue(-1)
        self.pause_box = QCheckBox("Pause")
        self.autoscroll_box = QCheckBox("Autoscroll")
        self.autoscroll_box.setChecked(True)
        self.clear_button = QPushButton("Clear")
        self.save_button = QPushButton("Save…")
        self.count_label = QLabel("0 frames")

        self.text_filter.textChanged.connect(self._filter_changed)
        self.function_filter.currentTextChanged.connect(self._filter_changed)
        self.node_filter.valueChanged.connect(self._filter_changed)
        self.pause_box.toggled.connect(self.set_paused)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(self._ask_save)

        bar = QHBoxLayout()
        for w in (self.text_filter, self.function_filter, self.node_filter, self.pause_box,
                  self.autoscroll_box, self.clear_button, self.save_button, self.count_label):
            bar.addWidget(w)
        bar.setStretch(0, 1)
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addLayout(bar)
        layout.addWidget(self.view)
        self.setWidget(body)

    # -- feeding -------------------------------------------------------------------------
    @property
    def paused(self) -> bool:
        return self.pause_box.isChecked()

    def add_frames(self, frames: Iterable[Any]) -> None:
        """Slot for ``SessionBridge.frameSeen``: record and show a batch of frames."""
        rows = [make_row(f) for f in frames]
        if not rows:
            return
        self.all_rows.extend(rows)
        if self.paused:
            self._held.extend(rows)
            del self._held[:-self.capacity]
        else:
            self._show(rows)
        self._count()

    def _show(self, rows: list[Row]) -> None:
        shown = [r for r in rows if self._filter.matches(r)] if self._filter else rows
        self.model.append(shown)
        if shown and self.autoscroll_box.isChecked():
            self.view.scrollToBottom()

    def set_paused(self, paused: bool) -> None:
        """Freeze the table; frames keep being recorded and appear on resume."""
        if self.pause_box.isChecked() != paused:
            self.pause_box.setChecked(paused)  # re-enters through toggled
            return
        if not paused and self._held:
            held, self._held = self._held, []
            self._show(held)
            self._count()

    def clear(self) -> None:
        self.all_rows.clear()
        self._held.clear()
        self.model.clear()
        self._count()

    def set_filter(self, text: str = "", function: str = "", node: int | None = None) -> None:
        """Filter programmatically (the widgets follow)."""
        self.text_filter.setText(text)
        self.function_filter.setCurrentText(function or ANY)
        self.node_filter.setValue(-1 if node is None else node)

    def _filter_changed(self, *_args: Any) -> None:
        function = self.function_filter.currentText()
        node = self.node_filter.value()
        self._filter = FrameFilter(self.text_filter.text().strip(),
                                   "" if function == ANY else function,
                                   None if node < 0 else node)
        rows = self.all_rows if not self.paused else list(self.all_rows)[:len(self.all_rows)
                                                                           - len(self._held)]
        self.model.replace(r for r in rows if self._filter.matches(r))
        if self.autoscroll_box.isChecked():
            self.view.scrollToBottom()
        self._count()

    def _count(self) -> None:
        shown, total = self.model.rowCount(), len(self.all_rows)
        self.count_label.setText(f"{shown} of {total} frames" if self._filter
                                 else f"{total} frames")
        self.countChanged.emit(shown, total)

    # -- saving --------------------------------------------------------------------------
    def _ask_save(self) -> None:
        path, _ = QFileDialog.getSaveFileName(
            self, "Save frames", "capture.asc",
            "python-can logs (*.asc *.blf *.log *.csv *.trc);;Plain text (*.txt)")
        if path:
            self.save(path)

    def save(self, path: str | Path) -> Worker:
        """Save every recorded frame on a worker; ``saved(path)`` or ``error`` follows."""
        rows = list(self.all_rows)
        self.save_button.setEnabled(False)

        def work(_progress: Any, _cancel: threading.Event) -> int:
            return save_frames(path, rows)

        worker = Worker(work, "Save frames")
        worker.finished.connect(lambda _n: self.saved.emit(str(path)))
        worker.failed.connect(lambda msg: self.error.emit(f"Saving {path}: {msg}"))
        worker.done.connect(lambda: self.save_button.setEnabled(True))
        self._save_worker = worker
        return worker.start()
