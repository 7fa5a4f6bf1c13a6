"""Filtering a large store off the GUI thread: the rows that pass are selected on a worker
while the table keeps showing its old rows; a newer filter cancels the one under way."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from pdcp_studio.app.trace.store import FrameStore, TraceFilter
from pdcp_studio.app.workers import Worker


class BackgroundFilter:
    """One filter run at a time. Ports: ``shown(store, filter, rows, end)`` with the rows
    selected among the store's frames before ``end``; ``failed(message)``."""

    def __init__(self, shown: Callable[[FrameStore, TraceFilter, Any, int], None],
                 failed: Callable[[str], None]) -> None:
        self._shown, self._failed = shown, failed
        self.worker: Worker | None = None

    def cancel(self) -> None:
        """Drop the run under way, if any (its rows are never shown)."""
        if self.worker is not None:
            self.worker.cancel()
            self.worker = None

    def start(self, store: FrameStore, flt: TraceFilter) -> None:
        end = store.end

        def work(progress: Any, cancel: threading.Event) -> Any:
            return store.select(flt, None, end, cancel,
                                lambda done, total: progress(done, total, ""))

        worker = Worker(work, "Filter frames")
        self.worker = worker

        def finished(rows: Any) -> None:
            if self.worker is worker:
                self.worker = None
                self._shown(store, flt, rows, end)

        def dropped() -> None:
            if self.worker is worker:
                self.worker = None

        def failed(message: str) -> None:
            dropped()
            self._failed(message)

        worker.finished.connect(finished)
        worker.cancelled.connect(dropped)
        worker.failed.connect(failed)
        worker.start()
