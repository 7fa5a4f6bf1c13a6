"""The start page: what the window shows when it opens on nothing (no file, no bus).

An empty graph tells a prosthetist nothing; this page offers what they came to do — the
guided tasks (New fitting, Replace a part, Restore a configuration), Connect…, Open…, the
simulated prosthesis to practise on, and the recent files — each one click away. It sits
in the window's central area beside the graph (:func:`install`) and gives way to the graph
as soon as a system is on screen.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from PySide6.QtCore import QT_TRANSLATE_NOOP, QEvent, QObject, Qt
from PySide6.QtWidgets import (
    QCommandLinkButton,
    QDockWidget,
    QFrame,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QScrollArea,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate

_CTX = "StartView"

#: The guided tasks as the page offers them: (task, title, what it does).
TASKS = (
    ("fitting", QT_TRANSLATE_NOOP("StartView", "New fitting"),
     QT_TRANSLATE_NOOP("StartView", "Connect to a prosthesis, check it, link its parts and "
                                    "store the result, step by step.")),
    ("replace", QT_TRANSLATE_NOOP("StartView", "Replace a part"),
     QT_TRANSLATE_NOOP("StartView", "Swap a part and link the new one in its place, with "
                                    "how alike it is said in words.")),
    ("restore", QT_TRANSLATE_NOOP("StartView", "Restore a configuration"),
     QT_TRANSLATE_NOOP("StartView", "Put a configuration file or an earlier fitting back on "
                                    "the prosthesis.")),
)
#: The page's widest column (px): lines a reader can follow on a wide screen.
MAX_WIDTH = 980
#: Recent files shown on the page (File → Open Recent has them all).
RECENT_SHOWN = 6


def _t(text: str) -> str:
    return translate(_CTX, text)


def _heading(text: str) -> QLabel:
    label = QLabel(text)
    label.setStyleSheet("font-size: 13pt; font-weight: bold;")
    label.setContentsMargins(0, 12, 0, 0)
    return label


def _link(title: str, description: str, slot: Any) -> QCommandLinkButton:
    button = QCommandLinkButton(title, description)
    button.clicked.connect(lambda _c=False: slot())
    return button


def folder_words(folder: Path) -> str:
    """A folder as its owner reads it: ``~/Fittings`` under the home folder, else whole."""
    try:
        inside = folder.resolve().relative_to(Path.home().resolve())
    except (ValueError, OSError, RuntimeError):
        return str(folder)
    return str(Path("~") / inside)


class StartView(QScrollArea):
    """The page itself; ``window`` is the main window whose actions it offers."""

    def __init__(self, window: Any) -> None:
        super().__init__()
        self.window_ = window
        self.setObjectName("StartView")
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)
        page = QWidget()
        page.setObjectName("StartPage")
        page.setStyleSheet("#StartPage { background: palette(base); }")
        outer = QHBoxLayout(page)
        holder = QWidget()
        holder.setMaximumWidth(MAX_WIDTH)  # lines a reader can follow on a wide screen
        column = QVBoxLayout(holder)
        outer.addStretch(1)
        outer.addWidget(holder, 12)
        outer.addStretch(1)
        title = QLabel(_t("PDCP Studio"))
        title.setStyleSheet("font-size: 20pt; font-weight: bold;")
        intro = QLabel(_t("See and set up the parts of a powered prosthesis. Choose what "
                          "you would like to do:"))
        intro.setWordWrap(True)
        column.addSpacing(18)
        column.addWidget(title)
        column.addWidget(intro)

        grid = QGridLayout()
        grid.setHorizontalSpacing(24)
        grid.setColumnStretch(0, 1)
        grid.setColumnStretch(1, 1)
        column.addLayout(grid)
        tasks = QVBoxLayout()
        tasks.addWidget(_heading(_t("Guided tasks")))
        self.task_buttons: dict[str, QCommandLinkButton] = {}
        for task, text, tip in TASKS:
            button = _link(_t(text), _t(tip), lambda t=task: window.open_task(t))
            self.task_buttons[task] = button
            tasks.addWidget(button)
        tasks.addStretch(1)
        direct = QVBoxLayout()
        direct.addWidget(_heading(_t("Work directly")))
        self.connect_button = _link(
            _t("Connect to a prosthesis…"),
            _t("Through a CAN adapter or the arbitrator's cable, to see it live."),
            window.ask_connect)
        self.open_button = _link(
            _t("Open a file…"),
            _t("A saved prosthesis or a stored configuration, to look at or prepare."),
            window.ask_open)
        self.sim_button = _link(
            _t("Try the simulated prosthesis"),
            _t("A transradial prosthesis with a spare hand, to practise on without a "
               "patient."),
            self._try_simulated)
        for button in (self.connect_button, self.open_button, self.sim_button):
            direct.addWidget(button)
        direct.addStretch(1)
        grid.addLayout(tasks, 0, 0)
        grid.addLayout(direct, 0, 1)

        column.addWidget(_heading(_t("Recent files")))
        self.recent_box = QVBoxLayout()
        column.addLayout(self.recent_box)
        self.recent_buttons: list[QCommandLinkButton] = []
        self.no_recent = QLabel(_t("No file opened yet. Files you open or save appear "
                                   "here."))
        self.no_recent.setStyleSheet("color: palette(mid);")
        column.addWidget(self.no_recent)
        column.addStretch(1)
        self.setWidget(page)
        self.refresh()

    def _try_simulated(self) -> None:
        from pdcp_studio.app.window.support import DEFAULT_BUS

        if self.window_.maybe_save():
            self.window_.connect_bus(DEFAULT_BUS)

    def refresh(self) -> None:
        """Show the recent files as they are now (the list changes while the app runs)."""
        for button in self.recent_buttons:
            self.recent_box.removeWidget(button)
            button.deleteLater()
        self.recent_buttons = []
        recent = getattr(self.window_, "recent_files", None)
        paths = recent.paths()[:RECENT_SHOWN] if recent is not None else []
        for path in paths:
            button = _link(path.name, folder_words(path.parent),
                           lambda p=path: self._open_recent(p))
            button.setToolTip(str(path))
            button.setMaximumWidth(MAX_WIDTH // 2)  # a column like the tasks', not a bar
            self.recent_box.addWidget(button)
            self.recent_buttons.append(button)
        self.no_recent.setVisible(not paths)

    def _open_recent(self, path: Path) -> None:
        if self.window_.maybe_save():
            self.window_.open_path(path)


class _DocksBack(QObject):
    """On closing the window from the start page, show the docks the page put away before
    the window's layout is saved (``remember_layout``'s filter runs after this one, as Qt
    runs the filter installed last first), so the next session has them."""

    def eventFilter(self, obj: QObject, event: QEvent) -> bool:
        if event.type() == QEvent.Type.Close:
            _docks_back(obj)
        return False


def install(window: Any) -> QStackedWidget:
    """Put the window's graph view in a stack with room for the start page (made when
    first shown); ``window.central`` is the stack."""
    stack = QStackedWidget()
    stack.setObjectName("CentralStack")
    view = window.takeCentralWidget()
    stack.addWidget(view)
    window.setCentralWidget(stack)
    window.central = stack
    window.start_view = None
    window._start_put_away = []
    return stack


def _docks_back(window: Any) -> None:
    for dock in window._start_put_away:
        dock.show()
    window._start_put_away = []


def show_start(window: Any) -> StartView:
    """Show the start page in the central area (refreshed), instead of an empty graph; the
    docks (an empty device list, inspector and plan) are put away until a system shows."""
    view = window.start_view
    if view is None:
        view = window.start_view = StartView(window)
        window.central.addWidget(view)
        window._start_docks_back = _DocksBack(window)
        window.installEventFilter(window._start_docks_back)
    else:
        view.refresh()
    window.central.setCurrentWidget(view)
    if not window._start_put_away:
        docks = window.findChildren(QDockWidget, options=Qt.FindChildOption.FindDirectChildrenOnly)
        window._start_put_away = [d for d in docks if not d.isHidden()]
        for dock in window._start_put_away:
            dock.hide()
    return view


def leave_start(window: Any) -> None:
    """Back to the graph (a system is on screen), with the docks the page put away."""
    if getattr(window, "start_view", None) is not None:
        window.central.setCurrentWidget(window.view)
        _docks_back(window)


def is_showing(window: Any) -> bool:
    view = getattr(window, "start_view", None)
    return view is not None and window.central.currentWidget() is view


__all__ = ["StartView", "install", "is_showing", "leave_start", "show_start"]
