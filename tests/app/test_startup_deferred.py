"""What a new window leaves until it is live (issue 11, start-up < 1.5 s), and that it then
comes: the accessible names of its controls (a screen reader's, never seen), the fitting
history (a hidden tab); and the toolbar's Undo/Redo, shortcuts and Help menu made without
looking at every child."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QTreeView

from pdcp_studio.app.window.controllers import desktop as window_desktop

pytestmark = pytest.mark.gui


def _unnamed_tree(window):
    return next(v for v in window.tree_dock.findChildren(QTreeView) if not v.accessibleName())


def test_controls_are_named_once_the_window_is_live_not_while_it_is_made(make_window, qtbot):
    window = make_window()
    assert not window.is_ready
    tree = _unnamed_tree(window)  # not named yet: the window is still being made
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    qtbot.waitUntil(lambda: bool(tree.accessibleName()), timeout=5000)
    assert window_desktop.name_controls(window) == []  # all of them, docks made since too
    window.live.disconnect_bus()


def test_the_fitting_history_is_read_once_the_window_is_live(make_window, qtbot):
    window = make_window()
    read_at_ready = []
    window.ready.connect(lambda: read_at_ready.append(window.history_panel.path))
    with qtbot.waitSignal(window.history_panel.loaded, timeout=20000):
        window.connect_bus("sim:transradial")
    assert read_at_ready == [""]  # not read while the window was being made
    assert window.history_panel.path.endswith("history.sqlite3")  # then read, verified
    assert window.history_panel.verify_report.ok
    with qtbot.waitSignal(window.history_panel.loaded, timeout=10000):
        window._load_patient_reference()  # as a later session starts: read at once
    window.live.disconnect_bus()


def test_a_live_window_names_a_new_control_at_once(make_window, qtbot):
    from PySide6.QtWidgets import QLineEdit

    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.show_start()
    field = QLineEdit(window)
    field.setPlaceholderText("Patient reference")
    field.show()
    qtbot.waitUntil(lambda: field.accessibleName() == "Patient reference", timeout=5000)


def test_shortcuts_and_the_toolbar_are_found_without_every_child(make_window):
    window = make_window()
    reachable = window_desktop._reachable_actions(window)
    assert window.act_write_pending in reachable and window.toolbar_undo in reachable
    assert window.act_manual in reachable  # the window's own (F1 anywhere)
    keys = [a.shortcut().toString() for a in reachable if not a.shortcut().isEmpty()]
    assert len(keys) == len(set(keys))
    assert window_desktop._toolbars(window) == window.toolbars
    assert window.toolbar_undo.toolTip() and not window.toolbar_undo.isEnabled()
    window.doc.undo_stack.push(_Step())
    assert window.toolbar_undo.isEnabled()  # follows Undo
    assert "Step" in window.toolbar_undo.toolTip()


def _Step():
    from PySide6.QtGui import QUndoCommand

    return QUndoCommand("Step")
