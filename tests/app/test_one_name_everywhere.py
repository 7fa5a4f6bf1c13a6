"""One name for every part and channel (issue 26 item 8): on ``sim:transradial`` with its spare
hand plugged in beside the hand (a twin pair), a part and a channel read the same in the
device tree, the graph's tooltip, the inspector, the status bar, the Bus events panel and
the command line's text; the serial number only where the twins need it, the numbers
(VID/PID/serial) only in the engineer's detail."""

from __future__ import annotations

import re

import pytest
from PySide6.QtWidgets import QLabel

from pdcp_studio.cli.live.scan import format_system
from pdcp_studio.cli.naming import names_for
from pdcp_studio.model.names import Names, short_forms
from pdcp_studio.model.refs import ChannelRef, DeviceKey

pytestmark = pytest.mark.gui

HAND = DeviceKey(2641, 769, 301)
SPARE = DeviceKey(2641, 769, 302)
EMG = DeviceKey(2641, 257, 101)
GRIP_OUT = ChannelRef(2641, 513, 201, 3)
GRIP_IN = ChannelRef(2641, 769, 301, 1)
T = 20000
NUMBERS = re.compile(r"\b2641/\d+/\d+\b")

HAND_NAME = "Multi-grip hand with wrist rotator (serial 301)"
SPARE_NAME = "Multi-grip hand with wrist rotator (serial 302)"


def _tree(window) -> dict:
    tree = window.tree
    return {tree.topLevelItem(i).data(0, 0x0100): tree.topLevelItem(i).text(0)
            for i in range(tree.topLevelItemCount())}


def _inspector_text(window) -> str:
    form = window.inspector.widget()
    return "\n".join(w.text() for w in form.findChildren(QLabel))


def test_a_part_and_a_channel_read_the_same_in_every_view(make_window, qtbot):
    window = make_window()
    said: list[str] = []
    window.live.statusMessage.connect(said.append)
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["sim"].widget()
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=T)
    # One hand on the bus: no serial number, the part's own words (its descriptor).
    assert window.scene.device_label(window.doc.system.devices[HAND]) == \
        "Multi-grip hand with wrist rotator"

    panel.select(SPARE)
    panel.plug_selected()  # the twin joins: both hands now need their serial numbers
    qtbot.waitUntil(lambda: SPARE in window.doc.system.devices, timeout=T)
    devices = window.doc.system.devices
    graph = {k: window.scene.device_label(d) for k, d in devices.items()}
    assert graph[HAND] == HAND_NAME and graph[SPARE] == SPARE_NAME
    assert graph[EMG] == "EMG electrode (wrist flexors)"

    # The device tree, its parts and its channel rows (the graph's rows say the same).
    qtbot.waitUntil(lambda: _tree(window) == graph, timeout=T)
    hand_row = next(window.tree.topLevelItem(i) for i in range(window.tree.topLevelItemCount())
                    if window.tree.topLevelItem(i).data(0, 0x0100) == HAND)
    assert hand_row.child(0).text(0) == "← #1 Power grip"
    assert window.scene.words.channel_label(GRIP_IN) == "Power grip"
    # The graph's card tooltip: the name in bold, the numbers in the grey detail.
    tip = window.scene.words.tooltip_for(devices[SPARE], None)
    assert tip.startswith(f"<b>{SPARE_NAME}</b>")
    assert "VID 2641 · PID 769 · serial 302" in tip
    # The inspector's title.
    window.doc.select(SPARE)
    assert SPARE_NAME in _inspector_text(window).splitlines()
    # The status bar: the part by its name, never "Device 2641/769/302 joined the bus".
    qtbot.waitUntil(lambda: f"{SPARE_NAME} joined the bus" in said, timeout=T)
    assert not any(NUMBERS.search(text) for text in said if "the bus" in text), said
    # The Bus events panel, its numbers in the row's detail only.
    events = window._leaf_docks["events"].widget()
    qtbot.waitUntil(lambda: f"{SPARE_NAME} joined the bus" in
                    [w for w, _y, _s in events.rows()], timeout=T)
    assert not any(NUMBERS.search(w) for w, _y, _s in events.rows())

    # A channel: the part's name and the channel's descriptor, alike everywhere.
    system = window.doc.system
    out_name = "Pattern-recognition control unit, Power grip set point"
    in_name = f"{HAND_NAME}, Power grip"
    assert system.source_of(GRIP_IN) == GRIP_OUT
    row = devices[HAND].channels[1]
    assert f"Fed by {out_name}" in window.scene.words.tooltip_for(devices[HAND], row)
    window.doc.select(GRIP_IN)
    text = _inspector_text(window)
    assert "Input 1: Power grip" in text and f"Fed by {out_name}" in text
    assert f"{HAND_NAME} · " in text  # the channel's part, by its one name

    # The command line's text names them alike, the numbers beside them in brackets.
    session = window.live.bridge.session
    listing = format_system(session.system())
    assert f"{SPARE_NAME}  [2641/769/302, node " in listing
    assert f"link {out_name} → {in_name}  [{GRIP_OUT} → {GRIP_IN}]" in listing
    cli = names_for(session.system())
    assert {k: cli.part(k) for k in graph} == graph
    assert cli.channel(GRIP_IN) == in_name
    window.live.disconnect_bus()


def test_a_part_gone_from_the_system_keeps_its_name_and_twins_only_get_serials():
    """The naming rule itself (``model/names.py``): own name, else descriptor, else the
    catalogue's product; a part known only by its numbers is its product (with its serial
    only where a known part reads the same); a channel: descriptor, else profile name,
    else "channel N", its number added only for two channels that read alike."""
    from pdcp_studio.bus.sim.rigs import load_prosthesis
    from pdcp_studio.model.system import Device

    system = load_prosthesis("transradial")
    names = Names(system)
    assert names.part(HAND) == "Hand" and names.part(SPARE) == "Spare hand"  # own names
    for d in system.devices.values():
        d.name = ""  # as a live bus tells them: the descriptors, the hands now twins
    names = Names(system)
    assert names.part(HAND) == HAND_NAME and names.part(SPARE) == SPARE_NAME
    assert names.part(EMG) == "EMG electrode (wrist flexors)"
    system.devices[EMG].descriptor = ""
    assert Names(system).part(EMG) == "EMG sensor"  # the catalogue's product
    other = DeviceKey(2641, 257, 999)  # known only by its numbers: its product...
    assert Names(system).part(other) == "EMG sensor (serial 999)"  # ...a twin of the EMG
    assert Names(None).part(other) == "EMG sensor"
    assert Names(None).part(DeviceKey(9, 9, 9)) == "unknown device (9/9/9)"
    gone = Names(None, among=[Device(2641, 769, 301, descriptor="Multi-grip hand")])
    assert gone.part(HAND) == "Multi-grip hand"
    # Channels: twins by their numbers.
    hand = system.devices[HAND]
    hand.channels[2].descriptor = "Power grip"
    names = Names(system)
    assert names.channel_only(GRIP_IN) == "Power grip (channel 1)"
    hand.channels[2].descriptor = ""
    assert Names(system).channel_only(ChannelRef(*HAND, 2)) == "channel 2"
    assert Names(system).channel_only(ChannelRef(*HAND, 2), "Pinch Grip") == "Pinch Grip"


def test_a_narrow_card_abbreviates_a_word_alike_on_every_card():
    """"EMG flex. 1" and "EMG flex. 11", never "EMG fle. 11" (the cut no longer depends on
    how many pixels a card has); numbers and a twin's serial stay whole."""
    assert short_forms("EMG flexor 1")[:2] == ["EMG flexor 1", "EMG flex. 1"]
    assert short_forms("EMG flexor 11")[:3] == ["EMG flexor 11", "EMG flex. 11", "flex. 11"]
    assert short_forms("EMG extensor 11")[1] == "EMG exte. 11"
    assert all("(serial 302)" in form for form in short_forms(SPARE_NAME))
    assert not any("fle." in f for f in short_forms("EMG flexor 11") + short_forms(
        "EMG flexor 1"))


def test_summary_cards_cut_a_word_alike_whatever_their_number(make_window, qtbot):
    """On the large rig zoomed out, every card shows its name or one of its fixed short
    forms: "flexor" reads "flex." on every card that shortens it (the trial saw "EMG flex.
    1" beside "EMG fle. 11"), and no two cards read the same."""
    window = make_window(size=(1400, 900))
    with qtbot.waitSignal(window.ready, timeout=60000):
        window.connect_bus("sim:large")
    scene = window.scene
    qtbot.waitUntil(lambda: len(scene.cards) >= 32, timeout=60000)
    window.view.set_zoom(0.22)
    scene.render_pending()
    shown = {}
    for key, card in scene.cards.items():
        assert card.summary
        label = scene.device_label(card.device)
        text = card.texts()[0]
        assert text in short_forms(label) or any(
            text.endswith(form) for form in short_forms(label)), (label, text)
        shown[key] = text
    words = {w for text in shown.values() for w in text.split() if w.endswith(".")}
    assert not any(w.startswith("fle") and w != "flex." for w in words), words
    assert len(set(shown.values())) == len(shown)
    window.live.disconnect_bus()
