"""The bus-time model against known values and an independent bit-level reference.

Known values: the worst-case lengths of Davis et al. (2007) eq. (1) for base frames — 55 bits
for DLC 0 … 135 bits for DLC 8, the figure quoted for an 8-byte standard frame at 1 Mbit/s;
the CRC-15/CAN check value 0x059E for "123456789" (the CRC catalogue's check string); and an
all-dominant frame (ID 0, DLC 0) whose CRC is 0, so its 34 stuffed-region bits are all 0 and
get a stuff bit after every fifth: 6 stuff bits, 34 + 6 + 13 = 53 bits.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.bustime import (
    BusTimeMeter,
    crc15,
    frame_bits,
    frame_bitstream,
    frame_time_us,
    stuff_bit_count,
    worst_case_bits,
)
from pdcp_studio.protocol import messages as M


def bits_of(data: bytes) -> list[int]:
    return [byte >> shift & 1 for byte in data for shift in range(7, -1, -1)]


def stuffed(bits: list[int]) -> list[int]:
    """Reference stuffer, written as the standard says: watch the transmitted stream itself."""
    out: list[int] = []
    for bit in bits:
        out.append(bit)
        if len(out) >= 5 and len(set(out[-5:])) == 1:
            out.append(1 - bit)
    return out


@pytest.mark.parametrize("dlc, bits", [(0, 55), (1, 65), (2, 75), (3, 85), (4, 95),
                                       (5, 105), (6, 115), (7, 125), (8, 135)])
def test_worst_case_lengths(dlc, bits):
    assert worst_case_bits(dlc) == bits
    assert frame_bits(0x305, bytes(dlc), worst_case=True) == bits
    assert frame_time_us(0x305, bytes(dlc), worst_case=True) == bits  # 1 µs per bit at 1 Mbit/s
    assert frame_time_us(0x305, bytes(dlc), worst_case=True, bitrate=500_000) == 2 * bits


def test_crc15_check_value():
    assert crc15(bits_of(b"123456789")) == 0x059E


def test_all_dominant_frame_exact_length():
    stream = frame_bitstream(0, b"")
    assert stream == [0] * 34
    assert stuff_bit_count(stream) == 6 and frame_bits(0, b"") == 53


def test_stream_layout_of_a_pdcp_frame():
    arbitration_id, data = M.GetParameter(5, 9, 0).encode()  # 0x305: 03 09 00
    stream = frame_bitstream(arbitration_id, data)
    assert len(stream) == 19 + 24 + 15
    assert stream[:12] == [0, *bits_of(b"\x03\x05")[5:]]  # SOF, then the 11 ID bits
    assert stream[12:19] == [0, 0, 0, 0, 0, 1, 1]  # RTR, IDE, r0, DLC 3
    assert stream[19:43] == bits_of(data)
    crc = int("".join(map(str, stream[43:])), 2)
    assert crc == crc15(stream[:43])


@settings(max_examples=400, deadline=None)
@given(st.integers(0, 0x7FF), st.binary(max_size=8))
def test_exact_stuffing_matches_reference_and_bound(arbitration_id, data):
    stream = frame_bitstream(arbitration_id, data)
    sent = stuffed(stream)
    assert stuff_bit_count(stream) == len(sent) - len(stream)
    assert frame_bits(arbitration_id, data) == len(sent) + 13
    assert frame_bits(arbitration_id, data) <= worst_case_bits(len(data))
    # No six equal bits in a row survive stuffing.
    assert "000000" not in "".join(map(str, sent)) and "111111" not in "".join(map(str, sent))


def test_out_of_range_frames_are_refused():
    with pytest.raises(ValueError, match="11-bit"):
        frame_bits(0x800, b"")
    with pytest.raises(ValueError, match="9 data bytes"):
        frame_bits(0x100, bytes(9))
    with pytest.raises(ValueError, match="DLC 9"):
        worst_case_bits(9)


def test_meter_adds_frames_and_reports_load():
    meter = BusTimeMeter()
    assert meter.load() is None and meter.span_s == 0.0
    frames = [M.GetParameter(5, 9, 0).encode(), M.GetParameterResponse(5, 1, 9, 0, b"\x01").encode()]
    for i, (arbitration_id, data) in enumerate(frames * 5):
        meter.add(arbitration_id, data, timestamp=10.0 + i * 0.001)
    expected = 5 * sum(frame_bits(a, d) for a, d in frames)
    assert meter.frames == 10 and meter.bits == expected
    assert meter.bus_time_us == pytest.approx(expected) and meter.span_s == pytest.approx(0.009)
    assert meter.load() == pytest.approx(expected * 1e-6 / 0.009)
    assert meter.load(1.0) == pytest.approx(expected * 1e-6)
    worst = BusTimeMeter(worst_case=True)
    for arbitration_id, data in frames:
        worst.add(arbitration_id, data)
    assert worst.bits == worst_case_bits(3) + worst_case_bits(5) >= 2 * expected / 10
    meter.reset()
    assert meter.bits == meter.frames == 0 and meter.load() is None


# -- the table-driven counts against the bit-by-bit definition ----------------------------------


def plain_bits(arbitration_id: int, data: bytes) -> int:
    stream = frame_bitstream(arbitration_id, data)
    return len(stream) + stuff_bit_count(stream) + 13


@settings(max_examples=600, deadline=None)
@given(st.integers(0, 0x7FF), st.binary(max_size=8))
def test_table_driven_length_equals_bit_by_bit(arbitration_id, data):
    assert frame_bits(arbitration_id, data) == plain_bits(arbitration_id, data)


def test_extremes_that_stuff_most_and_least():
    # Runs of equal bits across byte and chunk boundaries, every length, both identifiers.
    patterns = [b"\x00", b"\xff", b"\x0f", b"\xf0", b"\x1f", b"\xf8", b"\x55", b"\xaa"]
    for arbitration_id in (0, 1, 0x3E0, 0x41F, 0x7FF):
        for n in range(9):
            for p in patterns:
                data = (p * 8)[:n]
                assert frame_bits(arbitration_id, data) == plain_bits(arbitration_id, data)


def test_meter_batches_equal_bit_by_bit_over_many_random_frames():
    rng = random.Random(16)
    frames = [(rng.randrange(0x800), rng.randbytes(rng.randint(0, 8))) for _ in range(10_000)]
    meter = BusTimeMeter()
    for arbitration_id, data in frames:  # more than two batches, the last one partial
        meter.add(arbitration_id, data)
    assert meter.frames == len(frames)
    assert meter.bits == sum(plain_bits(a, d) for a, d in frames)
    with pytest.raises(ValueError):
        meter.add(0x800, b"")
    assert meter.frames == len(frames)  # a refused frame is not counted


def test_frames_no_base_frame_can_be_are_counted_never_indexed():
    """A Vector test capture holds a 29-bit ID marked standard (0x4444444): the fast path
    must count it at its worst case, not index the base-frame tables with it."""
    from pdcp_studio.bus.trace.bustime import BusTimeMeter, worst_case_bits

    meter = BusTimeMeter()
    meter.add_base(0x4444444, bytes(8), 0.0)
    meter.add_base(0x123, bytes(2), 0.001)
    assert meter.frames == 2
    assert meter.bits >= worst_case_bits(8) + 20
