"""What the window says to the user: a line in the status bar, and errors in a box too.

The controllers get this object instead of the window: they can speak, never reach in.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

from PySide6.QtWidgets import QMessageBox, QWidget

from pdcp_studio.model.safe_text import shown

log = logging.getLogger("pdcp_studio.app.window.main_window")  # the name it always logged under


class StatusLine:
    """``say`` shows a message for a while; ``error`` also logs it and, unless the window
    is quiet (a scripted run), shows it in a box over ``parent``."""

    def __init__(self, show: Callable[[str, int], None], parent: QWidget,
                 quiet: Callable[[], bool]) -> None:
        self._show = show
        self._parent = parent
        self._quiet = quiet

    def say(self, text: str, timeout_ms: int = 8000) -> None:
        self._show(shown(text), timeout_ms)  # file and part names: shown, never run

    def error(self, title: str, text: str) -> None:
        """Tell the user; in the status bar too, so scripted runs leave a trace."""
        log.warning("%s: %s", title, text)
        text = shown(text, newlines=True)
        self._show(f"{title}: {text}", 0)
        if not self._quiet():
            QMessageBox.warning(self._parent, title, text)
