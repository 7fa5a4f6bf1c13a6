"""Switching to another prosthesis with pending changes asks about the pending changes, never
"Save the changes to sim:…?" (issue 26 point 9: a live view is never saved to the prosthesis)."""

from __future__ import annotations

import pytest

from pdcp_studio.app.documents import commands

pytestmark = pytest.mark.gui


def test_switching_prosthesis_with_pending_changes_asks_about_them(make_window, qtbot,
                                                                   monkeypatch):
    window = make_window()
    window.connect_bus("sim:transradial")
    qtbot.waitUntil(lambda: window.live.is_live and window.doc.session is window.live.bridge,
                    timeout=20000)
    doc = window.doc
    doc.undo_stack.push(commands.RemoveLinkCommand(doc, doc.system.links[0]))
    qtbot.waitUntil(lambda: window.transactions.unwritten() == 1, timeout=5000)
    asked: list[int] = []
    answers = iter([False, True])

    def ask_unwritten(n: int) -> bool:
        asked.append(n)
        return next(answers)

    monkeypatch.setattr(window, "ask_unwritten", ask_unwritten)
    monkeypatch.setattr(window, "ask_save_changes",
                        lambda: pytest.fail("asked to save a live view to the prosthesis"))
    window.quiet = False
    try:
        assert window.maybe_save() is False and asked == [1]  # kept: stays connected
        assert window.live.url == "sim:transradial"
        assert window.maybe_save() is True and asked == [1, 1]  # left without them
    finally:
        window.quiet = True


def test_the_live_status_line_counts_with_plurals(make_window, qtbot):
    window = make_window()
    said: list[str] = []
    window.live.statusMessage.connect(said.append)
    window.connect_bus("sim:transradial")
    qtbot.waitUntil(lambda: any(s.startswith("Live: ") for s in said), timeout=20000)
    line = next(s for s in said if s.startswith("Live: "))
    assert "4 devices, 5 links" in line and "(s)" not in line
