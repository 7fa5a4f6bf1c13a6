"""Plans previewed on the graph and in the list, then applied as one undo step or discarded."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
CONTROL = DeviceKey(2641, 513, 201)
FLEXOR = DeviceKey(2641, 257, 101)


@pytest.fixture
def window(make_window):
    return make_window(TRANSRADIAL)


def test_autoconfigure_preview_then_apply_and_undo(window):
    doc, scene, panel = window.doc, window.scene, window.plan_panel
    assert not doc.system.links
    plan = window.preview_plan("autoconfigure")
    assert plan is not None and len(plan.actions) == 5
    # Drawn on the graph as additions, listed with reasons and similarity breakdowns.
    assert [i.kind for i in scene.preview_items] == ["add"] * 5
    view = panel.actions_view
    assert view.rowCount() == 5
    assert [view.item(0, c).text() for c in (0, 1)] == ["1.", "Add"]
    # Plain words in the table; the engine's words in the selected row's detail.
    assert "drives a part of the prosthesis" in view.item(0, 3).text()
    assert "0x" not in view.item(0, 2).text() and "terminal" not in view.item(0, 3).text()
    view.selectRow(0)
    detail = panel.detail.toPlainText()
    assert "terminal channel" in detail and "profile 3 levels" in detail
    assert "add 5, remove 0" in panel.summary.text()
    # Nothing changed yet.
    assert not doc.system.links and doc.undo_stack.count() == 0
    assert panel.apply_button.isEnabled()
    panel.apply_button.click()
    assert len(doc.system.links) == 5 == len(scene.link_items)
    assert not scene.preview_items and doc.preview_plan is None
    assert doc.undo_stack.count() == 1  # the whole plan is one step
    assert window.isWindowModified()
    window.act_undo.trigger()
    assert not doc.system.links and not scene.link_items
    window.act_redo.trigger()
    assert set(doc.system.links) == set(plan.final_links)


def test_discard_changes_nothing(window):
    window.preview_plan("autoconfigure")
    assert window.scene.preview_items
    window.plan_panel.discard_button.click()
    assert not window.scene.preview_items
    assert not window.doc.system.links
    assert window.doc.undo_stack.count() == 0
    assert not window.plan_panel.apply_button.isEnabled()


def test_enforce_sole_access_draws_removals(window):
    doc = window.doc
    out = ChannelRef(*FLEXOR, 1)
    a, b = Link(out, ChannelRef(*CONTROL, 1)), Link(out, ChannelRef(*CONTROL, 2))
    doc.add_link(a)
    doc.add_link(b)  # the model allows it; the graph marks the conflict
    assert {a, b} <= window.scene.states.conflict_links
    assert window.scene.link_items[a].conflict
    plan = window.preview_plan("enforce")
    assert plan is not None and plan.removed
    kinds = {i.kind for i in window.scene.preview_items}
    assert kinds == {"remove"}
    assert all(i.link in (a, b) for i in window.scene.preview_items)
    window.plan_panel.apply()
    assert len([lk for lk in doc.system.links if lk.output == out]) == 1
    assert not window.scene.states.conflict_links


def test_replacements_and_startup_preview(window):
    for mode in ("replacements", "startup"):
        plan = window.preview_plan(mode)
        assert plan is not None, window.statusBar().currentMessage()
        assert plan.mode == mode
        assert window.plan_panel.summary.text()


def test_plan_on_opened_configuration_uses_it(window, tmp_path):
    # Save a linked system's links as a .pdcfg, then plan start-up against it.
    system = system_file.load_path(TRANSRADIAL)
    from pdcp_studio.engine import plan_autoconfigure

    plan_autoconfigure(system).apply(system)
    doc = Document(system)
    scene = BusScene(doc)
    assert len(scene.link_items) == 5
    from pdcp_studio.app.documents import files

    files.save_configuration(system, tmp_path / "c.pdcfg")
    assert window.open_path(tmp_path / "c.pdcfg")
    assert window.plan_panel.configuration() is window.doc.config
    plan = window.preview_plan("replacements")
    assert plan is not None and plan.configuration is not None
