"""The window names each system from the profile tree that fits it (issue 11: the shipped
tree no longer mixes the thesis test hierarchy into the prosthetic one), and its Profile
tree window shows the two named trees; an edit there renames the cards."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.model.refs import ChannelRef

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "resources" / "systems"


def test_each_system_is_named_by_its_own_tree(make_window):
    window = make_window(SYSTEMS / "transradial.json")
    assert window.doc.tree.name == "Prosthesis"
    assert window.doc.profile_name(0x2220) == "Power Grip"
    assert window.open_path(SYSTEMS / "thesis-test2.json")
    assert window.doc.tree.name == "Thesis test rig"
    assert window.doc.profile_name(0x2120) == "Y"  # not "Terminal Device › …" names
    assert window.doc.profile_name(0x2200) == "Push Button"


def test_the_profile_tree_window_shows_both_trees_and_edits_rename(make_window, qtbot):
    window = make_window(SYSTEMS / "thesis-test2.json")
    window.show_profile_tree()
    dialog = window.profile_tree_dialog
    dialog.confirm_discard = lambda: True
    assert [dialog.tabs.tabText(i) for i in range(dialog.tabs.count())][:2] == [
        "Prosthesis", "Thesis test rig"]
    assert dialog.editor.tree.name == "Thesis test rig"  # the tree this system uses
    dialog.editor.rename(0x2120, "Joystick Y")
    assert window.doc.profile_name(0x2120) == "Joystick Y"
    ref = next(r for r, ch in window.doc.system.channels() if ch.profile == 0x2120)
    assert isinstance(ref, ChannelRef)
    dialog.close()
