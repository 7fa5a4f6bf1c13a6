"""Dropdown lists wide enough for their entries: never cut in the middle.

Qt's combo box popup is as wide as the box and elides long entries in the middle
("Multi-gr…rotator"). When any popup list takes the keyboard focus (it does as it opens),
the application-wide hook widens it to its longest entry (up to the screen's width) and
turns eliding off, so no dialog or panel has to remember to do it.

The hook is the application's ``focusChanged`` signal, not an application-wide event
filter: a filter written in Python is entered for every event of every object on the GUI
thread (about 1,100 a second while the bus is scanned, three quarters of all the GUI
thread's entries into Python), and each entry waits for the interpreter lock the bus
threads hold — the longest part of the GUI thread's gaps during scans (benchmarks/gui.py).
"""

from __future__ import annotations

from PySide6.QtCore import QObject, Qt
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
    """Widens a combo box's popup when its list takes the focus (it does as it opens)."""

    def fit(self, _old: QWidget | None, new: QWidget | None) -> None:
        container = new.parentWidget() if new is not None else None
        if container is None or not container.isWindow():
            return
        combo = container.parentWidget()
        if isinstance(combo, QComboBox) and combo.view() is new:
            fit_popup(combo, container)


def install(app: QApplication | None = None) -> None:
    """Install the hook once on the application."""
    target = app if app is not None else QApplication.instance()
    if not isinstance(target, QApplication) or getattr(target, _INSTALLED, None) is not None:
        return  # no widgets application (yet), or installed already
    popups = _FitPopups(target)
    target.focusChanged.connect(popups.fit)
    setattr(target, _INSTALLED, popups)


def keep_whole(combo: QComboBox) -> None:
    """A closed box as wide as its longest entry (never "Spare ha"), and the whole chosen
    entry in its tooltip when a narrow panel squeezes it anyway."""
    combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToContents)
    base = combo.toolTip()

    def tip(text: str) -> None:
        combo.setToolTip(f"{text}\n{base}" if base and text else text or base)

    combo.currentTextChanged.connect(tip)
    tip(combo.currentText())
