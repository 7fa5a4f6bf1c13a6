"""The main window's live-bus side: the docks a bridge brings, and the Bus menu's commands.

Kept apart from :mod:`main_window` so everything that needs a connected bus (monitor dock,
live plot, simulator panel, reading, cancelling, comparing and writing configurations)
reads in one place; the connection itself is :mod:`pdcp_studio.app.live.live_bus`.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt, QTimer

from pdcp_studio.app.words.plural import count

log = logging.getLogger("pdcp_studio.app.window.main_window")  # the name it always logged under
#: The trace and live plot docks are made this long after the window is up (they are
#: hidden tabs; made at once, they held the first window back ~0.3 s).
TRACE_DOCKS_AFTER_MS = 100
#: How often the window looks whether the trace docks' modules have been imported.
TRACE_IMPORT_POLL_MS = 20


def _import_trace_modules() -> None:
    """Import what the trace and live plot docks need (on a thread; no widget is made)."""
    import pdcp_studio.app.live.plot
    import pdcp_studio.app.trace.dock  # noqa: F401


class BusMixin:
    """Bus docks (made once per window, fed by each new bridge) and bus commands."""

    if TYPE_CHECKING:  # a mixin of a QObject: Qt gives it tr()
        tr: Callable[[str], str]

    def ask_connect(self) -> None:
        from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

        url = ConnectDialog.get_url(self)
        if url and self.maybe_save():
            self.connect_bus(url)

    def offer_other_arbitrator(self, url: str, message: str) -> bool:
        """A Connect that found another arbitrator on the bus: offer a listen-only monitor
        or the host link instead (True when that was the failure)."""
        from pdcp_studio.app.dialogs import arbitrator_found

        connecting = self.live.connecting
        if not arbitrator_found.is_other_arbitrator(getattr(connecting, "exception", None)):
            return False
        arbitrator_found.offer(self, url, message)
        return True

    def _attach_bus_docks_safely(self, bridge: Any) -> None:
        """A dock that fails to build must not cost the connection: log it and go on."""
        try:
            self._attach_bus_docks(bridge)
        except Exception as err:
            log.exception("bus docks")
            self.show_message(self.tr("Some bus panels are unavailable: {err}").format(err=err))

    def _attach_bus_docks(self, bridge: Any) -> None:
        """Bus events, simulator panel, trace and live plot for a new bridge (made once,
        reused). The trace and the plot are hidden tabs at first and the costliest part of
        the window (numpy, the trace store: ~0.3 s of a 2-core machine): the first ones are
        made just after the window is up (:meth:`_make_trace_docks`), or at once when the
        selection asks the plot for a signal; the trace then shows every frame since the
        session started, kept meanwhile."""
        from pdcp_studio.app.docks import sim_panel

        self._keep_frames(None)  # an earlier bridge's, whose docks were never made
        self._trace_bridge = None
        monitor, plot = self._leaf_docks.get("monitor"), self._leaf_docks.get("plot")
        if monitor is not None:
            bridge.frameSeen.connect(monitor.add_frames)
        if plot is not None:
            bridge.channelValues.connect(plot.widget().add_values)
        if monitor is None or plot is None:
            self._trace_bridge = bridge
            if monitor is None:
                self._keep_frames(bridge)
            if getattr(self, "is_ready", False):
                self._trace_docks_soon()
        if not getattr(self, "_trace_docks_wired", False):
            self._trace_docks_wired = True
            self.ready.connect(self._trace_docks_soon)  # the first system is on screen
            self.doc.selectionChanged.connect(self._plot_selection)
        events = self._events_dock()
        bridge.busEvent.connect(events.widget().add_event)
        bridge.scanned.connect(self._scan_finished)  # any scan's end is said in the status bar
        if bridge.is_sim:
            old = self._leaf_docks.pop("sim", None)
            if old is not None:
                old.close()
                old.deleteLater()
            panel = sim_panel.SimPanel(bridge, name_of=self._device_name)
            dock = self._dock(self.tr("Simulator"), "SimDock", panel,
                              Qt.DockWidgetArea.RightDockWidgetArea)
            self.tabifyDockWidget(self.inspector_dock, dock)
            self.inspector_dock.raise_()
            self._leaf_docks["sim"] = dock

    def scan_bus(self) -> Any:
        """Scan the bus on its worker; the status bar says when it started and finished."""
        worker = self.live.scan()
        if worker is not None:
            self.show_message(self.tr("Scanning the bus…"), 0)
        return worker

    def _scan_finished(self, system: Any) -> None:
        devices = len(getattr(system, "devices", {}))
        links = len(getattr(system, "links", []))
        self.show_message(self.tr("Scan finished: {devices}, {links}").format(
            devices=count("BusMixin", "%n device(s)", devices),
            links=count("BusMixin", "%n link(s)", links)))

    def _device_name(self, key: Any) -> str | None:
        """The name the graph gives a device on screen (None if it is not there)."""
        device = self.doc.system.devices.get(key)
        return self.scene.device_label(device) if device is not None else None

    def _trace_docks_soon(self) -> None:
        """Make the trace docks shortly: their modules (numpy, the trace store: ~0.2 s of
        imports) are imported on a thread first, so the GUI thread only builds the widgets
        (~30 ms) — importing them there froze the new window for 0.1-0.45 s."""
        if getattr(self, "_trace_bridge", None) is None:
            return
        loader = threading.Thread(target=_import_trace_modules, name="import trace docks",
                                  daemon=True)

        def when_imported() -> None:
            if loader.is_alive():
                QTimer.singleShot(TRACE_IMPORT_POLL_MS, self, when_imported)
            else:
                self._make_trace_docks()

        def start() -> None:  # once the window has been painted and is in the user's hands
            loader.start()
            when_imported()

        QTimer.singleShot(TRACE_DOCKS_AFTER_MS, self, start)

    def _keep_frames(self, bridge: Any) -> None:
        """Keep ``bridge``'s frames until the trace exists (None: stop keeping them)."""
        old = getattr(self, "_keeping_from", None)
        if old is not None:
            old.frameSeen.disconnect(self._kept)
        self._keeping_from = bridge
        self._early_frames: list[Any] = []
        if bridge is not None:
            bridge.frameSeen.connect(self._kept)

    def _kept(self, frames: Any) -> None:
        self._early_frames.append(frames)

    def _tab_beside_plan(self, key: str, dock: Any, events: Any, made: list[Any]) -> None:
        """A bottom dock as a tab beside the plan's, in the View menu before the events'."""
        self.tabifyDockWidget(self.plan_dock, dock)
        self._view_action_before(events, dock)
        self._leaf_docks[key] = dock
        made.append(dock)

    def _make_trace_docks(self) -> None:
        """The trace (monitor) and live plot docks, if not made yet, fed by the bridge
        they were made for: the trace gets the frames kept since its session started."""
        from pdcp_studio.app.live import plot as live_plot
        from pdcp_studio.app.trace import dock as monitor_dock

        bridge, self._trace_bridge = getattr(self, "_trace_bridge", None), None
        if bridge is None:
            return  # made already (on demand), or a later bridge has them
        keeping = self._keeping_from is bridge  # the trace did not exist for it
        early = self._early_frames if keeping else []
        self._keep_frames(None)
        live = bridge is self.live.bridge
        started = live and self.doc.session is bridge  # its first snapshot is on screen
        events = self._leaf_docks.get("events")
        made = []
        monitor = self._leaf_docks.get("monitor")  # (a capture dropped meanwhile makes it)
        if monitor is None:
            monitor = monitor_dock.MonitorDock(self)
            self.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, monitor)
            self._tab_beside_plan("monitor", monitor, events, made)
            if started:
                monitor.reset_for_session(self.doc.system)  # as _session_started does
        if keeping:
            for frames in early:
                monitor.add_frames(frames)
            if live:
                bridge.frameSeen.connect(monitor.add_frames)
        if "plot" not in self._leaf_docks:
            plot = live_plot.LivePlot()
            dock = self._dock(self.tr("Live plot"), "LivePlotDock", plot,
                              Qt.DockWidgetArea.BottomDockWidgetArea)
            self._tab_beside_plan("plot", dock, events, made)
            if started:
                plot.set_system(self.doc.system)  # as _session_started does
            if live:
                bridge.channelValues.connect(plot.add_values)
        if events is not None and made:
            self.tabifyDockWidget(made[-1], events)  # the tabs in their usual order
        self.plan_dock.raise_()
        if made:  # where they were last time, once laid out (as window_desktop does)
            QTimer.singleShot(0, self, lambda: self._restore_made_docks(made))

    def _restore_made_docks(self, docks: list[Any]) -> None:
        from pdcp_studio.app.window.desktop import name_controls

        for dock in docks:
            self.restoreDockWidget(dock)
            name_controls(dock)

    def _view_action_before(self, before: Any, dock: Any) -> None:
        """``dock``'s entry in the View menu, before ``before``'s (None: last)."""
        if before is None:
            self.view_menu.addAction(dock.toggleViewAction())
        else:
            self.view_menu.insertAction(before.toggleViewAction(), dock.toggleViewAction())

    def _events_dock(self) -> Any:
        """The bus events list (made once): which link the bus made, why, how similar."""
        from pdcp_studio.app.docks.events_panel import EventsPanel

        dock = self._leaf_docks.get("events")
        if dock is None:
            panel = EventsPanel(lambda: self.doc.system, self.doc.profile_name)
            dock = self._dock(self.tr("Bus events"), "EventsDock", panel,
                              Qt.DockWidgetArea.BottomDockWidgetArea)
            self.tabifyDockWidget(self.plan_dock, dock)
            self.plan_dock.raise_()
            self.view_menu.addAction(dock.toggleViewAction())
            self._leaf_docks["events"] = dock
        return dock

    def _session_started(self, bridge: Any) -> None:
        """A new session is on screen: the bus panels start afresh on it (no frames, values
        or node map of the previous session), and plans get its stored configuration."""
        from pdcp_studio.app.dialogs.arbitrator_found import stop_watching

        stop_watching(self)  # a passive monitor of another bus gives way to the session
        system = self.doc.system
        if getattr(self, "_keeping_from", None) is bridge:
            self._early_frames.clear()  # the trace starts afresh with the session too
        monitor = self._leaf_docks.get("monitor")
        if monitor is not None and hasattr(monitor, "reset_for_session"):
            monitor.reset_for_session(system)
        plot = self._leaf_docks.get("plot")
        if plot is not None:
            plot.widget().set_channel(None)
            plot.widget().set_system(system)  # names and units of its signals
        bridge.simChanged.connect(lambda _what: (self.live.refresh(),
                                                 self.reread_configuration()))
        bridge.configurationWritten.connect(lambda _c: self.reread_configuration())
        # Any transaction on this prosthesis (ours, or the arbitrator's own over the host
        # link) may have changed the stored configuration: previews must use the new one.
        bridge.busEvent.connect(self._bus_event)
        self.reread_configuration()

    def _bus_event(self, event: Any) -> None:
        kind = type(event).__name__
        if kind == "TransactionDone":
            self.reread_configuration()
        elif kind == "BusState" and event.state == "yielded":
            self._other_arbitrator_appeared(event.message)

    def _other_arbitrator_appeared(self, message: str) -> None:
        """Another arbitrator started on our bus: our session has stopped writing (§5).
        Say so plainly and offer the safe ways on, as when it is found on connecting."""
        from pdcp_studio.app.dialogs import arbitrator_found

        url = self.live.url
        self.live.disconnect_bus()  # it writes nothing more; edits could not be written
        arbitrator_found.offer(self, url, message, later=True)

    def _bus_seen(self, system: Any) -> None:
        """After any bus event: the monitor names frames by the bus's node IDs as they are
        now (a hot-swapped device may have a new one); the plot drops a channel that left."""
        events = self._leaf_docks.get("events")
        if events is not None:
            events.widget().name_devices(system)
        sim = self._leaf_docks.get("sim")
        if sim is not None and hasattr(sim.widget(), "relabel"):
            sim.widget().relabel()  # the simulator panel names devices as the graph does
        monitor = self._leaf_docks.get("monitor")
        if monitor is not None and hasattr(monitor, "reset_for_session"):
            monitor.reset_for_session(system, keep_frames=True)
        plot = self._leaf_docks.get("plot")
        if plot is not None:
            plot.widget().set_system(system)
            for series in list(plot.widget().series):
                if system.channel(series.ref) is None:
                    plot.widget().remove_channel(series.ref)

    def _detach_bus_docks(self) -> None:
        """The session ended: no panel may keep acting on it (the simulator's goes)."""
        old = self._leaf_docks.pop("sim", None)
        if old is not None:
            old.close()
            old.deleteLater()
        plot = self._leaf_docks.get("plot")
        if plot is not None:
            plot.widget().set_channel(None)

    def reread_configuration(self) -> None:
        """Read the arbitrator's stored configuration again (after connecting, every write
        and every bus event that may change it): previews always use the current one."""
        bridge = self.live.bridge
        if bridge is None:
            return
        session = bridge.session
        bridge.run(lambda _p, _c: session.read_configuration(), "Read configuration",
                   lambda c, b=bridge: self._stored_configuration_seen(b, c))

    def _stored_configuration_seen(self, bridge: Any, collection: Any) -> None:
        if bridge is self.live.bridge and self.doc.session is bridge:
            self.doc.config = collection

    def read_configuration(self) -> None:
        """Ask the arbitrator for its stored configuration (on the bridge's worker)."""
        bridge = self.live.bridge
        if bridge is None:
            self.show_message(self.tr("Read configuration: connect to a bus first"))
            return
        bridge.run(lambda _p, _c: bridge.session.read_configuration(),
                   "Read configuration", self._configuration_read)

    def _configuration_read(self, collection: Any) -> None:
        self.doc.config = collection
        n = len(getattr(collection, "configurations", []))
        links = sum(len(c.links) for c in getattr(collection, "configurations", []))
        self.show_message(self.tr("Read the arbitrator's stored configuration: {configurations}, "
                                  "{links} — Find replacements and Start-up now use it").format(
            configurations=count("BusMixin", "%n configuration(s)", n),
            links=count("BusMixin", "%n link(s)", links)))

    def cancel_bus_work(self) -> None:
        if self.live.connecting is not None and self.live.connecting.is_running:
            self.live.connecting.cancel()
        if self.live.bridge is not None:
            self.live.bridge.cancel_all()
        self.show_message(self.tr("Cancelling…"))

    def _plot_selection(self, obj: object) -> None:
        from pdcp_studio.model.refs import ChannelRef
        from pdcp_studio.model.system import Link

        if obj is not None and getattr(self, "_trace_bridge", None) is not None:
            self._make_trace_docks()  # the plot follows the selection from the start
        dock = self._leaf_docks.get("plot")
        if dock is None:
            return
        if isinstance(obj, Link):
            dock.widget().set_link(obj, str(obj))
        elif isinstance(obj, ChannelRef):
            ch = self.doc.system.channel(obj)
            if ch is not None and ch.is_output:
                dock.widget().set_channel(obj, str(obj))

    def show_compare(self) -> None:
        from pdcp_studio.app.dialogs import compare_dialog as mod

        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge, parent=self)
        if self.doc.config is not None:
            dialog.set_file_sources(mod.sources_of_collection(self.doc.title, self.doc.config),
                                    self.doc.config)
        dialog.show()

    def compare_with_prosthesis(self, path: Any) -> Any:
        """Compare a file's links with the prosthesis (on screen and its arbitrator's stored
        configuration), staying connected; returns the dialog."""
        from pdcp_studio.app.dialogs import compare_dialog as mod

        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge, parent=self)
        dialog.load_file(path)
        if self.live.bridge is not None:
            dialog.read_arbitrator()
        dialog.show()
        self.compare_dialog = dialog
        return dialog

    def ask_write_configuration(self) -> None:
        from pdcp_studio.app.dialogs import write_config_dialog as mod

        if self.live.bridge is None:
            self.error_box(self.tr("Write configuration"), self.tr("connect to a bus first"))
            return
        dialog = mod.WriteConfigDialog.for_system(self.live.bridge, self.doc.system, self)
        # Whatever came of it, plans must use what the arbitrator stores now.
        dialog.verified.connect(lambda _ok, _msg: self.reread_configuration())
        dialog.verified.connect(lambda _ok, _msg: self.history_panel.refresh())
        dialog.show()
