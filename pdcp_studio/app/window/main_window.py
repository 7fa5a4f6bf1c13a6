"""The main window: the bus graph in the middle, the tree, inspector and plan around it.

Everything shown follows one :class:`Document`; menus turn into undo commands, plans or
session calls. The window never blocks on the bus: connecting, refreshing and applying
run on workers (:mod:`pdcp_studio.app.live.live_bus`), with progress in the status bar.
Widgets of the live bus (monitor, live plot, simulator panel, compare and write dialogs)
come from their own modules; the few that a build may lack are imported defensively.

This module builds the window (docks, status bar, signal wiring) and follows the document
from loading to closing; the rest of :class:`MainWindow` comes from mixins, one job each:
:mod:`window_menus` (actions, menus, toolbar), :mod:`window_files` (open, save),
:mod:`window_export` (PNG/SVG, report), :mod:`window_bus` (live-bus docks and commands),
:mod:`window_recovery` (autosave, crash recovery), :mod:`window_transactions` (pending
changes, Write to prosthesis, fitting history); shared names are in
:mod:`window_support`.
"""

from __future__ import annotations

import gc
import logging
from typing import Any

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QCloseEvent, QShowEvent
from PySide6.QtWidgets import (
    QDockWidget,
    QLabel,
    QMainWindow,
    QMessageBox,
    QProgressBar,
    QWidget,
)

from pdcp_studio.app.docks.inspector import Inspector
from pdcp_studio.app.docks.plan_panel import PlanPanel
from pdcp_studio.app.docks.tree_panel import DeviceTree
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView
from pdcp_studio.app.gui_gc import collect_on_gui_thread
from pdcp_studio.app.live.live_bus import OFFLINE, LiveController
from pdcp_studio.app.window import start_view
from pdcp_studio.app.window.bus import BusMixin
from pdcp_studio.app.window.export import ExportMixin
from pdcp_studio.app.window.files import FileHandlingMixin
from pdcp_studio.app.window.menus import MenusMixin
from pdcp_studio.app.window.policy import PolicyMixin
from pdcp_studio.app.window.recovery import RecoveryMixin
from pdcp_studio.app.window.support import (
    DEFAULT_BUS,
    FILE_FILTERS,
    OFFLINE_SYSTEM,
)
from pdcp_studio.app.window.transactions import TransactionsMixin
from pdcp_studio.model.system import System

__all__ = ["DEFAULT_BUS", "FILE_FILTERS", "OFFLINE_SYSTEM", "MainWindow",
           "start_default"]

log = logging.getLogger(__name__)


class MainWindow(MenusMixin, FileHandlingMixin, ExportMixin, BusMixin, RecoveryMixin,
                 TransactionsMixin, PolicyMixin, QMainWindow):
    """PDCP Studio's window on one document."""

    #: The first system is on screen and laid out (a file, a bus, or the offline fallback).
    ready = Signal()

    def __init__(self, doc: Document | None = None, parent: QWidget | None = None, *,
                 recovery: Any = None) -> None:
        super().__init__(parent)
        self.doc = doc if doc is not None else Document()
        if gc.isenabled():  # (not during the app's quiet start-up: start_up_over does it)
            collect_on_gui_thread()  # a closed window is never freed on a bus thread
        self.setWindowTitle(self.tr("PDCP Studio"))
        self.resize(1360, 820)
        self.scene = BusScene(self.doc, self)
        self.view = GraphView(self.scene, self)
        self.setCentralWidget(self.view)
        start_view.install(self)  # the start page shares the central area (app/start_view)
        self.live = LiveController(self.doc, self)
        self.live.on_data = self.scene.note_data
        self.live.layout_shape = lambda: self.scene.layout_aspect
        self._is_ready = False
        self._leaf_docks: dict[str, QDockWidget] = {}
        self._build_docks()
        self._build_status()
        self._build_actions()
        self._build_menus()
        self._build_transactions()
        self._build_policy()
        self._connect()
        self._update_title()
        self.recovery = recovery
        self.autosaver: Any = None
        if recovery is not None:
            self._start_autosave(recovery)
        from pdcp_studio.app.window.desktop import install_desktop

        install_desktop(self)  # recent files, drops, Help, shortcuts, accessible names
        from pdcp_studio.app.widgets.combo_popups import install as fit_combo_popups

        fit_combo_popups()  # dropdown entries shown whole, never cut in the middle

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
        self.tree_dock = self._dock(self.tr("Devices"), "DevicesDock", self.tree,
                                    Qt.DockWidgetArea.LeftDockWidgetArea)
        self.inspector_dock = self._dock(self.tr("Inspector"), "InspectorDock", self.inspector,
                                         Qt.DockWidgetArea.RightDockWidgetArea)
        self.plan_dock = self._dock(self.tr("Plan"), "PlanDock", self.plan_panel,
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
        self.mode_label = QLabel(self.tr("Offline"))
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
        self.live.disconnected.connect(self._detach_bus_docks)
        self.live.stateChanged.connect(lambda _s: self._update_mode())
        self.live.bridgeReady.connect(self._attach_bus_docks_safely)
        self.live.sessionStarted.connect(self._session_started)
        self.live.snapshotTaken.connect(self._bus_seen)
        self._update_mode()

    # -- title, status ----------------------------------------------------------------
    def _update_title(self) -> None:
        """The document, then the connection (the project and its target), then the app."""
        state = self.live.state_text()
        if self.doc.path is None and self.doc.session is not None:  # the bus is the document
            self.setWindowTitle(
                self.tr("{v0}{v1}[*] — PDCP Studio").format(v0=state[:1].upper(), v1=state[1:])
            )
        else:
            where = "" if self.live.state == OFFLINE else f" — {state}"
            self.setWindowTitle(
                self.tr("{title}[*]{where} — PDCP Studio").format(title=self.doc.title, where=where)
            )
        self.setWindowModified(self.doc.is_dirty)

    def _update_mode(self) -> None:
        from pdcp_studio.app.live import live_bus as live_mod

        live = self.live.is_live and self.doc.session is self.live.bridge
        state = self.live.state
        if state == live_mod.CONNECTING:
            text = (self.tr("● Live on {0} — connecting to {1}…") if live else
                    self.tr("Connecting to {1}…")).format(self.live.url,
                                                          self.live.connecting_url)
        elif state == live_mod.LIVE and live:
            text = self.tr("● Live on {0}").format(self.live.url)
        elif state == live_mod.DISCONNECTED:
            text = self.tr("Disconnected from {0}").format(self.live.last_url)
        else:
            text = self.tr("Offline")
        self.mode_label.setText(text)
        colour = {live_mod.LIVE: "color: #0b7a4b; font-weight: bold;",
                  live_mod.CONNECTING: "color: #8a5a00;",
                  live_mod.DISCONNECTED: "color: #b91c1c;"}.get(state, "color: #66707b;")
        self.mode_label.setStyleSheet(colour)
        self.mode_label.setToolTip(self.tr("The prosthesis this window is connected to "
                                           "(the document is the project, the prosthesis "
                                           "the target)"))
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
        start_view.leave_start(self)
        self.view.fit_all()
        self._mark_ready()

    def show_start(self) -> None:
        """Nothing to show (no file, no bus): the start page instead of an empty graph."""
        start_view.show_start(self)
        self._mark_ready()

    def _mark_ready(self) -> None:
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

    def connect_bus(self, url: str, opening: Any = None) -> None:
        """Connect on a worker; the document switches to the bus when it answers
        (``opening``: the session already being opened, see ``LiveController``)."""
        self.live.connect_bus(url, opening)

    def _on_connected(self, url: str) -> None:
        self._update_mode()
        self._loaded()

    def _on_connect_failed(self, url: str, message: str) -> None:
        if not self._is_ready and url == DEFAULT_BUS:
            self.open_offline_default(f"the simulated prosthesis did not start ({message})")
            return
        if self.offer_other_arbitrator(url, message):
            self._update_mode()
            if not self._is_ready:
                self._loaded()
            return
        where = "" if message.startswith(url) else f"{url}: "
        self.error_box(self.tr("Cannot connect"), f"{where}{message}")
        self._update_mode()
        if not self._is_ready and getattr(self, "quiet", False):
            self._loaded()  # a scripted run exits on the failure: nothing to offer
        elif not self._is_ready:
            self.show_start()  # nothing on screen: what the user can do instead

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
        self.show_message(
            self.tr("Offline: {why}. Showing the shipped {OFFLINE_SYSTEM}.").format(
                why=why, OFFLINE_SYSTEM=OFFLINE_SYSTEM
            ),
            0,
        )

    def error_box(self, title: str, text: str) -> None:
        """Tell the user; in the status bar too, so scripted runs leave a trace."""
        log.warning("%s: %s", title, text)
        self.show_message(f"{title}: {text}", 0)
        if not getattr(self, "quiet", False):
            QMessageBox.warning(self, title, text)

    # -- editing, plans ----------------------------------------------------------------
    def arrange(self) -> None:
        from pdcp_studio.app.documents import commands

        new = self.scene.relayout()
        moves = {k: (self.doc.positions[k], p) for k, p in new.items()
                 if k in self.doc.positions and self.doc.positions[k] != p}
        if moves:
            self.doc.undo_stack.push(commands.MoveDevicesCommand(self.doc, moves))
        self.view.fit_all()

    def preview_plan(self, mode: str) -> Any:
        self.plan_dock.show()
        self.plan_dock.raise_()
        plan = self.plan_panel.preview(mode)
        if plan is not None:
            # once the rows have their heights (never after the table is gone)
            QTimer.singleShot(0, self.plan_panel.actions_view, self._fit_plan_dock)
        return plan

    def _fit_plan_dock(self, tries: int = 4, asked: int = 0) -> None:
        """Grow the plan dock so an ordinary plan's rows all show (never past half the
        window, never shrinking what the user made larger). The dock area's size includes
        its tab bar and the rows wrap anew at the new width, so it looks again until the
        rows fit."""
        view = self.plan_panel.actions_view
        view.resizeRowsToContents()
        missing = view.verticalHeader().length() - view.viewport().height()
        if missing <= 0 or self.plan_dock.isFloating() or not self.plan_dock.isVisible():
            return
        height = min(max(asked, self.plan_dock.height()) + missing + 2, self.height() // 2)
        if height > max(asked, self.plan_dock.height()):
            self.resizeDocks([self.plan_dock], [height], Qt.Orientation.Vertical)
            if tries > 1:
                QTimer.singleShot(30, view, lambda: self._fit_plan_dock(tries - 1, height))

    def show_profile_tree(self) -> None:
        from pdcp_studio.app.dialogs.profile_tree_editor import ProfileTreeDialog

        dialog = ProfileTreeDialog(parent=self, trees=self.doc.trees)  # edited in place
        primary = self.doc.tree.primary  # the tree naming most of this system
        dialog.tabs.setCurrentIndex(self.doc.trees.index(primary)
                                    if primary in self.doc.trees else 0)
        dialog.treesChanged.connect(self._tree_changed)
        dialog.show()
        self.profile_tree_dialog = dialog

    def _tree_changed(self, trees: Any) -> None:
        self.doc.set_trees(trees)
        self.scene.update()
        self.tree.rebuild()
        self.inspector.show_object(self.doc.selection)


    def about(self) -> None:
        from pdcp_studio import __version__

        QMessageBox.about(self, self.tr("About PDCP Studio"),
                          self.tr("PDCP Studio {version__}\nSee and configure the PDCP bus "
                                  "inside a powered prosthesis.").format(version__=__version__))

    # -- closing ----------------------------------------------------------------------
    def closeEvent(self, event: QCloseEvent) -> None:
        if not self.confirm_unwritten() or not self.maybe_save():
            event.ignore()
            return
        self.live.disconnect_bus()
        from pdcp_studio.app.dialogs.arbitrator_found import stop_watching

        stop_watching(self)  # a listen-only monitor, if one runs
        if self.autosaver is not None:
            self.autosaver.clean()  # closed on purpose: nothing to recover next time
        event.accept()


def start_default(window: MainWindow) -> None:
    """What bare ``pdcp-studio`` shows: the simulated prosthesis (offline if it fails)."""
    QTimer.singleShot(0, lambda: window.connect_bus(DEFAULT_BUS))
