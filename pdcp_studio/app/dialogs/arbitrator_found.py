"""Connecting found another bus arbitrator: say so plainly and offer what is safe.

On a ``can:`` bus PDCP Studio listens before it arbitrates; if it hears another arbitrator
(most likely the prosthesis's own control unit) it does nothing on that bus
(``OtherArbitratorError``, reference §5). The window then shows :class:`ArbitratorFoundDialog`
with the two safe ways on:

* **Watch the bus (listen only)** — the monitor dock fed by a
  :class:`~pdcp_studio.app.live.passive_monitor.PassiveMonitor`, which never sends a frame;
* **Connect through the host link** — the Connect dialog on its serial tab, to talk to the
  prosthesis's own arbitrator over its cable.

The engineer's detail (what was heard) is one click away in the dialog's details.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QHBoxLayout,
    QLabel,
    QLayout,
    QPushButton,
    QStatusBar,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate

if TYPE_CHECKING:
    from pdcp_studio.app.live.passive_monitor import PassiveMonitor

WATCH, HOST_LINK = "watch", "host-link"


def is_other_arbitrator(error: BaseException | None) -> bool:
    """True when a failed Connect failed because another arbitrator runs the bus."""
    from pdcp_studio.bus.session.live import OtherArbitratorError

    return isinstance(error, OtherArbitratorError)


class ArbitratorFoundDialog(QDialog):
    """Another arbitrator is on the bus: watch it, use the host link, or leave it.

    Signal ``chosen(str)``: ``WATCH`` or ``HOST_LINK`` (nothing when cancelled).
    """

    chosen = Signal(str)

    def __init__(self, url: str, detail: str, parent: QWidget | None = None, *,
                 later: bool = False) -> None:
        super().__init__(parent)
        self.url = url
        self.setWindowTitle(self.tr("Another bus arbitrator is running"))
        self.setMinimumWidth(520)
        if later:
            head = self.tr(
                "<p><b>Another arbitrator started on this bus</b> — most likely the "
                "prosthesis's own control unit.</p><p>PDCP Studio stopped sending at once "
                "and disconnected: only one arbitrator may run a bus.</p>")
        else:
            head = self.tr(
                "<p><b>This bus already has an arbitrator</b> — most likely the prosthesis's "
                "own control unit.</p><p>PDCP Studio did not take part in it: nothing was "
                "sent to the prosthesis. Only one arbitrator may run a bus.</p>")
        self.text = QLabel(head + self.tr(
            "<p>You can <b>watch the bus</b>: see its traffic in the monitor without sending "
            "anything. Or <b>connect through the host link</b>: the prosthesis's own "
            "arbitrator answers over its serial cable, and you can read and configure it "
            "there.</p>"))
        self.text.setWordWrap(True)
        self.text.setTextFormat(Qt.TextFormat.RichText)
        self.text.setFixedWidth(500)  # a known width: its wrapped height is then exact
        # A window does not size itself by height-for-width: give the wrapped text its height.
        self.text.setMinimumHeight(self.text.heightForWidth(500))
        self.detail = QLabel(self.tr("Bus: {url}\n{detail}").format(url=url, detail=detail))
        self.detail.setWordWrap(True)
        self.detail.setFixedWidth(500)
        self.detail.setMinimumHeight(self.detail.heightForWidth(500))
        self.detail.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.detail.hide()
        self.details_button = QPushButton(self.tr("Details"))
        self.details_button.setCheckable(True)
        self.details_button.toggled.connect(self.detail.setVisible)
        self.buttons = QDialogButtonBox()
        self.watch_button = self.buttons.addButton(self.tr("Watch the bus (listen only)"),
                                                   QDialogButtonBox.ButtonRole.AcceptRole)
        self.host_button = self.buttons.addButton(self.tr("Connect through the host link…"),
                                                  QDialogButtonBox.ButtonRole.AcceptRole)
        self.buttons.addButton(QDialogButtonBox.StandardButton.Cancel)
        self.watch_button.setToolTip(self.tr("Show the bus's frames in the monitor; PDCP "
                                             "Studio sends nothing (listen-only)"))
        self.host_button.setToolTip(self.tr("Open the connection dialog on the serial host "
                                            "link"))
        self.watch_button.clicked.connect(lambda: self._choose(WATCH))
        self.host_button.clicked.connect(lambda: self._choose(HOST_LINK))
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.text)
        row = QHBoxLayout()
        row.addWidget(self.details_button)
        row.addStretch(1)
        layout.addLayout(row)
        layout.addWidget(self.detail)
        layout.addWidget(self.buttons)
        # Wrapped text: the dialog grows with it (and with the details), never clips it.
        layout.setSizeConstraint(QLayout.SizeConstraint.SetMinimumSize)

    def _choose(self, what: str) -> None:
        self.chosen.emit(what)
        self.accept()


class ListeningIndicator(QWidget):
    """The status bar's "Listening to … (sends nothing)" with a Stop button."""

    def __init__(self, url: str, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.label = QLabel(self.tr("Listening to {url} — sends nothing").format(url=url))
        self.label.setStyleSheet("color: #1d4ed8;")
        self.stop_button = QPushButton(self.tr("Stop listening"))
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.label)
        layout.addWidget(self.stop_button)


def offer(window: Any, url: str, message: str, *, later: bool = False
          ) -> ArbitratorFoundDialog:
    """Show the dialog for ``url`` (not modal: the window stays usable) and act on the choice;
    ``later``: the other arbitrator appeared while PDCP Studio was arbitrating."""
    detail = message[len(url) + 2:] if message.startswith(f"{url}: ") else message
    dialog = ArbitratorFoundDialog(url, detail, window, later=later)
    dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
    dialog.chosen.connect(lambda what: _act(window, url, what))
    window.arbitrator_found_dialog = dialog
    window.show_message(translate("ArbitratorFound", "{url}: another bus arbitrator is running "
                                  "this bus — PDCP Studio sent nothing").format(url=url), 0)
    dialog.open()
    return dialog


def _act(window: Any, url: str, what: str) -> None:
    if what == WATCH:
        watch(window, url)
    elif what == HOST_LINK:
        open_host_link(window)


def open_host_link(window: Any) -> Any:
    """The Connect dialog on its serial host-link tab; connecting follows its choice."""
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

    dialog = ConnectDialog(window)
    dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
    dialog.tabs.setCurrentWidget(dialog.pages["serial"])
    dialog.accepted.connect(lambda: dialog.url() and window.connect_bus(dialog.url()))
    window.host_link_dialog = dialog
    dialog.open()
    return dialog


def watch(window: Any, url: str) -> Any:
    """Listen to ``url`` in the monitor dock (never sending); returns the PassiveMonitor."""
    from pdcp_studio.app.live.passive_monitor import PassiveMonitor
    from pdcp_studio.app.window.desktop import monitor_dock

    stop_watching(window)
    dock = monitor_dock(window)
    dock.clear()
    dock.show()
    dock.raise_()
    monitor = PassiveMonitor(url, window)
    monitor.frames.connect(dock.add_frames)
    indicator = ListeningIndicator(url)
    indicator.stop_button.clicked.connect(lambda: stop_watching(window))
    bar: QStatusBar = window.statusBar()
    bar.addPermanentWidget(indicator)
    monitor.stopped.connect(lambda reason, m=monitor: _stopped(window, m, reason))
    window.passive_monitor, window.listening_indicator = monitor, indicator
    monitor.start()
    window.show_message(translate("ArbitratorFound", "Watching {url} without sending: its "
                                  "frames appear in the monitor").format(url=url))
    return monitor


def stop_watching(window: Any) -> None:
    """Stop the passive monitor, if any (when the user says so or connects elsewhere)."""
    monitor = getattr(window, "passive_monitor", None)
    indicator = getattr(window, "listening_indicator", None)
    window.passive_monitor = window.listening_indicator = None
    if monitor is not None:
        monitor.stop()
    if indicator is not None:
        window.statusBar().removeWidget(indicator)
        indicator.deleteLater()


def _stopped(window: Any, monitor: PassiveMonitor, reason: str) -> None:
    if getattr(window, "passive_monitor", None) is not monitor:
        return
    stop_watching(window)
    if reason:
        window.show_message(translate("ArbitratorFound", "Stopped listening to {url}: "
                                      "{reason}").format(url=monitor.url, reason=reason), 0)
