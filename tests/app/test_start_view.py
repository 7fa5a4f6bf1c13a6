"""The start page (issue 11): a window opened on nothing shows the guided tasks, Connect,
Open, the simulated prosthesis and the recent files instead of an empty graph, and gives
way to the graph (with its docks) once a system is shown."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtWidgets import QApplication, QDockWidget

from pdcp_studio.app.window import start_view

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
APPENDIX_D = ROOT / "resources" / "systems" / "appendix-d.json"


def _docks(window):
    return [d for d in window.findChildren(QDockWidget) if d.parent() is window]


@pytest.fixture
def start(make_window):
    window = make_window()
    window.recent_files.add(APPENDIX_D)
    window.recent_files.add(TRANSRADIAL)  # newest first
    window.show_start()
    assert start_view.is_showing(window) and window.is_ready
    return window


def test_the_start_page_shows_instead_of_an_empty_graph(start, qtbot):
    page = start.start_view
    assert start.central.currentWidget() is page and not start.view.isVisible()
    assert not any(d.isVisible() for d in _docks(start))  # no empty device list or plan
    assert [b.text() for b in page.recent_buttons] == ["transradial.json", "appendix-d.json"]
    assert page.no_recent.isHidden()
    for button in [*page.task_buttons.values(), page.connect_button, page.open_button,
                   page.sim_button, *page.recent_buttons]:
        assert button.isVisible() and button.description()


@pytest.mark.parametrize("task", ["fitting", "replace", "restore"])
def test_each_task_button_opens_its_wizard(start, qtbot, task):
    from pdcp_studio.app.wizards import make_wizard

    start.start_view.task_buttons[task].click()
    wizard = start.task_wizard
    assert wizard.isVisible()
    assert type(wizard) is type(make_wizard(start, task))
    wizard.close()


def test_a_recent_file_opens_and_the_graph_comes_back_with_its_docks(start, qtbot):
    before = {d.objectName() for d in start.findChildren(QDockWidget)
              if d in start._start_put_away}
    assert {"DevicesDock", "InspectorDock", "PlanDock"} <= before
    start.start_view.recent_buttons[1].click()  # appendix-d.json
    assert start.doc.path.name == "appendix-d.json"
    assert not start_view.is_showing(start) and start.central.currentWidget() is start.view
    assert start.view.isVisible() and start.doc.system.devices
    assert {d.objectName() for d in _docks(start) if d.isVisible()} >= before


def test_connect_open_and_the_simulated_prosthesis(start, qtbot, monkeypatch):
    from pdcp_studio.app.dialogs import connect_dialog
    from pdcp_studio.app.window.controllers import files as window_files

    asked = []
    monkeypatch.setattr(connect_dialog.ConnectDialog, "get_url",
                        staticmethod(lambda parent: asked.append("connect") or None))
    monkeypatch.setattr(window_files.QFileDialog, "getOpenFileName",
                        staticmethod(lambda *a, **k: (asked.append("open") or str(TRANSRADIAL),
                                                      "")))
    start.start_view.connect_button.click()
    assert asked == ["connect"] and start_view.is_showing(start)  # cancelled: still here
    start.start_view.open_button.click()
    assert asked == ["connect", "open"] and not start_view.is_showing(start)
    assert start.doc.path.name == "transradial.json"
    start.show_start()  # back on the page (e.g. a failed connect)
    with qtbot.waitSignal(start.live.connected, timeout=20000):
        start.start_view.sim_button.click()
    assert start.live.url == "sim:transradial"
    qtbot.waitUntil(lambda: not start_view.is_showing(start), timeout=5000)
    start.live.disconnect_bus()


def test_a_window_opened_on_a_file_or_bus_never_shows_it(make_window):
    window = make_window(TRANSRADIAL)
    assert window.start_view is None and window.central.currentWidget() is window.view


def test_without_recent_files_the_page_says_where_they_will_appear(make_window):
    window = make_window()
    window.show_start()
    assert window.start_view.recent_buttons == [] and window.start_view.no_recent.isVisible()


def test_closing_on_the_start_page_saves_the_layout_with_the_docks(make_window):
    from PySide6.QtCore import QSettings

    from pdcp_studio.app.window.controllers.desktop import STATE_KEY, remember_layout

    window = make_window()
    remember_layout(window)
    window.show_start()
    window.close()
    assert not window._start_put_away
    assert all(not d.isHidden() for d in _docks(window)
               if d.objectName() in ("DevicesDock", "InspectorDock", "PlanDock"))
    assert QSettings().value(STATE_KEY) is not None


def test_the_start_page_in_german(make_window):
    from pdcp_studio.app import i18n

    from .test_translation import _kept_in_german

    english = _page_texts(_page(make_window))
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        german = _page_texts(_page(make_window))
    finally:
        i18n.uninstall(app)
    same = (german & english) - _kept_in_german() - {"PDCP Studio"}
    assert not same, sorted(same)
    assert "Neue Versorgung" in german and "Direkt arbeiten" in german
    assert any(t.startswith("Eine transradiale Prothese") for t in german)  # a description


def _page(make_window):
    window = make_window()
    window.show_start()
    return window.start_view


def _page_texts(page):
    from PySide6.QtWidgets import QCommandLinkButton

    from .test_translation import _plain, _texts

    return _texts(page) | {_plain(b.description()) for b in
                           page.findChildren(QCommandLinkButton) if b not in page.recent_buttons}


def test_bare_gui_opens_on_the_start_page(tmp_path):
    """``pdcp-studio gui`` with no file and no bus: the start page, drawn (a real process)."""
    import os
    import subprocess
    import sys

    from PySide6.QtGui import QImage

    out = tmp_path / "start.png"
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=str(tmp_path))
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "gui", "--screenshot",
                           str(out), "--size", "1200x780"], capture_output=True, text=True,
                          timeout=60, env=env, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    image = QImage(str(out))
    assert (image.width(), image.height()) == (1200, 780)
    dark = sum(1 for x in range(0, 1200, 4) for y in range(100, 400, 4)
               if QImage.pixelColor(image, x, y).value() < 80)
    assert dark > 200  # the page's text, not an empty graph


def test_folders_under_home_are_shown_from_home(tmp_path, monkeypatch):
    monkeypatch.setattr(Path, "home", staticmethod(lambda: tmp_path))
    assert start_view.folder_words(tmp_path / "Fittings") == str(Path("~") / "Fittings")
    assert start_view.folder_words(Path("/srv/clinic")) == "/srv/clinic"


def test_f1_on_the_start_page_opens_the_manual_at_starting(start):
    from pdcp_studio.app.dialogs import help_viewer

    assert help_viewer.section_for(start.start_view.task_buttons["fitting"]) == "start"
    for lang in ("en", "de"):
        text = help_viewer.manual_path(lang).read_text("utf-8")
        assert ("start page" if lang == "en" else "Startseite") in text
