"""Dropdown lists wide enough for their entries: never cut in the middle.

Qt's combo box popup is as wide as the box and elides long entries in the middle
("Multi-gr…rotator"). One application-wide event filter widens every popup to its longest
entry (up to the screen's width) when it opens and turns eliding off, so no dialog or
panel has to remember to do it.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtWidgets import QApplication, QComboBox, QStyle, QWidget

_INSTALLED = "_pdcp_combo_popups"


def fit_popup(combo: QComboBox, container: QWidget | None = None) -> int:
    """Make ``combo``'s popup as wide as its longest entry; returns that width."""
    view = combo.view()
    view.setTextElideMode(Qt.TextElideMode.ElideNone)
    scroll = combo.style().pixelMetric(QStyle.PixelMetric.PM_ScrollBarExtent)
    width = max(combo.width(), view.sizeHintForColumn(0) + 2 * view.frameWidth() + scroll + 8)
    screen = combo.screen()
    if screen is not None:
        width = min(width, screen.availableGeometry().width())
    view.setMinimumWidth(width)
    if container is not None and container.width() < width:
        container.resize(width, container.height())
    return width


class _FitPopups(QObject):
    """Widens a combo box's popup container when it is shown."""

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if event.type() == QEvent.Type.Show and isinstance(watched, QWidget):
            parent = watched.parentWidget()
            if isinstance(parent, QComboBox) and watched.isWindow():
                fit_popup(parent, watched)
        return False


def install(app: QApplication | None = None) -> None:
    """Install the filter once on the application."""
    app = app or QApplication.instance()  # type: ignore[assignment]
    if app is None or getattr(app, _INSTALLED, None) is not None:
        return
    popups = _FitPopups(app)
    app.installEventFilter(popups)
    setattr(app, _INSTALLED, popups)
