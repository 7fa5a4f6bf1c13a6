"""The main window's live-bus side: the docks a bridge brings, and the Bus menu's commands.

Kept apart from :mod:`main_window` so everything that needs a connected bus (monitor dock,
live plot, simulator panel, reading, cancelling, comparing and writing configurations)
reads in one place; the connection itself is :mod:`pdcp_studio.app.live`.
"""

from __future__ import annotations

import logging
from typing import Any

from PySide6.QtCore import Qt

log = logging.getLogger("pdcp_studio.app.main_window")  # the name it always logged under


class BusMixin:
    """Bus docks (made once per window, fed by each new bridge) and bus commands."""

    def ask_connect(self) -> None:
        from pdcp_studio.app.connect_dialog import ConnectDialog

        url = ConnectDialog.get_url(self)
        if url and self.maybe_save():
            self.connect_bus(url)

    def _attach_bus_docks_safely(self, bridge: Any) -> None:
        """A dock that fails to build must not cost the connection: log it and go on."""
        try:
            self._attach_bus_docks(bridge)
        except Exception as err:
            log.exception("bus docks")
            self.show_message(f"Some bus panels are unavailable: {err}")

    def _attach_bus_docks(self, bridge: Any) -> None:
        """Monitor, live plot and simulator panel for a new bridge (made once, reused)."""
        from pdcp_studio.app import live_plot, monitor_dock, sim_panel

        dock = self._leaf_docks.get("monitor")
        if dock is None:
            dock = monitor_dock.MonitorDock(self)
            self.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, dock)
            self.tabifyDockWidget(self.plan_dock, dock)
            self.plan_dock.raise_()
            self.view_menu.addAction(dock.toggleViewAction())
            self._leaf_docks["monitor"] = dock
        bridge.frameSeen.connect(dock.add_frames)
        dock = self._leaf_docks.get("plot")
        if dock is None:
            plot = live_plot.LivePlot()
            dock = self._dock("Live plot", "LivePlotDock", plot,
                              Qt.DockWidgetArea.BottomDockWidgetArea)
            self.tabifyDockWidget(self.plan_dock, dock)
            self.plan_dock.raise_()
            self.view_menu.addAction(dock.toggleViewAction())
            self._leaf_docks["plot"] = dock
            self.doc.selectionChanged.connect(self._plot_selection)
        bridge.channelValues.connect(dock.widget().add_values)
        if bridge.is_sim:
            old = self._leaf_docks.pop("sim", None)
            if old is not None:
                old.close()
                old.deleteLater()
            panel = sim_panel.SimPanel(bridge)
            dock = self._dock("Simulator", "SimDock", panel,
                              Qt.DockWidgetArea.RightDockWidgetArea)
            self.tabifyDockWidget(self.inspector_dock, dock)
            self.inspector_dock.raise_()
            self._leaf_docks["sim"] = dock

    def read_configuration(self) -> None:
        """Ask the arbitrator for its stored configuration (on the bridge's worker)."""
        bridge = self.live.bridge
        if bridge is None:
            self.show_message("Read configuration: connect to a bus first")
            return
        bridge.run(lambda _p, _c: bridge.session.read_configuration(),
                   "Read configuration", self._configuration_read)

    def _configuration_read(self, collection: Any) -> None:
        self.doc.config = collection
        n = len(getattr(collection, "configurations", []))
        links = sum(len(c.links) for c in getattr(collection, "configurations", []))
        self.show_message(f"Read the arbitrator's stored configuration: {n} configuration(s), "
                          f"{links} links — Find replacements and Start-up now use it")

    def cancel_bus_work(self) -> None:
        if self.live.connecting is not None and self.live.connecting.is_running:
            self.live.connecting.cancel()
        if self.live.bridge is not None:
            self.live.bridge.cancel_all()
        self.show_message("Cancelling…")

    def _plot_selection(self, obj: object) -> None:
        from pdcp_studio.model.refs import ChannelRef
        from pdcp_studio.model.system import Link

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
        from pdcp_studio.app import compare_dialog as mod

        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge, parent=self)
        if self.doc.config is not None:
            dialog.set_file_sources(mod.sources_of_collection(self.doc.title, self.doc.config))
        dialog.show()

    def ask_write_configuration(self) -> None:
        from pdcp_studio.app import write_config_dialog as mod

        if self.live.bridge is None:
            self.error_box("Write configuration", "connect to a bus first")
            return
        dialog = mod.WriteConfigDialog.for_system(self.live.bridge, self.doc.system, self)
        dialog.show()
