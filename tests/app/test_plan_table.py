"""The plan table reads without scrolling (issue 11 item 6): plain words that wrap, never
cut and never wider than the table; the engineer's detail in the pane beside it; the plan
operations in one place (the Plan menu and the plan dock, not the toolbar too)."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtCore import QRect, Qt
from PySide6.QtWidgets import QToolBar

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"


def test_an_ordinary_plan_reads_without_scrolling(make_window, qtbot):
    window = make_window(TRANSRADIAL, size=(1600, 1000))
    window.resizeDocks([window.plan_dock], [300], Qt.Orientation.Vertical)
    window.preview_plan("autoconfigure")
    view = window.plan_panel.actions_view
    qtbot.waitUntil(lambda: view.viewport().width() > 300, timeout=3000)
    qtbot.wait(50)
    assert view.rowCount() == 5
    # Nothing sideways: the columns fit the table.
    total = sum(view.columnWidth(c) for c in range(view.columnCount()))
    assert total <= view.viewport().width() + 2
    assert not view.horizontalScrollBar().isVisible()
    # No cell is cut: each row is tall enough for its wrapped text.
    metrics = view.fontMetrics()
    for row in range(view.rowCount()):
        for col in range(view.columnCount()):
            text = view.item(row, col).text()
            needed = metrics.boundingRect(QRect(0, 0, view.columnWidth(col) - 8, 10000),
                                          int(Qt.TextFlag.TextWordWrap), text).height()
            assert needed <= view.rowHeight(row), (row, col, text)
    # Every row of an ordinary plan is on screen at once.
    assert view.verticalScrollBar().maximum() == 0
    # Plain words in the cells; the engine's words (codes, rule keys) in the detail pane.
    cells = " ".join(view.item(r, c).text() for r in range(5) for c in range(5))
    assert "0x" not in cells and "terminal channel" not in cells
    view.selectRow(1)
    assert "0x" in window.plan_panel.detail.toPlainText()


def test_the_plan_dock_grows_to_show_an_ordinary_plan(make_window, qtbot):
    """At the window's default layout (the plan dock shorter than five wrapped rows), a
    preview makes the dock tall enough for every row, and never taller than half the window."""
    window = make_window(TRANSRADIAL, size=(1600, 1000))
    window.show()
    qtbot.waitExposed(window)
    view = window.plan_panel.actions_view
    window.preview_plan("autoconfigure")
    qtbot.wait(100)
    assert view.rowCount() == 5
    qtbot.waitUntil(lambda: view.verticalScrollBar().maximum() == 0, timeout=3000)
    assert window.plan_dock.height() <= window.height() // 2


def test_plan_operations_are_not_duplicated_in_the_toolbar(make_window):
    window = make_window(TRANSRADIAL)
    toolbar = window.findChild(QToolBar, "MainToolBar")
    on_toolbar = {a.text() for a in toolbar.actions()}
    for action in window.plan_actions.values():
        assert action.text() not in on_toolbar
    # Still one click away: the plan dock's buttons and the Plan menu.
    assert set(window.plan_panel.mode_buttons) == set(window.plan_actions)
