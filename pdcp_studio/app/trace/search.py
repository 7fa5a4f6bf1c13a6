"""Finding a frame: the next (or previous) one whose text, function, ID or data holds what
was typed, searched on a worker over every frame of the store, not only the rows painted.

The frames found are kept for the same text: searching again goes on from where the last
search stopped instead of reading the store again.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np

from pdcp_studio.app.trace.model import TraceModel, TraceView
from pdcp_studio.app.trace.store import TraceFilter
from pdcp_studio.app.workers import Worker


class FrameFinder:
    """Searches the table's store; ``found(row)`` reports the row selected (-1: none).

    ``select_row(row)`` shows a table row; ``failed(message)`` reports a search that broke."""

    def __init__(self, model: TraceModel, view: TraceView, select_row: Callable[[int], None],
                 found: Callable[[int], None], failed: Callable[[str], None]) -> None:
        self._model, self._view, self._select_row = model, view, select_row
        self._found, self._failed = found, failed
        self._worker: Worker | None = None
        self._hits: tuple[str, np.ndarray, int] | None = None  # needle, hits, scanned up to

    def forget(self) -> None:
        """The store changed or was replaced: the frames found so far are stale."""
        self._hits = None

    def find(self, needle: str, forward: bool = True) -> Worker:
        """Go to the next (or previous) frame after the selected row that holds
        ``needle`` (stripped, not empty)."""
        store = self._model.store
        hits = self._hits
        start = 0
        if hits is not None and hits[0] == needle and hits[2] <= store.end:
            start = hits[2]
        end = store.end
        current = self._view.currentIndex()
        origin = self._model.absolute(current.row()) if current.isValid() else (
            store.base - 1 if forward else store.end)

        def work(_progress: Any, cancel: threading.Event) -> Any:
            return store.select(TraceFilter(text=needle), start, end, cancel)

        worker = Worker(work, "Find frames")
        self._worker = worker

        def finished(more: Any) -> None:
            old = self._hits[1] if (self._hits is not None and start) else np.zeros(0, np.int64)
            found = np.concatenate((old, more))
            self._hits = (needle, found, end)
            self._go_to_hit(found, origin, forward)

        worker.finished.connect(finished)
        worker.failed.connect(self._failed)
        return worker.start()

    def _go_to_hit(self, hits: np.ndarray, origin: int, forward: bool) -> None:
        m = self._model
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
            self._found(-1)
            return
        self._select_row(row)
        self._found(row)
