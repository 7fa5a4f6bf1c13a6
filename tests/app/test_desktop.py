"""Desktop conventions: recent files, drops, Help (manual with F1, About), shortcuts, a
toolbar that keeps its place, accessible names, and the window layout remembered."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from PySide6.QtCore import QMimeData, QPoint, QPointF, QSettings, Qt, QUrl
from PySide6.QtGui import QAction, QDragEnterEvent, QDropEvent
from PySide6.QtWidgets import QApplication, QToolBar

from pdcp_studio.app.dialogs import help_viewer
from pdcp_studio.app.window.controllers import desktop as window_desktop
from pdcp_studio.app.window.recent_files import RecentFiles

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
APPENDIX_D = ROOT / "resources" / "systems" / "appendix-d.json"
CAPTURE = ROOT / "tests" / "data" / "captures" / "pdcp-session.asc"


@pytest.fixture
def window(make_window):
    return make_window(TRANSRADIAL, size=(1200, 800))


def _drop(window, widget, path: Path) -> None:
    """What Qt hands the window's drop filter when a file is dropped on ``widget`` (Qt
    routes drops only during a real drag, so the filter gets the event directly)."""
    data = QMimeData()
    data.setUrls([QUrl.fromLocalFile(str(path))])
    for kind in (QDragEnterEvent, QDropEvent):
        event = kind(QPoint(20, 20) if kind is QDragEnterEvent else QPointF(20, 20),
                     Qt.DropAction.CopyAction, data, Qt.MouseButton.LeftButton,
                     Qt.KeyboardModifier.NoModifier)
        assert window._desktop_filter.eventFilter(widget, event) is True
        assert event.isAccepted()


def test_recent_files_keep_the_newest_first_and_only_existing(tmp_path):
    settings = QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat)
    recent = RecentFiles(settings)
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text("{}")
    b.write_text("{}")
    recent.add(a)
    recent.add(b)
    recent.add(a)
    assert recent.paths() == [a.resolve(), b.resolve()]
    b.unlink()
    assert recent.paths() == [a.resolve()]


def test_opened_files_are_offered_in_open_recent_and_reopen(window, qtbot, tmp_path):
    copy = tmp_path / "appendix.json"
    shutil.copy(APPENDIX_D, copy)
    assert window.open_path(copy)
    assert window.recent_files.paths()[0] == copy.resolve()
    window.recent_menu.rebuild()
    entry = next(a for a in window.recent_menu.actions() if a.text().endswith("appendix.json"))
    assert window.open_path(TRANSRADIAL)
    entry.trigger()
    assert window.doc.path == copy


def test_only_documents_and_captures_are_taken(window):
    data = QMimeData()
    data.setUrls([QUrl.fromLocalFile("/tmp/notes.txt")])
    event = QDragEnterEvent(QPoint(5, 5), Qt.DropAction.CopyAction, data,
                            Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier)
    assert window._desktop_filter.eventFilter(window, event) is False
    assert window.acceptDrops()


def test_a_system_dropped_on_the_graph_opens(window, qtbot):
    _drop(window, window.view.viewport(), APPENDIX_D)
    qtbot.waitUntil(lambda: window.doc.path == APPENDIX_D, timeout=5000)
    assert len(window.doc.system.devices) == 3


def test_a_capture_dropped_on_the_window_opens_in_the_monitor(window, qtbot):
    assert "monitor" not in window._leaf_docks
    _drop(window, window, CAPTURE)
    qtbot.waitUntil(lambda: "monitor" in window._leaf_docks, timeout=5000)
    dock = window._leaf_docks["monitor"]
    qtbot.waitUntil(lambda: dock.model.rowCount() > 0, timeout=10000)


def test_f1_opens_the_manual_at_the_section_for_the_view(window, qtbot):
    window.view.setFocus()
    assert help_viewer.section_for(window.view) == "graph"
    assert help_viewer.section_for(window.inspector) == "inspector"
    assert help_viewer.section_for(window.plan_panel) == "plans"
    viewer = help_viewer.open_manual(window, "plans")
    qtbot.waitExposed(viewer)
    assert viewer.current_heading().startswith("Plans")
    assert viewer.show_section("graph") and viewer.current_heading() == "The graph"
    for key in set(help_viewer.VIEW_SECTIONS.values()) | {"start"}:
        assert key in viewer.headings, f"the manual has no section {key!r}"
    viewer.close()
    assert window.act_manual.shortcut().toString() == "F1"


def test_about_names_the_versions():
    text = help_viewer.versions_text()
    for part in ("PDCP Studio", "Python", "Qt", "PySide6", "python-can"):
        assert part in text


def test_plans_and_connect_have_shortcuts_and_no_shortcut_is_taken_twice(window):
    keys = [a.shortcut().toString() for a in window.plan_actions.values()]
    assert keys[:4] == ["Ctrl+1", "Ctrl+2", "Ctrl+3", "Ctrl+4"]
    assert window.act_connect.shortcut().toString() == "Ctrl+K"
    every = [a.shortcut().toString() for a in window.findChildren(QAction)
             if not a.shortcut().isEmpty()]
    assert len(every) == len(set(every)), sorted(every)


def test_toolbar_buttons_keep_their_place_when_the_undo_text_grows(make_window, qtbot):
    window = make_window(APPENDIX_D, size=(1200, 800))
    toolbar = window.findChild(QToolBar, "MainToolBar")
    fit = toolbar.widgetForAction(window.act_fit)
    before = fit.mapTo(window, QPoint(0, 0))
    link = next(iter(window.doc.system.links))
    window.doc.select(link)
    window.scene.delete_selected()
    assert window.act_undo.text() != "&Undo"  # it now names the step
    QApplication.processEvents()
    assert fit.mapTo(window, QPoint(0, 0)) == before
    assert window.toolbar_undo.isEnabled()
    assert "Undo" in window.toolbar_undo.toolTip() and len(window.toolbar_undo.toolTip()) > 4
    window.toolbar_undo.trigger()
    assert link in window.doc.system.links


def test_every_control_of_the_window_has_an_accessible_name(window):
    assert window_desktop.name_controls(window) == []
    assert window.view.accessibleName()


def test_window_geometry_and_docks_come_back(make_window, tmp_path, qtbot):
    settings = QSettings(str(tmp_path / "layout.ini"), QSettings.Format.IniFormat)
    first = make_window(TRANSRADIAL, size=(1000, 700))
    window_desktop.remember_layout(first, settings)
    first.resize(1250, 700)
    first.plan_dock.hide()
    first.doc.mark_saved()
    first.close()
    second = make_window(TRANSRADIAL)
    window_desktop.remember_layout(second, settings)
    # The offscreen screen is 800 px wide: Qt fits a restored width to it, not the height.
    qtbot.waitUntil(lambda: second.size().height() == 700, timeout=3000)
    assert not second.plan_dock.isVisible()
