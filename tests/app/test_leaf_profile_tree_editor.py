"""Profile-tree editor: add, rename and number nodes, vendor-reserved marks, undo, atomic save."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.app.dialogs.profile_tree_editor import (
    COL_COMPONENT,
    COL_NAME,
    COL_NOTE,
    COL_PROFILE,
    VENDOR,
    ProfileTreeDialog,
    ProfileTreeEditor,
    load_tree,
)
from pdcp_studio.model.profile_tree import TREE_FORMAT

pytestmark = pytest.mark.gui


@pytest.fixture
def editor(qtbot, resources, tmp_path):
    path = tmp_path / "tree.json"
    path.write_text((resources / "profiles" / "prosthesis.json").read_text("utf-8"), "utf-8")
    widget = ProfileTreeEditor(load_tree(path), path)
    qtbot.addWidget(widget)
    return widget


def _row(editor: ProfileTreeEditor, profile: int) -> list[str]:
    item = editor._item(profile)
    assert item is not None, f"no row for 0x{profile:04X}"
    return [item.text(c) for c in (COL_NAME, COL_COMPONENT, COL_PROFILE, COL_NOTE)]


def test_add_rename_renumber_with_vendor_mark_and_undo(editor):
    assert _row(editor, 0x4620) == ["Wrist", "0x2", "0x4620", ""]
    new = editor.add_child(0x4000, "Temperature")  # under Sensor: first free even component
    assert new == 0x4E00
    assert _row(editor, 0x4E00) == ["Temperature", "0xE", "0x4E00", ""]
    assert editor.rename(0x4E00, "Skin temperature")
    assert editor.rename(0x4E00, "Skin temperature") is False  # a no-op pushes nothing
    moved = editor.renumber(0x4E00, 0x5)  # odd: reserved for vendors
    assert moved == 0x4500
    assert _row(editor, 0x4500) == ["Skin temperature", "0x5", "0x4500", VENDOR]
    assert editor.tree.node(0x4500).vendor_reserved
    assert editor.undo_stack.count() == 3 and editor.dirty

    editor.undo_stack.undo()  # renumber
    assert editor._item(0x4500) is None and _row(editor, 0x4E00)[0] == "Skin temperature"
    editor.undo_stack.undo()  # rename
    assert _row(editor, 0x4E00)[0] == "Temperature"
    editor.undo_stack.undo()  # add
    assert editor.tree.node(0x4E00) is None and not editor.dirty
    editor.undo_stack.redo()
    assert editor.tree.node(0x4E00).name == "Temperature"


def test_a_subtree_moves_with_a_renumbered_node(editor):
    assert editor.renumber(0x4200, 0x3) == 0x4300  # EMG → 0x3, its muscles follow
    assert _row(editor, 0x4320)[0] == "Muscle"
    assert editor.tree.node(0x4200) is None


def test_refused_edits_push_nothing_and_say_why(qtbot, editor):
    with qtbot.waitSignal(editor.error) as blocker:
        assert editor.add_child(0x4000, "Clash", component=0x2) is None
    assert "already used" in blocker.args[0]
    with qtbot.waitSignal(editor.error) as blocker:
        assert editor.renumber(0x4200, 0x4) is None  # Encoder has 0x4
    assert "already used" in blocker.args[0]
    with qtbot.waitSignal(editor.error) as blocker:
        assert editor.add_child(0x4222, "Too deep") is None
    assert "4 levels" in blocker.args[0]
    assert editor.undo_stack.count() == 0
    assert editor.status.text() == blocker.args[0]  # shown to the user as well


def test_in_place_edits_of_name_and_component(qtbot, editor):
    item = editor._item(0x4800)
    item.setText(COL_NAME, "Pressure pad")  # what the item delegate does on commit
    qtbot.waitUntil(lambda: editor.tree.node(0x4800).name == "Pressure pad", timeout=2000)
    editor._item(0x4800).setText(COL_COMPONENT, "9")
    qtbot.waitUntil(lambda: editor.tree.node(0x4900) is not None, timeout=2000)
    assert _row(editor, 0x4900)[3] == VENDOR
    editor._item(0x4900).setText(COL_COMPONENT, "zz")  # refused: the row shows 0x9 again
    qtbot.waitUntil(lambda: _row(editor, 0x4900)[1] == "0x9", timeout=2000)
    assert editor.undo_stack.count() == 2


def test_save_is_a_profile_tree_resource_and_reloads(qtbot, editor, tmp_path):
    editor.add_child(0x0000, "Vendor root", component=0xB)
    with qtbot.waitSignal(editor.saved) as blocker:
        assert editor.save() == editor.path
    assert blocker.args == [str(editor.path)]
    assert not editor.dirty
    doc = json.loads(editor.path.read_text("utf-8"))
    assert doc["format"] == TREE_FORMAT
    assert {"name": "Vendor root", "component": "0xB"} in doc["nodes"]
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    again = ProfileTreeEditor()
    qtbot.addWidget(again)
    assert again.load(editor.path)
    assert again.tree.to_json() == editor.tree.to_json()
    assert again.tree.node(0xB000).vendor_reserved


def test_save_failure_and_bad_file_are_reported(qtbot, editor, tmp_path):
    with qtbot.waitSignal(editor.error) as blocker:
        assert editor.save(tmp_path / "missing-dir" / "t.json") is None
    assert "missing-dir" in blocker.args[0]
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "pdcp-profile-tree/1", "nodes": [{"name": "x", "component": 16}]}')
    with qtbot.waitSignal(editor.error) as blocker:
        assert not editor.load(bad)
    assert "nodes[0].component" in blocker.args[0]


def test_dialog_asks_before_discarding_unsaved_edits(qtbot, resources, monkeypatch):
    dialog = ProfileTreeDialog(load_tree(resources / "profiles" / "prosthesis.json"))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.editor.add_child(0x2000, "Hook")
    asked: list[bool] = []
    monkeypatch.setattr(dialog, "confirm_discard", lambda: asked.append(True) or False)
    dialog.reject()
    assert asked == [True] and dialog.isVisible()
    monkeypatch.setattr(dialog, "confirm_discard", lambda: True)
    dialog.reject()
    assert not dialog.isVisible()


def test_new_trees_are_offered_in_the_user_profile_folder(tmp_path, monkeypatch):
    from pdcp_studio.app.dialogs.profile_tree_editor import default_save_path
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.storage import profile_trees as document

    monkeypatch.setattr(document, "user_profiles_dir", lambda: tmp_path / "profiles")
    path = default_save_path(ProfileTree("Acme hands / 2026"))
    assert path == tmp_path / "profiles" / "Acme-hands---2026.json"
    assert path.parent.is_dir()
    monkeypatch.setattr(document, "user_profiles_dir", lambda: None)
    assert default_save_path(ProfileTree("x")).name == "x.json"


def test_the_shipped_trees_are_two_named_trees_with_no_vendor_reserved_node(qtbot):
    """Issue 11: the prosthetic tree and the thesis test tree are shown apart, by name, and
    none of their shipped nodes is marked vendor-reserved."""
    from pdcp_studio.storage.profile_trees import load_profile_trees

    trees = load_profile_trees(user_dir=False)
    dialog = ProfileTreeDialog(trees=trees)
    dialog.confirm_discard = lambda: True  # closing at teardown must not ask (modal)
    qtbot.addWidget(dialog)
    dialog.show()
    names = [dialog.tabs.tabText(i) for i in range(dialog.tabs.count())]
    assert names == ["Prosthesis", "Thesis test rig"]
    for i, editor in enumerate(dialog.editors):
        dialog.tabs.setCurrentIndex(i)
        assert dialog.editor is editor
        rows = [_row(editor, value) for value, _node in editor.tree.walk()]
        assert rows and all(r[3] == "" for r in rows), editor.tree.name
    prosthesis, tests = dialog.editors
    assert _row(prosthesis, 0x2220)[0] == "Power Grip"
    assert _row(tests, 0x2120)[0] == "Y"
    assert prosthesis._item(0x2100) is None  # no joystick axis in the prosthetic tree
    # An edit in one tab is that tree's only, and reported for the window.
    with qtbot.waitSignal(dialog.treesChanged):
        dialog.editors[1].add_child(0x1000, "Ring")
    assert trees[1].node(0x1400).name == "Ring" and trees[0].node(0x1400) is None


def test_a_vendors_odd_node_added_to_the_prosthetic_tree_is_still_marked(qtbot):
    from pdcp_studio.storage.profile_trees import load_profile_trees

    prosthesis = load_profile_trees(user_dir=False)[0]
    editor = ProfileTreeEditor(prosthesis)
    qtbot.addWidget(editor)
    new = editor.add_child(0x4000, "Vendor sensor", component=0xB)
    assert _row(editor, new)[3] == VENDOR
