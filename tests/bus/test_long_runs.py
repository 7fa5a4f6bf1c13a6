"""Long runs on an echoing bus: the per-frame bookkeeping stays bounded and never fails.

python-can's virtual bus with ``receive_own_messages=True`` hands every frame back to its
sender, as ``udp_multicast`` does across processes; a connection told to drop its own frames
must keep working for any number of distinct frames (issue 15: it died after 4,096).
"""

from __future__ import annotations

import gc
import os
import time

import can
import pytest

from pdcp_studio.bus.connection import ECHO_MAX_PENDING, Connection, EchoFilter
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.model.refs import DeviceKey
from tests.bus.test_arbitrator_rig import load


def _echoing_connection() -> Connection:
    bus = can.Bus(interface="virtual", channel=unique_virtual_channel("pdcp-echo"),
                  receive_own_messages=True)
    return Connection(bus, name="echo", drop_own=True)


def _distinct(i: int) -> tuple[int, bytes]:
    return 0x100 + i % 0x600, i.to_bytes(4, "little")


def _drain(conn: Connection) -> list[can.Message]:
    got = []
    while (item := conn.get(0.0)) is not None:
        got.append(item)
    return got


def test_the_echo_filter_outlives_100000_distinct_frames_through_a_connection():
    conn = _echoing_connection()
    try:
        for i in range(100_000):
            conn.send(*_distinct(i))
            if i % 64 == 63:
                assert _drain(conn) == []  # every echo is recognised as our own
                assert conn._echoes.remembered <= ECHO_MAX_PENDING
        # the last echoes arrive through the Notifier thread
        for _ in range(40):
            _drain(conn)
            if len(conn._echoes) == 0:
                break
            conn.get(0.05)
        assert len(conn._echoes) == 0
        assert conn.sent == 100_000 and conn.received == 0
    finally:
        conn.close()


def test_a_foreign_frame_equal_to_one_sent_long_ago_is_not_taken_for_an_echo():
    echoes = EchoFilter(window_s=2.0, max_pending=8)
    echoes.sent((0x123, b"\x01"), now=0.0)
    assert not echoes.is_echo((0x123, b"\x01"), now=2.5)  # the echo never came in time
    echoes.sent((0x123, b"\x01"), now=3.0)
    assert echoes.is_echo((0x123, b"\x01"), now=3.1)
    assert not echoes.is_echo((0x123, b"\x01"), now=3.2)  # one send, one echo


def test_the_echo_filter_is_bounded_for_100000_distinct_frames_echoed_or_not():
    echoes = EchoFilter()
    now = 0.0
    for i in range(100_000):
        now += 0.0002  # 5 kHz, faster than the window expires anything
        echoes.sent(_distinct(i), now)
        if i % 3:  # two thirds come back, one third are lost
            assert echoes.is_echo(_distinct(i), now)
        assert echoes.remembered <= ECHO_MAX_PENDING
    assert len(echoes) <= ECHO_MAX_PENDING
    assert echoes.forgotten > 0
    # repeated identical frames (a heartbeat) are matched one echo per send
    for _ in range(3):
        echoes.sent((0x700, b"\x05"), now)
    assert [echoes.is_echo((0x700, b"\x05"), now) for _ in range(4)] == [True, True, True, False]


# -- the device host and the arbitrator on an echoing bus, 100,000 distinct frames -----------
def _rss_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="RSS from /proc")
def test_device_host_and_arbitrator_hold_100000_distinct_frames_on_an_echoing_bus():
    """Every role hears its own frames back (as on udp_multicast) and drops them; after
    100,000 distinct frames sent through both, links are intact, requests are answered, no
    device left, and memory and every per-frame table stayed bounded."""
    from pdcp_studio.bus import events as ev
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.model import parameters as P
    from pdcp_studio.protocol import ChannelData

    channel = unique_virtual_channel("pdcp-echo-long")

    def bus() -> can.BusABC:
        return can.Bus(interface="virtual", channel=channel, receive_own_messages=True)

    system = load("transradial", beacon_ms=200)  # gone after 0.7 s: a loaded CI machine
    events: list[object] = []
    arb = Arbitrator(bus(), startup_quiet_s=0.15, drop_own=True)
    arb.subscribe(lambda e: None if isinstance(e, ev.ChannelValue) else events.append(e))
    host = DeviceHost(bus(), [SimulatedDevice(d, data_rate_hz=0) for d in
                              system.devices.values()], name="echo devices", drop_own=True)
    try:
        keys = [d.key for d in system.devices.values() if d.present]
        deadline = time.monotonic() + 10
        while len(arb.devices_present()) < len(keys) and time.monotonic() < deadline:
            time.sleep(0.02)
        assert sorted(arb.devices_present()) == sorted(keys)
        assert arb.wait_settled(10)
        links = arb.system().links
        assert links
        out = links[0].output
        node = arb.channel_node_id(out)
        assert node is not None
        sensor = DeviceKey(out.vid, out.pid, out.serial)

        def drive(count: int, start: int) -> None:
            """``count`` distinct frames: channel data from the host (as the sensor would
            send it) and, every fourth, a data frame from the arbitrator on a free node."""
            for i in range(start, start + count):
                if i % 4:
                    host.conn.send(*ChannelData(node, i.to_bytes(4, "little")).encode())
                else:
                    arb.conn.send(0x0FE, i.to_bytes(4, "little"))
                if i % 500 == 499:  # let the receivers keep up: queues are not the test
                    until = time.monotonic() + 5
                    while (max(arb.conn.inbound.qsize(), host.conn.inbound.qsize()) > 200
                           and time.monotonic() < until):
                        time.sleep(0.001)

        drive(20_000, 0)
        rss_start = _rss_bytes()
        drive(80_000, 20_000)
        time.sleep(0.3)
        gc.collect()
        rss_end = _rss_bytes()
        # Still working: every device present, no departure, links as before, requests
        # answered, the host's devices still alive.
        assert sorted(arb.devices_present()) == sorted(keys)
        assert not [e for e in events if isinstance(e, ev.DeviceLeft)]
        assert arb.system().links == links
        assert arb.get_parameter(sensor, P.DEVICE_CHANNEL_COUNT) == b"\x01"
        assert host.failures == 0
        assert arb.data_frames >= 70_000
        # Bounded: the echo filters and the per-frame tables.
        for conn in (arb.conn, host.conn):
            assert conn._echoes.remembered <= ECHO_MAX_PENDING
        assert len(host._timers) < 100
        assert len(arb._nodes) <= 254
        assert rss_end - rss_start < 16 * 1024 * 1024, (rss_start, rss_end)
    finally:
        arb.close()
        host.close()


def test_a_stream_of_our_own_echoes_does_not_hold_get_past_its_deadline():
    """The role's thread runs its timers (beacons!) between get() calls: draining thousands
    of its own echoes must not keep it inside get() while they keep coming."""
    conn = _echoing_connection()
    try:
        for i in range(5_000):
            conn.send(*_distinct(i))
        deadline = time.monotonic() + 5
        while conn.inbound.qsize() < 4_000 and time.monotonic() < deadline:
            time.sleep(0.01)
        started = time.monotonic()
        assert conn.get(0.0) is None
        assert time.monotonic() - started < 0.05
        assert conn.inbound.qsize() > 3_000  # it returned long before draining them all
    finally:
        conn.close()


def test_a_flood_the_consumer_cannot_keep_up_with_is_dropped_and_counted(monkeypatch):
    from pdcp_studio.bus import connection

    monkeypatch.setattr(connection, "INBOUND_MAX", 100)
    bus = can.Bus(interface="virtual", channel=unique_virtual_channel("pdcp-flood"))
    conn = Connection(bus, name="flooded")
    try:
        for i in range(300):
            conn._listener(can.Message(arbitration_id=0x100, data=i.to_bytes(2, "little"),
                                       is_extended_id=False))
        assert conn.inbound.qsize() == 100 and conn.dropped == 200
        conn.post(lambda: None)  # the consumer's own requests always get through
        assert conn.inbound.qsize() == 101
    finally:
        conn.close()
