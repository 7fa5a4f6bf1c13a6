"""The bus monitor dock: a trace that keeps up with a saturated bus and opens any capture.

Public API
    ``MonitorDock(parent=None, capacity=DEFAULT_CAPACITY)`` — a QDockWidget.
    Slots: ``add_frames(list[FrameSeen])`` (connect ``SessionBridge.frameSeen``),
    ``set_system(system)`` (node names for the node filter; output channels' node IDs so
    data frames are named as such). Methods: ``set_paused(bool)``,
    ``set_filter(text="", function="", node=None)`` (node None: any; 0: broadcast),
    ``find_frame(text, forward=True) -> Worker`` (``found(row)`` follows), ``add_marker(name="")``,
    ``jump_to_marker(i)``, ``set_time_mode(mode)``, ``clear()``, ``flush()``,
    ``save(path) -> Worker``, ``load_capture(path) -> Worker``, ``cancel_load()``,
    ``show_live()``, ``shown_rows()``, ``reset_for_session(system, keep_frames=False)``.
    Properties: ``paused``, ``all_rows`` (the frames of what is shown: the live ring, or the
    opened capture), ``store`` (that ``FrameStore``). Signals: ``saved(str)``, ``loaded(str)``,
    ``error(str)``, ``countChanged(int shown, int total)``, ``loadProgress(int frames)``,
    ``found(int row)`` (-1: nothing found), ``filtered()``.

How it keeps up (issue 16): ``add_frames`` only queues the batch (the session decoded it off
the GUI thread). Every ``REFRESH_MS`` a timer turns the queued frames into one column chunk
of the live ring (``trace_store``; bounded to ``capacity`` frames), updates the per-ID
statistics with vectorised counts, and lets the virtual-row table (``trace_model``) insert
the new rows at once; a larger backlog is taken ``INGEST_SLICE`` frames per turn of the
event loop. The statistics view makes a row only for the identifiers it paints. An opened
capture is decoded on a worker into its own store (shown apart from the live frames, which
keep being recorded); its first rows show at once and the rest follow chunk by chunk with
progress and a Stop button. Filters and search over a large store run on a worker and return
row lists; small ones are filtered at once.
"""

from __future__ import annotations

import shutil
import tempfile
import threading
import weakref
from collections.abc import Iterable
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from PySide6.QtCore import QT_TRANSLATE_NOOP, Qt, QTimer, Signal
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
    QProgressBar,
    QSizePolicy,
    QSplitter,
    QTableView,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.capture import load_capture as _load_into
from pdcp_studio.app.trace.capture import save_store, stored_rows
from pdcp_studio.app.trace.disk import FileFrameStore, FileTexts
from pdcp_studio.app.trace.model import (
    TIME_MODES,
    StatsModel,
    TraceModel,
    TraceView,
    decoded_fields,
)
from pdcp_studio.app.trace.record import LiveRecorder
from pdcp_studio.app.trace.store import (
    CHANNEL_DATA,
    ChunkBuilder,
    Frame,
    FrameStore,
    IdStats,
    Tables,
    TraceFilter,
    line_head,
)
from pdcp_studio.app.workers import Worker
from pdcp_studio.protocol.codes import FunctionCode

__all__ = ["CHANNEL_DATA", "FrameFilter", "MonitorDock", "Row", "_decoded", "make_row"]

DEFAULT_CAPACITY = 100_000
#: Queued frames become table rows this often: one insert per tick whatever the bus rate.
REFRESH_MS = 100
#: Stores up to this many frames are filtered on the GUI thread (a few ms); larger ones on
#: a worker.
FILTER_AT_ONCE = 200_000
#: Queued live frames taken per turn of the event loop (~3 ms of work on a quiet machine):
#: a backlog (a burst, or the window busy elsewhere) is taken slice by slice with the
#: window's other events in between, not in one long stall.
INGEST_SLICE = 1000
#: The per-ID statistics are refreshed this often.
STATS_MS = 500
ANY = QT_TRANSLATE_NOOP("MonitorDock", "(any)")
FrameFilter = TraceFilter


class Row(NamedTuple):
    """One frame as classified for the table (kept for callers of ``make_row``)."""

    timestamp: float
    arbitration_id: int
    data: bytes
    text: str
    node: int
    function: str
    who: str


def make_row(frame: Any, channel_nodes: frozenset[int] | set[int] = frozenset()) -> Row:
    """A classified row from a ``FrameSeen`` (or anything with its four fields), in O(1)."""
    tables = _ROW_TABLES
    builder = ChunkBuilder(tables, channel_nodes)
    data = bytes(frame.data)
    builder.add(float(frame.timestamp), int(frame.arbitration_id), data,
                line_head(str(getattr(frame, "text", "") or "")))
    store = FrameStore(tables)
    store.append(builder.take())
    f = store.frame(0)
    return Row(f.timestamp, f.arbitration_id, f.data, str(getattr(frame, "text", "") or ""),
               f.node, f.function, f.who)


_ROW_TABLES = Tables()


def live_tables(owner: object) -> Tables:
    """String tables whose decoded texts are in a temporary folder removed with ``owner``."""
    folder = tempfile.mkdtemp(prefix="pdcp-live-")
    texts = FileTexts(folder)
    weakref.finalize(owner, _remove_texts, texts, folder)
    return Tables(texts)


def _remove_texts(texts: FileTexts, folder: str) -> None:
    texts.close()
    shutil.rmtree(folder, ignore_errors=True)


_WARM: list[threading.Thread] = []


def _warm_up() -> None:
    """Import the capture readers (python-can, the decoder) on a thread, once: opening a
    capture then shows its first rows without waiting ~0.3 s for them."""
    if _WARM:
        return

    def load() -> None:
        import can.io  # noqa: F401

        import pdcp_studio.bus.trace.monitor  # noqa: F401

    _WARM.append(threading.Thread(target=load, name="trace warm-up", daemon=True))
    _WARM[0].start()


_FROZEN: list[bool] = []


def _spare_the_collector() -> None:
    """Move what the app has made so far out of the cyclic collector's sight, once, when
    the trace first gets busy (live frames, or a capture being read).

    Python's full collections walk every tracked object — 50,000-100,000 once the window
    is up, 15-40 ms on a quiet machine and several times that while a thread decodes a bus
    or a capture; every frame and decoded text made afterwards keeps triggering them.
    Objects made before this (modules, widgets, tables) live as long as the app anyway;
    they are still freed when no longer referenced, only cycles among them are not looked
    for again (``gc.freeze``)."""
    if not _FROZEN:
        _FROZEN.append(True)
        import gc

        gc.freeze()


def _decoded(text: str) -> str:
    """The fields of a ``DecodedFrame.line`` (``time  prio  who function  fields``)."""
    head = line_head(text)
    return text if head is text else decoded_fields(head)


def _tool_button(text: str) -> QToolButton:
    """A compact text button (the dock's rows stay narrow)."""
    button = QToolButton()
    button.setText(text)
    button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextOnly)
    return button


class Marker(NamedTuple):
    index: int  # type: ignore[assignment]  # the absolute frame index
    time: float
    name: str


class MonitorDock(QDockWidget):
    """The trace: frames, per-ID statistics, markers, filters and search (module doc)."""

    saved = Signal(str)
    loaded = Signal(str)
    error = Signal(str)
    countChanged = Signal(int, int)
    loadProgress = Signal(int)  # frames of an opened capture read so far
    found = Signal(int)  # the table row a search found, -1 for none
    filtered = Signal()  # a filter's rows are shown

    def __init__(self, parent: QWidget | None = None, capacity: int = DEFAULT_CAPACITY) -> None:
        super().__init__(translate("MonitorDock", "Bus monitor"), parent)
        self.setObjectName("MonitorDock")
        self.capacity = capacity
        # the ring is bounded by ``capacity``; its decoded texts, which a long session keeps
        # adding, are on disk (a bounded window of them in memory), removed with the dock
        self.live_store = FrameStore(live_tables(self), max_rows=capacity)
        self.live_stats = IdStats(self.live_store.tables)
        self._builder = ChunkBuilder(self.live_store.tables)
        self._incoming: list[Any] = []
        self.frames_seen = 0  # live frames counted since the last clear, kept or not
        self.capture_store: FrameStore | None = None
        self.capture_stats: IdStats | None = None
        self.capture_path: str | None = None
        self.capture_total = 0
        self._filter = TraceFilter()
        self._save_worker: Worker | None = None
        self._save_path = ""
        self._load_path = ""
        self._load_worker: Worker | None = None
        self._filter_worker: Worker | None = None
        self._find_worker: Worker | None = None
        self._hits: tuple[str, np.ndarray, int] | None = None  # needle, hits, scanned up to
        self.markers: list[Marker] = []
        self._link_map: dict[int, tuple[Any, tuple[Any, ...]]] = {}
        self._node_names: dict[int, str] = {}
        self._nodes_listed: set[int] = set()
        self._counted = (-1, -1)
        self.recorder: LiveRecorder | None = None

        self.model = TraceModel(self)
        self.stats_model = StatsModel(self)
        self.stats_model.names = self.model.names  # one map of device names
        self._build_widgets()
        self._tick_timer = QTimer(self)
        self._tick_timer.setInterval(REFRESH_MS)
        self._tick_timer.timeout.connect(self._tick)
        self._tick_timer.start()
        self._more = QTimer(self)  # the next slice of a large backlog, once events ran
        self._more.setSingleShot(True)
        self._more.setInterval(0)
        self._more.timeout.connect(self._tick)
        # The statistics repaint on their own, slower beat, between the table's.
        self._stats_timer = QTimer(self)
        self._stats_timer.setInterval(STATS_MS)
        self._stats_timer.timeout.connect(self._refresh_stats)
        QTimer.singleShot(REFRESH_MS // 2, self._stats_timer.start)
        _warm_up()
        self._refilter = QTimer(self)  # typing in the filter: refilter once it pauses
        self._refilter.setSingleShot(True)
        self._refilter.setInterval(150)
        self._refilter.timeout.connect(self._filter_changed)
        self.model.show(self.live_store)

    # -- widgets -------------------------------------------------------------------------
    def _build_widgets(self) -> None:
        fixed = QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont)
        self.view = TraceView()
        self.view.setModel(self.model)
        self.view.setFont(fixed)
        self.view.verticalHeader().setVisible(False)
        self.view.verticalHeader().setDefaultSectionSize(18)
        self.view.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Fixed)
        self.view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
        self.view.setSelectionMode(QTableView.SelectionMode.SingleSelection)
        self.view.setWordWrap(False)
        header = self.view.horizontalHeader()
        header.setStretchLastSection(True)
        for col, width in enumerate((92, 52, 70, 150, 170)):
            header.resizeSection(col, width)
        header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)

        self.stats_view = TraceView()
        self.stats_view.setModel(self.stats_model)
        self.stats_view.setFont(fixed)
        self.stats_view.verticalHeader().setVisible(False)
        self.stats_view.verticalHeader().setDefaultSectionSize(18)
        self.stats_view.setWordWrap(False)
        self.stats_view.setSelectionBehavior(QTableView.SelectionBehavior.SelectRows)
        self.stats_view.horizontalHeader().setStretchLastSection(True)
        metrics = self.stats_view.fontMetrics()
        for col, sample in enumerate(("0x000", "BA→#00 ", "000,000", "0000.000",
                                      "0000.000", "00 00 00 00 ")):
            head = str(self.stats_model.headerData(col, Qt.Orientation.Horizontal))
            self.stats_view.horizontalHeader().resizeSection(
                col, max(metrics.horizontalAdvance(sample),
                         self.stats_view.horizontalHeader().fontMetrics().horizontalAdvance(
                             head)) + 14)
        self.stats_view.doubleClicked.connect(self._stats_row_chosen)
        self.stats_view.setToolTip(self.tr("Per identifier: frames counted, mean period, "
                                           "last period, last data and what it means. "
                                           "Double-click to show only that identifier."))

        self.text_filter = QLineEdit()
        self.text_filter.setPlaceholderText(self.tr("Filter text, ID or data…"))
        self.text_filter.setClearButtonEnabled(True)
        self.function_filter = QComboBox()
        self.function_filter.addItem(translate("MonitorDock", str(ANY)), ANY)
        self.function_filter.addItems([CHANNEL_DATA, *sorted({c.title for c in FunctionCode})])
        self.function_filter.setSizeAdjustPolicy(
            QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.function_filter.setMinimumContentsLength(12)
        self.node_filter = QComboBox()
        self.node_filter.setToolTip(self.tr("Show the frames of one node only"))
        self.node_filter.setSizeAdjustPolicy(
            QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.node_filter.setMinimumContentsLength(12)
        self._fill_node_filter()
        self.find_edit = QLineEdit()
        self.find_edit.setPlaceholderText(self.tr("Find text or ID…"))
        self.find_edit.setClearButtonEnabled(True)
        self.find_prev = QToolButton()
        self.find_prev.setText("▲")
        self.find_prev.setToolTip(self.tr("Find the previous frame"))
        self.find_next = QToolButton()
        self.find_next.setText("▼")
        self.find_next.setToolTip(self.tr("Find the next frame"))

        self.pause_box = QCheckBox(self.tr("Pause"))
        self.pause_box.setToolTip(self.tr("Freeze the table; frames are still recorded and "
                                          "counted"))
        self.autoscroll_box = QCheckBox(self.tr("Autoscroll"))
        self.autoscroll_box.setChecked(True)
        self.time_mode = QComboBox()
        for mode in TIME_MODES:
            self.time_mode.addItem(translate("TraceModel", str(mode)))
        self.time_mode.setToolTip(self.tr("How the Time column counts"))
        self.time_mode.setSizeAdjustPolicy(
            QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.time_mode.setMinimumContentsLength(12)
        self.marker_button = _tool_button(self.tr("Add marker"))
        self.marker_button.setToolTip(self.tr("Mark the selected frame, or the newest one"))
        self.marker_box = QComboBox()
        self.marker_box.setMinimumContentsLength(10)
        self.marker_box.setSizeAdjustPolicy(
            QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.marker_box.setToolTip(self.tr("Go to a marker (times since a marker count "
                                           "from it)"))
        from pdcp_studio.app.widgets.combo_popups import keep_whole

        keep_whole(self.marker_box)  # "Grip closes 3.89" whole, not cut
        self.marker_box.addItem(self.tr("No markers"))
        self.marker_box.setEnabled(False)
        self.count_label = QLabel(self.tr("0 frames"))
        # Long counts (and "recording to …") must not widen the dock, and so the window.
        self.count_label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        self.count_label.setMinimumWidth(140)
        self.load_bar = QProgressBar()
        self.load_bar.setRange(0, 1000)
        self.load_bar.setMaximumWidth(160)
        self.load_bar.setTextVisible(True)
        self.load_bar.setVisible(False)
        self.record_button = _tool_button(self.tr("Record…"))
        self.record_button.setCheckable(True)
        self.record_button.setToolTip(self.tr("Write every live frame to a capture file (the "
                                              "table keeps only the newest ones)"))
        self.record_button.clicked.connect(self._toggle_recording)
        self.clear_button = _tool_button(self.tr("Clear"))
        self.save_button = _tool_button(self.tr("Save…"))
        self.open_button = _tool_button(self.tr("Open…"))
        self.open_button.setToolTip(self.tr("Show a capture file (python-can log formats)"))
        self.live_button = _tool_button(self.tr("Back to live"))
        self.live_button.setToolTip(self.tr("Close the capture and show the live frames again"))
        self.live_button.setVisible(False)
        self.stop_load_button = _tool_button(self.tr("Stop loading"))
        self.stop_load_button.setVisible(False)

        self.text_filter.textChanged.connect(lambda _t: self._refilter.start())
        self.function_filter.currentIndexChanged.connect(self._filter_changed)
        self.node_filter.currentIndexChanged.connect(self._filter_changed)
        self.find_edit.returnPressed.connect(lambda: self.find_frame(self.find_edit.text()))
        self.find_next.clicked.connect(lambda: self.find_frame(self.find_edit.text()))
        self.find_prev.clicked.connect(
            lambda: self.find_frame(self.find_edit.text(), forward=False))
        self.pause_box.toggled.connect(self.set_paused)
        self.time_mode.currentIndexChanged.connect(self.set_time_mode)
        self.marker_button.clicked.connect(lambda: self.add_marker())
        self.marker_box.activated.connect(self.jump_to_marker)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(self._ask_save)
        self.open_button.clicked.connect(self._ask_open)
        self.live_button.clicked.connect(self.show_live)
        self.stop_load_button.clicked.connect(self.cancel_load)

        self.text_filter.setMinimumWidth(90)
        self.find_edit.setMinimumWidth(90)
        # Three short rows: the dock must not make the window wider than a laptop screen.
        filters, finding, actions = QHBoxLayout(), QHBoxLayout(), QHBoxLayout()
        w: QWidget
        for w in (self.text_filter, self.function_filter, self.node_filter):
            filters.addWidget(w)
        filters.setStretch(0, 1)
        for w in (self.find_edit, self.find_prev, self.find_next, self.time_mode,
                  self.marker_button, self.marker_box):
            finding.addWidget(w)
        finding.setStretch(0, 1)
        for w in (self.pause_box, self.autoscroll_box, self.count_label, self.load_bar):
            actions.addWidget(w)
        actions.addStretch(1)
        for w in (self.stop_load_button, self.live_button, self.record_button,
                  self.clear_button, self.open_button, self.save_button):
            actions.addWidget(w)
        # Statistics under the frames, both the dock's full width: side by side, a dock
        # beside the inspector is too narrow to show either's meaning column.
        self.splitter = QSplitter(Qt.Orientation.Vertical)
        self.splitter.addWidget(self.view)
        self.splitter.addWidget(self.stats_view)
        self.splitter.setStretchFactor(0, 3)
        self.splitter.setStretchFactor(1, 2)
        self.splitter.setSizes([620, 380])
        self.splitter.setChildrenCollapsible(True)
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(2, 2, 2, 2)
        layout.addLayout(filters)
        layout.addLayout(finding)
        layout.addLayout(actions)
        layout.addWidget(self.splitter)
        self.setWidget(body)

    # -- what is shown -------------------------------------------------------------------
    @property
    def store(self) -> FrameStore:
        """The frames the table shows: the opened capture's, or the live ring."""
        return self.capture_store if self.capture_store is not None else self.live_store

    @property
    def stats(self) -> IdStats:
        return self.capture_stats if self.capture_stats is not None else self.live_stats

    @property
    def all_rows(self) -> list[Frame]:
        """Every frame of what is shown (the live ring or the capture), oldest first."""
        self.flush()
        return stored_rows(self.store)

    def shown_rows(self) -> list[Frame]:
        """The frames the table shows now (filtered; frozen while paused)."""
        self.flush()
        m = self.model
        return [m.store.frame(m.absolute(r)) for r in range(m.rowCount())]

    @property
    def paused(self) -> bool:
        """True while the table is frozen (frames are still recorded and counted)."""
        return self.pause_box.isChecked()

    # -- feeding -------------------------------------------------------------------------
    def add_frames(self, frames: Iterable[Any]) -> None:
        """Slot for ``SessionBridge.frameSeen``: queue a batch (taken on the next tick)."""
        self._incoming.extend(frames)

    def flush(self) -> None:
        """Take the queued frames and bring the table and statistics up to date now (else:
        on the next tick)."""
        self._ingest()  # all of them, not a slice
        self._tick()
        self._refresh_stats()

    def _ingest(self, limit: int | None = None) -> None:
        """Turn the queued frames (at most ``limit`` of them) into rows and statistics."""
        if not self._incoming:
            return
        if limit is not None and len(self._incoming) > limit:
            frames, self._incoming = self._incoming[:limit], self._incoming[limit:]
        else:
            frames, self._incoming = self._incoming, []
        _spare_the_collector()
        if self.recorder is not None:
            self.recorder.feed([(f.timestamp, f.arbitration_id, f.data) for f in frames])
        add = self._builder.add
        for f in frames:
            add(f.timestamp, f.arbitration_id, f.data if type(f.data) is bytes else bytes(f.data),
                line_head(f.text or ""))
        chunk = self._builder.take()
        for node in self._builder.channel_nodes - self._link_map.keys():
            self._link_map[node] = (f"node {node}", ())  # named by the session's decoder
        self.frames_seen += len(frames)
        self.live_stats.update(chunk)
        self.live_store.append(chunk)

    def _tick(self) -> None:
        if not self._incoming and self.model.end == self.store.end and \
                self._load_worker is None:
            return  # nothing came: nothing to do
        self._ingest(INGEST_SLICE)
        if self._incoming:  # more than a slice waits: the rest after the events queued now
            self._more.start()
        if not self.paused and self._filter_worker is None:
            added = self.model.sync()
            if added and self.autoscroll_box.isChecked() and self.capture_store is None:
                self.view.scrollToBottom()  # live frames; a capture stays at its start
        self._count()

    def _refresh_stats(self) -> None:
        if self.stats_view.isVisible() or not self.isVisible():
            self.stats_model.refresh(self.stats.view())
        self._list_new_nodes()

    def set_paused(self, paused: bool) -> None:
        """Freeze the table; frames keep being recorded and counted and appear on resume."""
        if self.pause_box.isChecked() != paused:
            self.pause_box.setChecked(paused)  # re-enters through toggled
            return
        self._ingest()
        if paused:
            self.model.show(self.store.snapshot(), self._filter, self.model.rows, self.model.end)
        else:
            self._show_filtered()

    def clear(self) -> None:
        """Forget the frames shown (live: the ring and its statistics) and the markers."""
        self._incoming.clear()
        self.store.clear()
        self.stats.clear()
        if self.capture_store is None:
            self.frames_seen = 0
        self.markers.clear()
        self._refresh_markers()
        self._hits = None
        self.model.show(self.store, self._filter)
        self.model.clear()
        self.stats_model.refresh([])
        self._count()

    def set_system(self, system: Any) -> None:
        """Learn node names (devices and output channels) and which nodes send channel data,
        so a capture opened later names its links."""
        for device in system.devices.values():
            self.model.names[tuple(device.key)] = device.label
            if device.node_id is not None:
                self._node_names[device.node_id] = device.label
        for ref, ch in system.channels():
            if ch.is_output and ch.node_id is not None:
                self._builder.channel_nodes.add(ch.node_id)
                self._link_map[ch.node_id] = (ref, tuple(system.inputs_fed_by(ref)))
                device = system.device(ref.device)
                owner = device.label if device is not None else str(ref)
                self._node_names[ch.node_id] = self.tr("{device} output {index}").format(
                    device=owner, index=ref.index)
        self._fill_node_filter()

    @property
    def channel_nodes(self) -> set[int]:
        """Node IDs of output channels: their frames are channel data."""
        return self._builder.channel_nodes

    @channel_nodes.setter
    def channel_nodes(self, nodes: Iterable[int]) -> None:
        self._builder.channel_nodes = set(nodes)

    def reset_for_session(self, system: Any, *, keep_frames: bool = False) -> None:
        """Follow the bus this dock shows: forget the node map (node IDs are reassigned
        after a reset or hot-swap) and learn ``system``'s; a new session (``keep_frames``
        False) also starts with no frames, so two sessions' frames are never mixed."""
        if not keep_frames and self.capture_store is None:
            self.clear()
        elif not keep_frames:
            self._incoming.clear()
            self.live_store.clear()
            self.live_stats.clear()
        self._builder.channel_nodes.clear()
        self._link_map.clear()
        self._node_names.clear()
        self.model.names.clear()
        self.set_system(system)

    # -- node filter ---------------------------------------------------------------------
    def _fill_node_filter(self) -> None:
        box = self.node_filter
        current = box.currentData() if box.count() else None
        box.blockSignals(True)
        try:
            box.clear()
            box.addItem(self.tr("Any node"), None)
            box.addItem(self.tr("Broadcast"), 0)
            nodes = set(self._node_names) | self._nodes_listed
            for node in sorted(nodes - {0}):
                name = self._node_names.get(node)
                box.addItem(self.tr("{name} (node {node})").format(name=name, node=node)
                            if name else self.tr("Node {node}").format(node=node), node)
            found = box.findData(current)
            box.setCurrentIndex(max(0, found))
        finally:
            box.blockSignals(False)

    def _list_new_nodes(self) -> None:
        seen = {aid & 0xFF for aid in self.stats.ids() if aid <= 0x7FF}
        if not seen <= self._nodes_listed | set(self._node_names) | {0}:
            self._nodes_listed |= seen
            self._fill_node_filter()

    # -- filters and search --------------------------------------------------------------
    def set_filter(self, text: str = "", function: str = "", node: int | None = None) -> None:
        """Filter programmatically (the widgets follow; the table is filtered once).
        ``node`` None shows every node, 0 the broadcasts."""
        widgets = (self.text_filter, self.function_filter, self.node_filter)
        for w in widgets:
            w.blockSignals(True)
        try:
            self.text_filter.setText(text)
            self.function_filter.setCurrentText(function or translate("MonitorDock", str(ANY)))
            if node is not None and self.node_filter.findData(node) < 0:
                self._nodes_listed.add(node)
                self._fill_node_filter()
            self.node_filter.setCurrentIndex(max(0, self.node_filter.findData(node)))
        finally:
            for w in widgets:
                w.blockSignals(False)
        self._filter_changed()

    def _filter_changed(self, *_args: Any) -> None:
        self._refilter.stop()
        node = self.node_filter.currentData()
        self._filter = TraceFilter(
            self.text_filter.text().strip(),
            "" if self.function_filter.currentIndex() <= 0 else self.function_filter.currentText(),
            None if node is None else int(node))
        self._show_filtered()

    def _show_filtered(self) -> None:
        """Show the current store through the filter: at once when small, else the rows
        are selected on a worker (the table keeps its old rows meanwhile)."""
        self._ingest()
        flt = self._filter
        store = self.store if not self.paused else self.model.store
        if self._filter_worker is not None:
            self._filter_worker.cancel()
            self._filter_worker = None
        if not flt or len(store) <= FILTER_AT_ONCE:
            self.model.show(store, flt)
            self._after_filter()
            return
        end = store.end
        self.count_label.setText(self.tr("Filtering…"))

        def work(progress: Any, cancel: threading.Event) -> Any:
            return store.select(flt, None, end, cancel,
                                lambda done, total: progress(done, total, ""))

        worker = Worker(work, "Filter frames")
        self._filter_worker = worker

        def finished(rows: Any) -> None:
            if self._filter_worker is worker:
                self._filter_worker = None
                self.model.show(store, flt, rows, end)
                self._after_filter()

        def dropped() -> None:
            if self._filter_worker is worker:
                self._filter_worker = None

        worker.finished.connect(finished)
        worker.cancelled.connect(dropped)
        def failed(message: str) -> None:
            dropped()
            self.error.emit(message)

        worker.failed.connect(failed)
        worker.start()

    def _after_filter(self) -> None:
        if not self.paused:
            self.model.sync()
        if self.autoscroll_box.isChecked():
            self.view.scrollToBottom()
        self._count()
        self.filtered.emit()

    def find_frame(self, text: str, forward: bool = True) -> Worker | None:
        """Go to the next (or previous) frame after the selected row whose text, function,
        ID (``0x…``) or data contains ``text``; the search runs on a worker over all the
        frames of the store, and ``found(row)`` follows (-1: none in the table)."""
        needle = text.strip()
        if not needle:
            return None
        self.flush()
        store = self.model.store
        hits = self._hits
        start = 0
        if hits is not None and hits[0] == needle and hits[2] <= store.end:
            start = hits[2]
        end = store.end
        current = self.view.currentIndex()
        origin = self.model.absolute(current.row()) if current.isValid() else (
            store.base - 1 if forward else store.end)

        def work(_progress: Any, cancel: threading.Event) -> Any:
            return store.select(TraceFilter(text=needle), start, end, cancel)

        worker = Worker(work, "Find frames")
        self._find_worker = worker

        def finished(more: Any) -> None:
            old = self._hits[1] if (self._hits is not None and start) else np.zeros(0, np.int64)
            found = np.concatenate((old, more))
            self._hits = (needle, found, end)
            self._go_to_hit(found, origin, forward)

        worker.finished.connect(finished)
        worker.failed.connect(self.error.emit)
        return worker.start()

    def _go_to_hit(self, hits: np.ndarray, origin: int, forward: bool) -> None:
        m = self.model
        if m.rows is not None and len(hits):
            hits = hits[np.isin(hits, m.rows)]
        hits = hits[hits >= m.store.base]
        if forward:
            pos = int(np.searchsorted(hits, origin, side="right"))
            target = int(hits[pos]) if pos < len(hits) else None
        else:
            pos = int(np.searchsorted(hits, origin, side="left")) - 1
            target = int(hits[pos]) if pos >= 0 else None
        row = None if target is None else m.row_of(target)
        if row is None:
            self.found.emit(-1)
            return
        self._select_row(row)
        self.found.emit(row)

    def _select_row(self, row: int) -> None:
        self.autoscroll_box.setChecked(False)  # do not jump away from what was found
        index = self.model.index(row, 0)
        self.view.setCurrentIndex(index)
        self.view.scrollTo(index, QTableView.ScrollHint.PositionAtCenter)

    def _stats_row_chosen(self, index: Any) -> None:
        stat = self.stats_model.stats[index.row()]
        self.set_filter(text=f"0x{stat.arbitration_id:03X}")

    # -- time and markers ----------------------------------------------------------------
    def set_time_mode(self, mode: int) -> None:
        """Time since start, clock time, since the previous row, or since the marker."""
        if self.time_mode.currentIndex() != mode:
            self.time_mode.setCurrentIndex(mode)  # re-enters through the signal
            return
        self.model.set_time_mode(mode)

    def add_marker(self, name: str = "") -> Marker | None:
        """Mark the selected frame, or the newest frame shown; times since a marker count
        from the newest marker until another is chosen."""
        self.flush()
        current = self.view.currentIndex()
        m = self.model
        if current.isValid():
            index = m.absolute(current.row())
        elif m.rowCount():
            index = m.absolute(m.rowCount() - 1)
        else:
            return None
        marker = Marker(index, m.store.timestamp(index),
                        name or self.tr("Marker {n}").format(n=len(self.markers) + 1))
        self.markers.append(marker)
        m.markers[index] = marker.name
        m.set_marker_time(marker.time)
        row = m.row_of(index)
        if row is not None:
            m.dataChanged.emit(m.index(row, 0), m.index(row, m.columnCount() - 1))
        self._refresh_markers()
        self.marker_box.setCurrentIndex(len(self.markers) - 1)
        return marker

    def jump_to_marker(self, i: int) -> None:
        """Select the marked frame (or the first shown after it) and count from it."""
        if not 0 <= i < len(self.markers):
            return
        marker = self.markers[i]
        self.model.set_marker_time(marker.time)
        row = self.model.row_of(marker.index, nearest=True)
        if row is not None:
            self._select_row(row)

    def _refresh_markers(self) -> None:
        box = self.marker_box
        box.clear()
        t0 = self.model.t0 or 0.0
        for marker in self.markers:
            box.addItem(f"{marker.name}  {marker.time - t0:.3f} s")
        if not self.markers:
            box.addItem(self.tr("No markers"))
        box.setEnabled(bool(self.markers))

    # -- recording -----------------------------------------------------------------------
    def _toggle_recording(self, on: bool) -> None:
        if not on:
            self.stop_recording()
            return
        path, _ = QFileDialog.getSaveFileName(
            self, self.tr("Record live frames"), "recording.blf",
            self.tr("python-can logs (*.blf *.asc *.log *.csv *.trc)"))
        if path:
            self.start_recording(path)
        else:
            self.record_button.setChecked(False)

    def start_recording(self, path: str | Path) -> None:
        """Write every live frame from now on to ``path`` (a python-can capture by
        extension), on a thread, until ``stop_recording()``."""
        self.stop_recording()
        try:
            self.recorder = LiveRecorder(path, dict(self._link_map))
        except Exception as err:
            self.record_button.setChecked(False)
            self.error.emit(self.tr("Recording {path}: {message}").format(path=path,
                                                                          message=err))
            return
        self.record_button.setChecked(True)
        self.record_button.setText(self.tr("Recording"))
        self._count()

    def stop_recording(self) -> int:
        """Finish the recording (the file is complete once this returns); the count."""
        if self.recorder is not None:
            self._ingest()  # what is queued goes in too
        recorder, self.recorder = self.recorder, None
        self.record_button.setChecked(False)
        self.record_button.setText(self.tr("Record…"))
        if recorder is None:
            return 0
        written = recorder.stop()
        if recorder.error:
            self.error.emit(self.tr("Recording {path}: {message}").format(
                path=recorder.path, message=recorder.error))
        else:
            self.saved.emit(str(recorder.path))
        self._count()
        return written

    def _count(self) -> None:
        shown = self.model.rowCount()
        total = len(self.store)
        if self.capture_store is not None:
            text = (self.tr("{shown} of {total} frames").format(shown=f"{shown:,}",
                                                                 total=f"{total:,}")
                    if self._filter else self.tr("{total} frames").format(total=f"{total:,}"))
        else:
            seen = self.frames_seen
            text = (self.tr("{shown} of {total} frames").format(shown=f"{shown:,}",
                                                                 total=f"{seen:,}")
                    if self._filter or seen != shown
                    else self.tr("{total} frames").format(total=f"{seen:,}"))
        if self.recorder is not None:
            text += self.tr(" · recording to {name}").format(name=self.recorder.path.name)
        if self._filter_worker is None:
            self.count_label.setText(text)
        if (shown, total) != self._counted:
            self._counted = (shown, total)
            self.countChanged.emit(shown, total)

    # -- saving and opening --------------------------------------------------------------
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
        """Save every frame of what is shown on a worker; ``saved(path)`` or ``error``."""
        self.flush()
        store = self.store.snapshot()
        links = dict(self._link_map)
        self.save_button.setEnabled(False)

        def work(_progress: Any, _cancel: threading.Event) -> int:
            return save_store(path, store, links)

        worker = Worker(work, "Save frames")
        self._save_path = str(path)
        worker.finished.connect(self._save_finished)  # bound slots: dropped with the dock
        worker.failed.connect(self._save_failed)
        worker.done.connect(self._save_done)
        self._save_worker = worker
        return worker.start()

    def load_capture(self, path: str | Path) -> Worker:
        """Show a capture (any python-can log format) apart from the live frames.

        Decoded on a worker into a store of its own (with the node map saved beside the
        capture when there is one): the first rows show at once, the rest as they are read,
        with ``loadProgress(frames)``, a progress bar and ``cancel_load()``. Live frames keep
        being recorded and come back with ``show_live()``. ``loaded(path)`` or ``error``.
        """
        self.cancel_load()
        _spare_the_collector()
        links = dict(self._link_map)  # a capture may start after the set-up that names them
        store = FileFrameStore()  # on disk: memory stays flat however long the capture
        stats = IdStats(store.tables)

        def work(progress: Any, cancel: threading.Event) -> int:
            return _load_into(store, stats, path, links, progress, cancel)

        self._enter_capture(str(path), store, stats)
        worker = Worker(work, "Load capture")
        self._load_path = str(path)
        worker.progress.connect(self._capture_progress)
        worker.finished.connect(self._capture_loaded)
        worker.failed.connect(self._load_failed)
        worker.done.connect(self._capture_done)
        self._load_worker = worker
        self.stop_load_button.setVisible(True)
        self.load_bar.setValue(0)
        self.load_bar.setVisible(True)
        self.count_label.setVisible(False)  # the bar counts meanwhile (and the row stays short)
        return worker.start()

    def show_frames(self, store: FrameStore, stats: IdStats | None = None,
                    title: str = "") -> None:
        """Show frames already in a store (a capture read elsewhere) apart from the live
        ones, as ``load_capture`` does; ``show_live()`` returns."""
        self.cancel_load()
        if stats is None:
            stats = IdStats(store.tables)
            for chunk in store.chunks:
                stats.update(chunk)
        self._enter_capture(title or self.tr("frames"), store, stats)
        self.capture_total = len(store)

    def cancel_load(self) -> None:
        """Stop reading an opened capture (what was read stays shown)."""
        if self._load_worker is not None and self._load_worker.is_running:
            self._load_worker.cancel()

    def show_live(self) -> None:
        """Close the opened capture: the table shows the live frames again."""
        self.cancel_load()
        self.capture_path = None
        if self.capture_store is not None:
            self.capture_store.close()  # its temporary files go now
        self.capture_store = self.capture_stats = None
        self.live_button.setVisible(False)
        self.stop_load_button.setVisible(False)
        self.load_bar.setVisible(False)
        self.count_label.setVisible(True)
        self.setWindowTitle(self.tr("Bus monitor"))
        self._reset_view()

    def _enter_capture(self, path: str, store: FrameStore, stats: IdStats) -> None:
        if self.capture_store is not None and self.capture_store is not store:
            self.capture_store.close()  # the capture shown before: its temporary files go
        self.capture_path = path
        self.capture_total = 0
        self.capture_store, self.capture_stats = store, stats
        self.live_button.setVisible(True)
        self.setWindowTitle(self.tr("Bus monitor — capture %1").replace("%1", Path(path).name))
        self._reset_view()

    def _reset_view(self) -> None:
        self.markers.clear()
        self._refresh_markers()
        self._hits = None
        self.model.t0 = None
        self.model.markers.clear()
        self.model.marker_time = None
        self._show_filtered()
        self._refresh_stats()
        self._count()

    def _capture_progress(self, done: int, permille: int, _text: str) -> None:
        self.load_bar.setValue(permille)
        self.load_bar.setFormat(self.tr("%1 frames").replace("%1", f"{done:,}"))
        self.loadProgress.emit(done)
        if self.model.rowCount() == 0:
            self._tick()  # the first rows at once

    def _capture_loaded(self, total: int) -> None:
        if self.capture_store is None:
            return
        self.capture_total = total
        self.flush()
        self.loaded.emit(self._load_path)

    def _capture_done(self) -> None:
        if self.sender() is not self._load_worker:
            return  # an earlier capture's reader, replaced by a newer one
        self._load_worker = None
        self.stop_load_button.setVisible(False)
        self.load_bar.setVisible(False)
        self.count_label.setVisible(True)
        self.flush()

    def _load_failed(self, message: str) -> None:
        self.error.emit(self.tr("Reading {load_path}: {message}").format(
            load_path=self._load_path, message=message))

    def _save_finished(self, _count: int) -> None:
        self.saved.emit(self._save_path)

    def _save_failed(self, message: str) -> None:
        self.error.emit(self.tr("Saving {save_path}: {message}").format(
            save_path=self._save_path, message=message))

    def _save_done(self) -> None:
        self.save_button.setEnabled(True)
