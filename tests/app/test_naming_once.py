"""A panel that names every part of a large system looks the system's naming up once, not
once per part or channel: each lookup reads the whole system (``app/words/part_names.names``
checks that no part's or channel's name has changed), so a lookup per row made the device
tree and the trace's node list quadratic: on ``sim:full`` (93 devices, 161 outputs) 280
and 323 lookups, a third of the GUI thread's 0.17-0.19 s stop when the bus's first picture
arrives (1.4 s once under CI's CPU burners). The plan, its ghost links, the Checks and the
report name parts in batches the same way (:func:`part_names.one_naming`)."""

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


class _CountedCache(dict):
    """``part_names``'s cache, counting the lookups that read the whole system."""

    looked = 0

    def get(self, key, default=None):
        type(self).looked += 1
        return super().get(key, default)


@pytest.fixture
def whole_system_reads(monkeypatch):
    _CountedCache.looked = 0
    monkeypatch.setattr(part_names, "_CACHE", _CountedCache())
    return _CountedCache


def test_one_naming_answers_a_batch_from_one_lookup_and_sees_changes_after_it(
        whole_system_reads):
    system = load_path(FULL)
    first = next(iter(system.devices))
    with part_names.one_naming(system) as naming:
        assert whole_system_reads.looked == 1
        assert part_names.names(system) is naming
        for ref, _ch in system.channels():
            part_names.channel_name(system, ref)
        assert whole_system_reads.looked == 1  # every name from the one naming
        with part_names.one_naming(system):  # nested: the same, given back after
            pass
        assert part_names.names(system) is naming
        other = load_path(FULL)  # another system is looked up as ever
        part_names.part_name(other, first)
        assert whole_system_reads.looked == 2
    system.devices[first].name = "Renamed part"
    assert part_names.part_name(system, first) == "Renamed part"  # not held any more


def test_a_plan_preview_of_254_devices_names_its_rows_and_ghosts_in_a_few_lookups(
        make_window, tmp_path, whole_system_reads):
    """A 254-device autoconfigure preview looked the naming up 7,268 times (12 s of a frozen
    window on the 2-core machine; 0.9 s with one lookup per table and per graph)."""
    from pdcp_studio.storage.system_file import save_path
    from tests.app.test_graph import big_system

    system = big_system(254)
    for link in list(system.links):
        system.remove_link(link)
    path = tmp_path / "big.json"
    save_path(system, path)
    window = make_window(path)
    whole_system_reads.looked = 0
    plan = window.preview_plan("autoconfigure")
    assert len(plan.actions) >= 60
    assert whole_system_reads.looked <= 10
    ghosts = window.scene.ghosts.preview
    assert len(ghosts) == len(plan.actions)
    assert "Control 0, Power Grip → Hand 0, Power Grip" in "".join(g.toolTip() for g in ghosts)


def test_the_checks_name_every_findings_parts_in_one_lookup(whole_system_reads):
    """252 findings of a 254-device system: 643 lookups (5 s of the window's opening)."""
    from pdcp_studio.app.docks.inspector_checks import checked_findings
    from tests.app.test_graph import big_system

    system = big_system(254)
    for link in list(system.links):
        system.remove_link(link)
    findings, texts = checked_findings(system, autoconfigure=True)
    assert len(findings) >= 60 and len(texts) == len(findings)
    assert whole_system_reads.looked <= 2
    assert any("Hand 0" in text for text, _detail in texts)
