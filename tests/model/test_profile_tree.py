"""The named profile tree shipped as resources, and its editing rules."""

import json

import pytest

from pdcp_studio.errors import ProfileError
from pdcp_studio.model.profile_tree import ProfileTree


@pytest.fixture
def fig46(resources):
    return ProfileTree.from_json(json.loads((resources / "profiles/prosthesis.json").read_text()))


def test_figure_4_6_names(fig46):
    assert fig46.name_of(0x4620) == "Sensor › Accelerometer › Wrist"
    assert fig46.short_name(0x2220) == "Power Grip"
    assert fig46.short_name(0x2240) == "Pinch Grip"
    assert fig46.short_name(0x2600) == "Wrist Rotation"


def test_unknown_tail_shown_in_hex(fig46):
    assert fig46.name_of(0x4E00) == "Sensor › 0xE"
    assert fig46.short_name(0x4E00) == "0x4E00"
    assert fig46.name_of(0) == "(null profile)"


def test_the_two_shipped_trees_stand_alone_and_each_names_its_systems(fig46, resources):
    """The prosthetic tree and the thesis test tree overlap (both use root 0x2): they are
    never merged; best_tree picks the one that names a system's channels."""
    from pdcp_studio.model.profile_tree import best_tree

    tests = ProfileTree.from_json(json.loads((resources / "profiles/thesis-tests.json").read_text()))
    assert fig46.name == "Prosthesis" and tests.name == "Thesis test rig"
    assert tests.short_name(0x2110) == "X" and fig46.short_name(0x2110) == "0x2110"
    assert fig46.short_name(0x2000) == "Terminal Device" and tests.short_name(0x2000) == "Joystick"
    # Figure 4.6's nodes keep their values in the prosthetic tree.
    assert fig46.name_of(0x4222) == "Sensor › EMG › Muscle › Flexor"
    for value in (0x2220, 0x2240, 0x2600, 0x4224, 0x4620, 0x4640, 0x4800, 0x4400):
        assert fig46.names_exactly(value)
    # Hand, wrist, elbow, EMG and the control unit are all there.
    names = {n.name for _v, n in fig46.walk()}
    assert {"Grip", "Wrist Rotation", "Elbow", "EMG", "Control Unit"} <= names
    trees = [fig46, tests]
    assert best_tree(trees, [0x2220, 0x4222, 0x2600]) is fig46  # transradial
    assert best_tree(trees, [0x2110, 0x2120, 0x1220, 0x2200]) is tests  # thesis tests
    assert best_tree(trees, []) is fig46
    # Neither marks its own nodes vendor-reserved: the test tree names who assigned its
    # odd components; a tree that does not still marks an odd node.
    assert not any(t.is_vendor_reserved(n) for t in trees for _v, n in t.walk())
    assert tests.vendor and tests.to_json()["vendor"] == tests.vendor
    assert ProfileTree.from_json(tests.to_json()).vendor == tests.vendor


def test_edit_add_rename_renumber_remove(fig46):
    p = fig46.add(0x4000, "Vendor force sensor", 0xB)
    assert p == 0x4B00
    assert fig46.node(p).vendor_reserved and fig46.is_vendor_reserved(fig46.node(p))
    fig46.rename(p, "Force")
    assert fig46.short_name(0x4B00) == "Force"
    new = fig46.renumber(p, 0xE)
    assert new == 0x4E00 and fig46.short_name(0x4E00) == "Force"
    fig46.remove(0x4E00)
    assert fig46.node(0x4E00) is None


def test_edit_refusals(fig46):
    with pytest.raises(ProfileError, match="already used"):
        fig46.add(0x4000, "Dup", 0x2)
    with pytest.raises(ProfileError, match="no room"):
        fig46.add(0x4222, "Too deep", 0x2)
    with pytest.raises(ProfileError, match="1…15"):
        fig46.add(0, "Bad", 0)


def test_json_round_trip(fig46):
    again = ProfileTree.from_json(fig46.to_json())
    assert again.walk() == fig46.walk() or [p for p, _ in again.walk()] == [p for p, _ in fig46.walk()]


def test_bad_tree_names_the_path():
    doc = {"format": "pdcp-profile-tree/1", "nodes": [{"name": "A", "component": "0x1",
                                                        "children": [{"name": "B", "component": 16}]}]}
    with pytest.raises(ProfileError, match=r"nodes\[0\]\.children\[0\]\.component"):
        ProfileTree.from_json(doc)
