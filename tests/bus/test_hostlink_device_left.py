"""A part that leaves says why over the host link too (issue 28 item 6, docs/host-link.md
§5.7): DEVICE_LEFT carries the arbitrator's silence, beacon interval and reason, and the PC
reads them into its DeviceLeft (an event with the key alone still works)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.client import open_hostlink_session
from pdcp_studio.bus.hostlink.testing.relay import PtyRelay
from pdcp_studio.bus.session.urls import parse_bus_url
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.protocol.hostlink_messages import Event

from .hostlink_rig import arbitrator_rig_with_devices, wait_for

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
VID = 0x0A51
EMG1 = DeviceKey(VID, 257, 101)


@pytest.fixture(scope="module")
def rig(tmp_path_factory):
    memory = tmp_path_factory.mktemp("hostlink-left") / "memory.bin"
    with arbitrator_rig_with_devices(SYSTEMS / "transradial.json", memory) as parts:
        yield parts


@pytest.fixture
def session(rig):
    _, server, _ = rig
    with PtyRelay(server.slave_path) as relay:
        s = open_hostlink_session(parse_bus_url(f"serial:{relay.client_path}@128000"),
                                  monitor=False)
        try:
            yield s
        finally:
            s.close()


def _left(events: list[object]) -> list[ev.DeviceLeft]:
    return [e for e in events if isinstance(e, ev.DeviceLeft)]


# -- end to end: a simulated part unplugged behind the arbitrator --------------------
def test_a_part_unplugged_behind_the_arbitrator_leaves_with_its_reason_on_the_pc(rig, session):
    arbitrator, _, host = rig
    session.scan()
    on_pc: list[object] = []
    at_arb: list[object] = []
    session.subscribe(on_pc.append)
    arbitrator.subscribe(at_arb.append)
    host.unplug(EMG1)
    try:
        assert wait_for(lambda: _left(on_pc), 15.0), "no DeviceLeft crossed the host link"
        assert _left(at_arb)
        sent, got = _left(at_arb)[0], _left(on_pc)[0]
        assert got.key == sent.key == EMG1
        assert sent.why.startswith("no beacon for")
        assert got.why == sent.why  # the arbitrator's own words, not an empty reason
        assert got.silent_s == pytest.approx(sent.silent_s, abs=0.001)
        assert got.interval_s == pytest.approx(sent.interval_s, abs=0.001)
        assert got.interval_s > 0 and got.silent_s >= 3 * got.interval_s
    finally:
        host.plug(EMG1)
        assert wait_for(lambda: arbitrator.system().devices[EMG1].present, 15.0)


# -- the PC's event reader --------------------
def _read(session, body: bytes) -> list[ev.DeviceLeft]:
    seen: list[object] = []
    unsubscribe = session.subscribe(seen.append)
    try:
        session._on_event(bytes([Event.DEVICE_LEFT]) + body)  # the line thread's call
    finally:
        unsubscribe()
    return _left(seen)


def test_a_device_left_with_the_key_alone_still_works(session):
    [left] = _read(session, hr.pack_key(EMG1))
    assert (left.key, left.why, left.silent_s, left.interval_s) == (EMG1, "", 0.0, 0.0)


def test_a_device_left_with_its_reason_is_read_whole(session):
    body = hr.pack_left(EMG1, 1.9, 0.5, "no beacon for 1.9 s, 3 beacon intervals")
    [left] = _read(session, body)
    assert left.key == EMG1
    assert left.why == "no beacon for 1.9 s, 3 beacon intervals"
    assert (left.silent_s, left.interval_s) == (1.9, 0.5)


def test_bad_utf8_in_the_reason_is_shown_replaced_never_raised(session):
    body = hr.pack_key(EMG1) + b"\xd0\x07\xf4\x01" + b"gone \xff\xfe\xc3"
    [left] = _read(session, body)
    assert left.key == EMG1 and left.why.startswith("gone ") and "\ufffd" in left.why
    assert (left.silent_s, left.interval_s) == (2.0, 0.5)


def test_an_over_long_reason_is_accepted(session):
    body = hr.pack_key(EMG1) + b"\x00\x00\x00\x00" + b"x" * 300
    [left] = _read(session, body)
    assert left.why == "x" * 300


def test_a_tail_too_short_for_the_times_is_ignored_and_a_short_key_is_dropped(session):
    [left] = _read(session, hr.pack_key(EMG1) + b"\x01\x02")
    assert (left.key, left.why, left.silent_s) == (EMG1, "", 0.0)
    assert _read(session, hr.pack_key(EMG1)[:5]) == []  # malformed: logged, never raised


# -- the arbitrator's encoding --------------------
def test_the_server_sends_the_reason_cut_to_200_bytes(rig):
    _, server, _ = rig
    why = "no beacon for 1.9 s, 3 beacon intervals: " + "é" * 200  # 41 + 2 n bytes
    message = server.handlers.event_message(
        ev.DeviceLeft(EMG1, why=why, silent_s=1.9, interval_s=0.5))
    assert message is not None and message[0] == Event.DEVICE_LEFT
    body = message[1:]
    assert body[:10] == hr.pack_key(EMG1) + b"\x6c\x07\xf4\x01"  # 1900 ms, 500 ms
    assert len(body[10:]) == 199  # 200 would split an "é": cut at a character boundary
    assert why.startswith(body[10:].decode("utf-8"))
    assert hr.unpack_left(body) == hr.Left(EMG1, 1.9, 0.5, body[10:].decode("utf-8"))


def test_the_server_saturates_long_silences_and_sends_the_key_alone_when_it_knows_nothing(rig):
    _, server, _ = rig
    long = server.handlers.event_message(ev.DeviceLeft(EMG1, why="w", silent_s=100.0,
                                                       interval_s=0.5))
    assert long is not None and long[7:9] == b"\xff\xff"
    bare = server.handlers.event_message(ev.DeviceLeft(EMG1))
    assert bare == bytes([Event.DEVICE_LEFT]) + hr.pack_key(EMG1)


# -- a replaced part (DEVICE_REPLACED, §5.7) --------------------
EMG2 = DeviceKey(VID, 257, 102)


def test_the_server_says_a_replacement_as_such_not_as_a_part_that_left(rig):
    _, server, _ = rig
    message = server.handlers.event_message(ev.DeviceReplaced(EMG1, EMG2))
    assert message == bytes([Event.DEVICE_REPLACED]) + hr.pack_key(EMG1) + hr.pack_key(EMG2)


def test_the_pc_reads_a_replacement_into_the_same_event_as_on_the_bus(session):
    seen: list[object] = []
    unsubscribe = session.subscribe(seen.append)
    try:
        session._on_event(bytes([Event.DEVICE_REPLACED]) + hr.pack_key(EMG1)
                          + hr.pack_key(EMG2))
        session._on_event(bytes([Event.DEVICE_REPLACED]) + hr.pack_key(EMG1))  # malformed
    finally:
        unsubscribe()
    assert [(type(e).__name__, e.key, getattr(e, "new", None)) for e in seen] == [
        ("DeviceReplaced", EMG1, EMG2)]  # the short one is logged, never raised
