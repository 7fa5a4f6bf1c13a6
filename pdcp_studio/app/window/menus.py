"""The main window's actions, menus and toolbar.

Kept apart from :mod:`main_window` so the long list of what the user can trigger (and
where it shows) reads in one place; every action only calls a method of the window.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QT_TRANSLATE_NOOP
from PySide6.QtGui import QAction, QKeySequence

from pdcp_studio.app.docks.plan_panel import OPERATIONS
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.support import DEFAULT_BUS

#: The Tasks menu: the guided tasks (app/wizards), their menu texts and tips.
TASK_MENU = (
    ("fitting", QT_TRANSLATE_NOOP("Wizards", "&New fitting…"),
     QT_TRANSLATE_NOOP("Wizards", "Connect, scan, check, link and store a prosthesis step by "
                                  "step")),
    ("replace", QT_TRANSLATE_NOOP("Wizards", "&Replace a part…"),
     QT_TRANSLATE_NOOP("Wizards", "Swap a part and link the new one in its place step by "
                                  "step")),
    ("restore", QT_TRANSLATE_NOOP("Wizards", "Re&store a configuration…"),
     QT_TRANSLATE_NOOP("Wizards", "Put a configuration file or an earlier fitting back on "
                                  "the prosthesis")),
)


class MenusMixin:
    """Builds ``act_*``, ``plan_actions``, the menus (``view_menu``, ``bus_menu``) and the
    toolbar (``toolbars``)."""

    if TYPE_CHECKING:  # a mixin of a QObject: Qt gives it tr()
        tr: Callable[[str], str]

    def _action(self, text: str, slot: Any, shortcut: Any = None, tip: str = "") -> QAction:
        action = QAction(text, self)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
        if tip:
            action.setStatusTip(tip)
        action.triggered.connect(lambda _checked=False: slot())
        return action

    def go_to_device(self, key: Any) -> None:
        """Select a device and centre its card in the graph."""
        self.doc.select(key)
        card = self.scene.cards.get(key)
        if card is not None:
            self.view.centerOn(card.sceneBoundingRect().center())

    def ask_go_to_device(self) -> None:
        from pdcp_studio.app.docks.device_finder import DeviceFinder

        self.device_finder = DeviceFinder(self.doc.system, self.go_to_device, self)
        self.device_finder.show()
        self.device_finder.field.setFocus()

    def _build_actions(self) -> None:
        K = QKeySequence.StandardKey
        self.act_open = self._action(
            self.tr("&Open…"),
            self.ask_open,
            K.Open,
            self.tr("Open a system file (.json) or a configuration (.pdcfg)"),
        )
        self.act_save = self._action(self.tr("&Save"), self.save, K.Save)
        self.act_save_as = self._action(self.tr("Save &As…"), self.ask_save_as, K.SaveAs)
        self.act_export_png = self._action(self.tr("Export graph as &PNG…"),
                                           lambda: self.ask_export("png"))
        self.act_export_svg = self._action(self.tr("Export graph as S&VG…"),
                                           lambda: self.ask_export("svg"))
        self.act_report = self._action(self.tr("Fitting &report (PDF)…"), self.ask_report)
        self.act_quit = self._action(self.tr("&Quit"), self.close, K.Quit)
        self.act_undo = self.doc.undo_stack.createUndoAction(self, self.tr("&Undo"))
        self.act_undo.setShortcut(QKeySequence(K.Undo))
        self.act_redo = self.doc.undo_stack.createRedoAction(self, self.tr("&Redo"))
        self.act_redo.setShortcut(QKeySequence(K.Redo))
        self.act_delete = self._action(self.tr("&Delete link"), self.scene.delete_selected,
                                       K.Delete, self.tr("Remove the selected links"))
        self.act_fit = self._action(self.tr("&Fit to window"), self.view.fit_all, "Ctrl+0")
        self.act_find = self._action(self.tr("&Go to device…"), self.ask_go_to_device, K.Find,
                                     self.tr("Find a device by name and show it on the graph"))
        self.act_zoom_in = self._action(
            self.tr("Zoom &in"), lambda: self.view.zoom_by(1.25), K.ZoomIn
        )
        self.act_zoom_out = self._action(
            self.tr("Zoom &out"), lambda: self.view.zoom_by(0.8), K.ZoomOut
        )
        self.act_legend = self._action(
            self.tr("Show &legend"),
            lambda: self.view.set_legend_visible(self.act_legend.isChecked()),
        )
        self.act_legend.setCheckable(True)
        self.act_legend.setChecked(self.view.legend_visible())
        self.view.legendVisibleChanged.connect(self.act_legend.setChecked)
        self.act_arrange = self._action(self.tr("&Arrange in layers"), self.arrange,
                                        tip=self.tr("Lay the cards out again: sensors → control → "
                                            "terminal devices (one undo step)"))
        self.plan_actions = {
            mode: self._action(translate("PlanPanel", text) + "…",
                               lambda m=mode: self.preview_plan(m))
            for mode, text in OPERATIONS}
        self.act_connect = self._action(
            self.tr("&Connect…"),
            self.ask_connect,
            tip=self.tr("Connect to a simulated prosthesis or a CAN bus"),
        )
        self.act_connect_sim = self._action(
            self.tr("Open the &simulated prosthesis"),
            lambda: self.maybe_save() and self.connect_bus(DEFAULT_BUS))
        self.act_disconnect = self._action(self.tr("&Disconnect"), self.live.disconnect_bus)
        self.act_scan = self._action(self.tr("&Scan the bus"), self.scan_bus)
        self.act_read_config = self._action(
            self.tr("&Read the stored configuration"), self.read_configuration,
            tip=self.tr("Read the arbitrator's stored configuration; plans that take a "
                "configuration (Find replacements, Start-up) then use it"))
        self.act_cancel = self._action(
            self.tr("Ca&ncel bus work"),
            self.cancel_bus_work,
            None,
            self.tr("Cancel what the bus is doing for you (scan, apply…)"),
        )
        self.act_compare = self._action(self.tr("Co&mpare configurations…"), self.show_compare)
        self.act_write = self._action(self.tr("&Write configuration to the arbitrator…"),
                                      self.ask_write_configuration)
        self.act_profiles = self._action(self.tr("&Profile tree…"), self.show_profile_tree)
        self.act_about = self._action(self.tr("&About PDCP Studio"), self.about)
        self.task_actions = {  # guided tasks (app/wizards)
            task: self._action(translate("Wizards", text), lambda t=task: self.open_task(t),
                               tip=translate("Wizards", tip))
            for task, text, tip in TASK_MENU}

    def open_task(self, task: str) -> Any:
        """Open a guided task (a wizard beside the window)."""
        from pdcp_studio.app.wizards import open_wizard

        return open_wizard(self, task)

    def _build_menus(self) -> None:
        mb = self.menuBar()
        m = mb.addMenu(self.tr("&File"))
        for a in (self.act_open, self.act_save, self.act_save_as):
            m.addAction(a)
        m.addSeparator()
        for a in (self.act_export_png, self.act_export_svg, self.act_report):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_quit)
        m = mb.addMenu(self.tr("&Edit"))
        for a in (self.act_undo, self.act_redo):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_delete)
        m.addSeparator()
        m.addAction(self.act_profiles)
        self.view_menu = m = mb.addMenu(self.tr("&View"))
        for a in (self.act_find, self.act_fit, self.act_zoom_in, self.act_zoom_out,
                  self.act_arrange, self.act_legend):
            m.addAction(a)
        m.addSeparator()
        for dock in (self.tree_dock, self.inspector_dock, self.plan_dock):
            m.addAction(dock.toggleViewAction())
        m = mb.addMenu(self.tr("&Plan"))
        for a in self.plan_actions.values():
            m.addAction(a)
        self.tasks_menu = m = mb.addMenu(translate("Wizards", "&Tasks"))
        for a in self.task_actions.values():
            m.addAction(a)
        self.bus_menu = m = mb.addMenu(self.tr("&Bus"))
        for a in (self.act_connect, self.act_connect_sim, self.act_disconnect, self.act_scan,
                  self.act_read_config, self.act_cancel):
            m.addAction(a)
        m.addSeparator()
        m.addAction(self.act_compare)
        m.addAction(self.act_write)
        mb.addMenu(self.tr("&Help")).addAction(self.act_about)
        tb = self.addToolBar("Main")
        tb.setObjectName("MainToolBar")
        tb.setMovable(False)
        self.toolbars = [tb]
        for a in (self.act_open, self.act_save, None, self.act_undo, self.act_redo, None,
                  self.act_fit, self.act_arrange, None, self.act_connect):
            # The plan operations live in the Plan menu and the plan dock, next to the plan
            # they show: not a third time here.
            if a is None:
                tb.addSeparator()
            else:
                tb.addAction(a)
