"""Saving what the trace shows: every frame of the store (not only the rows painted), on a
worker, as a python-can capture or as decoded text (by extension)."""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject
from PySide6.QtWidgets import QToolButton

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.files.capture import save_store
from pdcp_studio.app.trace.store import FrameStore
from pdcp_studio.app.workers import Worker


class FrameSaving(QObject):
    """Writes a store's frames; the Save button waits meanwhile.

    Ports: ``saved(path)`` and ``failed(message)``. A child of the dock: the worker's
    signals go nowhere once the dock is gone."""

    def __init__(self, parent: QObject, button: QToolButton, saved: Callable[[str], None],
                 failed: Callable[[str], None]) -> None:
        super().__init__(parent)
        self._button, self._saved, self._failed = button, saved, failed
        self._worker: Worker | None = None
        self._path = ""

    def save(self, path: str | Path, store: FrameStore, links: dict[int, Any] | None,
             node_map: Any = None) -> Worker:
        """Save ``store`` (a snapshot: live frames keep coming) to ``path``, with the node
        map of ``links`` (the live frames') or ``node_map`` (an opened capture's own)."""
        self._button.setEnabled(False)

        def work(_progress: Any, _cancel: threading.Event) -> int:
            return save_store(path, store, links, node_map=node_map)

        worker = Worker(work, "Save frames")
        self._path = str(path)
        worker.finished.connect(self._finished)
        worker.failed.connect(self._failure)
        worker.done.connect(self._done)
        self._worker = worker
        return worker.start()

    def _finished(self, _count: int) -> None:
        self._saved(self._path)

    def _failure(self, message: str) -> None:
        self._failed(translate("MonitorDock", "Saving {save_path}: {message}").format(
            save_path=self._path, message=message))

    def _done(self) -> None:
        self._button.setEnabled(True)
