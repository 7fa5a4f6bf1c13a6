"""The guided tasks in German: every page's title, explanation, buttons and choices, the
Tasks menu, and the sentences a plan is explained in."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.wizards import TASKS, make_wizard

from .test_translation import _data_strings, _is_data, _kept_in_german, _plain, _texts

pytestmark = pytest.mark.gui


def _wizard_texts(window) -> set[str]:
    out: set[str] = set()
    for task in TASKS:
        wizard = make_wizard(window, task)
        out.add(_plain(wizard.windowTitle()))
        for page_id in wizard.pageIds():
            page = wizard.page(page_id)
            out |= {_plain(page.title())} | _texts(page)
            out.add(_plain(page.buttonText(wizard.WizardButton.CommitButton)))
        wizard.deleteLater()
    for action in window.task_actions.values():
        out |= {_plain(action.text()), _plain(action.statusTip())}
    out.add(_plain(window.tasks_menu.title()))
    return out


def _sentences() -> set[str]:
    from pdcp_studio.app.wizards import words
    from pdcp_studio.engine import Similarity

    return {words.similarity_words(Similarity(20, 2, True, False, False), 0x2220),
            words.similarity_words(Similarity(8, 1, False, False, False), 0x2220),
            words.action_words("replace a part")}


def test_every_wizard_page_is_translated(make_window, qtbot):
    window = make_window()
    english = _wizard_texts(window) | _sentences()
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        german = _wizard_texts(make_window()) | _sentences()  # menus are made translated
    finally:
        i18n.uninstall(app)
    data = _data_strings(window)
    same = {t for t in german & english if t and not _is_data(t, data)} - _kept_in_german()
    assert not same, f"untranslated in the German wizards: {sorted(same)}"
    assert "Neue Versorgung" in german and "Ein Teil ersetzen" in german
