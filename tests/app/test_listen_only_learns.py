"""Listening to a bus another arbitrator runs (issue 27 item 1): the monitor learns the
node map from the traffic as the trace of a capture does — channel data is channel data,
not "undecodable" — and the graph shows the parts and links the traffic proves."""

from __future__ import annotations

import pytest

from pdcp_studio.app.live.heard_bus import heard_system
from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.files.reader import CaptureReader

from .test_arbitrator_found import _connect_and_get_offer, taken_bus  # noqa: F401

pytestmark = pytest.mark.gui


def test_listening_shows_channel_data_and_the_parts_the_traffic_proves(
        make_window, qtbot, taken_bus):  # noqa: F811
    channel, first, _tap = taken_bus
    window = make_window()
    dialog = _connect_and_get_offer(window, qtbot, f"can:virtual:{channel}")
    dialog.watch_button.click()
    monitor = window.passive_monitor
    assert monitor is not None and monitor.wait_open(5)
    dock = window._leaf_docks["monitor"]
    qtbot.waitUntil(lambda: any(d.name.startswith("Channel node")
                                for d in window.doc.system.devices.values()), timeout=15_000)
    qtbot.wait(1500)  # a second more of traffic, every node placed
    dock.flush()
    rows = dock.all_rows
    late = rows[len(rows) // 2:]  # once the learner has heard each node a few times
    data = [r for r in late if r.function == "Channel data"]
    assert data and all("channel node" in r.text for r in data)
    assert not [r for r in late if "undecodable" in r.function or "unattributed" in r.text]
    # Frames heard before their node was placed say so, never their first byte's name.
    assert all(r.function == "unattributed" for r in rows if "unattributed" in r.text)
    system = window.doc.system
    devices = [d for d in system.devices.values() if d.name.startswith("Device at node")]
    outputs = [d for d in system.devices.values() if d.name.startswith("Channel node")]
    bus = first.system()
    assert {d.node_id for d in devices} == {d.node_id for d in bus.devices.values()}
    streaming = {ch.node_id for _ref, ch in bus.channels() if ch.is_output and ch.node_id}
    assert {d.channels[1].node_id for d in outputs} <= streaming
    assert not system.links  # listening mid-session proves no link: none is drawn
    assert window.doc.session is None  # nothing to send through
    window.listening_indicator.stop_button.click()


def test_a_set_up_heard_gives_the_parts_their_identity_and_the_links_it_wrote():
    decoder = FrameDecoder(passive=True)
    decoder.learn_from_traffic([])
    for msg in CaptureReader("tests/data/captures/pdcp-session.asc"):
        decoder.decode_message(msg)
    system = heard_system(decoder)
    assert [str(link) for link in system.links] == ["1/10/4#1 → 2/2/5#2"]
    hand = system.devices[(1, 10, 4)]
    assert hand.node_id == 5 and hand.channels[1].node_id == 6 and hand.channels[1].is_output
    assert system.devices[(2, 2, 5)].channels[2].is_input
