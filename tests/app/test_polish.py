"""Small polish (issue 11): counts in English read "1 link" / "2 links" (Qt's plural forms),
the plan's detail pane explains itself whole, the Simulator panel's replacement box shows
the whole name, and the Restore task names a bad file once."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.wizards import make_wizard
from pdcp_studio.app.words.plural import count, english

from .trace_imports import wait_for_trace_imports

pytestmark = pytest.mark.gui


def test_counts_read_right_in_english_and_german(qtbot):
    assert english("%n link(s)", 1) == "1 link" and english("%n link(s)", 2) == "2 links"
    assert english("%n part(s) found", 0) == "0 parts found"
    assert count("Wizards", "%n link(s) led to it.", 1) == "1 link led to it."
    assert count("Wizards", "%n link(s) led to it.", 3) == "3 links led to it."
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        assert count("Wizards", "%n link(s) led to it.", 1) == "1 Verbindung führte zu ihm."
        assert count("Wizards", "%n link(s) led to it.", 3) == "3 Verbindungen führten zu ihm."
    finally:
        i18n.uninstall(app)


def test_the_plan_detail_pane_says_what_it_is_for_in_full(make_window, qtbot):
    window = make_window()
    detail = window.plan_panel.detail
    text = detail.toPlainText()
    assert text.startswith("Select a row for the engineer's detail")
    assert text.endswith("similarity score")  # wrapped to the pane, not cut off


def test_the_restore_task_names_a_bad_file_once(make_window, qtbot, tmp_path):
    window = make_window()
    bad = tmp_path / "broken.pdcfg"
    bad.write_bytes(b"\x02\x01")
    wizard = make_wizard(window, "restore")
    qtbot.addWidget(wizard)
    assert not wizard.source_page.load_file(bad)
    status = wizard.source_page.status.text()
    assert status.startswith(f"Cannot read {bad}: ") and status.count(str(bad)) == 1, status


def test_the_replacement_box_shows_the_whole_name(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["sim"].widget()
    window._leaf_docks["sim"].raise_()
    qtbot.waitUntil(lambda: panel.replace_combo.count() == 1, timeout=20000)
    combo = panel.replace_combo
    qtbot.waitUntil(combo.isVisible, timeout=5000)
    text = combo.currentText()
    assert text == "Multi-grip hand with wrist rotator (serial 302)"
    assert combo.width() >= combo.fontMetrics().horizontalAdvance(text) + 20
    assert text in combo.toolTip()
    wait_for_trace_imports(qtbot)
    window.live.disconnect_bus()


def test_the_app_warns_of_a_skipped_catalogue_file(make_window, qtbot, tmp_path,
                                                   monkeypatch):
    from pdcp_studio import paths
    from pdcp_studio.model import catalog

    folder = tmp_path / "catalogs"
    folder.mkdir()
    (folder / "vendor.json").write_text("{", encoding="utf-8")
    monkeypatch.setattr(paths, "user_catalogs_dir", lambda: folder)
    catalog.reload_default_catalog()
    try:
        window = make_window()
        window.inspector.show_object(None)
        label = window.inspector.editors["catalog_problems"]
        assert str(folder / "vendor.json") in label.text() and "not JSON" in label.text()
        assert "vendor.json" in window.statusBar().currentMessage()
    finally:
        catalog.reload_default_catalog()
