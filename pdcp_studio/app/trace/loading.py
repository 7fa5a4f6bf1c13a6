"""Opening a capture in the trace: read and decoded on a worker into a store of its own,
with a progress bar and a Stop button in the bar while it reads."""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.bar import TraceBar
from pdcp_studio.app.trace.capture import load_capture
from pdcp_studio.app.trace.store import FrameStore, IdStats
from pdcp_studio.app.workers import Worker


class CaptureLoading(QObject):
    """The reader of the capture being opened (one at a time) and its progress.

    Ports: ``progressed(frames)`` as it reads; ``loaded(total, path)`` once it has read the
    whole capture; ``finished()`` when it stops, read or not; ``failed(message)``.
    A child of the dock: the worker's signals go nowhere once the dock is gone."""

    def __init__(self, parent: QObject, bar: TraceBar, progressed: Callable[[int], None],
                 loaded: Callable[[int, str], None], finished: Callable[[], None],
                 failed: Callable[[str], None]) -> None:
        super().__init__(parent)
        self._bar = bar
        self._progressed, self._loaded, self._finished = progressed, loaded, finished
        self._failed = failed
        self.worker: Worker | None = None
        self._path = ""

    def start(self, path: str | Path, store: FrameStore, stats: IdStats,
              links: dict[int, Any]) -> Worker:
        """Read ``path`` into ``store`` and ``stats`` (the node map saved beside it too)."""

        def work(progress: Any, cancel: threading.Event) -> int:
            return load_capture(store, stats, path, links, progress, cancel)

        worker = Worker(work, "Load capture")
        self._path = str(path)
        worker.progress.connect(self._progress)
        worker.finished.connect(self._read)
        worker.failed.connect(self._failure)
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
        self._bar.load_bar.setValue(permille)
        self._bar.load_bar.setFormat(
            translate("MonitorDock", "%1 frames").replace("%1", f"{done:,}"))
        self._progressed(done)

    def _read(self, total: int) -> None:
        self._loaded(total, self._path)

    def _done(self) -> None:
        if self.sender() is not self.worker:
            return  # an earlier capture's reader, replaced by a newer one
        self.worker = None
        self.hide_progress()
        self._finished()

    def _failure(self, message: str) -> None:
        self._failed(translate("MonitorDock", "Reading {load_path}: {message}").format(
            load_path=self._path, message=message))
