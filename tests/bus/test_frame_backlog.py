"""Frames nobody watches yet wait undecoded (issue 11): opening a simulated prosthesis does not
decode its ~450 start-up frames for display, yet what is shown afterwards is the same.

Real parts: the simulated prosthesis on python-can's virtual bus, the arbitrator, its
frame decoder.
"""

from __future__ import annotations

import time

import can

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator import frame_events as arbitrator_module
from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.protocol import Beacon, BindRequest


def _frames_seen(session, seconds: float, until=lambda events: False) -> list[ev.FrameSeen]:
    got: list[ev.FrameSeen] = []
    stop = session.subscribe(lambda e: got.append(e) if isinstance(e, ev.FrameSeen) else None)
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and not until(got):
        time.sleep(0.02)
    stop()
    return got


def test_frames_shown_after_opening_know_what_start_up_taught_the_decoder():
    with open_session("sim:transradial") as session:
        arb = session.arbitrator  # type: ignore[attr-defined]
        assert arb._decoder is None  # nothing decoded for display while it opened
        assert len(arb._unshown) > 100  # its start-up frames wait, undecoded
        flexor_to_cu = "2641/257/101#1 → 2641/513/201#1"  # a link start-up made
        seen = _frames_seen(session, 5.0,
                            lambda got: any(flexor_to_cu in f.text for f in got))
        data = [f for f in seen if "Channel data" in f.text]
        assert data, "no channel data shown within 5 s"
        # The link of an output is known only from the set-up frames before the subscriber
        # came: the waiting frames were decoded, in order, first.
        assert any(flexor_to_cu in f.text for f in data)
        # Times count from the session's first frame, not from the first one shown.
        assert float(seen[0].text.split()[0]) > 0.0
        assert arb._unshown == []


def test_without_session_subscribers_frames_wait_and_their_number_is_bounded(monkeypatch):
    monkeypatch.setattr(arbitrator_module, "FRAME_BACKLOG", 16)
    channel = unique_virtual_channel("pdcp-backlog")
    device = can.Bus(interface="virtual", channel=channel)
    arb = Arbitrator(can.Bus(interface="virtual", channel=channel), name="backlog",
                     frame_events=True, direct=True)
    watching = [False]
    shown: list[ev.FrameSeen] = []
    stop = arb.subscribe(lambda e: shown.append(e) if isinstance(e, ev.FrameSeen) else None,
                         wants_frames=lambda: watching[0])
    try:
        for _ in range(40):  # beacons from a node nobody bound: heard, not shown
            aid, data = Beacon(77).encode()
            device.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))
        assert arb.wait_for(lambda: arb.conn.inbound.empty(), 2.0)
        time.sleep(0.1)
        assert shown == []
        assert len(arb._unshown) < 16  # decoded in batches: memory stays bounded
        assert arb._decoder is not None and arb._decoder.stats.frames >= 32
        watching[0] = True
        aid, data = BindRequest(9, 1, 2, 3).encode()
        device.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))
        assert arb.wait_for(lambda: any("Bind Device Request" in f.text for f in shown), 2.0)
        assert arb._unshown == []
        assert arb._decoder.stats.frames >= 41  # every frame heard, in order, once
    finally:
        stop()
        arb.close()
        device.shutdown()


def test_a_subscriber_without_a_say_always_gets_frames():
    channel = unique_virtual_channel("pdcp-backlog")
    device = can.Bus(interface="virtual", channel=channel)
    arb = Arbitrator(can.Bus(interface="virtual", channel=channel), name="always",
                     frame_events=True)
    shown: list[ev.FrameSeen] = []
    stop = arb.subscribe(lambda e: shown.append(e) if isinstance(e, ev.FrameSeen) else None)
    try:
        aid, data = Beacon(77).encode()
        device.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))
        assert arb.wait_for(lambda: any("Device Beacon" in f.text and f.arbitration_id == aid
                                        for f in shown), 2.0)
        stop()
        stop()  # idempotent
        assert arb._frame_gates == []
    finally:
        arb.close()
        device.shutdown()
