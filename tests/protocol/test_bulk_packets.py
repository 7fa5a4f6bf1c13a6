"""Bulk transfer: 6-byte packets numbered from 1 (001 §3.3.6–3.3.7)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.bulk import (
    MAX_PAYLOAD,
    PACKET_SIZE,
    BulkReassembler,
    Packet,
    packet_count,
    packetize,
)


def test_limits() -> None:
    assert PACKET_SIZE == 6
    assert MAX_PAYLOAD == 1530


@pytest.mark.parametrize(
    ("size", "lengths"),
    [(0, []), (1, [1]), (6, [6]), (7, [6, 1]), (17, [6, 6, 5]), (33, [6, 6, 6, 6, 6, 3])],
)
def test_packetize_sizes(size: int, lengths: list[int]) -> None:
    packets = packetize(bytes(range(size)))
    assert [len(p.data) for p in packets] == lengths
    assert [p.packet_id for p in packets] == list(range(1, len(lengths) + 1))
    assert packet_count(size) == len(lengths)


def test_packetize_17_bytes_as_in_001() -> None:
    assert packetize(bytes(range(1, 18))) == [
        Packet(1, bytes([1, 2, 3, 4, 5, 6])),
        Packet(2, bytes([7, 8, 9, 10, 11, 12])),
        Packet(3, bytes([13, 14, 15, 16, 17])),
    ]


def test_packetize_limit() -> None:
    packets = packetize(bytes(MAX_PAYLOAD))
    assert len(packets) == 255 and packets[-1].packet_id == 255
    with pytest.raises(FrameError, match="1531 bytes does not fit: at most 1530"):
        packetize(bytes(MAX_PAYLOAD + 1))


def test_reassembler_in_order() -> None:
    r = BulkReassembler(8)
    assert not r.complete and r.next_packet_id == 1
    assert r.add(1, b"abcdef") is False
    assert r.received == 6 and r.next_packet_id == 2
    assert r.add(2, bytearray(b"gh")) is True
    assert r.complete and r.result() == b"abcdefgh"


def test_empty_transfer_is_complete_at_once() -> None:
    r = BulkReassembler(0)
    assert r.complete and r.result() == b""


@pytest.mark.parametrize("size", [-1, MAX_PAYLOAD + 1, 65535])
def test_reassembler_rejects_impossible_size(size: int) -> None:
    with pytest.raises(FrameError, match="does not fit"):
        BulkReassembler(size)


def test_wrong_packet_id() -> None:
    r = BulkReassembler(12)
    with pytest.raises(FrameError, match="bulk packet 2 arrived, packet 1 expected"):
        r.add(2, b"abcdef")
    r.add(1, b"abcdef")
    with pytest.raises(FrameError, match="bulk packet 1 arrived, packet 2 expected"):
        r.add(1, b"abcdef")  # a repeat


def test_overflow_and_short_packets() -> None:
    r = BulkReassembler(8)
    with pytest.raises(FrameError, match="carries 5 bytes and is short"):
        r.add(1, b"abcde")
    r.add(1, b"abcdef")
    with pytest.raises(FrameError, match="carries 3 bytes and overflows the transfer"):
        r.add(2, b"ghi")
    r.add(2, b"gh")
    with pytest.raises(FrameError, match="already complete"):
        r.add(3, b"x")


def test_too_long_packet() -> None:
    with pytest.raises(FrameError, match="carries 7 bytes and is too long"):
        BulkReassembler(20).add(1, b"1234567")


def test_result_before_the_end() -> None:
    r = BulkReassembler(7)
    r.add(1, b"abcdef")
    with pytest.raises(FrameError, match="incomplete: 6 of 7 bytes"):
        r.result()


@given(st.binary(max_size=MAX_PAYLOAD))
def test_packetize_then_reassemble(payload: bytes) -> None:
    r = BulkReassembler(len(payload))
    for packet in packetize(payload):
        assert 1 <= len(packet.data) <= PACKET_SIZE
        r.add(*packet)
    assert r.result() == payload
