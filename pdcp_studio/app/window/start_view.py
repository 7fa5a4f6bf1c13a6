"""The start page: what the window shows when it opens on nothing (no file, no bus).

An empty graph tells a prosthetist nothing; this page offers what they came to do — the
guided tasks (New fitting, Replace a part, Restore a configuration), Connect…, Open…, the
simulated prosthesis to practise on, and the recent files — each one click away. It sits
in the window's central area beside the graph (:class:`StartPage`) and gives way to the graph
as soon as a system is on screen.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path

from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtWidgets import (
    QCommandLinkButton,
    QDockWidget,
    QFrame,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QMainWindow,
    QScrollArea,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.actions import TASKS
from pdcp_studio.model.safe_text import shown

_CTX = "StartView"

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


def _link(title: str, description: str,
          slot: Callable[[], object]) -> QCommandLinkButton:
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


class StartOffers:
    """What the page's buttons do: the window's commands, handed in as callables."""

    def __init__(self, *, open_task: Callable[[str], object], ask_connect: Callable[[], object],
                 ask_open: Callable[[], object], try_simulated: Callable[[], object],
                 open_recent: Callable[[Path], object],
                 recent_paths: Callable[[], list[Path]]) -> None:
        self.open_task = open_task
        self.ask_connect = ask_connect
        self.ask_open = ask_open
        self.try_simulated = try_simulated
        self.open_recent = open_recent
        self.recent_paths = recent_paths


class StartView(QScrollArea):
    """The page itself; ``offers`` says what its buttons do."""

    def __init__(self, offers: StartOffers) -> None:
        super().__init__()
        self.offers = offers
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
        for task in TASKS:
            button = _link(_t(task.title), _t(task.description),
                           partial(offers.open_task, task.id))
            self.task_buttons[task.id] = button
            tasks.addWidget(button)
        tasks.addStretch(1)
        direct = QVBoxLayout()
        direct.addWidget(_heading(_t("Work directly")))
        self.connect_button = _link(
            _t("Connect to a prosthesis…"),
            _t("Through a CAN adapter or the arbitrator's cable, to see it live."),
            offers.ask_connect)
        self.open_button = _link(
            _t("Open a file…"),
            _t("A saved prosthesis or a stored configuration, to look at or prepare."),
            offers.ask_open)
        self.sim_button = _link(
            _t("Try the simulated prosthesis"),
            _t("A transradial prosthesis with a spare hand, to practise on without a "
               "patient."),
            offers.try_simulated)
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

    def refresh(self) -> None:
        """Show the recent files as they are now (the list changes while the app runs)."""
        for button in self.recent_buttons:
            self.recent_box.removeWidget(button)
            button.deleteLater()
        self.recent_buttons = []
        paths = self.offers.recent_paths()[:RECENT_SHOWN]
        for path in paths:
            button = _link(shown(path.name), shown(folder_words(path.parent)),
                           partial(self.offers.open_recent, path))
            button.setToolTip(shown(str(path)))
            button.setMaximumWidth(MAX_WIDTH // 2)  # a column like the tasks', not a bar
            self.recent_box.addWidget(button)
            self.recent_buttons.append(button)
        self.no_recent.setVisible(not paths)


class StartPage(QObject):
    """The start page's place in ``window``: the graph ``view`` in a stack (``central``)
    with room for the page (``start_view``, made when first shown). While the page shows,
    the docks (an empty device list, inspector and plan) are put away (``put_away``)."""

    def __init__(self, window: QMainWindow, view: QWidget, offers: StartOffers) -> None:
        super().__init__(window)
        self.host = window
        self.view = view
        self.offers = offers
        self.central = QStackedWidget()
        self.central.setObjectName("CentralStack")
        taken = window.takeCentralWidget()
        self.central.addWidget(taken if taken is not None else view)
        window.setCentralWidget(self.central)
        self.start_view: StartView | None = None
        self.put_away: list[QDockWidget] = []

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        """On closing the window from the start page, show the docks the page put away
        before the window's layout is saved (``remember_layout``'s filter runs after this
        one, as Qt runs the filter installed last first), so the next session has them."""
        if event.type() == QEvent.Type.Close:
            self._docks_back()
        return False

    def _docks_back(self) -> None:
        for dock in self.put_away:
            dock.show()
        self.put_away = []

    def show(self) -> StartView:
        """Show the start page in the central area (refreshed), instead of an empty graph;
        the docks are put away until a system shows."""
        page = self.start_view
        if page is None:
            page = self.start_view = StartView(self.offers)
            self.central.addWidget(page)
            self.host.installEventFilter(self)
        else:
            page.refresh()
        self.central.setCurrentWidget(page)
        if not self.put_away:
            docks = self.host.findChildren(
                QDockWidget, options=Qt.FindChildOption.FindDirectChildrenOnly)
            self.put_away = [d for d in docks if not d.isHidden()]
            for dock in self.put_away:
                dock.hide()
        return page

    def leave(self) -> None:
        """Back to the graph (a system is on screen), with the docks the page put away."""
        if self.start_view is not None:
            self.central.setCurrentWidget(self.view)
            self._docks_back()

    def is_showing(self) -> bool:
        return self.start_view is not None and self.central.currentWidget() is self.start_view


def is_showing(window: QMainWindow) -> bool:
    """Is ``window`` (a main window with a ``start_page``) showing its start page?"""
    page = getattr(window, "start_page", None)
    return isinstance(page, StartPage) and page.is_showing()


__all__ = ["StartOffers", "StartPage", "StartView", "is_showing"]
