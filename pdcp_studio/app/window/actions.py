"""What the user can trigger in the main window, declared once as data.

One table (:data:`ACTIONS`) says for every action its text, shortcut, tip, the menu and
group it shows in, whether the toolbar has it and when it is enabled; :class:`WindowActions`
makes the ``QAction`` objects from it and builds the menu bar and the toolbar. The guided
tasks (:data:`TASKS`) give both the Tasks menu's rows and the start page's buttons. The
handlers are not in the table: the window hands in a command for each action id.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import NamedTuple

from PySide6.QtCore import QObject
from PySide6.QtGui import QAction, QKeySequence, QUndoStack
from PySide6.QtWidgets import QMainWindow, QMenu, QToolBar

from pdcp_studio.app.docks.plan_panel import OPERATIONS
from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.wizards import TASKS as wizard_tasks

#: The translation context of the window's own action texts.
CONTEXT = "WindowActions"

K = QKeySequence.StandardKey


class Task(NamedTuple):
    """A guided task (app/wizards): its Tasks menu row and its start page button."""

    id: str
    menu_text: str  # context "Wizards"
    menu_tip: str  # context "Wizards"
    title: str  # context "StartView"
    description: str  # context "StartView"


#: What the Tasks menu and the start page say of each guided task, by its id.
_TASK_WORDS: dict[str, tuple[str, str, str, str]] = {
    "fitting": (
        QT_TRANSLATE_NOOP("Wizards", "&New fitting…"),
        QT_TRANSLATE_NOOP("Wizards", "Connect, scan, check, link and store a prosthesis "
                                     "step by step"),
        QT_TRANSLATE_NOOP("StartView", "New fitting"),
        QT_TRANSLATE_NOOP("StartView", "Connect to a prosthesis, check it, link its parts "
                                       "and store the result, step by step.")),
    "replace": (
        QT_TRANSLATE_NOOP("Wizards", "&Replace a part…"),
        QT_TRANSLATE_NOOP("Wizards", "Swap a part and link the new one in its place step "
                                     "by step"),
        QT_TRANSLATE_NOOP("StartView", "Replace a part"),
        QT_TRANSLATE_NOOP("StartView", "Swap a part and link the new one in its place, "
                                       "with how alike it is said in words.")),
    "restore": (
        QT_TRANSLATE_NOOP("Wizards", "Re&store a configuration…"),
        QT_TRANSLATE_NOOP("Wizards", "Put a configuration file or an earlier fitting back "
                                     "on the prosthesis"),
        QT_TRANSLATE_NOOP("StartView", "Restore a configuration"),
        QT_TRANSLATE_NOOP("StartView", "Put a configuration file or an earlier fitting "
                                       "back on the prosthesis.")),
}

#: The guided tasks, in the order and with the ids the wizards declare them (app/wizards).
TASKS = tuple(Task(task_id, *_TASK_WORDS[task_id]) for task_id in wizard_tasks)

#: Plan shortcuts, in the order of the Plan menu.
PLAN_KEYS = ("Ctrl+1", "Ctrl+2", "Ctrl+3", "Ctrl+4", "Ctrl+5", "Ctrl+6", "Ctrl+7")
CONNECT_KEY = "Ctrl+K"
DISCONNECT_KEY = "Ctrl+Shift+K"

#: Conditions an action's ``enabled_when`` may name (the window says when they hold).
LIVE, PENDING, POLICY = "live", "pending", "policy"

#: How an action is made: by the table, by the undo stack, or handed in ready-made (a
#: dock's show/hide action).
PLAIN, UNDO, REDO, GIVEN = "plain", "undo", "redo", "given"


@dataclass(frozen=True)
class ActionSpec:
    """One row of the table; ``group`` changes put a separator in the menu (and toolbar)."""

    id: str
    text: str
    menu: str
    group: int = 0
    context: str = CONTEXT
    shortcut: QKeySequence.StandardKey | str | None = None
    tip: str = ""
    toolbar: int | None = None
    enabled_when: str | None = None
    checkable: bool = False
    kind: str = PLAIN
    suffix: str = ""


#: The menus in the menu bar's order: (id, title, translation context).
MENUS = (
    ("file", QT_TRANSLATE_NOOP("WindowActions", "&File"), CONTEXT),
    ("edit", QT_TRANSLATE_NOOP("WindowActions", "&Edit"), CONTEXT),
    ("view", QT_TRANSLATE_NOOP("WindowActions", "&View"), CONTEXT),
    ("plan", QT_TRANSLATE_NOOP("WindowActions", "&Plan"), CONTEXT),
    ("tasks", QT_TRANSLATE_NOOP("Wizards", "&Tasks"), "Wizards"),
    ("bus", QT_TRANSLATE_NOOP("WindowActions", "&Bus"), CONTEXT),
    ("help", QT_TRANSLATE_NOOP("WindowActions", "&Help"), CONTEXT),
)

A = ActionSpec
ACTIONS: tuple[ActionSpec, ...] = (
    A("open", QT_TRANSLATE_NOOP("WindowActions", "&Open…"), "file", 0, shortcut=K.Open,
      tip=QT_TRANSLATE_NOOP("WindowActions",
                            "Open a system file (.json) or a configuration (.pdcfg)"),
      toolbar=0),
    A("save", QT_TRANSLATE_NOOP("WindowActions", "&Save"), "file", 0, shortcut=K.Save,
      toolbar=0),
    A("save_as", QT_TRANSLATE_NOOP("WindowActions", "Save &As…"), "file", 0,
      shortcut=K.SaveAs),
    A("export_png", QT_TRANSLATE_NOOP("WindowActions", "Export graph as &PNG…"), "file", 1),
    A("export_svg", QT_TRANSLATE_NOOP("WindowActions", "Export graph as S&VG…"), "file", 1),
    A("export_pdf", QT_TRANSLATE_NOOP("WindowActions", "Export graph as P&DF…"), "file", 1),
    A("report", QT_TRANSLATE_NOOP("WindowActions", "Fitting &report (PDF)…"), "file", 1),
    A("quit", QT_TRANSLATE_NOOP("WindowActions", "&Quit"), "file", 2, shortcut=K.Quit),
    A("undo", QT_TRANSLATE_NOOP("WindowActions", "&Undo"), "edit", 0, shortcut=K.Undo,
      toolbar=1, kind=UNDO),
    A("redo", QT_TRANSLATE_NOOP("WindowActions", "&Redo"), "edit", 0, shortcut=K.Redo,
      toolbar=1, kind=REDO),
    A("delete", QT_TRANSLATE_NOOP("WindowActions", "&Delete link"), "edit", 1,
      shortcut=K.Delete, tip=QT_TRANSLATE_NOOP("WindowActions", "Remove the selected links")),
    A("profiles", QT_TRANSLATE_NOOP("WindowActions", "&Profile tree…"), "edit", 2),
    A("find", QT_TRANSLATE_NOOP("MainWindow", "&Go to device…"), "view", 0,
      context="MainWindow", shortcut=K.Find,
      tip=QT_TRANSLATE_NOOP("MainWindow", "Find a device by name and show it on the graph")),
    A("fit", QT_TRANSLATE_NOOP("WindowActions", "&Fit to window"), "view", 0,
      shortcut="Ctrl+0", toolbar=2),
    A("zoom_in", QT_TRANSLATE_NOOP("WindowActions", "Zoom &in"), "view", 0,
      shortcut=K.ZoomIn),
    A("zoom_out", QT_TRANSLATE_NOOP("WindowActions", "Zoom &out"), "view", 0,
      shortcut=K.ZoomOut),
    A("arrange", QT_TRANSLATE_NOOP("WindowActions", "&Arrange in layers"), "view", 0,
      tip=QT_TRANSLATE_NOOP("WindowActions", "Lay the cards out again: sensors → control → "
                                             "terminal devices (one undo step)"),
      toolbar=2),
    A("legend", QT_TRANSLATE_NOOP("WindowActions", "Show &legend"), "view", 0,
      checkable=True),
    A("dock_devices", "", "view", 1, kind=GIVEN),
    A("dock_inspector", "", "view", 1, kind=GIVEN),
    A("dock_plan", "", "view", 1, kind=GIVEN),
    A("dock_pending", "", "view", 1, kind=GIVEN),
    A("history", QT_TRANSLATE_NOOP("MainWindow", "Fitting &history"), "view", 1,
      context="MainWindow", kind=GIVEN),
    *(A(f"plan_{mode}", str(text), "plan", context="PlanPanel", suffix="…",
        shortcut=key)
      for (mode, text), key in zip(OPERATIONS, PLAN_KEYS, strict=False)),
    *(A(f"task_{task.id}", task.menu_text, "tasks", context="Wizards", tip=task.menu_tip)
      for task in TASKS),
    A("write_pending", QT_TRANSLATE_NOOP("MainWindow", "&Write to prosthesis…"), "bus", 0,
      context="MainWindow", shortcut="Ctrl+Shift+W", enabled_when=PENDING,
      tip=QT_TRANSLATE_NOOP("MainWindow", "Show the pending changes' difference and write "
                                          "them in one transaction")),
    A("discard_pending", QT_TRANSLATE_NOOP("MainWindow", "&Discard pending changes"), "bus", 0,
      context="MainWindow", enabled_when=PENDING),
    A("connect", QT_TRANSLATE_NOOP("WindowActions", "&Connect…"), "bus", 1,
      shortcut=CONNECT_KEY, toolbar=3,
      tip=QT_TRANSLATE_NOOP("WindowActions",
                            "Connect to a simulated prosthesis or a CAN bus")),
    A("connect_sim", QT_TRANSLATE_NOOP("WindowActions", "Open the &simulated prosthesis"),
      "bus", 1),
    A("disconnect", QT_TRANSLATE_NOOP("WindowActions", "&Disconnect"), "bus", 1,
      shortcut=DISCONNECT_KEY, enabled_when=LIVE),
    A("scan", QT_TRANSLATE_NOOP("WindowActions", "&Scan the bus"), "bus", 1,
      enabled_when=LIVE),
    A("read_config", QT_TRANSLATE_NOOP("WindowActions", "&Read the stored configuration"),
      "bus", 1, enabled_when=LIVE,
      tip=QT_TRANSLATE_NOOP("WindowActions", "Read the arbitrator's stored configuration; "
                                             "plans that take a configuration (Find "
                                             "replacements, Start-up) then use it")),
    A("cancel", QT_TRANSLATE_NOOP("WindowActions", "Ca&ncel bus work"), "bus", 1,
      tip=QT_TRANSLATE_NOOP("WindowActions",
                            "Cancel what the bus is doing for you (scan, apply…)")),
    A("compare", QT_TRANSLATE_NOOP("WindowActions", "Co&mpare configurations…"), "bus", 2),
    A("write", QT_TRANSLATE_NOOP("WindowActions", "&Write configuration to the arbitrator…"),
      "bus", 2, enabled_when=LIVE),
    A("autoconfigure", QT_TRANSLATE_NOOP("WindowPolicy", "&Autoconfigure on this prosthesis"),
      "bus", 3, context="WindowPolicy", checkable=True, enabled_when=POLICY,
      tip=QT_TRANSLATE_NOOP("WindowPolicy", "Whether the prosthesis may link unconnected "
                                            "hand, wrist or elbow channels on its own; the "
                                            "change is previewed, confirmed and recorded in "
                                            "the fitting history")),
    A("manual", QT_TRANSLATE_NOOP("Desktop", "User &manual"), "help", 0, context="Desktop",
      shortcut=K.HelpContents,
      tip=QT_TRANSLATE_NOOP("Desktop", "The manual, at the part about what you are looking "
                                       "at")),
    A("about", QT_TRANSLATE_NOOP("WindowActions", "&About PDCP Studio"), "help", 1),
    A("about_qt", QT_TRANSLATE_NOOP("Desktop", "About &Qt"), "help", 1, context="Desktop"),
)
del A


class WindowActions:
    """The table's actions, made for one window: ``actions[id]``, the menus by id, the
    toolbar. ``commands[id]()`` runs when an action is triggered; ``given`` holds the
    ready-made actions (docks' show/hide); the undo stack makes Undo and Redo (their text
    follows the stack), whose command then replaces the stack's own step."""

    def __init__(self, parent: QObject, commands: Mapping[str, Callable[[], object]],
                 undo_stack: QUndoStack, given: Mapping[str, QAction]) -> None:
        self._specs = {spec.id: spec for spec in ACTIONS}
        self._actions: dict[str, QAction] = {}
        self.menus: dict[str, QMenu] = {}
        for spec in ACTIONS:
            text = translate(spec.context, spec.text) + spec.suffix if spec.text else ""
            if spec.kind == GIVEN:
                action = given[spec.id]
                if text:
                    action.setText(text)
            elif spec.kind == UNDO:
                action = undo_stack.createUndoAction(parent, text)
            elif spec.kind == REDO:
                action = undo_stack.createRedoAction(parent, text)
            else:
                action = QAction(text, parent)
            if spec.shortcut is not None:
                action.setShortcut(QKeySequence(spec.shortcut))
            if spec.tip:
                action.setStatusTip(translate(spec.context, spec.tip))
            if spec.checkable:
                action.setCheckable(True)
            command = commands.get(spec.id)
            if command is not None:
                if spec.kind in (UNDO, REDO):
                    action.triggered.disconnect()  # the command decides how to step
                action.triggered.connect(lambda _checked=False, c=command: c())
            self._actions[spec.id] = action

    def __getitem__(self, action_id: str) -> QAction:
        return self._actions[action_id]

    def with_prefix(self, prefix: str) -> dict[str, QAction]:
        """The actions whose id starts with ``prefix``, by the rest of their id."""
        return {k[len(prefix):]: a for k, a in self._actions.items() if k.startswith(prefix)}

    def set_enabled(self, condition: str, enabled: bool) -> None:
        """Enable or disable every action enabled when ``condition`` holds."""
        for action_id, spec in self._specs.items():
            if spec.enabled_when == condition:
                self._actions[action_id].setEnabled(enabled)

    def build_menus(self, window: QMainWindow) -> dict[str, QMenu]:
        """The menu bar, in :data:`MENUS` order, each menu's rows in the table's order."""
        bar = window.menuBar()
        for menu_id, title, context in MENUS:
            menu = bar.addMenu(translate(context, title))
            group: int | None = None
            for spec in ACTIONS:
                if spec.menu != menu_id:
                    continue
                if group is not None and spec.group != group:
                    menu.addSeparator()
                group = spec.group
                menu.addAction(self._actions[spec.id])
            self.menus[menu_id] = menu
        return self.menus

    def build_toolbar(self, window: QMainWindow) -> QToolBar:
        """The main toolbar: the rows with a toolbar group, a separator between groups."""
        toolbar = window.addToolBar("Main")
        toolbar.setObjectName("MainToolBar")
        toolbar.setMovable(False)
        group: int | None = None
        for spec in ACTIONS:
            if spec.toolbar is None:
                continue
            if group is not None and spec.toolbar != group:
                toolbar.addSeparator()
            group = spec.toolbar
            toolbar.addAction(self._actions[spec.id])
        return toolbar

