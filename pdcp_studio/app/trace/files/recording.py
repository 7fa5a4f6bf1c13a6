"""The trace's Record… button: every live frame written to a capture file from now on,
while the table keeps only the newest ones (``LiveRecorder`` does the writing)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtWidgets import QFileDialog, QToolButton, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.files.record import LiveRecorder


class LiveRecording:
    """Starts and stops the recording the button shows.

    Ports: ``links()`` the node map to save beside the file; ``ingest()`` takes the queued
    live frames (into the recording too, before it stops); ``changed()`` refreshes the
    frame count's line (which names the file); ``saved(path)`` and ``failed(message)``."""

    def __init__(self, button: QToolButton, parent: QWidget,
                 links: Callable[[], dict[int, Any]], ingest: Callable[[], None],
                 changed: Callable[[], None], saved: Callable[[str], None],
                 failed: Callable[[str], None]) -> None:
        self._button, self._parent = button, parent
        self._links, self._ingest, self._changed = links, ingest, changed
        self._saved, self._failed = saved, failed
        self.recorder: LiveRecorder | None = None
        button.clicked.connect(self.toggle)

    def toggle(self, on: bool) -> None:
        """The button: stop, or ask for a file and start."""
        if not on:
            self.stop()
            return
        path, _ = QFileDialog.getSaveFileName(
            self._parent, translate("MonitorDock", "Record live frames"), "recording.blf",
            translate("MonitorDock", "python-can logs (*.blf *.asc *.log *.csv *.trc)"))
        if path:
            self.start(path)
        else:
            self._button.setChecked(False)

    def start(self, path: str | Path) -> None:
        """Write every live frame from now on to ``path`` (a python-can capture by
        extension), on a thread, until ``stop()``."""
        self.stop()
        try:
            self.recorder = LiveRecorder(path, dict(self._links()))
        except Exception as err:
            self._button.setChecked(False)
            self._failed(translate("MonitorDock", "Recording {path}: {message}").format(
                path=path, message=err))
            return
        self._button.setChecked(True)
        self._button.setText(translate("MonitorDock", "Recording"))
        self._changed()

    def stop(self) -> int:
        """Finish the recording (the file is complete once this returns); the count."""
        if self.recorder is not None:
            self._ingest()  # what is queued goes in too
        recorder, self.recorder = self.recorder, None
        self._button.setChecked(False)
        self._button.setText(translate("MonitorDock", "Record…"))
        if recorder is None:
            return 0
        written = recorder.stop()
        if recorder.error:
            self._failed(translate("MonitorDock", "Recording {path}: {message}").format(
                path=recorder.path, message=recorder.error))
        else:
            self._saved(str(recorder.path))
        self._changed()
        return written
