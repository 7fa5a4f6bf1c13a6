"""The bus monitor dock: decoded frames in a table that stays fast under a flood.

Public API
    ``MonitorDock(parent=None, capacity=DEFAULT_CAPACITY)`` — a QDockWidget.
    Slots: ``add_frames(list[FrameSeen])`` (connect ``SessionBridge.frameSeen``),
    ``set_system(system)`` (node IDs of output channels, so data frames are named as such
    even when the session sent no decoded text). Methods: ``set_paused(bool)``,
    ``set_filter(text="", function="", node=None)``, ``clear()``,
    ``save(path) -> Worker`` (a python-can capture by extension — .asc .blf .csv .log .trc
    .db — through ``bus.monitor.Recorder``, or decoded text for .txt; written on a worker),
    ``load_capture(path) -> Worker`` (a capture read and decoded on a worker, then shown),
    ``shown_rows()``. Properties: ``paused``, ``all_rows`` (every frame kept, newest last,
    at most ``capacity``). Signals: ``saved(str path)``, ``loaded(str path)``, ``error(str)``,
    ``countChanged(int shown, int total)``.

Frames arrive in batches (``SessionBridge.frameSeen(list)``). The session's arbitrator has
already decoded them off the GUI thread (``FrameSeen.text``, from ``bus.monitor.FrameDecoder``),
so the dock only classifies each frame in O(1) (node, direction, function) for the filter.
It keeps every frame in a capped ring buffer (``capacity`` rows, oldest dropped first) and the
table model shows the ones that pass the filter, appending a whole batch with one
``beginInsertRows`` and dropping overflow with one ``beginRemoveRows``. Cell text is made
lazily in ``data()``, only for the rows on screen.

Note: a session reports ``FrameSeen`` only when its arbitrator was opened with frame events
on; without them the dock stays empty (the rest of the app is unaffected).
"""

from __future__ import annotations

import queue
import threading
from collections import deque
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any, NamedTuple

from PySide6.QtCore import (
    QT_TRANSLATE_NOOP,
    QAbstractTableModel,
    QElapsedTimer,
    QModelIndex,
    QPersistentModelIndex,
    Qt,
    QTimer,
    Signal,
)
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

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.workers import Worker
from pdcp_studio.protocol.codes import FunctionCode

DEFAULT_CAPACITY = 100_000
#: A visible table takes new rows at most this often: painting it costs the GUI thread
#: milliseconds, and a saturated bus brings a batch every few milliseconds.
REFRESH_MS = 250
#: Rows an opened capture sends to the table at a time (the first ones at once).
CAPTURE_CHUNK = 5000
CHANNEL_DATA = "Channel data"
ANY = QT_TRANSLATE_NOOP("MonitorDock", "(any)")
_ROOT = QModelIndex()  # the invisible root, shared as a default argument

COLUMNS = (QT_TRANSLATE_NOOP("MonitorDock", "Time"), QT_TRANSLATE_NOOP("MonitorDock", "ID"),
           QT_TRANSLATE_NOOP("MonitorDock", "Node"),
           QT_TRANSLATE_NOOP("MonitorDock", "Function"),
           QT_TRANSLATE_NOOP("MonitorDock", "Data"), QT_TRANSLATE_NOOP("MonitorDock", "Decoded"))
_MODE_BIT = 0x100


class Row(NamedTuple):
    """One frame as shown: the raw fields plus the node, direction and function derived once."""

    timestamp: float
    arbitration_id: int
    data: bytes
    text: str
    node: int
    function: str
    who: str


def make_row(frame: Any, channel_nodes: frozenset[int] | set[int] = frozenset()) -> Row:
    """A table row from a ``FrameSeen`` (or anything with its four fields), in O(1)."""
    data = bytes(frame.data)
    text = str(getattr(frame, "text", "") or "")
    arbitration_id = int(frame.arbitration_id)
    node = arbitration_id & 0xFF
    from_ba = bool(arbitration_id & _MODE_BIT)
    if not from_ba and (node in channel_nodes or CHANNEL_DATA in text):
        function, who = CHANNEL_DATA, f"#{node} data"
    else:
        who = (f"BA→#{node}" if node else "BA→all") if from_ba else f"#{node}→BA"
        if data:
            try:
                function = FunctionCode(data[0]).title
            except ValueError:
                function = f"0x{data[0]:02X}"
        else:
            function = ""
    return Row(float(frame.timestamp), arbitration_id, data, text, node, function, who)


def _decoded(text: str) -> str:
    """The fields of a ``DecodedFrame.line`` (``time  prio  who function  fields``): the table
    shows time, node and function in columns of their own. Other text is shown as is."""
    head, _, rest = text.lstrip().partition(" ")
    try:
        float(head)
    except ValueError:
        return text
    rest = rest.lstrip()
    parts = rest.split("  ", 2)  # priority, "who function", fields
    usual = len(parts) >= 2 and parts[0][:1] == "P" and "undecodable" not in parts[1]
    if not usual:
        return rest  # another shape, or why the frame does not decode: show all of it
    return parts[2] if len(parts) == 3 else ""


class FrameFilter(NamedTuple):
    """Text (case-insensitive, in the decoded text or hex data), function name, node ID."""

    text: str = ""
    function: str = ""
    node: int | None = None

    def __bool__(self) -> bool:
        return bool(self.text or self.function or self.node is not None)

    def matches(self, row: Row) -> bool:
        """Whether ``row`` passes this filter."""
        if self.node is not None and row.node != self.node:
            return False
        if self.function and row.function != self.function:
            return False
        if self.text:
            needle = self.text.lower()
            return (needle in row.text.lower() or needle in row.data.hex(" ")
                    or needle in row.function.lower())
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
            return translate("MonitorDock", COLUMNS[section])
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
            return row.who
        if col == 3:
            return row.function
        if col == 4:
            return row.data.hex(" ").upper()
        return _decoded(row.text)

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
        """Show exactly ``rows`` (a refilter), capped at the capacity."""
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


def save_frames(path: str | Path, rows: Sequence[Row], links: dict | None = None) -> int:
    """Write frames to ``path``: a python-can capture chosen by extension (.asc, .blf, .log,
    .csv, .trc — the bus monitor's Recorder, replaced only once complete, with the node map
    of ``links`` saved beside it), or decoded text for ``.txt``. Returns the count."""
    path = Path(path)
    if path.suffix.lower() == ".txt":
        t0 = rows[0].timestamp if rows else 0.0
        with open(path, "w", encoding="utf-8") as out:
            for r in rows:
                out.write(f"{r.timestamp - t0:12.6f}  0x{r.arbitration_id:03X}  {r.who:9}  "
                          f"{r.data.hex(' ').upper():23}  {r.function}  "
                          f"{_decoded(r.text)}".rstrip() + "\n")
        return len(rows)
    from pdcp_studio.bus.monitor import FrameDecoder, Recorder  # python-can loads only here

    node_map = FrameDecoder(dict(links or {})).node_map
    with Recorder(path, node_map=node_map) as recorder:
        for r in rows:
            recorder.write(r.arbitration_id, r.data, r.timestamp)
    return len(rows)


class MonitorDock(QDockWidget):
    """Decoded frames with filter, pause, clear, save and autoscroll (see the module doc)."""

    saved = Signal(str)
    loaded = Signal(str)
    error = Signal(str)
    countChanged = Signal(int, int)
    loadProgress = Signal(int)  # frames of an opened capture read so far

    def __init__(self, parent: QWidget | None = None, capacity: int = DEFAULT_CAPACITY) -> None:
        super().__init__(translate("MonitorDock", "Bus monitor"), parent)
        self.setObjectName("MonitorDock")
        self.capacity = capacity
        self.all_rows: deque[Row] = deque(maxlen=capacity)
        self._held: list[Row] = []  # rows that arrived while paused
        self._filter = FrameFilter()
        self._save_worker: Worker | None = None
        self._save_path = ""
        self._load_path = ""
        self._load_worker: Worker | None = None
        self.channel_nodes: set[int] = set()
        self._link_map: dict[int, tuple[Any, tuple[Any, ...]]] = {}  # for opened captures
        self.model = FrameTableModel(capacity, self)
        self._pending_view: list[Row] = []  # filtered rows not yet in the table
        self._view_clock = QElapsedTimer()
        self._view_clock.start()
        self._view_timer = QTimer(self)
        self._view_timer.setSingleShot(True)
        self._view_timer.timeout.connect(self._flush_view)
        #: While a capture is open the table shows it, apart from the live frames, which
        #: keep being recorded in ``live_rows`` and come back with ``show_live()``.
        self.capture_path: str | None = None
        self.capture_total = 0
        self.live_rows: deque[Row] = deque(maxlen=capacity)
        self._capture_chunks: queue.SimpleQueue[list[Row]] = queue.SimpleQueue()
        self._capture_timer = QTimer(self)
        self._capture_timer.setInterval(40)
        self._capture_timer.timeout.connect(self._take_capture_chunks)
        self._refilter = QTimer(self)  # typing in the filter: refilter once it pauses
        self._refilter.setSingleShot(True)
        self._refilter.setInterval(150)
        self._refilter.timeout.connect(self._filter_changed)

        self.view = QTableView()
        self.view.setModel(self.model)
        self.view.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.view.verticalHeader().setVisible(False)
        self.view.verticalHeader().setDefaultSectionSize(18)
        self.view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
        self.view.setWordWrap(False)
        header = self.view.horizontalHeader()
        header.setStretchLastSection(True)
        for col, width in enumerate((80, 50, 80, 170, 170)):
            header.resizeSection(col, width)
        header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)

        self.text_filter = QLineEdit()
        self.text_filter.setPlaceholderText(self.tr("Filter text or hex…"))
        self.text_filter.setClearButtonEnabled(True)
        self.function_filter = QComboBox()
        self.function_filter.addItem(translate("MonitorDock", ANY), ANY)
        self.function_filter.addItems([CHANNEL_DATA,
                                       *sorted({c.title for c in FunctionCode})])
        self.node_filter = QSpinBox()
        self.node_filter.setRange(-1, 254)
        self.node_filter.setSpecialValueText(self.tr("any node"))
        self.node_filter.setValue(-1)
        self.pause_box = QCheckBox(self.tr("Pause"))
        self.autoscroll_box = QCheckBox(self.tr("Autoscroll"))
        self.autoscroll_box.setChecked(True)
        self.clear_button = QPushButton(self.tr("Clear"))
        self.save_button = QPushButton(self.tr("Save…"))
        self.open_button = QPushButton(self.tr("Open…"))
        self.open_button.setToolTip(self.tr("Show a capture file (python-can log formats)"))
        self.live_button = QPushButton(self.tr("Back to live"))
        self.live_button.setToolTip(self.tr("Close the capture and show the live frames again"))
        self.live_button.setVisible(False)
        self.stop_load_button = QPushButton(self.tr("Stop loading"))
        self.stop_load_button.setVisible(False)
        self.count_label = QLabel(self.tr("0 frames"))

        self.text_filter.textChanged.connect(lambda _t: self._refilter.start())
        self.function_filter.currentTextChanged.connect(self._filter_changed)
        self.node_filter.valueChanged.connect(self._filter_changed)
        self.pause_box.toggled.connect(self.set_paused)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(self._ask_save)
        self.open_button.clicked.connect(self._ask_open)
        self.live_button.clicked.connect(self.show_live)
        self.stop_load_button.clicked.connect(self.cancel_load)

        # Long function names must not make the dock (and so the window) wide.
        self.function_filter.setSizeAdjustPolicy(
            QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.function_filter.setMinimumContentsLength(14)
        self.text_filter.setMinimumWidth(90)
        filters, actions = QHBoxLayout(), QHBoxLayout()
        for w in (self.text_filter, self.function_filter, self.node_filter):
            filters.addWidget(w)
        filters.setStretch(0, 1)
        for w in (self.pause_box, self.autoscroll_box, self.count_label):
            actions.addWidget(w)
        actions.addStretch(1)
        for w in (self.stop_load_button, self.live_button, self.clear_button, self.open_button,
                  self.save_button):
            actions.addWidget(w)
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addLayout(filters)
        layout.addLayout(actions)
        layout.addWidget(self.view)
        self.setWidget(body)

    # -- feeding -------------------------------------------------------------------------
    @property
    def paused(self) -> bool:
        """True while the table is frozen (frames are still recorded)."""
        return self.pause_box.isChecked()

    def add_frames(self, frames: Iterable[Any]) -> None:
        """Slot for ``SessionBridge.frameSeen``: record and show a batch of frames."""
        nodes = self.channel_nodes
        rows = [make_row(f, nodes) for f in frames]
        if not rows:
            return
        for r in rows:  # learn output channels named by the session's decoder
            if r.function == CHANNEL_DATA and r.node not in nodes:
                nodes.add(r.node)
                self._link_map.setdefault(r.node, (f"node {r.node}", ()))
        if self.capture_path is not None:  # a capture is shown: keep live frames apart
            self.live_rows.extend(rows)
            return
        self._add_rows(rows)

    def _add_rows(self, rows: list[Row]) -> None:
        self.all_rows.extend(rows)
        if self.paused:
            self._held.extend(rows)
            del self._held[:-self.capacity]
        else:
            self._show(rows)
        self._count()

    def _show(self, rows: list[Row]) -> None:
        shown = [r for r in rows if self._filter.matches(r)] if self._filter else rows
        if not shown:
            return
        self._pending_view.extend(shown)
        if len(self._pending_view) > self.capacity:
            del self._pending_view[:-self.capacity]
        wait = REFRESH_MS - self._view_clock.elapsed()
        if not self.view.isVisible() or wait <= 0:
            self._flush_view()
        elif not self._view_timer.isActive():
            self._view_timer.start(max(1, wait))

    def _flush_view(self) -> None:
        """Put the rows that came since the last refresh into the table, in one insert."""
        self._view_timer.stop()
        self._view_clock.restart()
        if not self._pending_view:
            return
        rows, self._pending_view = self._pending_view, []
        self.model.append(rows)
        if self.autoscroll_box.isChecked():
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
        self._pending_view.clear()
        self.model.clear()
        self._count()

    def set_system(self, system: Any) -> None:
        """Learn the output channels' node IDs (frames from them are channel data) and what
        they feed, so a capture opened later names its links."""
        for ref, ch in system.channels():
            if ch.is_output and ch.node_id is not None:
                self.channel_nodes.add(ch.node_id)
                self._link_map[ch.node_id] = (ref, tuple(system.inputs_fed_by(ref)))

    def reset_for_session(self, system: Any, *, keep_frames: bool = False) -> None:
        """Follow the bus this dock shows: forget the node map (node IDs are reassigned
        after a reset or hot-swap) and learn ``system``'s; a new session (``keep_frames``
        False) also starts with no frames, so two sessions' frames are never mixed."""
        if not keep_frames:
            self.clear()
        self.channel_nodes.clear()
        self._link_map.clear()
        self.set_system(system)

    def shown_rows(self) -> list[Row]:
        """The rows the table shows now (filtered; frozen while paused)."""
        self._flush_view()
        return list(self.model.rows)

    def set_filter(self, text: str = "", function: str = "", node: int | None = None) -> None:
        """Filter programmatically (the widgets follow; the table is filtered once)."""
        widgets = (self.text_filter, self.function_filter, self.node_filter)
        for w in widgets:
            w.blockSignals(True)
        try:
            self.text_filter.setText(text)
            self.function_filter.setCurrentText(function or translate("MonitorDock", ANY))
            self.node_filter.setValue(-1 if node is None else node)
        finally:
            for w in widgets:
                w.blockSignals(False)
        self._filter_changed()

    def _filter_changed(self, *_args: Any) -> None:
        self._refilter.stop()
        function = self.function_filter.currentText()
        node = self.node_filter.value()
        self._filter = FrameFilter(self.text_filter.text().strip(),
                                   "" if self.function_filter.currentIndex() == 0 else function,
                                   None if node < 0 else node)
        rows: Iterable[Row] = self.all_rows
        if self.paused and self._held:  # held rows appear on resume, not now
            rows = list(self.all_rows)[:max(0, len(self.all_rows) - len(self._held))]
        self._pending_view.clear()
        self.model.replace(r for r in rows if self._filter.matches(r))
        if self.autoscroll_box.isChecked():
            self.view.scrollToBottom()
        self._count()

    def _count(self) -> None:
        shown, total = self.model.rowCount() + len(self._pending_view), len(self.all_rows)
        self.count_label.setText(
            self.tr("{shown} of {total} frames").format(shown=shown, total=total)
            if self._filter
            else self.tr("{total} frames").format(total=total)
        )
        self.countChanged.emit(shown, total)

    # -- saving --------------------------------------------------------------------------
    def _ask_save(self) -> None:
        path, _ = QFileDialog.getSaveFileName(
            self, self.tr("Save frames"), "capture.asc",
            self.tr("python-can logs (*.asc *.blf *.log *.csv *.trc);;Plain text (*.txt)"))
        if path:
            self.save(path)

    def _ask_open(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self, self.tr("Open capture"), "",
            self.tr("python-can logs (*.asc *.blf *.log *.csv *.trc *.db *.gz);;All files (*)"))
        if path:
            self.load_capture(path)

    def save(self, path: str | Path) -> Worker:
        """Save every recorded frame on a worker; ``saved(path)`` or ``error`` follows."""
        rows = list(self.all_rows)
        links = dict(self._link_map)
        self.save_button.setEnabled(False)

        def work(_progress: Any, _cancel: threading.Event) -> int:
            return save_frames(path, rows, links)

        worker = Worker(work, "Save frames")
        self._save_path = str(path)
        worker.finished.connect(self._save_finished)  # bound slots: dropped with the dock
        worker.failed.connect(self._save_failed)
        worker.done.connect(self._save_done)
        self._save_worker = worker
        return worker.start()

    def load_capture(self, path: str | Path) -> Worker:
        """Show a capture (any python-can log format) apart from the live frames.

        Read and decoded on a worker (``bus.monitor.replay``, with the node map saved beside
        the capture when there is one); the first rows appear at once, the rest in chunks
        as they are read, with ``loadProgress(frames)``; ``cancel_load()`` stops it. Live
        frames keep being recorded in ``live_rows`` and return with ``show_live()``. The
        table holds the first ``capacity`` frames of the capture (all are counted);
        ``loaded(path)`` or ``error`` follows.
        """
        from pdcp_studio.bus.events import FrameSeen

        self.cancel_load()
        links = dict(self._link_map)  # a capture may start after the set-up that names them
        chunks: queue.SimpleQueue[list[Row]] = queue.SimpleQueue()
        self._capture_chunks = chunks
        capacity = self.capacity

        def work(progress: Any, cancel: threading.Event) -> int:
            from pdcp_studio.bus.monitor import FrameDecoder, read_node_map, replay

            decoder = FrameDecoder(links)
            node_map = read_node_map(path)
            if node_map is not None:
                decoder.load_node_map(node_map, f"{path}.nodemap.json")
            chunk: list[Row] = []
            count = 0
            size = 200  # the first rows go to the table at once
            for decoded in replay(path, decoder):
                if cancel.is_set():
                    break
                count += 1
                if count > capacity:
                    if count % CAPTURE_CHUNK == 0:
                        progress(count, 0, "")
                    continue  # counted (the total is shown), not kept
                chunk.append(make_row(FrameSeen(decoded.timestamp, decoded.arbitration_id,
                                                decoded.data, decoded.line)))
                if len(chunk) >= size:
                    chunks.put(chunk)
                    chunk, size = [], CAPTURE_CHUNK
                    progress(count, 0, "")
            if chunk:
                chunks.put(chunk)
            progress(count, 0, "")
            return count

        self._enter_capture(str(path))
        worker = Worker(work, "Load capture")
        self._load_path = str(path)
        worker.progress.connect(self._capture_progress)
        worker.finished.connect(self._capture_loaded)
        worker.failed.connect(self._load_failed)
        worker.done.connect(self._capture_done)
        self._load_worker = worker
        self.stop_load_button.setVisible(True)
        self._capture_timer.start()
        return worker.start()

    def cancel_load(self) -> None:
        """Stop reading an opened capture (what was read stays shown)."""
        if self._load_worker is not None and self._load_worker.is_running:
            self._load_worker.cancel()

    def show_live(self) -> None:
        """Close the opened capture: the table shows the live frames again."""
        self.cancel_load()
        self._capture_timer.stop()
        self.capture_path = None
        self.live_button.setVisible(False)
        self.stop_load_button.setVisible(False)
        self.setWindowTitle(self.tr("Bus monitor"))
        live, self.live_rows = list(self.live_rows), deque(maxlen=self.capacity)
        self.clear()
        self.model.t0 = None
        self._add_rows(live)

    def _enter_capture(self, path: str) -> None:
        if self.capture_path is None:
            self.live_rows = deque(self.all_rows, maxlen=self.capacity)
        self.capture_path = path
        self.capture_total = 0
        self.clear()
        self.model.t0 = None
        self.live_button.setVisible(True)
        self.setWindowTitle(self.tr("Bus monitor — capture %1").replace("%1", Path(path).name))

    def _take_capture_chunks(self, limit: int = 4) -> None:
        """Move what the worker decoded into the table, a few chunks per timer tick."""
        for _ in range(limit):
            try:
                chunk = self._capture_chunks.get_nowait()
            except queue.Empty:
                return
            self._add_rows(chunk)

    def _capture_progress(self, done: int, _total: int, _text: str) -> None:
        self.count_label.setText(self.tr("%1 frames read").replace("%1", f"{done:,}"))
        self.loadProgress.emit(done)

    def _capture_loaded(self, total: int) -> None:
        self._take_capture_chunks(limit=1 << 30)
        self._flush_view()
        self.capture_total = total
        if total > self.capacity:
            self.count_label.setText(self.tr("first %1 of %2 frames").replace(
                "%1", f"{self.capacity:,}").replace("%2", f"{total:,}"))
        self.loaded.emit(self._load_path)

    def _capture_done(self) -> None:
        self._capture_timer.stop()
        self._take_capture_chunks(limit=1 << 30)
        self.stop_load_button.setVisible(False)

    def _load_failed(self, message: str) -> None:
        self.error.emit(
            self.tr("Reading {load_path}: {message}").format(
                load_path=self._load_path, message=message
            )
        )

    def _save_finished(self, _count: int) -> None:
        self.saved.emit(self._save_path)

    def _save_failed(self, message: str) -> None:
        self.error.emit(
            self.tr("Saving {save_path}: {message}").format(
                save_path=self._save_path, message=message
            )
        )

    def _save_done(self) -> None:
        self.save_button.setEnabled(True)
