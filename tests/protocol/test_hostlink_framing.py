"""Host-link framing: messages survive the line; garbage and bad CRCs cost one message."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import hostlink as hl


def test_crc_check_value():
    # the standard check value of CRC-16/CCITT-FALSE
    assert hl.crc16_ccitt_false(b"123456789") == 0x29B1


def test_message_round_trip_byte_by_byte():
    msg = hl.HostMessage(hl.HostCommand.GET_PARAMETER, hl.pack_param(2, 2, 5, 1, 9))
    reader = hl.FrameReader()
    got = []
    for b in msg.encode():
        got += reader.feed(bytes([b]))
    assert got == [msg] and reader.errors == 0


def test_garbage_and_bad_crc_are_skipped():
    a = hl.HostMessage(0x10, b"one").encode()
    b = bytearray(hl.HostMessage(0x13, b"two").encode())
    b[-1] ^= 0xFF
    c = hl.HostMessage(0x16, b"three").encode()
    reader = hl.FrameReader()
    got = reader.feed(b"\x00\x01junk" + a + bytes(b) + c)
    assert [m.payload for m in got] == [b"one", b"three"]
    assert reader.errors >= 2


def test_reply_ids_come_in_threes():
    assert hl.reply_ok(hl.HostCommand.PING) == 0x11
    assert hl.reply_fail(hl.HostCommand.PING) == 0x12


def test_payload_helpers_check_sizes():
    assert hl.unpack_key(hl.pack_key(1, 2, 3)) == (1, 2, 3)
    out, inp = hl.unpack_link(hl.pack_link((2, 2, 4, 1), (2, 2, 5, 2)))
    assert out == (2, 2, 4, 1) and inp == (2, 2, 5, 2)
    addr, value = hl.unpack_param(hl.pack_param(2, 2, 5, 1, 4, b"\x01"))
    assert addr == (2, 2, 5, 1, 4) and value == b"\x01"
    with pytest.raises(FrameError):
        hl.unpack_key(b"\x00")
    with pytest.raises(FrameError):
        hl.unpack_link(b"\x00" * 5)
    with pytest.raises(FrameError):
        hl.HostMessage(0x100).encode()


@given(st.lists(st.tuples(st.integers(0, 255), st.binary(max_size=300)), max_size=8),
       st.integers(1, 64))
def test_any_chunking_gives_the_same_messages(items, chunk):
    msgs = [hl.HostMessage(i, p) for i, p in items]
    stream = b"".join(m.encode() for m in msgs)
    reader = hl.FrameReader()
    got = []
    for k in range(0, len(stream), chunk):
        got += reader.feed(stream[k : k + chunk])
    assert got == msgs


@given(st.binary(max_size=2000))
def test_any_bytes_never_raise(data):
    hl.FrameReader().feed(data)
