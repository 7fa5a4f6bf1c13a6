"""Moving a card on a live bus asks nothing (issue 11 item 6): the positions are remembered
per prosthesis and come back the next time it is connected; other edits still count."""

from __future__ import annotations

import pytest

from pdcp_studio.app.documents import commands

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


# -- per prosthesis, not per bus URL ---------------------------------------------------------
class Adapters:
    """Prostheses plugged into CAN adapters: a system's devices (simulated, without an
    arbitrator) on a python-can virtual channel, which the app connects to as ``can:``."""

    def __init__(self) -> None:
        self.hosts: dict[str, object] = {}

    def plug(self, system, channel: str = "") -> str:
        from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
        from pdcp_studio.bus.sim.device import SimulatedDevice
        from pdcp_studio.bus.sim.device_host import DeviceHost

        channel = channel or unique_virtual_channel("pdcp-layout")
        self.unplug(channel)
        self.hosts[channel] = DeviceHost(open_can_bus("virtual", channel),
                                         [SimulatedDevice(d) for d in system.devices.values()],
                                         name=channel)
        return f"can:virtual:{channel}"

    def unplug(self, channel: str) -> None:
        host = self.hosts.pop(channel, None)
        if host is not None:
            host.close()


@pytest.fixture
def adapters():
    made = Adapters()
    yield made
    for channel in list(made.hosts):
        made.unplug(channel)


def _connected(make_window, qtbot, url, system):
    window = _live(make_window, qtbot, url)
    assert window.doc.is_live_view and window.doc.live_url == url
    assert set(window.doc.system.devices) == set(system.devices)
    return window


def _move_all(window, dx, dy):
    """Move every card (one undo step each), let the layout be remembered, disconnect."""
    doc = window.doc
    for key in list(doc.system.devices):
        old = doc.positions[key]
        doc.undo_stack.push(commands.MoveDeviceCommand(doc, key, old, (old[0] + dx, old[1] + dy)))
    doc.remember_layout()
    window.live.disconnect_bus()
    return dict(doc.positions)


def _rig(name):
    from pdcp_studio.bus.sim.rigs import load_prosthesis

    return load_prosthesis(name)


def _replaced(system, old, new):
    """``system`` with part ``old`` unplugged and part ``new`` (same channels) plugged."""
    import copy
    from dataclasses import replace

    out = system.copy()
    out.clear_links()
    part = copy.deepcopy(out.remove_device(old))
    out.add_device(replace(part, vid=new.vid, pid=new.pid, serial=new.serial, node_id=None))
    return out


def test_the_same_prosthesis_on_another_bus_url_keeps_its_positions(make_window, qtbot,
                                                                     adapters):
    system = _rig("thesis-test4")
    first, second = adapters.plug(system), adapters.plug(system)
    assert first != second
    moved = _move_all(_connected(make_window, qtbot, first, system), 311.0, -57.0)

    again = _connected(make_window, qtbot, second, system)
    assert again.doc.positions == moved
    again.live.disconnect_bus()


def test_two_prostheses_on_one_bus_url_keep_their_positions_apart(make_window, qtbot,
                                                                  adapters):
    # thesis tests 2 and 4 are the same three boards (same serials) with other channels
    test4, test2 = _rig("thesis-test4"), _rig("thesis-test2")
    url = adapters.plug(test4, "pdcp-layout-clinic")
    moved4 = _move_all(_connected(make_window, qtbot, url, test4), 500.0, 80.0)

    assert adapters.plug(test2, "pdcp-layout-clinic") == url
    other = _connected(make_window, qtbot, url, test2)
    assert all(other.doc.positions[k] != moved4[k] for k in moved4)
    moved2 = _move_all(other, -200.0, 30.0)

    adapters.plug(test4, "pdcp-layout-clinic")
    back = _connected(make_window, qtbot, url, test4)
    assert back.doc.positions == moved4 != moved2
    back.live.disconnect_bus()


def test_a_replaced_part_takes_its_predecessors_place_the_others_stay(make_window, qtbot,
                                                                     adapters):
    from pdcp_studio.model.refs import DeviceKey

    arm = _rig("transradial")
    url = adapters.plug(arm, "pdcp-layout-arm")
    moved = _move_all(_connected(make_window, qtbot, url, arm), 240.0, 120.0)
    old_hand = DeviceKey(2641, 769, 301)
    others = {k: xy for k, xy in moved.items() if k != old_hand}

    # the hand replaced by another unit of the same product: it takes the old hand's place
    new_hand = DeviceKey(2641, 769, 303)
    swapped = _replaced(arm, old_hand, new_hand)
    adapters.plug(swapped, "pdcp-layout-arm")
    window = _connected(make_window, qtbot, url, swapped)
    assert window.doc.positions[new_hand] == moved[old_hand]
    assert {k: window.doc.positions[k] for k in others} == others
    window.live.disconnect_bus()

    # a part of another product: put beside the others, which stay where they were
    newcomer = DeviceKey(2641, 770, 1)
    swapped = _replaced(arm, old_hand, newcomer)
    adapters.plug(swapped, "pdcp-layout-arm")
    window = _connected(make_window, qtbot, url, swapped)
    assert {k: window.doc.positions[k] for k in others} == others
    assert window.doc.positions[newcomer] not in others.values()
    window.live.disconnect_bus()


def test_a_layout_kept_per_bus_url_by_an_older_version_is_still_used(make_window, qtbot):
    import json

    from PySide6.QtCore import QSettings

    from pdcp_studio.app.live import layout as live_layout
    from pdcp_studio.model.refs import DeviceKey

    url = "sim:thesis-test4"
    QSettings().setValue(live_layout._legacy_key(url), json.dumps(
        {"url": url, "saved": 1.0, "positions": {"2/2/4": [-900.0, 40.0]}}))
    window = _live(make_window, qtbot, url)
    assert window.doc.positions[DeviceKey(2, 2, 4)] == (-900.0, 40.0)
    window.doc.remember_layout()  # now kept for the prosthesis; the URL's entry is dropped
    assert not QSettings().value(live_layout._legacy_key(url), "")
    window.live.disconnect_bus()


def test_which_remembered_layout_is_this_prosthesis():
    from pdcp_studio.app.live.layout import Layout, best_layout

    a = Layout("a", {"1/1/1#x": (0, 0), "1/1/2#x": (1, 0), "1/2/3#y": (2, 0)}, saved=1)
    b = Layout("b", {"1/1/1#z": (0, 0)}, saved=2)
    assert best_layout([a, b], ["1/1/1#x", "1/1/2#x", "1/2/3#y"]) is a
    assert best_layout([a, b], ["1/1/1#x", "1/1/2#x", "9/9/9#q"]) is a  # one part replaced
    assert best_layout([a, b], ["1/1/1#x", "8/8/8#q", "9/9/9#q"]) is None  # under half
    assert best_layout([a, b], ["1/1/1#z"]) is b
    assert best_layout([a, b], ["1/1/1#w"]) is None  # same serial, other channels
