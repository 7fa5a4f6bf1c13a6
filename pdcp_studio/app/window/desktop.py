"""Desktop conventions for the main window: recent files, files dropped on the window,
Help (manual with F1 for the current view, About with versions, About Qt), shortcuts for
the plans and Connect, toolbar buttons that keep their place, accessible names on every
control, and the window's geometry and dock layout restored from the last session.

Kept apart from :mod:`main_window`: :func:`install_desktop` adds all of it to a built
window; :func:`remember_layout` is called only for a real session (tests and scripted runs
must not inherit a previous window's size or closed docks).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from PySide6.QtCore import QByteArray, QEvent, QModelIndex, QObject, QSettings, Qt, QTimer
from PySide6.QtGui import QAction, QDragEnterEvent, QDropEvent, QKeySequence
from PySide6.QtWidgets import (
    QAbstractButton,
    QAbstractItemView,
    QAbstractSlider,
    QAbstractSpinBox,
    QApplication,
    QComboBox,
    QDockWidget,
    QFormLayout,
    QGraphicsView,
    QHeaderView,
    QLabel,
    QLineEdit,
    QMainWindow,
    QPlainTextEdit,
    QScrollBar,
    QStyle,
    QTableView,
    QTextEdit,
    QToolBar,
    QTreeView,
    QWidget,
)
from shiboken6 import isValid

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.recent_files import RecentFiles, RecentMenu

#: What a dropped file is, by suffix.
DOCUMENT_SUFFIXES = (".json", ".pdcfg")
CAPTURE_SUFFIXES = (".asc", ".blf", ".csv", ".log", ".trc", ".mf4", ".db")

#: Plan shortcuts, in the order of the Plan menu.
PLAN_KEYS = ("Ctrl+1", "Ctrl+2", "Ctrl+3", "Ctrl+4", "Ctrl+5", "Ctrl+6", "Ctrl+7")
CONNECT_KEY = "Ctrl+K"
DISCONNECT_KEY = "Ctrl+Shift+K"

#: The controls that need an accessible name.
CONTROLS = (QAbstractButton, QLineEdit, QComboBox, QAbstractSpinBox, QAbstractSlider,
            QAbstractItemView, QTextEdit, QPlainTextEdit, QGraphicsView)

#: A new window's controls are named this long after it is live (painted, in the user's
#: hands: see name_when_live).
NAMES_AFTER_MS = 100

GEOMETRY_KEY = "window/geometry"
STATE_KEY = "window/state"
LAYOUT_VERSION = 1


def _plain(text: str) -> str:
    return text.replace("&&", "\0").replace("&", "").replace("\0", "&").rstrip("…:. ").strip()


def _form_label(widget: QWidget) -> str:
    """The text of the label a form layout shows for ``widget``, if any."""
    parent = widget.parentWidget()
    layout = parent.layout() if parent is not None else None
    if isinstance(layout, QFormLayout):
        label = layout.labelForField(widget)
        if isinstance(label, QLabel):
            return _plain(label.text())
    return ""


def _buddy_label(widget: QWidget) -> str:
    top = widget.window()
    for label in top.findChildren(QLabel):
        if label.buddy() is widget:
            return _plain(label.text())
    return ""


def _qt_part_name(widget: QWidget) -> str:
    """Names for the buttons Qt adds itself (menu bar and toolbar overflow)."""
    names = {"qt_menubar_ext_button": translate("Desktop", "More menus"),
             "qt_toolbar_ext_button": translate("Desktop", "More tools"),
             "qt_tableview_cornerbutton": translate("Desktop", "Select all")}
    return names.get(widget.objectName(), "")


def _headers(view: QAbstractItemView) -> str:
    """A table's or tree's column titles, as a name for it."""
    model = view.model()
    if model is None or not isinstance(view, QTableView | QTreeView):
        return ""  # a list's model has no columns to name it by
    try:
        count = model.columnCount(QModelIndex())
    except TypeError:  # a list model seen through a table: no column titles
        return ""
    titles = [str(model.headerData(c, Qt.Orientation.Horizontal) or "")
              for c in range(min(count, 4))]
    return ", ".join(t for t in titles if t and not t.isdigit())


def _part_of_another_control(widget: QWidget) -> bool:
    """Scroll bars, headers, a combo box's list and line edit: named by their owner."""
    if isinstance(widget, QScrollBar | QHeaderView):
        return True
    parent = widget.parentWidget()
    while parent is not None:
        if isinstance(parent, QComboBox | QAbstractSpinBox):
            return True
        parent = parent.parentWidget()
    return False


def accessible_name(widget: QWidget) -> str:
    """The best name for ``widget`` from what the user sees next to it."""
    candidates: list[str] = [_qt_part_name(widget)]
    if isinstance(widget, QAbstractButton):
        candidates.append(_plain(widget.text()))
    candidates += [_form_label(widget), _buddy_label(widget)]
    if isinstance(widget, QLineEdit):
        candidates.append(widget.placeholderText())
    candidates += [_plain(widget.toolTip()), _plain(widget.statusTip()),
                   _plain(widget.whatsThis())]
    if isinstance(widget, QComboBox) and widget.count():
        candidates.append(widget.itemText(0))
    if isinstance(widget, QAbstractItemView):
        candidates.append(_headers(widget))
    dock = widget.parentWidget()
    while dock is not None and not isinstance(dock, QDockWidget):
        dock = dock.parentWidget()
    if dock is not None:
        candidates.append(_plain(dock.windowTitle()))
    if isinstance(widget, QAbstractItemView | QTextEdit | QPlainTextEdit):
        candidates.append(_plain(widget.window().windowTitle()))
    return next((c for c in candidates if c), "")


def name_controls(root: QWidget) -> list[QWidget]:
    """Give every control under ``root`` an accessible name (and a description from its
    tooltip) where it has none; returns the controls still without one."""
    unnamed = []
    for widget in [root, *root.findChildren(QWidget)]:
        if not isinstance(widget, CONTROLS) or _part_of_another_control(widget):
            continue
        if not widget.accessibleName():
            name = accessible_name(widget)
            if name:
                widget.setAccessibleName(name)
            else:
                unnamed.append(widget)
        if not widget.accessibleDescription():
            tip = widget.toolTip() or widget.statusTip()
            if tip and _plain(tip) != widget.accessibleName():
                widget.setAccessibleDescription(tip)
    return unnamed


def dropped_files(event: QDragEnterEvent | QDropEvent) -> list[Path]:
    """Local files in a drag that PDCP Studio opens (documents and captures)."""
    data = event.mimeData()
    if not data.hasUrls():
        return []
    out = []
    for url in data.urls():
        if url.isLocalFile():
            path = Path(url.toLocalFile())
            if path.suffix.lower() in DOCUMENT_SUFFIXES + CAPTURE_SUFFIXES:
                out.append(path)
    return out


def open_dropped(window: Any, path: Path) -> bool:
    """Open a dropped file: a system or configuration as the document, a capture in the
    monitor."""
    if path.suffix.lower() in CAPTURE_SUFFIXES:
        dock = monitor_dock(window)
        dock.show()
        dock.raise_()
        dock.load_capture(path)
        window.show_message(translate("Desktop", "Opening capture {name}…")
                            .format(name=path.name))
        return True
    if not window.maybe_save():
        return False
    return bool(window.open_path(path))


def monitor_dock(window: Any) -> Any:
    """The window's monitor dock, made now if no bus has made it yet."""
    from pdcp_studio.app.trace.dock import MonitorDock

    dock = window._leaf_docks.get("monitor")
    if dock is None:
        dock = MonitorDock(window)
        window.addDockWidget(Qt.DockWidgetArea.BottomDockWidgetArea, dock)
        window.tabifyDockWidget(window.plan_dock, dock)
        window.view_menu.addAction(dock.toggleViewAction())
        window._leaf_docks["monitor"] = dock
        name_controls(dock)
    return dock


class _DesktopFilter(QObject):
    """Drops on the window and on the graph; names the controls of new dialogs and docks."""

    def __init__(self, window: Any) -> None:
        super().__init__(window)
        self.window = window

    def eventFilter(self, obj: QObject, event: QEvent) -> bool:
        kind = event.type()
        if kind in (QEvent.Type.DragEnter, QEvent.Type.DragMove):
            if dropped_files(event):  # type: ignore[arg-type]
                event.acceptProposedAction()  # type: ignore[attr-defined]
                return True
        elif kind == QEvent.Type.Drop:
            paths = dropped_files(event)  # type: ignore[arg-type]
            if paths:
                event.acceptProposedAction()  # type: ignore[attr-defined]
                # After the drop returns: opening may ask a question (a modal dialog).
                QTimer.singleShot(0, lambda: [open_dropped(self.window, p) for p in paths])
                return True
        elif kind == QEvent.Type.ChildPolished and obj is self.window and _is_live(obj):
            # (Before that, the window is named whole once it is live: name_when_live.)
            child = event.child()  # type: ignore[attr-defined]
            if isinstance(child, QWidget):
                QTimer.singleShot(0, lambda c=child: _name_later(c))
        return False


def _is_live(window: Any) -> bool:
    """Is ``window`` on screen with its first system (a window without that notion: yes)?"""
    return bool(getattr(window, "is_ready", True))


def name_when_live(window: Any, root: QWidget | None = None) -> None:
    """Name the controls under ``root`` (default: the whole window) now if the window is
    live, else all of the window's once it is.

    Accessible names are read by a screen reader, never seen: naming the ~190 widgets of a
    new window took 20-30 ms of start-up (the first wrapper of every Qt part) for nothing
    on its first frame."""
    if _is_live(window) or not hasattr(window, "ready"):
        name_controls(root if root is not None else window)
    elif not getattr(window, "_naming_when_live", False):
        window._naming_when_live = True
        window.ready.connect(lambda: QTimer.singleShot(NAMES_AFTER_MS, window,
                                                       lambda: _name_later(window)))


def _name_later(widget: QWidget) -> None:
    try:
        name_controls(widget)
    except RuntimeError:
        pass  # closed and deleted before the event loop came back


def _steady_toolbar(window: Any, toolbar: QToolBar) -> None:
    """Undo and Redo on the toolbar with fixed text (the full "Undo Add link …" as their
    tooltip), so the buttons after them never move."""
    style = window.style()
    for action, text, icon, key in (
            (window.act_undo, translate("Desktop", "Undo"),
             QStyle.StandardPixmap.SP_ArrowBack, "ToolbarUndo"),
            (window.act_redo, translate("Desktop", "Redo"),
             QStyle.StandardPixmap.SP_ArrowForward, "ToolbarRedo")):
        if action not in toolbar.actions():
            continue
        steady = QAction(style.standardIcon(icon), text, window)
        steady.setObjectName(key)
        steady.setEnabled(action.isEnabled())
        steady.setToolTip(_plain(action.text()))
        steady.triggered.connect(action.trigger)
        action.changed.connect(lambda a=action, s=steady: _follow(a, s))
        toolbar.insertAction(action, steady)
        toolbar.removeAction(action)
        setattr(window, f"toolbar_{key[7:].lower()}", steady)


def _follow(action: QAction, steady: QAction) -> None:
    """``steady`` enabled as ``action`` is, with its text as the tooltip (not while the
    window is being torn down: Qt says an action changed as it deletes it)."""
    if isValid(action) and isValid(steady):
        steady.setEnabled(action.isEnabled())
        steady.setToolTip(_plain(action.text()))


def _reachable_actions(window: Any) -> list[QAction]:
    """The actions a key can trigger: the window's own, its menus' (and their submenus'),
    its toolbars'. (Not ``findChildren(QAction)``: that first makes a Python wrapper for
    each of Qt's own actions, ~10 ms of start-up.)"""
    found: list[QAction] = list(window.actions())
    menus = [a.menu() for a in window.menuBar().actions() if a.menu() is not None]
    while menus:
        menu = menus.pop()
        for action in menu.actions():
            found.append(action)
            if action.menu() is not None:
                menus.append(action.menu())
    for toolbar in _toolbars(window):
        found += toolbar.actions()
    return list(dict.fromkeys(found))  # each once (an action may be in a menu and a toolbar)


def _toolbars(window: Any) -> list[QToolBar]:
    """The window's toolbars (as made: looking for them among its children first makes a
    Python wrapper for each of the ~190 child widgets, ~10 ms of start-up)."""
    made = getattr(window, "toolbars", None)
    return list(made) if made is not None else window.findChildren(QToolBar)


def _shortcuts(window: Any) -> None:
    taken = {a.shortcut().toString() for a in _reachable_actions(window)
             if not a.shortcut().isEmpty()}

    def give(action: QAction, key: str) -> None:
        if action.shortcut().isEmpty() and key not in taken:
            action.setShortcut(QKeySequence(key))
            taken.add(key)

    for action, key in zip(window.plan_actions.values(), PLAN_KEYS, strict=False):
        give(action, key)
    give(window.act_connect, CONNECT_KEY)
    give(window.act_disconnect, DISCONNECT_KEY)


def _help() -> Any:
    """The manual and About (imported when first asked for: not needed to start)."""
    from pdcp_studio.app.dialogs import help_viewer

    return help_viewer


def _help_menu(window: Any) -> None:
    menu = next((a.menu() for a in window.menuBar().actions()
                 if a.menu() is not None and window.act_about in a.menu().actions()), None)
    if menu is None:
        menu = window.menuBar().addMenu(translate("Desktop", "&Help"))
    window.help_menu = menu
    window.act_manual = QAction(translate("Desktop", "User &manual"), window)
    window.act_manual.setShortcut(QKeySequence(QKeySequence.StandardKey.HelpContents))
    window.act_manual.setShortcutContext(Qt.ShortcutContext.ApplicationShortcut)
    window.act_manual.setStatusTip(translate("Desktop", "The manual, at the part about what you "
                                                 "are looking at"))
    window.act_manual.triggered.connect(lambda _c=False: open_manual_here(window))
    window.act_about_qt = QAction(translate("Desktop", "About &Qt"), window)
    window.act_about_qt.triggered.connect(lambda _c=False: _help().show_about_qt(window))
    window.act_about.triggered.disconnect()
    window.act_about.triggered.connect(lambda _c=False: _help().show_about(window))
    menu.insertAction(window.act_about, window.act_manual)
    menu.insertSeparator(window.act_about)
    menu.addAction(window.act_about_qt)
    window.addAction(window.act_manual)


def open_manual_here(window: Any) -> Any:
    """The manual at the section for the dialog in front or the widget with the focus."""
    help_viewer = _help()
    front = QApplication.activeModalWidget() or QApplication.activeWindow()
    focus = QApplication.focusWidget()
    if front is not None and front is not window and front.objectName() != "HelpViewer":
        key = help_viewer.section_for(front)
    else:
        key = help_viewer.section_for(focus)
    return help_viewer.open_manual(window, key)


def _recent(window: Any) -> None:
    window.recent_files = RecentFiles()
    window.recent_menu = RecentMenu(window.recent_files,
                                    lambda p: open_dropped(window, Path(p)), window)
    file_menu = window.menuBar().actions()[0].menu()
    after = window.act_save if window.act_save in file_menu.actions() else None
    if after is not None:
        file_menu.insertMenu(after, window.recent_menu)
    else:
        file_menu.addMenu(window.recent_menu)

    def remember(path: object) -> None:
        if path is not None and Path(str(path)).is_file():
            window.recent_files.add(str(path))

    window.doc.pathChanged.connect(remember)


def install_desktop(window: QMainWindow) -> None:
    """Add the desktop conventions to a built :class:`MainWindow`."""
    w: Any = window
    _recent(w)
    _help_menu(w)
    _shortcuts(w)
    for toolbar in _toolbars(window):
        _steady_toolbar(w, toolbar)
    w.setAcceptDrops(True)
    w._desktop_filter = _DesktopFilter(w)
    w.installEventFilter(w._desktop_filter)
    w.view.viewport().installEventFilter(w._desktop_filter)
    w.view.setAccessibleName(translate("Desktop", "Bus graph"))
    w.view.setAccessibleDescription(translate(
        "Desktop", "The devices of the bus and the links between their channels"))
    name_when_live(w)
    w.live.bridgeReady.connect(lambda _b: QTimer.singleShot(0, lambda: _restore_docks(w)))


def _restore_docks(window: Any) -> None:
    """Docks made after start-up (monitor, plot, simulator) go where they were last time.
    (The docks are the window's own children: looking for them among all its descendants
    first makes a Python wrapper for each of its ~190 widgets, ~10 ms of start-up.)"""
    for dock in [c for c in window.children() if isinstance(c, QDockWidget)]:
        window.restoreDockWidget(dock)
        name_when_live(window, dock)


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
