"""Issue 26 (7, 9): the wizards ask for the patient reference and record it; the write
page's words name the button it shows; a wizard leaves the Simulator panel in view."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QPoint, QRect, QSize
from PySide6.QtWidgets import QWizard

from pdcp_studio.app.wizards import open_wizard
from pdcp_studio.app.wizards.placement import panel_rect, spot
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.gui

T = 20000


@pytest.fixture
def live(make_window, qtbot):
    window = make_window(size=(800, 780))
    window.move(0, 0)
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    assert window.live.is_live
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
    yield window
    wizard = getattr(window, "task_wizard", None)
    if wizard is not None:
        qtbot.waitUntil(lambda: not wizard.writing, timeout=T)
        wizard.close()
    window.live.disconnect_bus()


def _go(w, qtbot, page, after):
    qtbot.waitUntil(lambda: w.currentPage() is page, timeout=T)
    qtbot.waitUntil(page.isComplete, timeout=T)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is after, timeout=T)


def _commit_text(w) -> str:
    return w.button(QWizard.WizardButton.CommitButton).text().replace("&", "")


def test_the_write_page_names_the_button_it_shows_and_records_the_patient(live, qtbot):
    w = open_wizard(live, "fitting")
    _go(w, qtbot, w.connect_page, w.scan_page)
    _go(w, qtbot, w.scan_page, w.checks_page)
    _go(w, qtbot, w.checks_page, w.plan_page)
    _go(w, qtbot, w.plan_page, w.write_page)
    qtbot.waitUntil(w.write_page.isComplete, timeout=T)
    # start-up already linked the simulated prosthesis: nothing to write here
    page = w.write_page
    shown = [b for b in (QWizard.WizardButton.NextButton, QWizard.WizardButton.CommitButton)
             if w.button(b).isVisible()]
    assert shown == [QWizard.WizardButton.CommitButton]
    assert _commit_text(w) == "Continue"
    assert page.status.text() == "Press Continue to carry on; nothing is written."
    assert "Next" not in page.status.text()
    assert not page.patient.isVisible()  # nothing is written, nothing recorded
    _go(w, qtbot, w.write_page, w.store_page)
    qtbot.waitUntil(w.store_page.isComplete, timeout=T)
    # The store page writes: its button says so, and it asks for the patient reference.
    assert _commit_text(w) == "Store configuration"
    assert "Press the button below" in w.store_page.view.toPlainText()
    assert w.store_page.patient.isVisible() and w.store_page.patient.text() == ""
    w.store_page.patient.setText("  P-2026-042 ")
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.report_page, timeout=T)
    with History.open() as history:
        entry = history.entries()[-1]
    assert entry["action"] == "new fitting: store configuration"
    assert entry["patient"] == "P-2026-042"
    # remembered: the window has it, and the next wizard's write page starts with it
    assert live.patient_reference() == "P-2026-042"
    assert live.fitting_info().patient == "P-2026-042"
    w.close()
    again = open_wizard(live, "fitting")
    assert again.patient is None
    _go(again, qtbot, again.connect_page, again.scan_page)
    _go(again, qtbot, again.scan_page, again.checks_page)
    _go(again, qtbot, again.checks_page, again.plan_page)
    _go(again, qtbot, again.plan_page, again.write_page)
    assert again.write_page.patient.text() == "P-2026-042"


def test_every_wizard_that_writes_has_a_patient_field_on_its_write_pages(live):
    from pdcp_studio.app.wizards import TASKS
    from pdcp_studio.app.wizards.change_pages import WritePage

    for task in TASKS:
        w = open_wizard(live, task)
        pages = [w.page(i) for i in w.pageIds() if isinstance(w.page(i), WritePage)]
        assert pages, task
        assert all(p.patient.placeholderText().startswith("optional") for p in pages), task
        w.close()


# -- where the wizard goes -----------------------------------------------------------------
def test_spot_is_beside_the_panel_and_never_over_it():
    screen = QRect(0, 0, 1600, 1000)
    dock = QRect(1300, 60, 300, 700)
    place = spot(QSize(828, 632), dock, screen)
    assert place is not None and not place.intersects(dock) and screen.contains(place)
    assert place.right() < dock.left() and place.top() == dock.top()
    # a panel on the left: the wizard goes right of it
    left = QRect(0, 60, 300, 700)
    place = spot(QSize(828, 632), left, screen)
    assert place is not None and place.left() > left.right() and screen.contains(place)
    # no room beside it at full size: narrowed down to its minimum, still clear of it
    small = QRect(0, 0, 800, 800)
    place = spot(QSize(828, 632), QRect(520, 40, 280, 700), small, QSize(420, 400))
    assert place is not None and not place.intersects(QRect(520, 40, 280, 700))
    assert place.width() >= 420 and small.contains(place)
    # no room at all: None (the caller leaves the wizard where it is)
    assert spot(QSize(828, 632), QRect(100, 0, 600, 800), small, QSize(600, 600)) is None


@pytest.mark.parametrize("task", ["replace", "fitting"])
def test_the_wizard_does_not_cover_the_simulator_panel(live, qtbot, task):
    from PySide6.QtWidgets import QApplication

    dock = live._leaf_docks["sim"]
    dock.show()
    dock.raise_()
    qtbot.waitUntil(dock.isVisible, timeout=5000)
    w = open_wizard(live, task)
    qtbot.waitExposed(w)
    qtbot.wait(50)  # the placement runs once the wizard is shown
    panel = QRect(dock.mapToGlobal(QPoint(0, 0)), dock.size())
    assert panel_rect(dock) == panel
    screen = QApplication.primaryScreen().availableGeometry()
    has_room = (panel.left() - screen.left() >= w.minimumSizeHint().width() + 8
                or screen.right() - panel.right() >= w.minimumSizeHint().width() + 8)
    assert has_room  # the 800-pixel test screen has room left of the panel
    assert not w.frameGeometry().intersects(panel), (w.frameGeometry(), panel)
    # the page's Show the Simulator panel keeps it clear too (after the wizard was moved
    # over it)
    if task == "replace":
        w.move(panel.topLeft())
        assert w.frameGeometry().intersects(panel)
        w.missing_page.show_simulator()
        assert not w.frameGeometry().intersects(panel)


def test_in_german_the_write_page_names_the_button_it_shows(live, qtbot):
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app import i18n

    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        w = open_wizard(live, "fitting")
        _go(w, qtbot, w.connect_page, w.scan_page)
        _go(w, qtbot, w.scan_page, w.checks_page)
        _go(w, qtbot, w.checks_page, w.plan_page)
        _go(w, qtbot, w.plan_page, w.write_page)
        qtbot.waitUntil(w.write_page.isComplete, timeout=T)
        button = _commit_text(w)
        assert button == "Fortfahren"
        assert f"„{button}“" in w.write_page.status.text()
        assert w.write_page.patient_label.text() == "Patientenreferenz:"
        w.close()
    finally:
        i18n.uninstall(app)
