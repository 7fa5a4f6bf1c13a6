"""Connecting found another bus arbitrator: say so plainly and offer what is safe.

On a ``can:`` bus PDCP Studio listens before it arbitrates; if it hears another arbitrator
(most likely the prosthesis's own control unit) it does nothing on that bus
(``OtherArbitratorError``, reference §5). The window then shows :class:`ArbitratorFoundDialog`
with the two safe ways on:

* **Watch the bus (listen only)** — the monitor dock fed by a
  :class:`~pdcp_studio.app.live.passive_monitor.PassiveMonitor`, which never sends a frame;
* **Connect through the host link** — the Connect dialog on its serial tab, to talk to the
  prosthesis's own arbitrator over its cable.

The engineer's detail (what was heard) is one click away in the dialog's details. What follows
the choice (watching, the host link) is the window's:
``app/window/controllers/other_arbitrator.py``.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QHBoxLayout,
    QLabel,
    QLayout,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

WATCH, HOST_LINK = "watch", "host-link"


def is_other_arbitrator(error: BaseException | None) -> bool:
    """True when a failed Connect failed because another arbitrator runs the bus."""
    from pdcp_studio.bus.session.in_process import OtherArbitratorError

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
