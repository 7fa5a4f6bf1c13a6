"""The status bar's permanent part: the progress of bus work, and which prosthesis the
window is connected to (the document is the project, the prosthesis its target)."""

from __future__ import annotations

from PySide6.QtCore import QObject, QTimer
from PySide6.QtWidgets import QLabel, QProgressBar, QStatusBar

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.live import live_bus
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.model.safe_text import shown

_CTX = "MainWindow"  # the texts the window has always shown under its own name

#: The connection's colour by state (offline: grey).
COLOURS = {live_bus.LIVE: "color: #0b7a4b; font-weight: bold;",
           live_bus.CONNECTING: "color: #8a5a00;",
           live_bus.DISCONNECTED: "color: #b91c1c;"}


def _t(text: str) -> str:
    return translate(_CTX, text)


def window_title(live: LiveController, title: str, bus_is_document: bool) -> str:
    """The document (``title``, or the bus when it is the document), then the connection
    (the project and its target), then the app; ``[*]`` where Qt marks unsaved changes."""
    state = live.state_text()
    if bus_is_document:
        return _t("{v0}{v1}[*] — PDCP Studio").format(v0=state[:1].upper(), v1=state[1:])
    where = "" if live.state == live_bus.OFFLINE else f" — {state}"
    return _t("{title}[*]{where} — PDCP Studio").format(title=shown(title), where=where)


class ModeLine(QObject):
    """``progress`` and ``label`` at the right of ``bar``, following ``live``."""

    def __init__(self, bar: QStatusBar, live: LiveController) -> None:
        super().__init__(bar)
        self.bar = bar
        self.live = live
        self.label = QLabel(_t("Offline"))
        self.label.setContentsMargins(6, 0, 6, 0)
        self.progress = QProgressBar()
        self.progress.setMaximumWidth(180)
        self.progress.setTextVisible(False)
        self.progress.hide()
        self._hide = QTimer(self)
        self._hide.setSingleShot(True)
        self._hide.setInterval(700)
        self._hide.timeout.connect(self.progress.hide)
        bar.addPermanentWidget(self.progress)
        bar.addPermanentWidget(self.label)

    def show_state(self, on_screen: bool) -> None:
        """Say where the window is connected (``on_screen``: the document shows the
        live bus)."""
        live = self.live
        state = live.state
        if state == live_bus.CONNECTING:
            text = (_t("● Live on {0} — connecting to {1}…") if on_screen else
                    _t("Connecting to {1}…")).format(live.url, live.connecting_url)
        elif state == live_bus.LIVE and on_screen:
            text = _t("● Live on {0}").format(live.url)
        elif state == live_bus.DISCONNECTED:
            text = _t("Disconnected from {0}").format(live.last_url)
        else:
            text = _t("Offline")
        self.label.setText(text)
        self.label.setStyleSheet(COLOURS.get(state, "color: #66707b;"))
        self.label.setToolTip(_t("The prosthesis this window is connected to (the document "
                                 "is the project, the prosthesis the target)"))

    def on_progress(self, done: int, total: int, text: str) -> None:
        if self.progress.maximum() != max(0, total):
            self.progress.setMaximum(max(0, total))
        self.progress.setValue(min(done, total) if total else 0)
        if text and text != self.bar.currentMessage():
            self.bar.showMessage(text, 4000)

    def on_busy(self, busy: bool) -> None:
        # Hidden only after a quiet spell: back-to-back jobs (scans, refreshes) must not
        # re-lay-out and repaint the status bar on every start and end.
        if busy:
            self._hide.stop()
            if self.progress.isHidden():
                self.progress.setRange(0, 0)
                self.progress.show()
        else:
            self._hide.start()
