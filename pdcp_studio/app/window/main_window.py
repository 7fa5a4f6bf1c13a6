"""The main window: the bus graph in the middle, the tree, inspector and plan around it.

Everything shown follows one :class:`Document`; menus turn into undo commands, plans or
session calls. The window never blocks on the bus: connecting, refreshing and applying
run on workers (:mod:`pdcp_studio.app.live.live_bus`), with progress in the status bar.

The window is composed, not inherited: it builds its docks and status bar, then hands
each controller what that one needs (the document, the live connection, the status line,
itself as the parent of dialogs, a few callables) — :class:`FileController` (open, save),
:class:`GraphExport` (PNG/SVG, report), :class:`BusCommands` and :class:`BusDocks` (the
live bus), :class:`Transactions` and :class:`TransactionFlow` (pending changes, Write to
prosthesis, fitting history), :class:`PolicyController`, :class:`RecoveryController`,
:class:`StartPage` and :class:`Desktop`. Its actions, menus and toolbar are built from
one table (:mod:`.actions`). The methods below that only pass a call on keep the window's
long-standing face for scripts, dialogs and tests.
"""

from __future__ import annotations

import gc
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QCloseEvent, QImage, QShowEvent
from PySide6.QtWidgets import QDockWidget, QLabel, QMainWindow, QMessageBox, QWidget

from pdcp_studio.app.docks.pending_panel import PendingPanel
from pdcp_studio.app.docks.plan_panel import OPERATIONS, PlanPanel
from pdcp_studio.app.docks.tree_panel import DeviceTree
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.documents.files import Opened
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView
from pdcp_studio.app.gui_gc import collect_on_gui_thread
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window import questions
from pdcp_studio.app.window.actions import LIVE, TASKS, WindowActions
from pdcp_studio.app.window.bus_docks import BusDocks
from pdcp_studio.app.window.controllers.bus import BusCommands
from pdcp_studio.app.window.controllers.desktop import (
    Desktop,
    open_manual_here,
    show_about,
    show_about_qt,
    steady_toolbar,
)
from pdcp_studio.app.window.controllers.edit_commands import EditCommands
from pdcp_studio.app.window.controllers.export import GraphExport
from pdcp_studio.app.window.controllers.files import FileController, last_dir
from pdcp_studio.app.window.controllers.other_arbitrator import OtherArbitrator
from pdcp_studio.app.window.controllers.policy import PolicyController
from pdcp_studio.app.window.controllers.recovery import RecoveryController
from pdcp_studio.app.window.controllers.transaction_flow import TransactionFlow
from pdcp_studio.app.window.controllers.transactions import Transactions
from pdcp_studio.app.window.deferred_panel import DeferredPanel
from pdcp_studio.app.window.dock_area import add_dock
from pdcp_studio.app.window.mode_line import ModeLine, window_title
from pdcp_studio.app.window.start_view import StartOffers, StartPage, StartView
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.app.window.support import DEFAULT_BUS, FILE_FILTERS, OFFLINE_SYSTEM
from pdcp_studio.model.system import System

if TYPE_CHECKING:
    from pdcp_studio.app.dialogs.arbitrator_found import ArbitratorFoundDialog, ListeningIndicator
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog
    from pdcp_studio.app.docks.history_panel import HistoryPanel
    from pdcp_studio.app.docks.inspector import Inspector
    from pdcp_studio.app.live.passive_monitor import PassiveMonitor

__all__ = ["DEFAULT_BUS", "FILE_FILTERS", "OFFLINE_SYSTEM", "MainWindow",
           "start_default"]


class MainWindow(QMainWindow):
    """PDCP Studio's window on one document."""

    #: The first system is on screen and laid out (a file, a bus, or the offline fallback).
    ready = Signal()
    #: A scripted run: errors go to the status bar only, nothing is asked.
    quiet = False
    #: ``ask_leave_bus`` answers.
    LEAVE_COMPARE = questions.LEAVE_COMPARE
    LEAVE_DISCONNECT = questions.LEAVE_DISCONNECT
    LEAVE_CANCEL = questions.LEAVE_CANCEL

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
        self.live = LiveController(self.doc, self)
        self.live.on_data = self.scene.flow.note_data
        self.live.layout_shape = lambda: self.scene.layout_aspect
        self._is_ready = False
        self.recovery = recovery
        self.status_line = StatusLine(lambda text, ms: self.show_message(text, ms), self,
                                      lambda: bool(self.quiet))
        self.start_page = StartPage(self, self.view, StartOffers(
            open_task=self.open_task, ask_connect=lambda: self.ask_connect(),
            ask_open=lambda: self.files.ask_open(), try_simulated=self.try_simulated,
            open_recent=lambda path: self.maybe_save() and self.open_path(path),
            recent_paths=lambda: self.recent_files.paths()))
        self._build_docks()
        self._build_status()
        self._build_controllers()
        self._build_actions()
        self.policy = PolicyController(self.doc, self.live, self.policy_label,
                                       self.action_set["autoconfigure"],
                                       lambda change, title: bool(self.flow.run(change, title)))
        self.bus_docks = BusDocks(
            self, self.doc, self.live, self.scene, self.status_line,
            plan_dock=self.plan_dock, inspector_dock=self.inspector_dock,
            view_menu=self.view_menu, is_ready=lambda: self._is_ready, ready=self.ready,
            scan_finished=lambda system: self._scan_finished(system))
        self.other_arbitrator = OtherArbitrator(
            self, self.statusBar(), lambda text, ms: self.show_message(text, ms),
            lambda url: self.connect_bus(url), lambda: self.bus_docks.monitor_dock(),
            show_heard=lambda system, at: self.doc.set_system(system, positions=at))
        self._connect()
        self._update_title()
        self.crash_recovery = RecoveryController(self.doc, recovery, self.status_line, self,
                                                 self._loaded)
        self.desktop = Desktop(
            self, self.status_line, file_menu=self.action_set.menus["file"],
            before=self.act_save, monitor_dock=lambda: self.bus_docks.monitor_dock(),
            maybe_save=lambda: self.maybe_save(), open_path=lambda p: self.open_path(p),
            path_changed=self.doc.pathChanged, is_ready=lambda: self._is_ready,
            ready=self.ready, bridge_ready=self.live.bridgeReady, graph=self.view)
        from pdcp_studio.app.widgets.combo_popups import install as fit_combo_popups

        fit_combo_popups()  # dropdown entries shown whole, never cut in the middle

    # -- construction -----------------------------------------------------------------
    def _build_docks(self) -> None:
        # Side docks run the full height; the plan sits under the graph it explains.
        self.setCorner(Qt.Corner.BottomLeftCorner, Qt.DockWidgetArea.LeftDockWidgetArea)
        self.setCorner(Qt.Corner.BottomRightCorner, Qt.DockWidgetArea.RightDockWidgetArea)
        bottom = Qt.DockWidgetArea.BottomDockWidgetArea
        self.tree = DeviceTree(self.doc)
        self.plan_panel = PlanPanel(self.doc)
        self.tree_dock = add_dock(self, self.tr("Devices"), "DevicesDock", self.tree,
                                    Qt.DockWidgetArea.LeftDockWidgetArea)
        # On a live bus a hidden tab behind the Simulator (its panel made when first shown
        # or asked for); offline it is shown with the window and made then.
        self.inspector_dock = add_dock(self, self.tr("Inspector"), "InspectorDock", None,
                                       Qt.DockWidgetArea.RightDockWidgetArea)
        self._inspector = DeferredPanel(self.inspector_dock, lambda: _new_inspector(self),
                                        self._inspector_placed)
        self.plan_dock = add_dock(self, self.tr("Plan"), "PlanDock", self.plan_panel, bottom)
        self._docks_sized = False
        self.pending_panel = PendingPanel(self.doc)
        self.pending_dock = add_dock(self, self.tr("Pending changes"), "PendingDock",
                                       self.pending_panel, bottom)
        self.tabifyDockWidget(self.plan_dock, self.pending_dock)
        # A hidden tab: its panel is made when first shown or asked for (history_panel).
        self.history_dock = add_dock(self, self.tr("Fitting history"), "HistoryDock", None,
                                     bottom)
        self._history = DeferredPanel(self.history_dock, lambda: _new_history_panel(self),
                                      lambda panel: self.desktop.name_when_live(panel))
        self.tabifyDockWidget(self.plan_dock, self.history_dock)
        self.plan_dock.raise_()

    @property
    def inspector(self) -> Inspector:
        """The Inspector panel (made now if its dock was never shown)."""
        return self._inspector.panel()

    def _inspector_placed(self, panel: Inspector) -> None:
        panel.statusMessage.connect(self.show_message)
        panel.show_object(self.doc.selection)
        self.desktop.name_when_live(panel)  # (shown at the earliest with the window: made)

    @property
    def history_panel(self) -> HistoryPanel:
        """The Fitting history panel (made now if its tab was never shown)."""
        return self._history.panel()

    def showEvent(self, event: QShowEvent) -> None:
        """Size the docks once the window has its real size (earlier sizes do not stick)."""
        super().showEvent(event)
        if not self._docks_sized:
            self._docks_sized = True
            self.resizeDocks([self.tree_dock, self.inspector_dock], [300, 350],
                             Qt.Orientation.Horizontal)
            self.resizeDocks([self.plan_dock], [220], Qt.Orientation.Vertical)

    def _build_status(self) -> None:
        self.mode_line = ModeLine(self.statusBar(), self.live)
        self.mode_label, self.progress = self.mode_line.label, self.mode_line.progress
        self.policy_label = QLabel()
        self.statusBar().addPermanentWidget(self.policy_label)
        from pdcp_studio.app.window.controllers.archive import ArchiveStatus

        self.archive_status = ArchiveStatus(self.statusBar(), self,
                                            lambda: self.pending_panel.refresh())

    def _build_controllers(self) -> None:
        """The controllers, each given what it needs (late-bound: tests answer for it)."""
        status = self.status_line
        self.flow = TransactionFlow(
            self.doc, self.live, status, self,
            reread_configuration=lambda: self.bus.reread_configuration(),
            patient_reference=lambda: self.transactions.patient_reference())
        self.files = FileController(
            self.doc, self.live, status, self, loaded=self._loaded,
            is_ready=lambda: self._is_ready, open_config=self._open_config,
            compare=lambda path: self.bus.compare_with_prosthesis(path),
            ask_leave_bus=lambda path: self.ask_leave_bus(path),
            ask_save_changes=lambda: self.ask_save_changes())
        self.bus = BusCommands(
            self.doc, self.live, status, self, maybe_save=lambda: self.maybe_save(),
            connect_bus=lambda url: self.connect_bus(url),
            offer_arbitrator=self._offer_arbitrator,
            history_changed=lambda: self.history_panel.refresh())
        self.editing = EditCommands(self.doc, self, self.scene, self.view, self.plan_dock,
                                    self.plan_panel, self.tree, lambda: self._inspector.made)
        self.export = GraphExport(self.scene, self.doc, status, self,
                                  lambda path: self.write_fitting_report(path))

    def _build_actions(self) -> None:
        """Actions, menus and the toolbar from the one table (:mod:`.actions`)."""
        given = {
            "dock_devices": self.tree_dock.toggleViewAction(),
            "dock_inspector": self.inspector_dock.toggleViewAction(),
            "dock_plan": self.plan_dock.toggleViewAction(),
            "dock_pending": self.pending_dock.toggleViewAction(),
            "history": self.history_dock.toggleViewAction()}
        self.action_set = actions = WindowActions(self, window_commands(self),
                                                  self.doc.undo_stack, given)
        self.transactions = Transactions(
            self.doc, self.live, self.status_line, self.flow, self.pending_panel,
            self.pending_dock, self._history,
            write_actions=(actions["write_pending"], actions["discard_pending"]),
            ask_unwritten=lambda n: self.ask_unwritten(n), quiet=lambda: bool(self.quiet),
            graph_image=lambda: self.graph_image(), is_ready=lambda: self._is_ready,
            ready=self.ready)
        (self.act_open, self.act_save, self.act_save_as, self.act_export_png,
         self.act_export_svg, self.act_report, self.act_quit, self.act_undo, self.act_redo,
         self.act_delete, self.act_profiles, self.act_find, self.act_fit, self.act_zoom_in,
         self.act_zoom_out, self.act_arrange, self.act_legend, self.act_history,
         self.act_write_pending, self.act_discard_pending, self.act_connect,
         self.act_connect_sim, self.act_disconnect, self.act_scan, self.act_read_config,
         self.act_cancel, self.act_compare, self.act_write, self.act_autoconfigure,
         self.act_manual, self.act_about, self.act_about_qt) = (actions[key] for key in (
             "open", "save", "save_as", "export_png", "export_svg", "report", "quit", "undo",
             "redo", "delete", "profiles", "find", "fit", "zoom_in", "zoom_out", "arrange",
             "legend", "history", "write_pending", "discard_pending", "connect",
             "connect_sim", "disconnect", "scan", "read_config", "cancel", "compare", "write",
             "autoconfigure", "manual", "about", "about_qt"))
        self.plan_actions = actions.with_prefix("plan_")
        self.task_actions = actions.with_prefix("task_")
        self.act_legend.setChecked(self.view.legend_visible())
        self.view.legendVisibleChanged.connect(self.act_legend.setChecked)
        self.act_manual.setShortcutContext(Qt.ShortcutContext.ApplicationShortcut)
        self.addAction(self.act_manual)
        menus = actions.build_menus(self)
        self.view_menu, self.tasks_menu = menus["view"], menus["tasks"]
        self.bus_menu, self.help_menu = menus["bus"], menus["help"]
        toolbar = actions.build_toolbar(self)
        self.toolbars = [toolbar]
        steady = steady_toolbar(self, toolbar, self.act_undo, self.act_redo)
        self.toolbar_undo, self.toolbar_redo = steady["undo"], steady["redo"]

    def _connect(self) -> None:
        doc, live = self.doc, self.live
        doc.dirtyChanged.connect(lambda _d: self._update_title())
        doc.pathChanged.connect(lambda _p: self._update_title())
        doc.sessionChanged.connect(lambda _s: self._update_mode())
        doc.selectionChanged.connect(self._reveal)
        for source in (self.scene, self.plan_panel, live):
            source.statusMessage.connect(self.show_message)
        live.progress.connect(self.mode_line.on_progress)
        live.busyChanged.connect(self.mode_line.on_busy)
        live.connected.connect(self._on_connected)
        live.failed.connect(self._on_connect_failed)
        live.disconnected.connect(self._update_mode)
        live.disconnected.connect(self.bus_docks.detach)
        live.stateChanged.connect(lambda _s: self._update_mode())
        live.bridgeReady.connect(self.bus_docks.attach_safely)
        # A new session: a passive monitor of another bus gives way to it, the bus panels
        # start afresh on it, and plans get its stored configuration.
        live.sessionStarted.connect(lambda _b: self.other_arbitrator.stop_watching())
        live.sessionStarted.connect(self.bus_docks.session_started)
        live.sessionStarted.connect(self.bus.session_started)
        live.snapshotTaken.connect(self.bus_docks.bus_seen)
        self._update_mode()

    # -- title, status ----------------------------------------------------------------
    def _update_title(self) -> None:
        self.setWindowTitle(window_title(self.live, self.doc.title,
                                         self.doc.path is None and self.doc.session is not None))
        self.setWindowModified(self.doc.is_dirty)

    def _update_mode(self) -> None:
        live = self.live.is_live and self.doc.session is self.live.bridge
        self.mode_line.show_state(live)
        self.action_set.set_enabled(LIVE, live)
        self.plan_panel._update_buttons()
        self._update_title()

    def show_message(self, text: str, timeout_ms: int = 8000) -> None:
        self.statusBar().showMessage(text, timeout_ms)

    def error_box(self, title: str, text: str) -> None:
        """Tell the user; in the status bar too, so scripted runs leave a trace."""
        self.status_line.error(title, text)

    def _reveal(self, obj: object) -> None:
        item = self.scene.item_for(obj)
        if item is not None:
            self.view.centre_on_item(item.sceneBoundingRect())

    # -- loading ----------------------------------------------------------------------
    def _loaded(self) -> None:
        """The first system is on screen: fit it, then say so once."""
        self.start_page.leave()
        self.view.fit_all()
        self._mark_ready()

    def show_start(self) -> None:
        """Nothing to show (no file, no bus): the start page instead of an empty graph."""
        self.start_page.show()
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

    def try_simulated(self) -> None:
        if self.maybe_save():
            self.connect_bus(DEFAULT_BUS)

    def _on_connected(self, url: str) -> None:
        self._update_mode()
        self._loaded()

    def _on_connect_failed(self, url: str, message: str) -> None:
        if not self._is_ready and url == DEFAULT_BUS:
            self.open_offline_default(f"the simulated prosthesis did not start ({message})")
            return
        if self.bus.offer_other_arbitrator(url, message):
            self._update_mode()
            if not self._is_ready:
                self._loaded()
            return
        where = "" if message.startswith(url) else f"{url}: "
        self.error_box(self.tr("Cannot connect"), f"{where}{message}")
        self._update_mode()
        if not self._is_ready and self.quiet:
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

    def _offer_arbitrator(self, url: str, message: str, later: bool) -> None:
        self.other_arbitrator.offer(url, message, later=later)

    # What the other-arbitrator controller started, for the tests and the smoke run:
    @property
    def arbitrator_found_dialog(self) -> ArbitratorFoundDialog | None:
        return self.other_arbitrator.dialog

    @property
    def host_link_dialog(self) -> ConnectDialog | None:
        return self.other_arbitrator.host_link_dialog

    @property
    def passive_monitor(self) -> PassiveMonitor | None:
        return self.other_arbitrator.passive_monitor

    @property
    def listening_indicator(self) -> ListeningIndicator | None:
        return self.other_arbitrator.listening_indicator

    def _open_config(self, path: Path, collection: object) -> object:
        from pdcp_studio.app.configuration.window import open_config_window

        return open_config_window(self, path, collection)

    # -- editing, plans ----------------------------------------------------------------
    def preview_plan(self, mode: str) -> Any:
        return self.editing.preview_plan(mode)

    def show_profile_tree(self) -> None:
        self.editing.show_profile_tree()

    @property
    def profile_tree_dialog(self) -> Any:
        return self.editing.profile_tree_dialog

    @property
    def device_finder(self) -> Any:
        return self.editing.device_finder

    def open_task(self, task: str) -> Any:
        """Open a guided task (a wizard beside the window)."""
        from pdcp_studio.app.wizards import open_wizard

        return open_wizard(self, task)

    # -- the window's questions (tests answer them in its place) -----------------------
    def ask_save_changes(self) -> QMessageBox.StandardButton:
        """Save, Discard or Cancel."""
        return questions.ask_save_changes(self, self.doc.title)

    def ask_leave_bus(self, path: Path | None) -> str:
        """Compare, disconnect or cancel."""
        return questions.ask_leave_bus(self, self.live.url, path)

    def ask_unwritten(self, n: int) -> bool:
        """Leave with ``n`` pending changes not written?"""
        return questions.ask_unwritten(self, n)

    def ask_quit_live(self, n: int) -> str:
        """Quit a live view with ``n`` pending changes: write, discard or cancel."""
        return questions.ask_quit_live(self, n, self.live.url)

    # -- the controllers' calls, as the window always offered them ---------------------
    def open_path(self, path: str | Path) -> bool:
        return self.files.open_path(path)

    def show_opened(self, opened: Opened, path: Path | None) -> None:
        self.files.show_opened(opened, path)

    def save(self) -> bool:
        return self.files.save()

    def save_to(self, path: str | Path) -> bool:
        return self.files.save_to(path)

    def maybe_save(self) -> bool:
        """Before the document gives way (another file, another prosthesis): a file's
        changes are saved or discarded; a live view's are pending changes for the
        prosthesis, written or left — never "saved" to it."""
        if self.doc.is_live_view:
            self.doc.remember_layout()
            return bool(self.transactions.confirm_unwritten())
        return self.files.maybe_save()

    def _last_dir(self) -> str:
        return last_dir()

    def export_rect(self) -> Any:
        return self.export.export_rect()

    def graph_image(self, scale: float = 2.0) -> QImage:
        return self.export.graph_image(scale)

    def export_graph(self, path: str | Path) -> None:
        self.export.export_graph(path)

    def ask_connect(self) -> None:
        self.bus.ask_connect()

    def scan_bus(self) -> Any:
        return self.bus.scan_bus()

    def _scan_finished(self, system: Any) -> None:
        self.bus.scan_finished(system)

    def reread_configuration(self) -> None:
        self.bus.reread_configuration()

    def read_configuration(self) -> None:
        self.bus.read_configuration()

    @property
    def compare_dialog(self) -> Any:
        return self.bus.compare_dialog

    def ask_write_configuration(self) -> None:
        self.bus.ask_write_configuration()

    def _make_trace_docks(self) -> None:
        self.bus_docks.make_trace_docks()

    @property
    def _leaf_docks(self) -> dict[str, QDockWidget]:
        return self.bus_docks.leaf_docks

    def write_pending(self) -> bool:
        return self.transactions.write_pending()

    def fitting_info(self, entry: dict[str, Any] | None = None) -> Any:
        return self.transactions.fitting_info(entry)

    def write_fitting_report(self, path: Any, entry: dict[str, Any] | None = None) -> bool:
        return self.transactions.write_fitting_report(path, entry)

    def patient_reference(self) -> str:
        return self.transactions.patient_reference()

    def _load_patient_reference(self) -> None:
        self.transactions.load_patient_reference()

    def offer_recovery(self) -> bool:
        return self.crash_recovery.offer_recovery()

    def restore(self, entry: Any) -> bool:
        return self.crash_recovery.restore(entry)

    @property
    def autosaver(self) -> Any:
        return self.crash_recovery.autosaver

    @property
    def central(self) -> QWidget:
        return self.start_page.central

    @property
    def start_view(self) -> StartView | None:
        return self.start_page.start_view

    @property
    def _start_put_away(self) -> list[QDockWidget]:
        return self.start_page.put_away

    @property
    def recent_files(self) -> Any:
        return self.desktop.recent_files

    @property
    def recent_menu(self) -> Any:
        return self.desktop.recent_menu

    @property
    def _desktop_filter(self) -> Any:
        return self.desktop.filter

    # -- closing ----------------------------------------------------------------------
    def may_close(self) -> bool:
        """Ask once before closing. A live view's edits are pending changes for the
        prosthesis: written through the change road or discarded, never "saved" to it
        (its card positions are remembered unasked). A file's are saved."""
        if not self.doc.is_live_view:
            return self.transactions.confirm_unwritten() and self.maybe_save()
        self.doc.remember_layout()
        n = self.transactions.unwritten()
        if not n or self.quiet:
            return True
        answer = self.ask_quit_live(n)
        if answer == questions.QUIT_WRITE:
            self.transactions.write_pending()  # the window stays: quit again once written
            return False
        return answer == questions.QUIT_DISCARD

    def closeEvent(self, event: QCloseEvent) -> None:
        if not self.may_close():
            event.ignore()
            return
        self.live.disconnect_bus()
        self.other_arbitrator.stop_watching()  # a listen-only monitor, if one runs
        self.crash_recovery.clean()  # closed on purpose: nothing to recover next time
        event.accept()


def _new_inspector(window: MainWindow) -> Inspector:
    """The Inspector panel of ``window`` (its module imported only now)."""
    from pdcp_studio.app.docks.inspector import Inspector

    return Inspector(window.doc)


def _new_history_panel(window: MainWindow) -> HistoryPanel:
    """The Fitting history panel of ``window`` (its module imported only now)."""
    from pdcp_studio.app.docks.history_panel import HistoryPanel

    return HistoryPanel(window)


def start_default(window: MainWindow) -> None:
    """What bare ``pdcp-studio`` shows: the simulated prosthesis (offline if it fails)."""
    QTimer.singleShot(0, lambda: window.connect_bus(DEFAULT_BUS))


def window_commands(self: MainWindow) -> dict[str, Callable[[], object]]:
    """What each action of the table (:mod:`.actions`) does, by its id: the window hands
    each to the controller that owns it."""
    commands: dict[str, Callable[[], object]] = {
        "open": lambda: self.files.ask_open(),
        "save": lambda: self.save(),
        "save_as": lambda: self.files.ask_save_as(),
        "export_png": lambda: self.export.ask_export("png"),
        "export_svg": lambda: self.export.ask_export("svg"),
        "export_pdf": lambda: self.export.ask_export("pdf"),
        "report": lambda: self.export.ask_report(),
        "quit": self.close,
        "undo": lambda: self.flow.undo(),
        "redo": lambda: self.flow.redo(),
        "delete": self.scene.delete_selected,
        "profiles": lambda: self.editing.show_profile_tree(),
        "find": lambda: self.editing.ask_go_to_device(),
        "fit": self.view.fit_all,
        "zoom_in": lambda: self.view.zoom_by(1.25),
        "zoom_out": lambda: self.view.zoom_by(0.8),
        "arrange": lambda: self.editing.arrange(),
        "legend": lambda: self.view.set_legend_visible(self.act_legend.isChecked()),
        "write_pending": lambda: self.write_pending(),
        "discard_pending": lambda: self.transactions.discard_pending(),
        "connect": lambda: self.ask_connect(),
        "connect_sim": self.try_simulated,
        "disconnect": lambda: self.transactions.disconnect_asking(),
        "scan": lambda: self.scan_bus(),
        "read_config": lambda: self.read_configuration(),
        "cancel": lambda: self.bus.cancel_bus_work(),
        "compare": lambda: self.bus.show_compare(),
        "write": lambda: self.ask_write_configuration(),
        "autoconfigure": lambda: self.policy.set_autoconfigure(
            self.act_autoconfigure.isChecked()),
        "manual": lambda: open_manual_here(self),
        "about": lambda: show_about(self),
        "about_qt": lambda: show_about_qt(self),
    }
    for mode, _text in OPERATIONS:
        commands[f"plan_{mode}"] = partial(self.editing.preview_plan, mode)
    for task in TASKS:
        commands[f"task_{task.id}"] = partial(self.open_task, task.id)
    return commands
