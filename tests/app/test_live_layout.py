"""Moving a card on a live bus asks nothing (issue 11 item 6): the positions are remembered
per prosthesis and come back the next time it is connected; other edits still count."""

from __future__ import annotations

import pytest

from pdcp_studio.app import commands

pytestmark = pytest.mark.gui


def _live(make_window, qtbot, url="sim:thesis-test4"):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus(url)
    return window


def test_card_moves_on_a_live_view_are_remembered_not_asked_about(make_window, qtbot,
                                                                   monkeypatch):
    window = _live(make_window, qtbot)
    doc = window.doc
    assert doc.is_live_view
    key = next(iter(doc.system.devices))
    old = doc.positions[key]
    new = (old[0] + 137.0, old[1] - 42.0)
    doc.undo_stack.push(commands.MoveDeviceCommand(doc, key, old, new))
    assert doc.positions[key] == new
    assert not doc.is_dirty and not window.isWindowModified()
    monkeypatch.setattr(window, "ask_save_changes",
                        lambda: pytest.fail("asked to save a live view's card positions"))
    assert window.maybe_save()
    window.live.disconnect_bus()

    again = _live(make_window, qtbot)
    assert again.doc.positions[key] == new  # as this prosthesis was last laid out
    other = _live(make_window, qtbot, "sim:thesis-test2")
    assert other.doc.positions.get(key) != new  # another prosthesis keeps its own
    again.live.disconnect_bus()
    other.live.disconnect_bus()


def test_other_edits_on_a_live_view_still_count(make_window, qtbot):
    window = _live(make_window, qtbot)
    doc = window.doc
    key = next(iter(doc.system.devices))
    old = doc.positions[key]
    doc.undo_stack.push(commands.MoveDeviceCommand(doc, key, old, (old[0] + 5, old[1])))
    assert not doc.is_dirty
    link = doc.system.links[0]
    doc.undo_stack.push(commands.RemoveLinkCommand(doc, link))
    assert doc.is_dirty and window.isWindowModified()
    doc.undo_stack.undo()
    assert not doc.is_dirty
    window.live.disconnect_bus()


def test_a_project_file_still_asks_for_moved_cards(make_window, tmp_path):
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    window = make_window(root / "resources" / "systems" / "transradial.json")
    doc = window.doc
    key = next(iter(doc.system.devices))
    old = doc.positions[key]
    doc.undo_stack.push(commands.MoveDeviceCommand(doc, key, old, (old[0] + 5, old[1])))
    assert doc.is_dirty
