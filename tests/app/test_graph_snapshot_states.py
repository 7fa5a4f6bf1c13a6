"""A live snapshot that changes a device shows the graph's states once, in slices
(issue 11: the GUI thread never blocked > 50 ms while scans run): before, every changed
snapshot drew every card and link twice in one go (~25 ms each on a 93-device bus, more
while the bus threads hold the GIL)."""

from __future__ import annotations

import pytest

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import scene as scene_module
from pdcp_studio.app.graph.scene import BusScene
from tests.app.test_graph import big_system

pytestmark = pytest.mark.gui


def _live_scene(n: int = 40) -> tuple[Document, BusScene]:
    doc = Document(tree=None)
    doc.set_system(big_system(n), None, session=object())
    scene = BusScene(doc)
    scene.finish_building()
    return doc, scene


def _count_passes(scene: BusScene) -> list[int]:
    passes: list[int] = []
    original = scene._state_steps

    def counting():
        passes.append(1)
        return original()

    scene._state_steps = counting
    return passes


def test_a_changed_device_shows_the_states_once(qtbot):
    doc, scene = _live_scene()
    passes = _count_passes(scene)
    snapshot = doc.bus_system.copy()
    key = next(iter(snapshot.devices))
    snapshot.devices[key].present = False
    assert doc.sync_live(snapshot)
    qtbot.waitUntil(lambda: not scene._states_timer.isActive()
                    and scene._state_slices is None, timeout=5000)
    assert passes == [1]
    assert scene.cards[key].device.present is False


def test_the_states_are_shown_in_slices_and_end_as_at_once(qtbot, monkeypatch):
    doc, scene = _live_scene()
    monkeypatch.setattr(scene_module, "BUILD_BUDGET_S", 0.0)  # one item per turn
    doc.busChanged.emit()
    assert scene._state_slices is not None  # the rest waits for later turns
    qtbot.waitUntil(lambda: scene._state_slices is None, timeout=5000)
    sliced = {k: (c.problems, c.pending_rows, c.role) for k, c in scene.cards.items()}
    links = {lk: (i.pending, i.conflict, i.missing) for lk, i in scene.link_items.items()}
    scene.refresh_states()  # all at once, synchronously (its public behaviour)
    assert scene._state_slices is None
    assert sliced == {k: (c.problems, c.pending_rows, c.role) for k, c in scene.cards.items()}
    assert links == {lk: (i.pending, i.conflict, i.missing)
                     for lk, i in scene.link_items.items()}


def test_a_synchronous_update_supersedes_a_pass_in_slices(qtbot, monkeypatch):
    doc, scene = _live_scene()
    monkeypatch.setattr(scene_module, "BUILD_BUDGET_S", 0.0)
    doc.busChanged.emit()
    assert scene._state_slices is not None
    link = sorted(doc.system.links)[0]
    doc.remove_link(link)  # linksChanged: shown at once
    assert scene._state_slices is None and not scene._slice_timer.isActive()
    assert link not in scene.link_items
