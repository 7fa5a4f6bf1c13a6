"""A part swapped while the prosthesis is live takes its predecessor's place at once (issue 11,
item 6): the rule a connect follows (:mod:`pdcp_studio.app.live.layout`) applied to the parts
that join a live view — the other cards stay, and the positions are remembered for the
prosthesis."""

from __future__ import annotations

import pytest

from pdcp_studio.app.live.layout import (
    Joined,
    _overlap,
    place_joined,
    successors,
    swap_in,
    to_remember,
)
from pdcp_studio.model.refs import DeviceKey

HAND, SPARE = DeviceKey(2641, 769, 301), DeviceKey(2641, 769, 302)
ELBOW, SENSOR = DeviceKey(2641, 770, 1), DeviceKey(2641, 771, 7)


# -- pure decisions ---------------------------------------------------------------------------
def test_successors_same_part_first_then_same_product():
    gone = {"a": "1/1/1#x", "b": "1/1/2#x", "c": "1/2/3#y"}
    # the same unit with new channels takes its own place, not another unit's
    assert successors({"n": "1/1/2#z"}, gone) == {"n": "b"}
    # another unit of a product: the first gone unit of it, each place taken once
    assert successors({"n": "1/1/9#x", "m": "1/1/8#x"}, gone) == {"n": "a", "m": "b"}
    # another product: no predecessor
    assert successors({"n": "7/7/7#x"}, gone) == {}
    assert successors({}, gone) == {} and successors({"n": "1/1/1#x"}, {}) == {}


def test_a_replacement_takes_the_place_of_the_part_that_left():
    positions = {HAND: (600.0, 40.0), ELBOW: (0.0, 0.0), SENSOR: (300.0, 0.0)}
    got = place_joined(positions, {HAND: "2641/769/301#aa"}, {SPARE: "2641/769/302#aa"})
    assert got == Joined({SPARE: (600.0, 40.0)}, (HAND,))


def test_a_part_of_another_product_is_left_to_the_usual_rule():
    positions = {HAND: (600.0, 40.0), ELBOW: (0.0, 0.0)}
    got = place_joined(positions, {HAND: "2641/769/301#aa"}, {SENSOR: "2641/771/7#bb"})
    assert got == Joined({}, ())
    # nothing left the bus: a second unit of a product on the bus is a newcomer too
    got = place_joined(positions, {}, {SPARE: "2641/769/302#aa"})
    assert got == Joined({}, ())


def test_a_gone_part_with_no_card_is_no_predecessor():
    got = place_joined({ELBOW: (0.0, 0.0)}, {HAND: "2641/769/301#aa"},
                       {SPARE: "2641/769/302#aa"})
    assert got == Joined({}, ())


def test_the_remembered_layout_places_a_part_whose_predecessor_is_not_on_screen():
    positions = {ELBOW: (0.0, 0.0), SENSOR: (300.0, 0.0)}
    remembered = {"2641/769/301#aa": (600.0, 40.0), "2641/771/7#bb": (900.0, 0.0)}
    heights = {ELBOW: 100.0, SENSOR: 100.0, SPARE: 120.0, HAND: 120.0}
    # the spare takes the remembered hand's place; a part remembered itself, its own place
    got = place_joined(positions, {}, {SPARE: "2641/769/302#aa", HAND: "2641/769/301#aa"},
                       remembered=remembered, heights=heights, width=200.0)
    assert got.placed == {HAND: (600.0, 40.0)}  # its own place first; the spare: newcomer
    got = place_joined(positions, {}, {SPARE: "2641/769/302#aa"},
                       remembered=remembered, heights=heights, width=200.0)
    assert got == Joined({SPARE: (600.0, 40.0)}, ())
    # a card is there now: the remembered place is not taken over it
    crowded = {**positions, SENSOR: (650.0, 100.0)}
    got = place_joined(crowded, {}, {SPARE: "2641/769/302#aa"},
                       remembered=remembered, heights=heights, width=200.0)
    assert got == Joined({}, ())


def test_a_replacement_that_joined_first_swaps_places_with_the_part_that_leaves():
    positions = {HAND: (600.0, 40.0), SPARE: (600.0, 300.0), ELBOW: (0.0, 0.0)}
    given = {SPARE: (600.0, 300.0)}
    newcomers = {SPARE: "2641/769/302#aa"}
    assert swap_in({HAND: "2641/769/301#aa"}, newcomers, positions, given) == {
        SPARE: (600.0, 40.0), HAND: (600.0, 300.0)}
    # moved by the user since it joined: it stays where it was put
    moved = {**positions, SPARE: (650.0, 300.0)}
    assert swap_in({HAND: "2641/769/301#aa"}, newcomers, moved, given) == {}
    # another product left: nothing to swap
    assert swap_in({ELBOW: "2641/770/1#cc"}, newcomers, positions, given) == {}


def test_a_layout_keeps_the_parts_off_the_bus_only_where_no_replacement_stands():
    heights = {"h": 100.0, "s": 100.0, "e": 100.0}
    before = {"h": (600.0, 40.0), "e": (0.0, 0.0)}
    # the spare took the hand's place: the hand's place is the spare's now
    assert to_remember({"s": (600.0, 40.0), "e": (0.0, 0.0)}, ["h"], before, heights,
                       200.0) == {"s": (600.0, 40.0), "e": (0.0, 0.0)}
    # the hand only unplugged: it keeps its place
    assert to_remember({"e": (0.0, 0.0)}, ["h"], before, heights, 200.0) == before
    # never remembered: not remembered off the bus either
    assert to_remember({"e": (0.0, 0.0)}, ["h"], {}, heights, 200.0) == {"e": (0.0, 0.0)}


def test_a_part_not_seen_for_a_session_keeps_its_remembered_place():
    """Saved without the hand (unplugged before the connect), the layout still knows where
    the hand was: a spare plugged in later is given that place; once the spare stands
    there, the layout gives it to whichever hand comes."""
    from pdcp_studio.app.live import layout as live_layout
    from pdcp_studio.bus.sim.rigs import load_prosthesis

    arm = load_prosthesis("transradial")
    spare = arm.remove_device(SPARE)
    spare.present = True
    at = {k: (float(i * 300), 0.0) for i, k in enumerate(arm.devices)}
    live_layout.save(arm, at)
    hand = arm.remove_device(HAND)
    live_layout.save(arm, {k: (x, y + 5.0) for k, (x, y) in at.items() if k != HAND})
    arm.add_device(spare)
    assert live_layout.load(arm)[SPARE] == at[HAND]
    live_layout.save(arm, live_layout.load(arm))  # the spare at the hand's place: the hand
    arm.remove_device(SPARE)                      # is not remembered over it
    arm.add_device(hand)
    assert live_layout.load(arm)[HAND] == at[HAND]
    assert len(live_layout.stored_layouts()) == 1
    assert len(live_layout.stored_layouts()[0].at) == len(arm.devices)


def test_cards_overlap():
    assert _overlap((0, 0), 100, (50, 50), 100, 200)
    assert not _overlap((0, 0), 100, (0, 110), 100, 200)  # one under the other
    assert not _overlap((0, 0), 100, (250, 0), 100, 200)  # side by side
    assert _overlap((0, 0), 0, (0, 0), 0, 0)  # same corner, sizes unknown


# -- on the simulated prosthesis --------------------------------------------------------------
def _live(make_window, qtbot, url):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus(url)
    assert window.doc.is_live_view
    return window


def _card_rect(window, key):
    return window.scene.cards[key].sceneBoundingRect()


def _no_overlaps(window):
    cards = list(window.scene.cards)
    for i, a in enumerate(cards):
        for b in cards[i + 1:]:
            inter = _card_rect(window, a).intersected(_card_rect(window, b))
            assert inter.isEmpty() or inter.width() * inter.height() < 1, (a, b)


@pytest.mark.gui
def test_the_spare_hand_swapped_in_from_the_simulator_panel_takes_the_hands_place(
        make_window, qtbot):
    from pdcp_studio.app.live import layout as live_layout

    window = _live(make_window, qtbot, "sim:transradial")
    doc = window.doc
    before = dict(doc.positions)
    assert SPARE not in doc.system.devices
    panel = window._leaf_docks["sim"].widget()
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=5000)
    panel.select(HAND)
    index = next(i for i in range(panel.replace_combo.count())
                 if panel.replace_combo.itemData(i) == SPARE)
    panel.replace_combo.setCurrentIndex(index)
    qtbot.waitUntil(panel.replace_button.isEnabled, timeout=5000)
    panel.replace_button.click()
    qtbot.waitUntil(lambda: SPARE in window.scene.cards, timeout=10000)
    qtbot.waitUntil(lambda: not doc.system.devices[HAND].present, timeout=10000)

    # the spare's card is where the hand's was, at once; the others did not move
    assert doc.positions[SPARE] == before[HAND]
    assert window.scene.cards[SPARE].pos().toTuple() == before[HAND]
    others = {k: xy for k, xy in before.items() if k != HAND}
    assert {k: doc.positions[k] for k in others} == others
    # the hand, off the bus, was put aside: under the spare, in the same column
    hand = doc.positions[HAND]
    assert hand[0] == before[HAND][0] and hand[1] > before[HAND][1]
    _no_overlaps(window)
    # remembered for this prosthesis as a connect sees it: the parts on the bus
    bus = window.live.bridge.session.system()
    for key in [k for k, d in bus.devices.items() if not d.present]:
        bus.remove_device(key)
    assert set(bus.devices) == set(others) | {SPARE}
    qtbot.waitUntil(lambda: live_layout.load(bus) == {k: doc.positions[k] for k in bus.devices},
                    timeout=5000)
    window.live.disconnect_bus()

    # the simulator starts again with the first hand plugged in: it takes the spare's place
    # (its own, which the spare had taken), not the place its card was put aside to
    again = _live(make_window, qtbot, "sim:transradial")
    assert again.doc.positions == before
    again.live.disconnect_bus()


@pytest.mark.gui
def test_a_hot_swap_on_thesis_test4_puts_the_new_joystick_where_the_old_one_was(
        make_window, qtbot):
    d1, d2 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5)
    window = _live(make_window, qtbot, "sim:thesis-test4")
    doc = window.doc
    before = dict(doc.positions)
    assert d2 not in doc.system.devices
    bridge = window.live.bridge
    with qtbot.waitSignal(bridge.scriptFinished, timeout=30000):
        bridge.run_script("hot-swap")
    qtbot.waitUntil(lambda: d2 in window.scene.cards, timeout=10000)
    assert doc.positions[d2] == before[d1]
    assert {k: doc.positions[k] for k in before if k != d1} == {
        k: xy for k, xy in before.items() if k != d1}
    assert doc.positions[d1] != before[d1]  # the pulled joystick, put aside
    _no_overlaps(window)
    window.live.disconnect_bus()


@pytest.mark.gui
def test_a_part_plugged_in_live_goes_where_its_remembered_predecessor_was(make_window, qtbot):
    """The hand was last laid out in another session and is not on the bus at connect: the
    spare plugged in live takes the remembered hand's place, as a connect would give it."""
    from pdcp_studio.app.documents import commands
    from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import load_prosthesis

    arm = load_prosthesis("transradial")
    hand = arm.devices[HAND]
    arm.remove_device(SPARE)  # the simulator's spare, unplugged: not on this bus
    hosts = []

    def plug(parts, spare=None):
        channel = unique_virtual_channel("pdcp-live-swap")
        host = DeviceHost(open_can_bus("virtual", channel),
                          [SimulatedDevice(d) for d in parts], name=channel)
        hosts.append(host)
        if spare is not None:
            host.add(SimulatedDevice(spare), plugged=False)
        return host, f"can:virtual:{channel}"

    try:
        _host, url = plug(arm.devices.values())
        window = _live(make_window, qtbot, url)
        doc = window.doc
        for key in list(doc.system.devices):  # laid out by hand, then remembered
            old = doc.positions[key]
            doc.undo_stack.push(commands.MoveDeviceCommand(doc, key, old,
                                                           (old[0] + 180.0, old[1] + 90.0)))
        doc.remember_layout()
        moved = dict(doc.positions)
        window.live.disconnect_bus()

        import copy
        from dataclasses import replace

        spare = replace(copy.deepcopy(hand), serial=SPARE.serial, node_id=None)
        host, url = plug([d for k, d in arm.devices.items() if k != HAND], spare)
        window = _live(make_window, qtbot, url)
        doc = window.doc
        assert HAND not in doc.system.devices
        others = {k: xy for k, xy in moved.items() if k != HAND}
        assert {k: doc.positions[k] for k in others} == others
        host.plug(SPARE)
        qtbot.waitUntil(lambda: SPARE in window.scene.cards, timeout=10000)
        assert doc.positions[SPARE] == moved[HAND]
        assert {k: doc.positions[k] for k in others} == others
        window.live.disconnect_bus()
    finally:
        for host in hosts:
            host.close()
