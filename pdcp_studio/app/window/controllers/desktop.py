"""Desktop conventions for the main window: recent files, files dropped on the window,
the manual at the part the user looks at, toolbar buttons that keep their place,
accessible names on every control, and the window's geometry and dock layout restored
from the last session.

:class:`Desktop` adds them to a built window; :func:`remember_layout` is called only for a
real session (tests and scripted runs must not inherit a previous window's size or closed
docks). The Help menu's and the shortcuts' actions are in :mod:`.actions`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import (
    QByteArray,
    QChildEvent,
    QEvent,
    QObject,
    QSettings,
    QTimer,
    SignalInstance,
)
from PySide6.QtGui import QAction, QDragEnterEvent, QDragMoveEvent, QDropEvent
from PySide6.QtWidgets import (
    QApplication,
    QDockWidget,
    QGraphicsView,
    QMainWindow,
    QMenu,
    QStyle,
    QToolBar,
    QWidget,
)
from shiboken6 import isValid

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.trace.files.formats import is_capture_name
from pdcp_studio.app.widgets.accessible_names import name_controls, plain_label
from pdcp_studio.app.window.recent_files import RecentFiles, RecentMenu
from pdcp_studio.app.window.status import StatusLine

#: What a dropped file is, by suffix (captures: ``trace.formats``, the reader's list).
DOCUMENT_SUFFIXES = (".json", ".pdcfg")

#: A new window's controls are named this long after it is live (painted, in the user's
#: hands: see name_when_live).
NAMES_AFTER_MS = 100

GEOMETRY_KEY = "window/geometry"
STATE_KEY = "window/state"
LAYOUT_VERSION = 1


def dropped_files(event: QDragEnterEvent | QDragMoveEvent | QDropEvent) -> list[Path]:
    """Local files in a drag that PDCP Studio opens (documents and captures)."""
    data = event.mimeData()
    if not data.hasUrls():
        return []
    out = []
    for url in data.urls():
        if url.isLocalFile():
            path = Path(url.toLocalFile())
            if path.suffix.lower() in DOCUMENT_SUFFIXES or is_capture_name(path):
                out.append(path)
    return out


def _name_later(widget: QWidget) -> None:
    with contextlib.suppress(RuntimeError):  # closed and deleted before the event loop
        name_controls(widget)                # came back


class _DesktopFilter(QObject):
    """Drops on the window and on the graph (``open_paths``); names the controls of new
    dialogs and docks of ``window`` once it is live."""

    def __init__(self, window: QWidget, open_paths: Callable[[list[Path]], None],
                 is_live: Callable[[], bool]) -> None:
        super().__init__(window)
        self.window = window
        self._open_paths = open_paths
        self._is_live = is_live

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        kind = event.type()
        if kind in (QEvent.Type.DragEnter, QEvent.Type.DragMove) and isinstance(
                event, QDragMoveEvent):
            if dropped_files(event):
                event.acceptProposedAction()
                return True
        elif kind == QEvent.Type.Drop and isinstance(event, QDropEvent):
            paths = dropped_files(event)
            if paths:
                event.acceptProposedAction()
                # After the drop returns: opening may ask a question (a modal dialog).
                QTimer.singleShot(0, lambda: self._open_paths(paths))
                return True
        elif (kind == QEvent.Type.ChildPolished and isinstance(event, QChildEvent)
              and watched is self.window and self._is_live()):
            # (Before that, the window is named whole once it is live: name_when_live.)
            child = event.child()
            if isinstance(child, QWidget):
                QTimer.singleShot(0, lambda c=child: _name_later(c))
        return False


def _plain_follow(action: QAction, steady: QAction) -> None:
    """``steady`` enabled as ``action`` is, with its text as the tooltip (not while the
    window is being torn down: Qt says an action changed as it deletes it)."""
    if isValid(action) and isValid(steady):
        steady.setEnabled(action.isEnabled())
        steady.setToolTip(plain_label(action.text()))


def steady_toolbar(window: QWidget, toolbar: QToolBar, undo: QAction,
                   redo: QAction) -> dict[str, QAction]:
    """Undo and Redo on the toolbar with fixed text (the full "Undo Add link …" as their
    tooltip), so the buttons after them never move; the new buttons' actions by key
    (``undo``, ``redo``)."""
    style = window.style()
    made: dict[str, QAction] = {}
    for action, text, icon, key in (
            (undo, translate("Desktop", "Undo"),
             QStyle.StandardPixmap.SP_ArrowBack, "ToolbarUndo"),
            (redo, translate("Desktop", "Redo"),
             QStyle.StandardPixmap.SP_ArrowForward, "ToolbarRedo")):
        if action not in toolbar.actions():
            continue
        steady = QAction(style.standardIcon(icon), text, window)
        steady.setObjectName(key)
        steady.setEnabled(action.isEnabled())
        steady.setToolTip(plain_label(action.text()))
        steady.triggered.connect(action.trigger)
        action.changed.connect(lambda a=action, s=steady: _plain_follow(a, s))
        toolbar.insertAction(action, steady)
        toolbar.removeAction(action)
        made[key[7:].lower()] = steady
    return made


def _reachable_actions(window: QMainWindow) -> list[QAction]:
    """The actions a key can trigger: the window's own, its menus' (and their submenus'),
    its toolbars'. (Not ``findChildren(QAction)``: that first makes a Python wrapper for
    each of Qt's own actions, ~10 ms of start-up.)"""
    found: list[QAction] = list(window.actions())
    menus = [m for m in (a.menu() for a in window.menuBar().actions()) if isinstance(m, QMenu)]
    while menus:
        menu = menus.pop()
        for action in menu.actions():
            found.append(action)
            sub = action.menu()
            if isinstance(sub, QMenu):
                menus.append(sub)
    for toolbar in _toolbars(window):
        found += toolbar.actions()
    return list(dict.fromkeys(found))  # each once (an action may be in a menu and a toolbar)


def _toolbars(window: QMainWindow) -> list[QToolBar]:
    """The window's toolbars (as made: looking for them among its children first makes a
    Python wrapper for each of the ~190 child widgets, ~10 ms of start-up)."""
    made = getattr(window, "toolbars", None)
    return list(made) if made is not None else window.findChildren(QToolBar)


def _help() -> Any:
    """The manual and About (imported when first asked for: not needed to start)."""
    from pdcp_studio.app.dialogs import help_viewer

    return help_viewer


def open_manual_here(window: QWidget) -> Any:
    """The manual at the section for the dialog in front or the widget with the focus."""
    help_viewer = _help()
    front = QApplication.activeModalWidget() or QApplication.activeWindow()
    focus = QApplication.focusWidget()
    if front is not None and front is not window and front.objectName() != "HelpViewer":
        key = help_viewer.section_for(front)
    else:
        key = help_viewer.section_for(focus)
    return help_viewer.open_manual(window, key)


def show_about(window: QWidget) -> None:
    _help().show_about(window)


def show_about_qt(window: QWidget) -> None:
    _help().show_about_qt(window)


class Desktop(QObject):
    """The desktop conventions of one main ``window`` (see the module docstring).

    ``recent_files`` and ``recent_menu`` (in ``file_menu``, before ``before``); a file
    dropped or chosen there opens as the document (``maybe_save()``, ``open_path(path)``)
    or, a capture, in the monitor (``monitor_dock()``); ``is_ready()``/``ready`` say when
    the window is live, so its controls are named then (not while its first frame is
    made)."""

    def __init__(self, window: QMainWindow, status: StatusLine, *, file_menu: QMenu,
                 before: QAction, monitor_dock: Callable[[], Any],
                 maybe_save: Callable[[], bool], open_path: Callable[[Path], bool],
                 path_changed: SignalInstance, is_ready: Callable[[], bool],
                 ready: SignalInstance, bridge_ready: SignalInstance, graph: QWidget) -> None:
        super().__init__(window)
        self.host = window
        self.status = status
        self._monitor_dock = monitor_dock
        self._maybe_save = maybe_save
        self._open_path = open_path
        self._is_ready = is_ready
        self._ready = ready
        self._naming_when_live = False
        self._told_by: Any = None  # the trace whose outcome the status line says
        self.recent_files = RecentFiles()
        self.recent_menu = RecentMenu(self.recent_files,
                                      lambda p: self.open_dropped(Path(p)), window)
        if before in file_menu.actions():
            file_menu.insertMenu(before, self.recent_menu)
        else:
            file_menu.addMenu(self.recent_menu)
        path_changed.connect(self._remember)
        window.setAcceptDrops(True)
        self.filter = _DesktopFilter(window, self._open_all, is_ready)
        window.installEventFilter(self.filter)
        if isinstance(graph, QGraphicsView):
            graph.viewport().installEventFilter(self.filter)
        graph.setAccessibleName(translate("Desktop", "Bus graph"))
        graph.setAccessibleDescription(translate(
            "Desktop", "The devices of the bus and the links between their channels"))
        self.name_when_live()
        bridge_ready.connect(lambda _b: QTimer.singleShot(0, self, self._restore_docks))

    def open_dropped(self, path: Path) -> bool:
        """Open a dropped file: a system or configuration as the document, a capture in
        the monitor."""
        if is_capture_name(path):
            self.open_capture(path)
            return True
        if not self._maybe_save():
            return False
        return bool(self._open_path(path))

    def open_capture(self, path: Path) -> None:
        """Show a capture in the trace; the status line follows it (opened, or why not)."""
        dock = self._monitor_dock()
        if dock is not self._told_by:
            self._told_by = dock
            dock.loaded.connect(lambda p: self.status.say(translate(
                "Desktop", "Opened capture {name}").format(name=Path(p).name)))
            dock.error.connect(self.status.say)
        dock.show()
        dock.raise_()
        self.status.say(translate("Desktop", "Opening capture {name}…").format(name=path.name))
        dock.load_capture(path)

    def _open_all(self, paths: list[Path]) -> None:
        for path in paths:
            self.open_dropped(path)

    def _remember(self, path: object) -> None:
        if path is not None and Path(str(path)).is_file():
            self.recent_files.add(str(path))

    def name_when_live(self, root: QWidget | None = None) -> None:
        """Name the controls under ``root`` (default: the whole window) now if the window
        is live, else all of the window's once it is.

        Accessible names are read by a screen reader, never seen: naming the ~190 widgets
        of a new window took 20-30 ms of start-up (the first wrapper of every Qt part) for
        nothing on its first frame."""
        if self._is_ready():
            name_controls(root if root is not None else self.host)
        elif not self._naming_when_live:
            self._naming_when_live = True
            self._ready.connect(lambda: QTimer.singleShot(
                NAMES_AFTER_MS, self, lambda: _name_later(self.host)))

    def _restore_docks(self) -> None:
        """Docks made after start-up (monitor, plot, simulator) go where they were last
        time. (The docks are the window's own children: looking for them among all its
        descendants first makes a Python wrapper for each of its ~190 widgets, ~10 ms of
        start-up.)"""
        for dock in [c for c in self.host.children() if isinstance(c, QDockWidget)]:
            self.host.restoreDockWidget(dock)
            self.name_when_live(dock)


def remember_layout(window: QMainWindow, settings: QSettings | None = None) -> None:
    """Restore the last session's geometry and dock layout now; save them on close."""
    store = settings if settings is not None else QSettings()
    geometry = store.value(GEOMETRY_KEY)
    state = store.value(STATE_KEY)
    if isinstance(geometry, QByteArray | bytes):
        window.restoreGeometry(QByteArray(geometry))
    if isinstance(state, QByteArray | bytes):
        window.restoreState(QByteArray(state), LAYOUT_VERSION)

    class _Saver(QObject):
        def eventFilter(self, obj: QObject, event: QEvent) -> bool:
            if event.type() == QEvent.Type.Close:
                store.setValue(GEOMETRY_KEY, window.saveGeometry())
                store.setValue(STATE_KEY, window.saveState(LAYOUT_VERSION))
                store.sync()
            return False

    saver = _Saver(window)
    window.installEventFilter(saver)
    window._layout_saver = saver  # type: ignore[attr-defined]
