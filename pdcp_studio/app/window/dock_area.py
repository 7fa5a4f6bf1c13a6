"""Adding a dock to the main window: one call for the title, object name and area."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDockWidget, QMainWindow, QWidget


def add_dock(window: QMainWindow, title: str, name: str, widget: QWidget | None,
             area: Qt.DockWidgetArea) -> QDockWidget:
    """``widget`` in a new dock of ``window`` (``name``: the key its layout is saved by;
    ``widget`` None: the dock's panel is put in later, see :mod:`.deferred_panel`)."""
    dock = QDockWidget(title, window)
    dock.setObjectName(name)
    if widget is not None:
        dock.setWidget(widget)
    window.addDockWidget(area, dock)
    return dock
