"""A panel that names every part of a large system looks the system's naming up once, not
once per part or channel: each lookup reads the whole system (``app/words/part_names.names``
checks that no part's or channel's name has changed), so a lookup per row made the device
tree and the trace's node list quadratic — on ``sim:full`` (93 devices, 161 outputs) the
GUI thread stopped 0.1-0.2 s when the bus's first picture arrived, over a second on a
loaded machine."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.words import part_names
from pdcp_studio.storage.system_file import load_path

pytestmark = pytest.mark.gui

FULL = Path(__file__).resolve().parents[2] / "resources" / "systems" / "full.json"


@pytest.fixture
def lookups(monkeypatch):
    """How many times the whole-system naming is looked up (every importer's name)."""
    count = [0]
    real = part_names.names

    def counted(*args, **kwargs):
        count[0] += 1
        return real(*args, **kwargs)

    from pdcp_studio.app.docks import tree_panel

    monkeypatch.setattr(part_names, "names", counted)
    monkeypatch.setattr(tree_panel, "names", counted)
    return count


def test_the_device_tree_names_a_large_system_with_one_lookup(qtbot, lookups):
    from pdcp_studio.app.docks.tree_panel import DeviceTree

    system = load_path(FULL)
    assert len(system.devices) == 93
    tree = DeviceTree(Document(system))
    qtbot.addWidget(tree)
    lookups[0] = 0
    tree.rebuild()
    assert lookups[0] == 1
    assert tree.topLevelItemCount() == 93
    first = next(iter(system.devices))
    shown = {tree.topLevelItem(i).text(0) for i in range(93)}
    assert part_names.part_name(system, first) in shown  # the same names as before


def test_the_traces_node_list_names_a_large_system_with_one_lookup(qapp, lookups):
    from PySide6.QtWidgets import QComboBox

    from pdcp_studio.app.trace.bar import NodeChoice

    system = load_path(FULL)
    for n, (_ref, ch) in enumerate(c for c in system.channels() if c[1].is_output):
        ch.node_id = n + 94
    choice = NodeChoice(QComboBox())
    lookups[0] = 0
    choice.learn(system)
    assert lookups[0] == 1
    ref = next(r for r, c in system.channels() if c.is_output)
    assert choice.names[system.channel(ref).node_id] == part_names.channel_name(system, ref)
