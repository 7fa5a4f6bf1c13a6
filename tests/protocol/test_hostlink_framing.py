"""Host link 2 framing: COBS frames survive the line; garbage and bad CRCs cost one frame."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import hostlink as hl
from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind


def test_crc_check_value():
    assert hl.crc16_ccitt_false(b"123456789") == 0x29B1


@given(st.binary(max_size=600))
def test_cobs_round_trip_has_no_zero(data):
    encoded = hl.cobs_encode(data)
    assert 0 not in encoded
    assert hl.cobs_decode(encoded) == data
    assert len(encoded) <= len(data) + len(data) // 254 + 1


@given(st.sampled_from(list(Kind)), st.integers(0, 255), st.binary(max_size=255))
def test_frame_round_trip_byte_by_byte(kind, seq, payload):
    wire = Frame(kind, seq, payload).encode()
    assert wire.endswith(b"\x00") and wire.count(0) == 1
    assert len(wire) <= hl.MAX_WIRE
    reader = FrameReader()
    got = []
    for b in wire:
        got += reader.feed(bytes([b]))
    assert got == [Frame(kind, seq, payload)]


def test_oversize_payload_is_refused_on_encode():
    with pytest.raises(FrameError, match="256 bytes > 255"):
        Frame(Kind.DATA, 0, bytes(256)).encode()


def test_garbage_before_and_between_frames_costs_nothing_else():
    a, b = Frame(Kind.DATA, 1, b"\x03\x00\x00"), Frame(Kind.ACK, 7)
    reader = FrameReader()
    out = reader.feed(b"\x13\x37\xff\x00" + a.encode() + b"\x00\x00garbage\x00" + b.encode())
    frames = [f for f in out if isinstance(f, Frame)]
    assert frames == [a, b]
    assert reader.errors == 2  # the two garbage runs, each ended by a delimiter


def test_a_flipped_bit_is_caught_and_the_next_frame_still_arrives():
    a, b = Frame(Kind.DATA, 1, b"\x05hello"), Frame(Kind.DATA, 2, b"\x05world")
    wire = bytearray(a.encode())
    wire[4] ^= 0x10
    out = FrameReader().feed(bytes(wire) + b.encode())
    assert isinstance(out[0], FrameError) and out[1] == b


def test_a_run_longer_than_any_frame_is_dropped_with_bounded_memory():
    reader = FrameReader()
    out = reader.feed(b"\x01" * 5000 + b"\x00" + Frame(Kind.ACK, 3).encode())
    assert isinstance(out[0], FrameError) and "oversize" in str(out[0])
    assert out[1] == Frame(Kind.ACK, 3)
    assert len(reader._buf) == 0


def test_length_byte_must_match():
    raw = bytes([Kind.DATA, 0, 5]) + b"abc"
    wire = hl.cobs_encode(raw + hl.crc16_ccitt_false(raw).to_bytes(2, "big"))
    with pytest.raises(FrameError, match="length byte 5"):
        hl.parse_frame(wire)


@given(st.binary(max_size=2000))
def test_any_bytes_in_only_frames_or_frame_errors_out(data):
    for item in FrameReader().feed(data):
        assert isinstance(item, Frame | FrameError)
