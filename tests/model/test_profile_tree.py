"""The named profile tree shipped as resources, and its editing rules."""

import json

import pytest

from pdcp_studio.errors import ProfileError
from pdcp_studio.model.profile_tree import ProfileTree


@pytest.fixture
def fig46(resources):
    return ProfileTree.from_json(json.loads((resources / "profiles/thesis-fig4.6.json").read_text()))


def test_figure_4_6_names(fig46):
    assert fig46.name_of(0x4620) == "Sensor › Accelerometer › Wrist"
    assert fig46.short_name(0x2220) == "Power Grip"
    assert fig46.short_name(0x2240) == "Pinch Grip"
    assert fig46.short_name(0x2600) == "Wrist Rotation"


def test_unknown_tail_shown_in_hex(fig46):
    assert fig46.name_of(0x4A00) == "Sensor › 0xA"
    assert fig46.short_name(0x4A00) == "0x4A00"
    assert fig46.name_of(0) == "(null profile)"


def test_tests_tree_merges_with_figure_tree(fig46, resources):
    tests = ProfileTree.from_json(json.loads((resources / "profiles/thesis-tests.json").read_text()))
    merged = fig46.merged(tests)
    assert merged.short_name(0x1220) == tests.short_name(0x1220)
    assert merged.short_name(0x4620) == "Wrist"
    # the figure's Terminal Device (0x2) keeps its name; the tests' children join under it
    assert merged.short_name(0x2000) == "Terminal Device"
    assert merged.short_name(0x2110) == "X"


def test_edit_add_rename_renumber_remove(fig46):
    p = fig46.add(0x4000, "Vendor force sensor", 0xB)
    assert p == 0x4B00
    assert fig46.node(p).vendor_reserved
    fig46.rename(p, "Force")
    assert fig46.short_name(0x4B00) == "Force"
    new = fig46.renumber(p, 0xA)
    assert new == 0x4A00 and fig46.short_name(0x4A00) == "Force"
    fig46.remove(0x4A00)
    assert fig46.node(0x4A00) is None


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
