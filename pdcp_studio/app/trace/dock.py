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
of the live ring (``store``; bounded to ``capacity`` frames), updates the per-ID statistics
with vectorised counts, and lets the virtual-row table (``model``) insert the new rows at
once; a larger backlog is taken ``INGEST_SLICE`` frames per turn of the event loop. The
statistics view makes a row only for the identifiers it paints. An opened capture is
decoded on a worker into its own store (shown apart from the live frames, which keep being
recorded); its first rows show at once and the rest follow chunk by chunk with progress and
a Stop button. Filters and search over a large store run on a worker and return row lists;
small ones are filtered at once.

The dock composes parts that each do one job and get only what they need: ``bar`` (the
controls), ``tables`` (the two views), ``feed`` (the live ring), ``filtering``, ``search``,
``markers``, ``recording``, ``saving`` and ``loading``; it keeps what is shown (the live
ring or a capture), the filter, and the timers.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from pathlib import Path
from typing import Any, NamedTuple

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtWidgets import (
    QDockWidget,
    QFileDialog,
    QLabel,
    QSplitter,
    QStackedWidget,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.bar import ANY, TraceBar
from pdcp_studio.app.trace.disk import FileFrameStore
from pdcp_studio.app.trace.feed import LiveFeed
from pdcp_studio.app.trace.files.capture import CaptureVerdict, stored_rows
from pdcp_studio.app.trace.files.loading import CaptureLoading
from pdcp_studio.app.trace.files.record import LiveRecorder
from pdcp_studio.app.trace.files.recording import LiveRecording
from pdcp_studio.app.trace.files.saving import FrameSaving
from pdcp_studio.app.trace.filtering import BackgroundFilter
from pdcp_studio.app.trace.markers import Marker, Markers
from pdcp_studio.app.trace.model import StatsModel, TraceModel, decoded_fields
from pdcp_studio.app.trace.search import FrameFinder
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
from pdcp_studio.app.trace.tables import frame_table, show_plain, stats_table
from pdcp_studio.app.trace.verdict import problem_text, verdict_text
from pdcp_studio.app.workers import Worker

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
        self.feed = LiveFeed(self, capacity, self._taking)
        self.live_store, self.live_stats = self.feed.store, self.feed.stats
        self.capture_store: FrameStore | None = None
        self.capture_stats: IdStats | None = None
        self.capture_path: str | None = None
        self.capture_total = 0
        self._filter = TraceFilter()
        self._counted = (-1, -1)

        self.model = TraceModel(self)
        self.stats_model = StatsModel(self)
        self.stats_model.names = self.model.names  # one map of device names
        self._build_widgets()
        self.marker_list = Markers(self.model, self.view, self.bar, self._select_row)
        self.recording = LiveRecording(self.bar.record_button, self, lambda: self.feed.links,
                                       self.feed.ingest, self._count,
                                       self.saved.emit, self.error.emit)
        self.saving = FrameSaving(self, self.bar.save_button, self.saved.emit, self.error.emit)
        self.loading = CaptureLoading(self, self.bar, self._capture_progress,
                                      self._show_verdict, self._capture_loaded, self.flush,
                                      self._load_failed)
        #: What the opened capture is (None: live frames, or not known yet).
        self.verdict: CaptureVerdict | None = None
        #: Why the opened capture could not be read (shown where its rows would be).
        self.problem: str | None = None
        self.filtering = BackgroundFilter(self._filtered, self.error.emit)
        self.finder = FrameFinder(self.model, self.view, self._select_row, self.found.emit,
                                  self.error.emit)
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
        self.view = frame_table(self.model)
        self.stats_view = stats_table(self.stats_model)
        self.stats_view.doubleClicked.connect(self._stats_row_chosen)
        bar = self.bar = TraceBar()
        # The bar's widgets callers read by the dock's name.
        self.text_filter, self.node_filter, self.marker_box = (
            bar.text_filter, bar.node_filter, bar.marker_box)
        self.count_label, self.record_button = bar.count_label, bar.record_button
        self.live_button, self.stop_load_button = bar.live_button, bar.stop_load_button

        bar.text_filter.textChanged.connect(lambda _t: self._refilter.start())
        bar.function_filter.currentIndexChanged.connect(self._filter_changed)
        bar.node_filter.currentIndexChanged.connect(self._filter_changed)
        bar.find_edit.returnPressed.connect(lambda: self.find_frame(bar.find_edit.text()))
        bar.find_next.clicked.connect(lambda: self.find_frame(bar.find_edit.text()))
        bar.find_prev.clicked.connect(lambda: self.find_frame(bar.find_edit.text(), forward=False))
        bar.pause_box.toggled.connect(self.set_paused)
        bar.time_mode.currentIndexChanged.connect(self.set_time_mode)
        bar.marker_button.clicked.connect(lambda: self.add_marker())
        bar.marker_box.activated.connect(self.jump_to_marker)
        bar.clear_button.clicked.connect(self.clear)
        bar.save_button.clicked.connect(self._ask_save)
        bar.open_button.clicked.connect(self._ask_open)
        bar.live_button.clicked.connect(self.show_live)
        bar.stop_load_button.clicked.connect(self.cancel_load)

        # Statistics under the frames, both the dock's full width: side by side, a dock
        # beside the inspector is too narrow to show either's meaning column.
        self.splitter = QSplitter(Qt.Orientation.Vertical)
        self.splitter.addWidget(self.view)
        self.splitter.addWidget(self.stats_view)
        self.splitter.setStretchFactor(0, 3)
        self.splitter.setStretchFactor(1, 2)
        self.splitter.setSizes([620, 380])
        self.splitter.setChildrenCollapsible(True)
        # What an opened capture is (its verdict, node map, damage): over its rows.
        self.banner = QLabel()
        self.banner.setObjectName("TraceBanner")
        self.banner.setWordWrap(True)
        self.banner.setTextFormat(Qt.TextFormat.PlainText)
        self.banner.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.banner.setStyleSheet("#TraceBanner { background: palette(alternate-base); "
                                  "border: 1px solid palette(mid); padding: 3px; }")
        self.banner.setVisible(False)
        # A capture that cannot be read says why where its rows would be.
        self.problem_label = QLabel()
        self.problem_label.setObjectName("TraceProblem")
        self.problem_label.setWordWrap(True)
        self.problem_label.setTextFormat(Qt.TextFormat.PlainText)
        self.problem_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.problem_label.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        self.problem_label.setMargin(12)
        self.pages = QStackedWidget()
        self.pages.addWidget(self.splitter)
        self.pages.addWidget(self.problem_label)
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(2, 2, 2, 2)
        for row in bar.rows:
            layout.addLayout(row)
        layout.addWidget(self.banner)
        layout.addWidget(self.pages)
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
        return self.bar.pause_box.isChecked()

    # -- feeding -------------------------------------------------------------------------
    def add_frames(self, frames: Iterable[Any]) -> None:
        """Slot for ``SessionBridge.frameSeen``: queue a batch (taken on the next tick)."""
        self.feed.add(frames)

    @property
    def frames_seen(self) -> int:
        """Live frames counted since the last clear, kept or not."""
        return self.feed.frames_seen

    def flush(self) -> None:
        """Take the queued frames and bring the table and statistics up to date now (else:
        on the next tick)."""
        self.feed.ingest()  # all of them, not a slice
        self._tick()
        self._refresh_stats()

    def _taking(self, frames: list[Any]) -> None:
        """A batch of live frames becomes rows: into the recording too."""
        _spare_the_collector()
        recorder = self.recording.recorder
        if recorder is not None:
            recorder.feed([(f.timestamp, f.arbitration_id, f.data) for f in frames])

    def _tick(self) -> None:
        if not self.feed.incoming and self.model.end == self.store.end and \
                self.loading.worker is None:
            return  # nothing came: nothing to do
        self.feed.ingest(INGEST_SLICE)
        if self.feed.incoming:  # more than a slice waits: the rest after the events queued now
            self._more.start()
        if not self.paused and self.filtering.worker is None:
            added = self.model.sync()
            if added and self.bar.autoscroll_box.isChecked() and self.capture_store is None:
                self.view.scrollToBottom()  # live frames; a capture stays at its start
        self._count()

    def _refresh_stats(self) -> None:
        if self.stats_view.isVisible() or not self.isVisible():
            self.stats_model.refresh(self.stats.view())
        self.bar.nodes.heard({aid & 0xFF for aid in self.stats.ids() if aid <= 0x7FF})

    def set_paused(self, paused: bool) -> None:
        """Freeze the table; frames keep being recorded and counted and appear on resume."""
        if self.bar.pause_box.isChecked() != paused:
            self.bar.pause_box.setChecked(paused)  # re-enters through toggled
            return
        self.feed.ingest()
        if paused:
            self.model.show(self.store.snapshot(), self._filter, self.model.rows, self.model.end)
        else:
            self._show_filtered()

    def clear(self) -> None:
        """Forget the frames shown (live: the ring and its statistics) and the markers."""
        self.feed.incoming.clear()
        self.store.clear()
        self.stats.clear()
        if self.capture_store is None:
            self.feed.frames_seen = 0
        self.marker_list.clear()
        self.finder.forget()
        self.model.show(self.store, self._filter)
        self.model.clear()
        self.stats_model.refresh([])
        self._count()

    def set_system(self, system: Any) -> None:
        """Learn node names (devices and output channels) and which nodes send channel data,
        so a capture opened later names its links."""
        from pdcp_studio.app.words.part_names import part_names

        for key, name in part_names(system).items():  # the one name of every part
            self.model.names[(key.vid, key.pid, key.serial)] = name
        for ref, ch in system.channels():
            if ch.is_output and ch.node_id is not None:
                self.feed.learn_output(ch.node_id, (ref, tuple(system.inputs_fed_by(ref))))
        self.bar.nodes.learn(system)

    @property
    def channel_nodes(self) -> set[int]:
        """Node IDs of output channels: their frames are channel data."""
        return self.feed.channel_nodes

    @channel_nodes.setter
    def channel_nodes(self, nodes: Iterable[int]) -> None:
        self.feed.channel_nodes = nodes

    def reset_for_session(self, system: Any, *, keep_frames: bool = False) -> None:
        """Follow the bus this dock shows: forget the node map (node IDs are reassigned
        after a reset or hot-swap) and learn ``system``'s; a new session (``keep_frames``
        False) also starts with no frames, so two sessions' frames are never mixed."""
        if not keep_frames and self.capture_store is None:
            self.clear()
        elif not keep_frames:
            self.feed.drop()
        self.feed.forget_links()
        self.bar.nodes.names.clear()
        self.model.names.clear()
        self.set_system(system)

    # -- filters and search --------------------------------------------------------------
    def set_filter(self, text: str = "", function: str = "", node: int | None = None) -> None:
        """Filter programmatically (the widgets follow; the table is filtered once).
        ``node`` None shows every node, 0 the broadcasts."""
        widgets = (self.bar.text_filter, self.bar.function_filter, self.bar.node_filter)
        for w in widgets:
            w.blockSignals(True)
        try:
            self.bar.text_filter.setText(text)
            self.bar.function_filter.setCurrentText(function or translate("MonitorDock", str(ANY)))
            if node is not None:
                self.bar.nodes.include(node)
            self.bar.node_filter.setCurrentIndex(max(0, self.bar.node_filter.findData(node)))
        finally:
            for w in widgets:
                w.blockSignals(False)
        self._filter_changed()

    def _filter_changed(self, *_args: Any) -> None:
        self._refilter.stop()
        node = self.bar.node_filter.currentData()
        function = self.bar.function_filter
        self._filter = TraceFilter(
            self.bar.text_filter.text().strip(),
            "" if function.currentIndex() <= 0 else function.currentText(),
            None if node is None else int(node))
        self._show_filtered()

    def _show_filtered(self) -> None:
        """Show the current store through the filter: at once when small, else the rows
        are selected on a worker (the table keeps its old rows meanwhile)."""
        self.feed.ingest()
        flt = self._filter
        store = self.store if not self.paused else self.model.store
        self.filtering.cancel()
        if not flt or len(store) <= FILTER_AT_ONCE:
            self.model.show(store, flt)
            self._after_filter()
            return
        self.bar.count_label.setText(self.tr("Filtering…"))
        self.filtering.start(store, flt)

    def _filtered(self, store: FrameStore, flt: TraceFilter, rows: Any, end: int) -> None:
        self.model.show(store, flt, rows, end)
        self._after_filter()

    def _after_filter(self) -> None:
        if not self.paused:
            self.model.sync()
        if self.bar.autoscroll_box.isChecked():
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
        return self.finder.find(needle, forward)

    def _select_row(self, row: int) -> None:
        self.bar.autoscroll_box.setChecked(False)  # do not jump away from what was found
        index = self.model.index(row, 0)
        self.view.setCurrentIndex(index)
        self.view.scrollTo(index, QTableView.ScrollHint.PositionAtCenter)

    def _stats_row_chosen(self, index: Any) -> None:
        stat = self.stats_model.stats[index.row()]
        self.set_filter(text=f"0x{stat.arbitration_id:03X}")

    # -- time and markers ----------------------------------------------------------------
    def set_time_mode(self, mode: int) -> None:
        """Time since start, clock time, since the previous row, or since the marker."""
        if self.bar.time_mode.currentIndex() != mode:
            self.bar.time_mode.setCurrentIndex(mode)  # re-enters through the signal
            return
        self.model.set_time_mode(mode)

    def add_marker(self, name: str = "") -> Marker | None:
        """Mark the selected frame, or the newest frame shown; times since a marker count
        from the newest marker until another is chosen."""
        self.flush()
        return self.marker_list.add(name)

    def jump_to_marker(self, i: int) -> None:
        """Select the marked frame (or the first shown after it) and count from it."""
        self.marker_list.jump(i)

    @property
    def markers(self) -> list[Marker]:
        return self.marker_list.items

    # -- recording -----------------------------------------------------------------------
    @property
    def recorder(self) -> LiveRecorder | None:
        """The recording of the live frames under way, if any."""
        return self.recording.recorder

    def start_recording(self, path: str | Path) -> None:
        """Write every live frame from now on to ``path`` (a python-can capture by
        extension), on a thread, until ``stop_recording()``."""
        self.recording.start(path)

    def stop_recording(self) -> int:
        """Finish the recording (the file is complete once this returns); the count."""
        return self.recording.stop()

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
        if self.problem is not None:
            text = self.tr("not read")
        recorder = self.recording.recorder
        if recorder is not None:
            text += self.tr(" · recording to {name}").format(name=recorder.path.name)
        if self.filtering.worker is None:
            self.bar.count_label.setText(text)
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
        from pdcp_studio.app.trace.files.formats import open_filter

        path, _ = QFileDialog.getOpenFileName(self, self.tr("Open capture"), "", open_filter())
        if path:
            self.load_capture(path)

    def save(self, path: str | Path) -> Worker:
        """Save every frame of what is shown on a worker; ``saved(path)`` or ``error``."""
        self.flush()
        if self.capture_store is not None:  # its own node map, never the live session's
            verdict = self.verdict
            return self.saving.save(path, self.store.snapshot(), None,
                                    None if verdict is None else verdict.node_map_json)
        return self.saving.save(path, self.store.snapshot(), dict(self.feed.links))

    def load_capture(self, path: str | Path) -> Worker | None:
        """Show a capture (any format the reader knows, by content) apart from the live
        frames.

        Decoded on a worker into a store of its own with the capture's own node map (saved
        beside it, or learned from its traffic; never the live session's): the first rows
        show at once, the rest as they are read, with ``loadProgress(frames)``, a progress
        bar and ``cancel_load()``; the banner says what it is (``verdict``). Live frames keep
        being recorded and come back with ``show_live()``. ``loaded(path)``, or ``error``
        with the reason also shown where the rows would be (a pipe is refused at once:
        None is returned)."""
        from pdcp_studio.app.trace.files.capture import refuse_stream
        from pdcp_studio.bus.trace.files.capture import CaptureError

        self.cancel_load()
        _spare_the_collector()
        store = FileFrameStore()  # on disk: memory stays flat however long the capture
        stats = IdStats(store.tables)
        self._enter_capture(str(path), store, stats)
        try:
            refuse_stream(path)  # opening a FIFO would wait for a writer, beyond any Stop
        except CaptureError:
            self._load_failed(self.tr(
                "{path}: a pipe or a device, not a capture file (the app opens files; read "
                "a pipe with pdcp-studio monitor --replay)").format(path=path))
            return None
        return self.loading.start(path, store, stats)

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
        self.loading.cancel()

    def show_live(self) -> None:
        """Close the opened capture: the table shows the live frames again."""
        self.cancel_load()
        self.capture_path = None
        if self.capture_store is not None:
            self.capture_store.close()  # its temporary files go now
        self.capture_store = self.capture_stats = None
        self.bar.live_button.setVisible(False)
        self.loading.hide_progress()
        self._set_verdict(None, None)
        self.setWindowTitle(self.tr("Bus monitor"))
        self._reset_view()

    def _enter_capture(self, path: str, store: FrameStore, stats: IdStats) -> None:
        if self.capture_store is not None and self.capture_store is not store:
            self.capture_store.close()  # the capture shown before: its temporary files go
        self.capture_path = path
        self.capture_total = 0
        self.capture_store, self.capture_stats = store, stats
        self._set_verdict(None, None)
        self.bar.live_button.setVisible(True)
        self.setWindowTitle(self.tr("Bus monitor — capture %1").replace("%1", Path(path).name))
        self._reset_view()

    def _reset_view(self) -> None:
        self.marker_list.clear()
        self.finder.forget()
        self.model.t0 = None
        self.model.markers.clear()
        self.model.marker_time = None
        self._show_filtered()
        self._refresh_stats()
        self._count()

    def _capture_progress(self, done: int) -> None:
        self.loadProgress.emit(done)
        if self.model.rowCount() == 0:
            self._tick()  # the first rows at once

    def _capture_loaded(self, verdict: CaptureVerdict, path: str) -> None:
        if self.capture_store is None:
            return
        self.capture_total = verdict.frames
        self._set_verdict(verdict, None)
        self.flush()
        self.loaded.emit(path)

    def _show_verdict(self, verdict: CaptureVerdict) -> None:
        """What the opened capture is, once its first frames (or its end) say so."""
        if self.capture_store is not None:
            self._set_verdict(verdict, None, reading=True)

    def _load_failed(self, message: str) -> None:
        """The capture could not be read at all: why, where its rows would be."""
        if self.capture_store is not None:
            self._set_verdict(None, message)
        self._count()
        self.error.emit(message)

    def _set_verdict(self, verdict: CaptureVerdict | None, problem: str | None, *,
                     reading: bool = False) -> None:
        """The banner, the columns (plain CAN for a foreign capture) and the page shown."""
        self.verdict, self.problem = verdict, problem
        plain = verdict is not None and verdict.verdict == "not-pdcp"
        if plain != self.model.plain:
            show_plain(self.view, plain)
        self.model.set_plain(plain)
        self.stats_model.plain = plain
        for box in (self.bar.function_filter, self.bar.node_filter):
            box.setEnabled(not plain)  # PDCP's functions and nodes: none here
        if problem is not None:
            self.problem_label.setText(problem_text(problem))
            self.pages.setCurrentWidget(self.problem_label)
        else:
            self.pages.setCurrentWidget(self.splitter)
        self.banner.setText("" if verdict is None else verdict_text(verdict, reading=reading))
        self.banner.setVisible(verdict is not None)
