"""Long runs on an echoing bus: the per-frame bookkeeping stays bounded and never fails.

python-can's virtual bus with ``receive_own_messages=True`` hands every frame back to its
sender, as ``udp_multicast`` does across processes; a connection told to drop its own frames
must keep working for any number of distinct frames (issue 15: it died after 4,096).
"""

from __future__ import annotations

import can

from pdcp_studio.bus.connection import ECHO_MAX_PENDING, Connection, EchoFilter
from pdcp_studio.bus.urls import unique_virtual_channel


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
