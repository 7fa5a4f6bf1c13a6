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


# -- a system mixing thesis test devices and prosthetic devices ------------------------------
def _mixed(tmp_path):
    """transradial's prosthetic parts and thesis test 4's boards (LEDs/joystick) on one bus."""
    from pdcp_studio.storage import system_file

    arm = system_file.load_path(SYSTEMS / "transradial.json")
    rig = system_file.load_path(SYSTEMS / "thesis-test4.json")
    assert not set(arm.devices) & set(rig.devices)
    for device in rig.devices.values():
        arm.add_device(device)
    for link in rig.links:
        arm.add_link(link)
    path = tmp_path / "mixed.json"
    system_file.save_path(arm, path)
    return path, set(rig.devices)


def test_a_mixed_system_has_every_channel_named_everywhere(make_window, tmp_path):
    from PySide6.QtWidgets import QLabel

    from pdcp_studio.app.report import report_html
    from pdcp_studio.engine.modes import plan_autoconfigure
    from pdcp_studio.model import profile as prof

    path, thesis = _mixed(tmp_path)
    window = make_window(path)
    doc = window.doc
    channels = list(doc.system.channels())
    assert {ref.device for ref, _ in channels} >= thesis
    for ref, ch in channels:
        # cards and the devices panel: a name, not the hex code
        assert doc.profile_name(ch.profile) != prof.fmt(ch.profile), (ref, hex(ch.profile))
        assert doc.tree.node(ch.profile) is not None
        # the inspector's title names it
        window.inspector.show_object(ref)
        texts = " ".join(lbl.text() for lbl in window.inspector.findChildren(QLabel))
        assert doc.tree.name_of(ch.profile) in texts
    # a code both trees know is named as the devices carrying it read it
    by_device = {ref.device: [] for ref, _ in channels}
    for ref, ch in channels:
        by_device[ref.device].append(doc.tree.name_of(ch.profile))
    for key, names in by_device.items():
        root = "Joystick" if key in thesis else ("Terminal Device", "Sensor", "Control Unit")
        assert all(n.startswith(root) for n in names), (key, names)
    assert doc.profile_name(0x2200) == "Push Button"  # the boards' button, not a Grip
    assert doc.profile_name(0x2220) == "Power Grip"
    # the plan's words, and the report of the system it links
    plan = plan_autoconfigure(doc.system)
    words = plan.to_text(doc.tree)
    assert "Joystick › Axis › X" in words and "Terminal Device › Grip › Power Grip" in words
    linked = doc.system.copy()
    for link in plan.final_links:
        linked.add_link(link, check=False)
    html = report_html(linked, doc.tree)
    assert "does not name" not in html
    assert "Joystick › Axis › X" in html and "Terminal Device › Grip › Power Grip" in html


def test_the_precedence_between_trees_is_the_devices_then_the_system():
    from pdcp_studio.model.profile_tree import ProfileNames
    from pdcp_studio.storage.profile_trees import load_profile_trees

    trees = load_profile_trees(user_dir=False)
    hand, emg, button = [0x2220, 0x2240], [0x4222], [0x2200, 0x2110]
    names = ProfileNames(trees, [hand, emg, button])
    assert names.primary.name == "Prosthesis"
    assert names.name_of(0x2200) == "Joystick › Push Button"  # carried by a joystick board
    assert names.name_of(0x2110) == "Joystick › Axis › X"  # only the thesis tree knows it
    assert names.name_of(0x1110) == "LED Output › Bar Graph › Level"
    # a code carried by nothing: the tree naming most of the system
    assert names.name_of(0x2000) == "Terminal Device"
    # the same code on a prosthetic part: that part's family
    grip = ProfileNames(trees, [[0x2200, 0x2220, 0x2600], button])
    assert grip.name_of(0x2200) == "Terminal Device › Grip"  # 4 of its profiles vs 3
    tie = ProfileNames(trees, [[0x2200, 0x2220, 0x2240]])
    assert tie.name_of(0x2200) == "Terminal Device › Grip"
    # unknown tails: the tree knowing the longest start
    assert names.name_of(0x2130) == "Joystick › Axis › 0x3"
    # each value once in walk(), named by its tree
    walked = dict(names.walk())
    assert walked[0x2200].name == "Push Button" and walked[0x2220].name == "Power Grip"
    assert list(walked) == sorted(walked)
