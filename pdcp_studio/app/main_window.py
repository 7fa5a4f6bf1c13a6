"""The main window: the bus graph in the middle, the tree, inspector and plan around it.

Everything shown follows one :class:`Document`; menus turn into undo commands, plans or
session calls. The window never blocks on the bus: connecting, refreshing and applying
run on workers (:mod:`pdcp_studio.app.live`), with progress in the status bar.
Widgets of the live bus (monitor, live plot, simulator panel, compare and write dialogs)
come from their own modules; the few that a build may lack are imported defensively.
"""

from __future__ import annotations

import gc
import importlib
import logging
from pathlib import Path
from typing import Any

from PySide6.QtCore import QSettings, Qt, QTimer, Signal
from PySide6.QtGui import QAction, QCloseEvent, QImage, QKeySequence, QPainter, QShowEvent
from PySide6.QtWidgets import (
    QDockWidget,
    QFileDialog,
    QLabel,
    QMainWindow,
    QMessageBox,
    QProgressBar,
    QWidget,
)

from pdcp_studio.app import files
from pdcp_studio.app.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView
from pdcp_studio.app.inspector import Inspector
from pdcp_studio.app.live import LiveController
from pdcp_studio.app.plan_panel import OPERATIONS, PlanPanel
from pdcp_studio.app.tree_panel import DeviceTree
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.system import System

log = logging.getLogger(__name__)

DEFAULT_BUS = "sim:transradial"
OFFLINE_SYSTEM = "transradial.json"
FILE_FILTERS = ("PDCP files (*.json *.pdcfg);;System files (*.json);;"
                "Stored configurations (*.pdcfg);;All files (*)")


def optional_module(name: str) -> Any:
    """A leaf module of the app that this build may not have yet (None if absent)."""
    try:
        return importlib.import_module(f"pdcp_studio.app.{name}")
    except ModuleNotFoundError as err:
        if err.name == f"pdcp_studio.app.{name}":
            return None
        raise


class MainWindow(QMainWindow):
    """PDCP Studio's window on one document."""

    #: The first system is on screen and laid out (a file, a bus, or the offline fallback).
    ready = Signal()

    def __init__(self, doc: Document | None = None, parent: QWidget | None = None, *,
                 recovery: Any = None) -> None:
        super().__init__(parent)
        self.doc = doc if doc is not None else Document()
        self.setWindowTitle("PDCP Studio")
        self.resize(1360, 820)
        self.scene = BusScene(self.doc, self)
        self.view = GraphView(self.scene, self)
        self.setCentralWidget(self.view)
        self.live = LiveController(self.doc, self)
        self.live.on_data = self.scene.note_data
        self._is_ready = False
        self._leaf_docks: dict[str, QDockWidget] = {}
        self._build_docks()
        self._build_status()
        self._build_actions()
        self._build_menus()
        self._connect()
        self._update_title()
        self.recovery = recovery
        self.autosaver: Any = None
        if recovery is not None:
            self._start_autosave(recovery)

    # -- construction -----------------------------------------------------------------
    def _dock(self, title: str, name: str, widget: QWidget,
              area: Qt.DockWidgetArea) -> QDockWidget:
        dock = QDockWidget(title, self)
        dock.setObjectName(name)
        dock.setWidget(widget)
        self.addDockWidget(area, dock)
        return dock

    def _build_docks(self) -> None:
        # Side docks run the full height; the plan sits under the graph it explains.
        self.setCorner(Qt.Corner.BottomLeftCorner, Qt.DockWidgetArea.LeftDockWidgetArea)
        self.setCorner(Qt.Corner.BottomRightCorner, Qt.DockWidgetArea.RightDockWidgetArea)
        self.tree = DeviceTree(self.doc)
        self.inspector = Inspector(self.doc)
        self.plan_panel = PlanPanel(self.doc)
        self.tree_dock = self._dock("Devices", "DevicesDock", self.tree,
                                    Qt.DockWidgetArea.LeftDockWidgetArea)
        self.inspector_dock = self._dock("Inspector", "InspectorDock", self.inspector,
                                         Qt.DockWidgetArea.RightDockWidgetArea)
        self.plan_dock = self._dock("Plan", "PlanDock", self.plan_panel,
                                    Qt.DockWidgetArea.BottomDockWidgetArea)
        self._docks_sized = False

    def showEvent(self, event: QShowEvent) -> None:
        """Size the docks once the window has its real size (earlier sizes do not stick)."""
        super().showEvent(event)
        if not self._docks_sized:
            self._docks_sized = True
            self.resizeDocks([self.tree_dock, self.inspector_dock], [300, 350],
                             Qt.Orientation.Horizontal)
            self.resizeDocks([self.plan_dock], [220], Qt.Orientation.Vertical)

    def _build_status(self) -> None:
        bar = self.statusBar()
        self.mode_label = QLabel("Offline")
        self.mode_label.setContentsMargins(6, 0, 6, 0)
        self.progress = QProgressBar()
        self.progress.setMaximumWidth(180)
        self.progress.setTextVisible(False)
        self.progress.hide()
        self._progress_hide = QTimer(self)
        self._progress_hide.setSingleShot(True)
        self._progress_hide.setInterval(700)
        self._progress_hide.timeout.connect(self.progress.hide)
        bar.addPermanentWidget(self.progress)
        bar.addPermanentWidget(self.mode_label)

    def _action(self, text: str, slot: Any, shortcut: Any = None, tip: str = "") -> QAction:
        action = QAction(text, self)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
        if tip:
            action.setStatusTip(tip)
        action.triggered.connect(lambda _checked=False: slot())
        return action

    def _build_actions(self) -> None:
        K = QKeySequence.StandardKey
        self.act_open = self._action("&Open…", self.ask_open, K.Open,
                                     "Open a system file (.json) or a configuration (.pdcfg)")
        self.act_save = self._action("&Save", self.save, K.Save)
        self.act_save_as = self._action("Save &As…", self.ask_save_as, K.SaveAs)
        self.act_export_png = self._action("Export graph as &PNG…",
                                           lambda: self.ask_export("png"))
        self.act_export_svg = self._action("Export graph as S&VG…",
                                           lambda: self.ask_export("svg"))
        self.act_report = self._action("Fitting &report (PDF)…", self.ask_report)
        self.act_quit = self._action("&Quit", self.close, K.Quit)
        self.act_undo = self.doc.undo_stack.createUndoAction(self, "&Undo")
        self.act_undo.setShortcut(QKeySequence(K.Undo))
        self.act_redo = self.doc.undo_stack.createRedoAction(self, "&Redo")
        self.act_redo.setShortcut(QKeySequence(K.Redo))
        self.act_delete = self._action("&Delete link", self.scene.delete_selected,
                                       K.Delete, "Remove the selected links")
        self.act_fit = self._action("&Fit to window", self.view.fit_all, "Ctrl+0")
        self.act_zoom_in = self._action("Zoom &in", lambda: self.view.zoom_by(1.25), K.ZoomIn)
        self.act_zoom_out = self._action("Zoom &out", lambda: self.view.zoom_by(0.8), K.ZoomOut)
        self.act_legend = self._action("Show &legend", lambda: self.view.set_legend_visible(
            self.act_legend.isChecked()))
        self.act_legend.setCheckable(True)
        self.act_legend.setChecked(True)
        self.act_arrange = self._action("&Arrange in layers", self.arrange,
                                        tip="Lay the cards out again: sensors → control → "
                                            "terminal devices (one undo step)")
        self.plan_actions = {
            mode: self._action(f"{text}…", lambda m=mode: self.preview_plan(m))
            for mode, text in OPERATIONS}
        self.act_connect = self._action("&Connect…", self.ask_connect,
                                        tip="Connect to a simulated prosthesis or a CAN bus")
        self.act_connect_sim = self._action(
            "Open the &simulated prosthesis",
            lambda: self.maybe_save() and self.connect_bus(DEFAULT_BUS))
        self.act_disconnect = self._action("&Disconnect", self.live.disconnect_bus)
        self.act_scan = self._action("&Scan the bus", self.live.scan)
        self.act_read_config = self._action(
            "&Read the stored configuration", self.read_configuration,
            tip="Read the arbitrator's stored configuration; plans that take a "
                "configuration (Find replacements, Start-up) then use it")
        self.act_cancel = self._action("Ca&ncel bus work", self.cancel_bus_work, None,
                                       "Cancel what the bus is doing for you (scan, apply…)")
        self.act_compare = self._action("Co&mpare configurations…", self.show_compare)
        self.act_write = self._action("&Write configuration to the arbitrator…",
                                      self.ask_write_configuration)
        self.act_profiles = self._action("&Profile tree…", self.show_profile_tree)
        self.act_about = self._action("&About PDCP Studio", self.about)

    def _build_menus(self) -> None:
        mb = self.menuBar()
        m = mb.addMenu("&File")
        for a in (self.act_open, self.act_save, self.act_save_as):
            m.addAction(a)
        m.addSeparator()
        for a in (self.act_export_png, self.act_export_svg, self.act_report):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_quit)
        m = mb.addMenu("&Edit")
        for a in (self.act_undo, self.act_redo):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_delete)
        m.addSeparator()
        m.addAction(self.act_profiles)
        self.view_menu = m = mb.addMenu("&View")
        for a in (self.act_fit, self.act_zoom_in, self.act_zoom_out, self.act_arrange,
                  self.act_legend):
            m.addAction(a)
        m.addSeparator()
        for dock in (self.tree_dock, self.inspector_dock, self.plan_dock):
            m.addAction(dock.toggleViewAction())
        m = mb.addMenu("&Plan")
        for a in self.plan_actions.values():
            m.addAction(a)
        self.bus_menu = m = mb.addMenu("&Bus")
        for a in (self.act_connect, self.act_connect_sim, self.act_disconnect, self.act_scan,
                  self.act_read_config, self.act_cancel):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_compare)
        m.addAction(self.act_write)
        mb.addMenu("&Help").addAction(self.act_about)
        tb = self.addToolBar("Main")
        tb.setObjectName("MainToolBar")
        tb.setMovable(False)
        for a in (self.act_open, self.act_save, None, self.act_undo, self.act_redo, None,
                  self.act_fit, self.act_arrange, None, *self.plan_actions.values(), None,
                  self.act_connect):
            if a is None:
                tb.addSeparator()
            else:
                tb.addAction(a)

    def _connect(self) -> None:
        doc = self.doc
        doc.dirtyChanged.connect(lambda _d: self._update_title())
        doc.pathChanged.connect(lambda _p: self._update_title())
        doc.sessionChanged.connect(lambda _s: self._update_mode())
        doc.selectionChanged.connect(self._reveal)
        for source in (self.scene, self.inspector, self.plan_panel, self.live):
            source.statusMessage.connect(self.show_message)
        self.live.progress.connect(self._on_progress)
        self.live.busyChanged.connect(self._on_busy)
        self.live.connected.connect(self._on_connected)
        self.live.failed.connect(self._on_connect_failed)
        self.live.disconnected.connect(self._update_mode)
        self.live.bridgeReady.connect(self._attach_bus_docks_safely)
        self._update_mode()

    # -- title, status ----------------------------------------------------------------
    def _update_title(self) -> None:
        self.setWindowTitle(f"{self.doc.title}[*] — PDCP Studio")
        self.setWindowModified(self.doc.is_dirty)

    def _update_mode(self) -> None:
        live = self.live.is_live and self.doc.session is self.live.bridge
        self.mode_label.setText(f"Live: {self.live.url}" if live else "Offline")
        self.mode_label.setStyleSheet("color: #0b7a4b; font-weight: bold;" if live else
                                      "color: #66707b;")
        for a in (self.act_disconnect, self.act_scan, self.act_write, self.act_read_config):
            a.setEnabled(live)
        self.plan_panel._update_buttons()
        self._update_title()

    def show_message(self, text: str, timeout_ms: int = 8000) -> None:
        self.statusBar().showMessage(text, timeout_ms)

    def _on_progress(self, done: int, total: int, text: str) -> None:
        if self.progress.maximum() != max(0, total):
            self.progress.setMaximum(max(0, total))
        self.progress.setValue(min(done, total) if total else 0)
        if text and text != self.statusBar().currentMessage():
            self.statusBar().showMessage(text, 4000)

    def _on_busy(self, busy: bool) -> None:
        # Hidden only after a quiet spell: back-to-back jobs (scans, refreshes) must not
        # re-lay-out and repaint the status bar on every start and end.
        if busy:
            self._progress_hide.stop()
            if self.progress.isHidden():
                self.progress.setRange(0, 0)
                self.progress.show()
        else:
            self._progress_hide.start()

    def _reveal(self, obj: object) -> None:
        item = self.scene.item_for(obj)
        if item is not None:
            self.view.centre_on_item(item.sceneBoundingRect())

    # -- loading ----------------------------------------------------------------------
    def _loaded(self) -> None:
        """The first system is on screen: fit it, then say so once."""
        self.view.fit_all()
        if not self._is_ready:
            self._is_ready = True
            # Everything alive now (Qt wrappers, modules, the model) lives as long as the
            # window: move it out of the cyclic collector's view, so a full collection stops
            # costing the GUI thread 20–50 ms while the bus threads allocate (benchmarks/gui.py).
            gc.freeze()
            self.ready.emit()

    @property
    def is_ready(self) -> bool:
        return self._is_ready

    def open_path(self, path: str | Path) -> bool:
        """Open a system file or a .pdcfg; errors go to a message box and return False."""
        try:
            opened = files.open_path(path)
        except (PdcpError, OSError) as err:
            self.error_box("Cannot open", str(err))
            return False
        self.show_opened(opened, Path(path))
        return True

    def show_opened(self, opened: files.Opened, path: Path | None) -> None:
        """Put a loaded file on screen (offline)."""
        self.live.disconnect_bus()
        self.doc.set_system(opened.system, path, None, positions=opened.positions,
                            kind=opened.kind, config=opened.config)
        what = "configuration" if opened.kind == "config" else "system"
        note = f" ({opened.note})" if opened.note else ""
        self.show_message(f"Opened {what} {path.name if path else ''}: "
                          f"{len(opened.system.devices)} devices, "
                          f"{len(opened.system.links)} links{note}")
        self._loaded()

    def connect_bus(self, url: str) -> None:
        """Connect on a worker; the document switches to the bus when it answers."""
        self.live.connect_bus(url)

    def _on_connected(self, url: str) -> None:
        self._update_mode()
        self._loaded()

    def _on_connect_failed(self, url: str, message: str) -> None:
        if not self._is_ready and url == DEFAULT_BUS:
            self.open_offline_default(f"the simulated prosthesis did not start ({message})")
            return
        where = "" if message.startswith(url) else f"{url}: "
        self.error_box("Cannot connect", f"{where}{message}")
        self._update_mode()
        if not self._is_ready:
            self._loaded()

    def open_offline_default(self, why: str) -> None:
        """The shipped transradial system, linked by autoconfigure, with no bus behind it."""
        from pdcp_studio.engine import plan_autoconfigure
        from pdcp_studio.paths import systems_dir
        from pdcp_studio.storage import system_file

        system: System = system_file.load_path(systems_dir() / OFFLINE_SYSTEM)
        if not system.links:
            plan_autoconfigure(system).apply(system)
        self.doc.set_system(system, None, None, positions={})
        self._update_mode()
        self._loaded()
        self.show_message(f"Offline: {why}. Showing the shipped {OFFLINE_SYSTEM}.", 0)

    # -- files ------------------------------------------------------------------------
    def ask_open(self) -> None:
        if not self.maybe_save():
            return
        path, _ = QFileDialog.getOpenFileName(self, "Open", self._last_dir(), FILE_FILTERS)
        if path:
            self._remember_dir(path)
            self.open_path(path)

    def save(self) -> bool:
        if self.doc.path is None:
            return self.ask_save_as()
        return self.save_to(self.doc.path)

    def ask_save_as(self) -> bool:
        start = str(self.doc.path) if self.doc.path else str(Path(self._last_dir())
                                                             / "system.json")
        path, _ = QFileDialog.getSaveFileName(self, "Save as", start, FILE_FILTERS)
        if not path:
            return False
        self._remember_dir(path)
        return self.save_to(path)

    def save_to(self, path: str | Path) -> bool:
        """Save as a system file, or as a .pdcfg (links only) by the extension."""
        path = Path(path)
        try:
            if files.is_config_path(path):
                files.save_configuration(self.doc.system, path)
            else:
                files.save_system(self.doc.system, path, self.doc.positions)
        except (PdcpError, OSError, ValueError) as err:
            self.error_box("Cannot save", f"{path}: {err}")
            return False
        self.doc.kind = "config" if files.is_config_path(path) else "system"
        self.doc.mark_saved(path)
        self.show_message(f"Saved {path}")
        return True

    def maybe_save(self) -> bool:
        """True when it is fine to drop the document (saved, discarded, or clean)."""
        if not self.doc.is_dirty:
            return True
        answer = self.ask_save_changes()
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    def ask_save_changes(self) -> QMessageBox.StandardButton:
        """Save, Discard or Cancel (tests replace this method)."""
        SB = QMessageBox.StandardButton
        return QMessageBox.question(
            self, "Unsaved changes", f"Save the changes to {self.doc.title}?",
            SB.Save | SB.Discard | SB.Cancel, SB.Save)

    def _last_dir(self) -> str:
        return str(QSettings().value("files/last_dir", str(Path.home())))

    def _remember_dir(self, path: str) -> None:
        QSettings().setValue("files/last_dir", str(Path(path).parent))

    def error_box(self, title: str, text: str) -> None:
        """Tell the user; in the status bar too, so scripted runs leave a trace."""
        log.warning("%s: %s", title, text)
        self.show_message(f"{title}: {text}", 0)
        if not getattr(self, "quiet", False):
            QMessageBox.warning(self, title, text)

    # -- export -----------------------------------------------------------------------
    def graph_image(self, scale: float = 2.0) -> QImage:
        """The whole graph rendered off screen (for PNG export and the report)."""
        rect = self.scene.itemsBoundingRect().adjusted(-20, -20, 20, 20)
        image = QImage(max(1, int(rect.width() * scale)), max(1, int(rect.height() * scale)),
                       QImage.Format.Format_ARGB32)
        image.fill(self.scene.backgroundBrush().color())
        painter = QPainter(image)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        self.scene.render(painter, source=rect)
        painter.end()
        return image

    def export_graph(self, path: str | Path) -> None:
        path = Path(path)
        rect = self.scene.itemsBoundingRect().adjusted(-20, -20, 20, 20)
        if path.suffix.lower() == ".svg":
            from PySide6.QtSvg import QSvgGenerator

            gen = QSvgGenerator()
            gen.setFileName(str(path))
            gen.setSize(rect.size().toSize())
            gen.setViewBox(rect)
            gen.setTitle(self.doc.title)
            painter = QPainter(gen)
            self.scene.render(painter, source=rect)
            painter.end()
        elif not self.graph_image().save(str(path)):
            raise OSError(f"{path}: could not write the image")

    def ask_export(self, kind: str) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Export graph",
                                              str(Path(self._last_dir()) / f"bus.{kind}"),
                                              f"{kind.upper()} (*.{kind})")
        if path:
            try:
                self.export_graph(path)
                self.show_message(f"Exported {path}")
            except OSError as err:
                self.error_box("Cannot export", str(err))

    def ask_report(self) -> None:
        report = optional_module("report")
        if report is None:
            self.error_box("Report", "this build has no report module")
            return
        path, _ = QFileDialog.getSaveFileName(self, "Fitting report",
                                              str(Path(self._last_dir()) / "fitting.pdf"),
                                              "PDF (*.pdf)")
        if path:
            try:
                report.write_report(path, self.doc.system, self.doc.tree, self.graph_image())
                self.show_message(f"Wrote the fitting report {path}")
            except (PdcpError, OSError) as err:
                self.error_box("Cannot write the report", str(err))

    # -- editing, plans ----------------------------------------------------------------
    def arrange(self) -> None:
        from pdcp_studio.app import commands

        new = self.scene.relayout()
        moves = {k: (self.doc.positions[k], p) for k, p in new.items()
                 if k in self.doc.positions and self.doc.positions[k] != p}
        if moves:
            self.doc.undo_stack.push(commands.MoveDevicesCommand(self.doc, moves))
        self.view.fit_all()

    def preview_plan(self, mode: str) -> Any:
        self.plan_dock.show()
        self.plan_dock.raise_()
        return self.plan_panel.preview(mode)

    def show_profile_tree(self) -> None:
        mod = optional_module("profile_tree_editor")
        if mod is None:
            self.error_box("Profile tree", "this build has no profile-tree editor")
            return
        dialog = mod.ProfileTreeDialog(self.doc.tree, None, self)
        dialog.editor.treeChanged.connect(self._tree_changed)
        dialog.show()

    def _tree_changed(self, tree: Any) -> None:
        self.doc.tree = tree
        self.scene.update()
        self.tree.rebuild()
        self.inspector.show_object(self.doc.selection)

    # -- live bus ---------------------------------------------------------------------
    def ask_connect(self) -> None:
        mod = optional_module("connect_dialog")
        url = mod.ConnectDialog.get_url(self) if mod is not None else DEFAULT_BUS
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
        monitor = optional_module("monitor_dock")
        if monitor is not None:
            dock = self._leaf_docks.get("monitor")
            if dock is None:
                dock = monitor.MonitorDock(self)
                self.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, dock)
                self.tabifyDockWidget(self.plan_dock, dock)
                self.plan_dock.raise_()
                self.view_menu.addAction(dock.toggleViewAction())
                self._leaf_docks["monitor"] = dock
            bridge.frameSeen.connect(dock.add_frames)
        plot_mod = optional_module("live_plot")
        if plot_mod is not None:
            dock = self._leaf_docks.get("plot")
            if dock is None:
                plot = plot_mod.LivePlot()
                dock = self._dock("Live plot", "LivePlotDock", plot,
                                  Qt.DockWidgetArea.BottomDockWidgetArea)
                self.tabifyDockWidget(self.plan_dock, dock)
                self.plan_dock.raise_()
                self.view_menu.addAction(dock.toggleViewAction())
                self._leaf_docks["plot"] = dock
                self.doc.selectionChanged.connect(self._plot_selection)
            bridge.channelValues.connect(dock.widget().add_values)
        sim = optional_module("sim_panel")
        if sim is not None and bridge.is_sim:
            old = self._leaf_docks.pop("sim", None)
            if old is not None:
                old.close()
                old.deleteLater()
            panel = sim.SimPanel(bridge)
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
        mod = optional_module("compare_dialog")
        if mod is None:
            self.error_box("Compare", "this build has no compare dialog")
            return
        dialog = mod.CompareDialog(self.doc.system, bridge=self.live.bridge, parent=self)
        if self.doc.config is not None and hasattr(mod, "sources_of_collection"):
            dialog.set_file_sources(mod.sources_of_collection(self.doc.title, self.doc.config))
        dialog.show()

    def ask_write_configuration(self) -> None:
        mod = optional_module("write_config_dialog")
        if mod is None or self.live.bridge is None:
            self.error_box("Write configuration", "connect to a bus first")
            return
        dialog = mod.WriteConfigDialog.for_system(self.live.bridge, self.doc.system, self)
        dialog.show()

    def about(self) -> None:
        from pdcp_studio import __version__

        QMessageBox.about(self, "About PDCP Studio",
                          f"PDCP Studio {__version__}\nSee and configure the PDCP bus "
                          "inside a powered prosthesis.")

    # -- crash recovery -----------------------------------------------------------------
    def _start_autosave(self, recovery: Any) -> None:
        mod = optional_module("recovery")
        if mod is None:
            return
        doc = self.doc
        self.autosaver = mod.Autosaver(
            recovery, lambda: str(doc.path) if doc.path else "untitled",
            lambda: files.system_text(doc.system, doc.positions),
            path_fn=lambda: str(doc.path) if doc.path else None, parent=self)
        self.autosaver.error.connect(self.show_message)
        self.autosaver.watch(doc)

    def offer_recovery(self) -> bool:
        """After a crash: offer the autosaved documents; True if one was restored."""
        mod = optional_module("recovery")
        if mod is None or self.recovery is None:
            return False
        pending = self.recovery.pending()
        if not pending:
            return False
        dialog = mod.RecoveryDialog(pending, self)
        chosen = dialog.chosen() if dialog.exec() == dialog.DialogCode.Accepted else []
        for entry in pending:
            if not chosen or entry is not chosen[0]:
                self.recovery.discard(entry.name)
        if not chosen:
            return False
        return self.restore(chosen[0])

    def restore(self, entry: Any) -> bool:
        """Show an autosaved document, marked unsaved (its file, if any, is older)."""
        try:
            opened = files.loads_system(entry.text, entry.name)
        except PdcpError as err:
            self.error_box("Cannot recover", str(err))
            return False
        self.doc.set_system(opened.system, entry.path, None, dirty=True,
                            positions=opened.positions)
        self._loaded()
        self.show_message(f"Recovered unsaved work: {entry.title}")
        return True

    # -- closing ----------------------------------------------------------------------
    def closeEvent(self, event: QCloseEvent) -> None:
        if not self.maybe_save():
            event.ignore()
            return
        self.live.disconnect_bus()
        if self.autosaver is not None:
            self.autosaver.clean()  # closed on purpose: nothing to recover next time
        event.accept()


def start_default(window: MainWindow) -> None:
    """What bare ``pdcp-studio`` shows: the simulated prosthesis (offline if it fails)."""
    QTimer.singleShot(0, lambda: window.connect_bus(DEFAULT_BUS))
