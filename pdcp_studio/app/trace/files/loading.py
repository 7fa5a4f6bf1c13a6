"""Opening a capture in the trace: read and decoded on a worker into a store of its own
(with the capture's own node map, never the live session's), with a progress bar and a
Stop button in the bar while it reads, and what the capture is as soon as it is known."""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.bar import TraceBar
from pdcp_studio.app.trace.files.capture import CaptureVerdict, LoadState, load_capture
from pdcp_studio.app.trace.store import FrameStore, IdStats
from pdcp_studio.app.workers import Worker


class CaptureLoading(QObject):
    """The reader of the capture being opened (one at a time) and its progress.

    Ports: ``progressed(frames)`` as it reads; ``judged(verdict)`` once the capture's
    first frames say what it is (and again at its end); ``loaded(verdict, path)`` once it
    has read the capture (whole, up to its damage, or up to Stop); ``finished()`` when it
    stops, read or not; ``failed(message)`` when it could not be read at all.
    A child of the dock: the worker's signals go nowhere once the dock is gone."""

    def __init__(self, parent: QObject, bar: TraceBar, progressed: Callable[[int], None],
                 judged: Callable[[CaptureVerdict], None],
                 loaded: Callable[[CaptureVerdict, str], None], finished: Callable[[], None],
                 failed: Callable[[str], None]) -> None:
        super().__init__(parent)
        self._bar = bar
        self._progressed, self._loaded, self._finished = progressed, loaded, finished
        self._judged, self._failed = judged, failed
        self.worker: Worker | None = None
        self._path = ""
        self._state = LoadState()
        self._told: CaptureVerdict | None = None

    def start(self, path: str | Path, store: FrameStore, stats: IdStats) -> Worker:
        """Read ``path`` into ``store`` and ``stats`` with its own node map (saved beside
        it, or learned from its traffic)."""
        state = self._state = LoadState()
        self._told = None

        def work(progress: Any, cancel: threading.Event) -> CaptureVerdict:
            return load_capture(store, stats, path, progress, cancel, state)

        worker = Worker(work, "Load capture")
        self._path = str(path)
        worker.progress.connect(self._progress)
        worker.finished.connect(self._read)
        worker.failed.connect(self._failure)
        worker.cancelled.connect(self._stopped)
        worker.done.connect(self._done)
        self.worker = worker
        bar = self._bar
        bar.stop_load_button.setVisible(True)
        bar.load_bar.setValue(0)
        bar.load_bar.setVisible(True)
        bar.count_label.setVisible(False)  # the bar counts meanwhile (and the row stays short)
        return worker.start()

    def cancel(self) -> None:
        """Stop reading (what was read stays)."""
        if self.worker is not None and self.worker.is_running:
            self.worker.cancel()

    def hide_progress(self) -> None:
        bar = self._bar
        bar.stop_load_button.setVisible(False)
        bar.load_bar.setVisible(False)
        bar.count_label.setVisible(True)

    def _progress(self, done: int, permille: int, _text: str) -> None:
        if self.sender() is not self.worker:
            return  # an earlier capture's reader, replaced by a newer one
        verdict = self._state.verdict
        if verdict is not None and verdict is not self._told:
            self._told = verdict
            self._judged(verdict)
        self._bar.load_bar.setValue(permille)
        self._bar.load_bar.setFormat(
            translate("MonitorDock", "%1 frames").replace("%1", f"{done:,}"))
        self._progressed(done)

    def _read(self, verdict: CaptureVerdict) -> None:
        if self.sender() is not self.worker:
            return
        self._told = verdict
        self._loaded(verdict, self._path)

    def _stopped(self) -> None:
        """Stop was pressed: what was read stays, and the banner says so."""
        verdict = self._state.verdict
        if self.sender() is self.worker and verdict is not None and verdict.cancelled:
            self._read(verdict)

    def _done(self) -> None:
        if self.sender() is not self.worker:
            return  # an earlier capture's reader, replaced by a newer one
        self.worker = None
        self.hide_progress()
        self._finished()

    def _failure(self, message: str) -> None:
        if self.sender() is not self.worker:
            return
        self._failed(message)  # the reader's words name the file (and line or offset)
