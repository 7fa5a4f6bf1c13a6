"""A guided task names parts by its window's system only while it is open: once closed, the
words module's hook is let go (it leaked into what was named next, and kept the window's
document alive)."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.gui


def test_a_closed_wizard_lets_go_of_its_windows_system(make_window, qtbot):
    from pdcp_studio.app.wizards import open_wizard, words

    window = make_window()
    wizard = open_wizard(window, "fitting")
    assert words.shown_system is not None
    assert words.shown_system() is window.doc.system
    wizard.close()
    qtbot.waitUntil(lambda: words.shown_system is None, timeout=5000)
