"""The docks a live bus brings to the main window: bus events, the simulator panel, the
trace (monitor) and the live plot.

They are made once per window and fed by each new bridge; the costliest (trace, plot) are
made just after the window is up, their modules imported on a thread first. The connection
itself is :mod:`pdcp_studio.app.live.live_bus`.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, Qt, QTimer, SignalInstance
from PySide6.QtWidgets import QDockWidget, QMainWindow, QMenu, QWidget

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window.dock_area import add_dock
from pdcp_studio.app.window.status import StatusLine

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

log = logging.getLogger("pdcp_studio.app.window.main_window")  # the name it always logged under
#: The trace and live plot docks are made this long after the window is up (they are
#: hidden tabs; made at once, they held the first window back ~0.3 s).
TRACE_DOCKS_AFTER_MS = 100
#: How often the window looks whether the trace docks' modules have been imported.
TRACE_IMPORT_POLL_MS = 20

_CTX = "WindowBus"


def _t(text: str) -> str:
    return translate(_CTX, text)


def _import_trace_modules() -> None:
    """Import what the trace and live plot docks need (on a thread; no widget is made)."""
    import pdcp_studio.app.live.plot
    import pdcp_studio.app.trace.dock  # noqa: F401


class BusDocks(QObject):
    """The bus docks of ``host`` (``leaf_docks`` by key: events, sim, monitor, plot).

    New bottom docks go as tabs beside ``plan_dock``, the simulator's beside
    ``inspector_dock``; their show/hide actions go in ``view_menu``. ``is_ready()`` and
    ``ready`` say when the first system is on screen; ``scan_finished(system)`` hears the
    end of every scan."""

    def __init__(self, host: QMainWindow, doc: Document, live: LiveController,
                 scene: BusScene, status: StatusLine, *, plan_dock: QDockWidget,
                 inspector_dock: QDockWidget, view_menu: QMenu,
                 is_ready: Callable[[], bool], ready: SignalInstance,
                 scan_finished: Callable[[Any], None]) -> None:
        super().__init__(host)
        self.host = host
        self.doc = doc
        self.live = live
        self.scene = scene
        self.status = status
        self.plan_dock = plan_dock
        self.inspector_dock = inspector_dock
        self.view_menu = view_menu
        self._is_ready = is_ready
        self._ready = ready
        self._scan_finished = scan_finished
        self.leaf_docks: dict[str, QDockWidget] = {}
        self._trace_bridge: SessionBridge | None = None
        self._trace_docks_wired = False
        self._keeping_from: Any = None
        self._early_frames: list[Any] = []
        self._events_from: SessionBridge | None = None
        self._sim_dock: QDockWidget | None = None
        self._sim_shown = True

    def attach_safely(self, bridge: SessionBridge) -> None:
        """A dock that fails to build must not cost the connection: log it and go on."""
        try:
            self.attach(bridge)
        except Exception as err:
            log.exception("bus docks")
            self.status.say(_t("Some bus panels are unavailable: {err}").format(err=err))

    def attach(self, bridge: SessionBridge) -> None:
        """Bus events, simulator panel, trace and live plot for a new bridge (made once,
        reused). The trace and the plot are hidden tabs at first and the costliest part of
        the window (numpy, the trace store: ~0.3 s of a 2-core machine): the first ones are
        made just after the window is up (:meth:`make_trace_docks`), or at once when the
        selection asks the plot for a signal; the trace then shows every frame since the
        session started, kept meanwhile."""
        from pdcp_studio.app.docks import sim_panel

        self._keep_frames(None)  # an earlier bridge's, whose docks were never made
        self._trace_bridge = None
        monitor: Any = self.leaf_docks.get("monitor")
        plot = self.leaf_docks.get("plot")
        if monitor is not None:
            bridge.frameSeen.connect(monitor.add_frames)
        if plot is not None:
            bridge.channelValues.connect(self._widget(plot).add_values)
        if monitor is None or plot is None:
            self._trace_bridge = bridge
            if monitor is None:
                self._keep_frames(bridge)
            if self._is_ready():
                self._trace_docks_soon()
        if not self._trace_docks_wired:
            self._trace_docks_wired = True
            self._ready.connect(self._trace_docks_soon)  # the first system is on screen
            self.doc.selectionChanged.connect(self._plot_selection)
        events = self.events_dock()
        if bridge is not self._events_from:  # another prosthesis: none of the last one's
            self._events_from = bridge
            self._widget(events).clear()
        bridge.busEvent.connect(self._widget(events).add_event)
        bridge.scanned.connect(self._scan_finished)  # any scan's end is said in the status bar
        if bridge.is_sim:
            self._sim_panel_off()
            self._sim_panel_on(sim_panel.SimPanel(bridge, name_of=self._device_name))

    def _sim_panel_on(self, panel: QWidget) -> None:
        """The Simulator panel of a new simulated session, in the one Simulator dock (made
        the first time, with its View-menu entry; a wizard may point to it). The dock is
        kept between sessions: a new one made after a switch came back hidden, its
        predecessor's place restored as closed."""
        dock = self._sim_dock
        if dock is None:
            dock = add_dock(self.host, _t("Simulator"), "SimDock", panel,
                            Qt.DockWidgetArea.RightDockWidgetArea)
            self.host.tabifyDockWidget(self.inspector_dock, dock)
            self.inspector_dock.raise_()
            self.view_menu.addAction(dock.toggleViewAction())
            self._sim_dock = dock
        else:
            dock.setWidget(panel)
            dock.toggleViewAction().setEnabled(True)
            if self._sim_shown:
                dock.show()
        self.leaf_docks["sim"] = dock

    def _sim_panel_off(self) -> None:
        """No simulated session: its panel goes (it must not act on a closed session); the
        dock waits, hidden, for the next one, remembering whether it was shown."""
        dock = self.leaf_docks.pop("sim", None)
        if dock is None:
            return
        self._sim_shown = dock.toggleViewAction().isChecked()
        panel = dock.widget()
        if panel is not None:
            panel.setParent(None)
            panel.deleteLater()
        dock.hide()
        dock.toggleViewAction().setEnabled(False)

    @staticmethod
    def _widget(dock: QDockWidget) -> Any:
        """The panel in ``dock`` (its own methods, not a QWidget's)."""
        return dock.widget()

    def _device_name(self, key: Any) -> str | None:
        """The name the graph gives a device on screen (None if it is not there)."""
        device = self.doc.system.devices.get(key)
        return self.scene.device_label(device) if device is not None else None

    def _trace_docks_soon(self) -> None:
        """Make the trace docks shortly: their modules (numpy, the trace store: ~0.2 s of
        imports) are imported on a thread first, so the GUI thread only builds the widgets
        (~30 ms) — importing them there froze the new window for 0.1-0.45 s."""
        if self._trace_bridge is None:
            return
        loader = threading.Thread(target=_import_trace_modules, name="import trace docks",
                                  daemon=True)

        def when_imported() -> None:
            if loader.is_alive():
                QTimer.singleShot(TRACE_IMPORT_POLL_MS, self, when_imported)
            else:
                self.make_trace_docks()

        def start() -> None:  # once the window has been painted and is in the user's hands
            loader.start()
            when_imported()

        QTimer.singleShot(TRACE_DOCKS_AFTER_MS, self, start)

    def _keep_frames(self, bridge: SessionBridge | None) -> None:
        """Keep ``bridge``'s frames until the trace exists (None: stop keeping them)."""
        old = self._keeping_from
        if old is not None:
            old.frameSeen.disconnect(self._kept)
        self._keeping_from = bridge
        self._early_frames = []
        if bridge is not None:
            bridge.frameSeen.connect(self._kept)

    def _kept(self, frames: Any) -> None:
        self._early_frames.append(frames)

    def _tab_beside_plan(self, key: str, dock: QDockWidget, events: QDockWidget | None,
                         made: list[QDockWidget]) -> None:
        """A bottom dock as a tab beside the plan's, in the View menu before the events'."""
        self.host.tabifyDockWidget(self.plan_dock, dock)
        self._view_action_before(events, dock)
        self.leaf_docks[key] = dock
        made.append(dock)

    def make_trace_docks(self) -> None:
        """The trace (monitor) and live plot docks, if not made yet, fed by the bridge
        they were made for: the trace gets the frames kept since its session started."""
        from pdcp_studio.app.live import plot as live_plot
        from pdcp_studio.app.trace import dock as monitor_dock

        bridge, self._trace_bridge = self._trace_bridge, None
        if bridge is None:
            return  # made already (on demand), or a later bridge has them
        keeping = self._keeping_from is bridge  # the trace did not exist for it
        early = self._early_frames if keeping else []
        self._keep_frames(None)
        live = bridge is self.live.bridge
        started = live and self.doc.session is bridge  # its first snapshot is on screen
        events = self.leaf_docks.get("events")
        made: list[QDockWidget] = []
        monitor: Any = self.leaf_docks.get("monitor")  # (a capture dropped meanwhile makes it)
        if monitor is None:
            monitor = monitor_dock.MonitorDock(self.host)
            self.host.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, monitor)
            self._tab_beside_plan("monitor", monitor, events, made)
            if started:
                monitor.reset_for_session(self.doc.system)  # as session_started does
        if keeping:
            for frames in early:
                monitor.add_frames(frames)
            if live:
                bridge.frameSeen.connect(monitor.add_frames)
        if "plot" not in self.leaf_docks:
            plot = live_plot.LivePlot()
            plot.profile_name = self.doc.profile_name  # a channel named as the graph does
            dock = add_dock(self.host, _t("Live plot"), "LivePlotDock", plot,
                            Qt.DockWidgetArea.BottomDockWidgetArea)
            self._tab_beside_plan("plot", dock, events, made)
            if started:
                plot.set_system(self.doc.system)  # as session_started does
            if live:
                bridge.channelValues.connect(plot.add_values)
        if events is not None and made:
            self.host.tabifyDockWidget(made[-1], events)  # the tabs in their usual order
        self.plan_dock.raise_()
        if made:  # where they were last time, once laid out (as the desktop module does)
            QTimer.singleShot(0, self, lambda: self._restore_made_docks(made))

    def _restore_made_docks(self, docks: list[QDockWidget]) -> None:
        from pdcp_studio.app.widgets.accessible_names import name_controls

        for dock in docks:
            self.host.restoreDockWidget(dock)
            name_controls(dock)

    def _view_action_before(self, before: QDockWidget | None, dock: QDockWidget) -> None:
        """``dock``'s entry in the View menu, before ``before``'s (None: last)."""
        if before is None:
            self.view_menu.addAction(dock.toggleViewAction())
        else:
            self.view_menu.insertAction(before.toggleViewAction(), dock.toggleViewAction())

    def events_dock(self) -> QDockWidget:
        """The bus events list (made once): which link the bus made, why, how similar."""
        from pdcp_studio.app.docks.events_panel import EventsPanel

        dock = self.leaf_docks.get("events")
        if dock is None:
            panel = EventsPanel(lambda: self.doc.system, self.doc.profile_name)
            dock = add_dock(self.host, _t("Bus events"), "EventsDock", panel,
                            Qt.DockWidgetArea.BottomDockWidgetArea)
            self.host.tabifyDockWidget(self.plan_dock, dock)
            self.plan_dock.raise_()
            self.view_menu.addAction(dock.toggleViewAction())
            self.leaf_docks["events"] = dock
        return dock

    def monitor_dock(self) -> Any:
        """The monitor dock, made now if no bus has made it yet."""
        from pdcp_studio.app.trace.dock import MonitorDock

        dock = self.leaf_docks.get("monitor")
        if dock is None:
            from pdcp_studio.app.widgets.accessible_names import name_controls

            dock = MonitorDock(self.host)
            self.host.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, dock)
            self.host.tabifyDockWidget(self.plan_dock, dock)
            self.view_menu.addAction(dock.toggleViewAction())
            self.leaf_docks["monitor"] = dock
            name_controls(dock)
        return dock

    def session_started(self, bridge: SessionBridge) -> None:
        """A new session is on screen: the bus panels start afresh on it (no frames,
        values or node map of the previous session)."""
        system = self.doc.system
        if self._keeping_from is bridge:
            self._early_frames.clear()  # the trace starts afresh with the session too
        monitor = self.leaf_docks.get("monitor")
        if monitor is not None and hasattr(monitor, "reset_for_session"):
            monitor.reset_for_session(system)
        plot = self.leaf_docks.get("plot")
        if plot is not None:
            widget = self._widget(plot)
            for series in list(widget.series):  # signals of the previous prosthesis go
                widget.remove_channel(series.ref)
            widget.clear()
            widget.set_system(system)  # names and units of its signals

    def bus_seen(self, system: Any) -> None:
        """After any bus event: the monitor names frames by the bus's node IDs as they are
        now (a hot-swapped device may have a new one); the plot drops a channel that left."""
        events = self.leaf_docks.get("events")
        if events is not None:
            self._widget(events).name_devices(system)
        sim = self.leaf_docks.get("sim")
        if sim is not None and hasattr(sim.widget(), "relabel"):
            self._widget(sim).relabel()  # the simulator panel names devices as the graph does
        monitor = self.leaf_docks.get("monitor")
        if monitor is not None and hasattr(monitor, "reset_for_session"):
            monitor.reset_for_session(system, keep_frames=True)
        plot = self.leaf_docks.get("plot")
        if plot is not None:
            widget = self._widget(plot)
            widget.set_system(system)
            for series in list(widget.series):
                if system.channel(series.ref) is None:
                    widget.remove_channel(series.ref)

    def detach(self) -> None:
        """The session ended: no panel may keep acting on it (the simulator's goes)."""
        self._sim_panel_off()
        plot = self.leaf_docks.get("plot")
        if plot is not None:
            self._widget(plot).set_channel(None)

    def _plot_selection(self, obj: object) -> None:
        from pdcp_studio.model.refs import ChannelRef
        from pdcp_studio.model.system import Link

        if obj is not None and self._trace_bridge is not None:
            self.make_trace_docks()  # the plot follows the selection from the start
        dock = self.leaf_docks.get("plot")
        if dock is None:
            return
        if isinstance(obj, Link):
            self._widget(dock).set_link(obj, str(obj))
        elif isinstance(obj, ChannelRef):
            ch = self.doc.system.channel(obj)
            if ch is not None and ch.is_output:
                self._widget(dock).set_channel(obj, str(obj))
