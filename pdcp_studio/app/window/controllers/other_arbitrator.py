"""What the window does when Connect finds another bus arbitrator (reference §5).

The dialog (``app/dialogs/arbitrator_found.py``) offers the two safe ways on; this
controller carries the choice out and owns what it starts: the listen-only
:class:`~pdcp_studio.app.live.passive_monitor.PassiveMonitor` feeding the monitor dock, the
status bar's "Listening to …" indicator, and the Connect dialog on its host-link tab. It
receives what it needs from the window (a parent for dialogs, the status bar, the status
line, Connect, the monitor dock), never the window itself.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QStatusBar, QWidget

from pdcp_studio.app.dialogs.arbitrator_found import (
    HOST_LINK,
    WATCH,
    ArbitratorFoundDialog,
    ListeningIndicator,
)
from pdcp_studio.app.i18n import translate

if TYPE_CHECKING:
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog
    from pdcp_studio.app.live.passive_monitor import PassiveMonitor
    from pdcp_studio.app.trace.dock import MonitorDock
    from pdcp_studio.model.system import System


class OtherArbitrator:
    """Offer, watch, hand over to the host link, stop watching — one window's worth."""

    def __init__(self, parent: QWidget, status_bar: QStatusBar,
                 show_message: Callable[[str, int], None],
                 connect_bus: Callable[[str], None],
                 monitor_dock: Callable[[], MonitorDock],
                 show_heard: Callable[[System, dict[Any, Any]], None] | None = None) -> None:
        self._parent = parent
        self._status_bar = status_bar
        self._show_message = show_message
        self._connect_bus = connect_bus
        self._monitor_dock = monitor_dock
        self._show_heard = show_heard  # the parts and links listening proves, on the graph
        self.dialog: ArbitratorFoundDialog | None = None
        self.host_link_dialog: ConnectDialog | None = None
        self.passive_monitor: PassiveMonitor | None = None
        self.listening_indicator: ListeningIndicator | None = None

    def offer(self, url: str, message: str, *, later: bool = False) -> ArbitratorFoundDialog:
        """Show the dialog for ``url`` (not modal: the window stays usable) and act on the
        choice; ``later``: the other arbitrator appeared while PDCP Studio was arbitrating."""
        detail = message[len(url) + 2:] if message.startswith(f"{url}: ") else message
        dialog = ArbitratorFoundDialog(url, detail, self._parent, later=later)
        dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
        dialog.chosen.connect(lambda what: self._act(url, what))
        self.dialog = dialog
        self._show_message(translate("ArbitratorFound", "{url}: another bus arbitrator is "
                                     "running this bus — PDCP Studio sent nothing"
                                     ).format(url=url), 0)
        dialog.open()
        return dialog

    def _act(self, url: str, what: str) -> None:
        if what == WATCH:
            self.watch(url)
        elif what == HOST_LINK:
            self.open_host_link()

    def open_host_link(self) -> ConnectDialog:
        """The Connect dialog on its serial host-link tab; connecting follows its choice."""
        from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

        dialog = ConnectDialog(self._parent)
        dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
        dialog.tabs.setCurrentWidget(dialog.pages["serial"])

        def accepted() -> None:
            url = dialog.url()
            if url:
                self._connect_bus(url)

        dialog.accepted.connect(accepted)
        self.host_link_dialog = dialog
        dialog.open()
        return dialog

    def watch(self, url: str) -> PassiveMonitor:
        """Listen to ``url`` in the monitor dock (never sending)."""
        from pdcp_studio.app.live.passive_monitor import PassiveMonitor

        self.stop_watching()
        dock = self._monitor_dock()
        dock.clear()
        dock.show()
        dock.raise_()
        monitor = PassiveMonitor(url, self._parent)
        monitor.frames.connect(dock.add_frames)
        if self._show_heard is not None:
            monitor.heard.connect(self._show_heard)
        indicator = ListeningIndicator(url)
        indicator.stop_button.clicked.connect(lambda: self.stop_watching())
        self._status_bar.addPermanentWidget(indicator)
        monitor.stopped.connect(lambda reason, m=monitor: self._stopped(m, reason))
        self.passive_monitor, self.listening_indicator = monitor, indicator
        monitor.start()
        self._show_message(translate("ArbitratorFound", "Watching {url} without sending: its "
                                     "frames appear in the monitor").format(url=url), 8000)
        return monitor

    def stop_watching(self) -> None:
        """Stop the passive monitor, if any (when the user says so or connects elsewhere)."""
        monitor, indicator = self.passive_monitor, self.listening_indicator
        self.passive_monitor = self.listening_indicator = None
        if monitor is not None:
            monitor.stop()
        if indicator is not None:
            self._status_bar.removeWidget(indicator)
            indicator.deleteLater()

    def _stopped(self, monitor: PassiveMonitor, reason: str) -> None:
        if self.passive_monitor is not monitor:
            return
        self.stop_watching()
        if reason:
            self._show_message(translate("ArbitratorFound", "Stopped listening to {url}: "
                                         "{reason}").format(url=monitor.url, reason=reason), 0)
