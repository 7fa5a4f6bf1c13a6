"""The fast BLF reader (bus/trace/files/blf.py) reads every capture as python-can's BLFReader does:
the same frames, in the same order, with the same times to the last bit — on files python-can
writes, on hand-built object streams (other tools' object kinds and headers, padding, objects
split between containers, skipped kinds), on random ones (hypothesis), and on damaged files."""

from __future__ import annotations

import struct
import zlib
from decimal import Decimal
from pathlib import Path

import can
import pytest
from can.io import blf
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.files.blf import FastBLFReader, PlainFrame
from pdcp_studio.bus.trace.monitor import CaptureError, read_capture

START = 1_700_000_000.0


def fields(msg) -> tuple:
    """Everything a can.Message says, the data as bytes."""
    return (msg.timestamp, msg.arbitration_id, msg.is_extended_id, msg.is_remote_frame,
            msg.is_error_frame, msg.is_fd, msg.is_rx, msg.bitrate_switch,
            msg.error_state_indicator, msg.dlc, bytes(msg.data), msg.channel)


def read_both(path: Path) -> tuple[list, list]:
    """Both readers' frames; each list ends with the exception's class name if one ended
    it."""
    out = []
    for reader in (blf.BLFReader, FastBLFReader):
        got: list = []
        try:
            with reader(path) as frames:
                got.extend(frames)
        except (blf.BLFParseError, struct.error, zlib.error) as err:
            got.append(type(err).__name__)
        out.append(got)
    return out[0], out[1]


def assert_same(path: Path) -> list:
    """The fast reader's frames equal python-can's (a ``PlainFrame``'s message too)."""
    slow, fast = read_both(path)
    assert len(fast) == len(slow)
    for a, b in zip(slow, fast, strict=True):
        if isinstance(a, str):
            assert isinstance(b, str), b
            continue
        assert fields(b) == fields(a)
        if isinstance(b, PlainFrame):
            message = b.to_message()
            assert isinstance(message, can.Message) and type(message.data) is type(a.data)
            assert fields(message) == fields(a)
        else:
            assert isinstance(b, can.Message)
    return fast


def sample_messages() -> list[can.Message]:
    """Every kind of frame python-can writes to BLF, on three channels."""
    t = START + 0.000_123
    out = []
    for i in range(300):
        kind = i % 10
        common = dict(timestamp=t + i * 0.000_127, channel=i % 3, is_rx=i % 7 != 0)
        if kind == 0:
            out.append(can.Message(arbitration_id=0x1ABCDE0 + i, data=bytes([i % 256] * 8),
                                   is_extended_id=True, **common))
        elif kind == 1:
            out.append(can.Message(arbitration_id=0x123, is_remote_frame=True, dlc=i % 9,
                                   is_extended_id=False, **common))
        elif kind == 2:
            out.append(can.Message(arbitration_id=0x7FF, is_error_frame=True, data=b"\x01\x02",
                                   is_extended_id=False, **common))
        elif kind == 3:
            out.append(can.Message(arbitration_id=0x456, is_fd=True, bitrate_switch=i % 2 == 0,
                                   error_state_indicator=i % 3 == 0,
                                   data=bytes(range(i % 65)) if i % 65 in (
                                       0, 1, 8, 12, 16, 20, 24, 32, 48, 64) else bytes(12),
                                   is_extended_id=False, **common))
        else:
            out.append(can.Message(arbitration_id=(0x100 * kind + i) & 0x7FF,
                                   data=bytes([i % 256, kind] * (i % 5)),
                                   is_extended_id=False, **common))
    return out


def write(path: Path, messages, **kwargs) -> Path:
    with can.BLFWriter(str(path), **kwargs) as writer:
        for msg in messages:
            writer.on_message_received(msg)
    return path


@pytest.mark.parametrize("container", [64, 100, 1000, 128 * 1024])
@pytest.mark.parametrize("compression", [-1, 0])
def test_files_python_can_writes(tmp_path: Path, container: int, compression: int) -> None:
    """Extended, remote, error and FD frames, several channels, objects split between
    containers (small ones: almost every object is), compressed or not."""
    path = write(tmp_path / "c.blf", sample_messages(), max_container_size=container,
                 compression_level=compression)
    fast = assert_same(path)
    assert len(fast) == 300
    assert sum(isinstance(f, PlainFrame) for f in fast) == 180  # the others are Messages


# -- hand-built object streams -------------------------------------------------------------

def obj(obj_type: int, payload: bytes, ticks: int, *, version: int = 1, ten_us: bool = False,
        size_extra: int = 0, padding: int = 0) -> bytes:
    """One object (header version 1 or 2, or an unknown one), then ``padding`` zero bytes."""
    flags = 1 if ten_us else 2
    if version == 2:
        header = blf.OBJ_HEADER_V2_STRUCT.pack(flags, 0, 0, ticks)
    else:  # version 1, and any other number (python-can skips those)
        header = blf.OBJ_HEADER_V1_STRUCT.pack(flags, 0, 0, ticks)
    header_size = blf.OBJ_HEADER_BASE_STRUCT.size + len(header)
    body = header + payload + bytes(size_extra)
    base = blf.OBJ_HEADER_BASE_STRUCT.pack(b"LOBJ", header_size, version,
                                           blf.OBJ_HEADER_BASE_STRUCT.size + len(body),
                                           obj_type)
    return base + body + bytes(padding)


def can_msg(channel: int, flags: int, dlc: int, can_id: int, data: bytes) -> bytes:
    return blf.CAN_MSG_STRUCT.pack(channel, flags, dlc, can_id, data)


def fd64(channel: int, dlc: int, valid: int, can_id: int, fd_flags: int, direction: int,
         data: bytes, ext_offset: int = 0) -> bytes:
    return blf.CAN_FD_MSG_64_STRUCT.pack(channel, dlc, valid, 0, can_id, 0, fd_flags, 0, 0, 0,
                                         0, 0, direction, ext_offset, 0) + data


def blf_file(path: Path, stream: bytes, cuts: list[int], *, methods=None,
             start: tuple = (2023, 11, 2, 14, 22, 13, 20, 250)) -> Path:
    """A BLF file of ``stream`` cut into containers at ``cuts`` (each compressed with zlib
    unless ``methods`` says otherwise: 0 none, 2 zlib, anything else unknown)."""
    pieces, last = [], 0
    for cut in [*sorted(set(cuts)), len(stream)]:
        if cut > last:
            pieces.append(stream[last:cut])
            last = cut
    body = bytearray()
    for k, piece in enumerate(pieces):
        method = 2 if methods is None else methods[k % len(methods)]
        data = zlib.compress(piece) if method == 2 else piece
        size = blf.OBJ_HEADER_BASE_STRUCT.size + blf.LOG_CONTAINER_STRUCT.size + len(data)
        body += blf.OBJ_HEADER_BASE_STRUCT.pack(b"LOBJ", 16, 1, size, blf.LOG_CONTAINER)
        body += blf.LOG_CONTAINER_STRUCT.pack(method, len(piece)) + data + bytes(size % 4)
    header = blf.FILE_HEADER_STRUCT.pack(b"LOGG", blf.FILE_HEADER_SIZE, 5, 0, 0, 0, 2, 6, 8, 1,
                                         0, 0, 0, 0, *start, *start)
    path.write_bytes(header + bytes(blf.FILE_HEADER_SIZE - len(header)) + bytes(body))
    return path


def other_tools_stream() -> bytes:
    """Objects other tools write: CAN_MESSAGE2 with its extra fields, version-2 headers,
    10 µs times, CAN_FD_MESSAGE_64 (with the data shorter than it says), markers and
    unknown kinds, an unknown header version, padding between objects."""
    parts = [
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 8, 0x123, bytes(range(8))), 1_000),
        obj(blf.CAN_MESSAGE2, can_msg(2, blf.DIR, 4, 0x124, b"\x01\x02\x03\x04" + bytes(4))
            + bytes(8), 2_000, size_extra=0),
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 3, 0x125, b"abc" + bytes(5)), 300, ten_us=True),
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 2, 0x126, b"xy" + bytes(6)), 4_000, version=2),
        obj(blf.CAN_MESSAGE, can_msg(3, blf.REMOTE_FLAG, 5, 0x127, bytes(8)), 5_000),
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 8, 0x80000000 | 0x18FF00AA, bytes(8)), 6_000,
            padding=4),
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 12, 0x128, bytes(range(8))), 6_500),  # dlc > 8
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 1, 0x60000129, b"\x07" + bytes(7)), 6_600),
        obj(blf.GLOBAL_MARKER, blf.GLOBAL_MARKER_STRUCT.pack(0, 0, 0, 0, 1, 1, 1) + b"abc",
            7_000, padding=3),
        obj(999, b"something else" + bytes(2), 8_000),
        obj(blf.CAN_MESSAGE, can_msg(1, 0, 8, 0x12A, bytes(8)), 8_500, version=3),
        obj(blf.CAN_FD_MESSAGE_64, fd64(1, 13, 32, 0x12B, 0x3000, 1, bytes(range(20))), 9_000),
        obj(blf.CAN_FD_MESSAGE_64, fd64(2, 9, 12, 0x8000012C, 0x5010, 0, bytes(range(12))),
            10_000, version=2),
        obj(blf.CAN_FD_MESSAGE, blf.CAN_FD_MSG_STRUCT.pack(1, 0, 10, 0x12D, 0, 0, 0x7, 16,
                                                           bytes(range(64))), 11_000),
        obj(blf.CAN_ERROR_EXT, blf.CAN_ERROR_EXT_STRUCT.pack(1, 0, 0, 0, 0, 3, 0, 0x12E, 0,
                                                             b"\x01\x02\x03" + bytes(5)),
            12_000),
        obj(blf.CAN_MESSAGE2, can_msg(1, 0, 8, 0x12F, bytes(range(8, 16))), 2**63 + 12_345),
    ]
    return b"".join(parts)


def test_other_tools_objects(tmp_path: Path) -> None:
    stream = other_tools_stream()
    fast = assert_same(blf_file(tmp_path / "o.blf", stream, [], methods=[0]))
    assert len(fast) == 13  # the marker, the unknown kind and header version are skipped


def test_objects_split_at_every_byte(tmp_path: Path) -> None:
    """An object may end in the next container, wherever the cut falls."""
    stream = other_tools_stream()
    for cut in range(0, len(stream), 3):
        assert len(assert_same(blf_file(tmp_path / "s.blf", stream, [cut, cut + 50]))) == 13


def test_unknown_compression_and_no_start(tmp_path: Path) -> None:
    """A container of an unknown compression is skipped (python-can warns); a file without
    a start time counts from 0."""
    stream = other_tools_stream()
    path = blf_file(tmp_path / "u.blf", stream, [96, 200, 400], methods=[2, 0, 7],
                    start=(0,) * 8)
    assert_same(path)


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_random_object_streams(tmp_path: Path, data) -> None:
    """Random frames and objects, cut into containers at random places."""
    parts = []
    for _ in range(data.draw(st.integers(0, 25))):
        kind = data.draw(st.sampled_from(["can", "can2", "fd64", "fd", "error", "marker"]))
        ticks = data.draw(st.integers(0, 2**64 - 1))
        version = data.draw(st.sampled_from([1, 1, 2]))
        ten_us = data.draw(st.booleans())
        padding = data.draw(st.integers(0, 4))
        can_id = data.draw(st.integers(0, 2**32 - 1) | st.integers(0, 0x7FF))
        channel = data.draw(st.integers(0, 5))
        if kind in ("can", "can2"):
            flags = data.draw(st.sampled_from([0, blf.DIR, blf.REMOTE_FLAG, 0x81]))
            payload = can_msg(channel, flags, data.draw(st.integers(0, 15)), can_id,
                              data.draw(st.binary(min_size=8, max_size=8)))
            obj_type = blf.CAN_MESSAGE if kind == "can" else blf.CAN_MESSAGE2
        elif kind == "fd64":
            body = data.draw(st.binary(max_size=64))
            payload = fd64(channel, data.draw(st.integers(0, 15)),
                           data.draw(st.integers(0, 64)), can_id,
                           data.draw(st.integers(0, 0xFFFF)), data.draw(st.integers(0, 1)),
                           body)
            obj_type = blf.CAN_FD_MESSAGE_64
        elif kind == "fd":
            payload = blf.CAN_FD_MSG_STRUCT.pack(
                channel, data.draw(st.integers(0, 255)), data.draw(st.integers(0, 15)),
                can_id, 0, 0, data.draw(st.integers(0, 7)), data.draw(st.integers(0, 64)),
                data.draw(st.binary(min_size=64, max_size=64)))
            obj_type = blf.CAN_FD_MESSAGE
        elif kind == "error":
            payload = blf.CAN_ERROR_EXT_STRUCT.pack(
                channel, 0, 0, 0, 0, data.draw(st.integers(0, 15)), 0, can_id, 0,
                data.draw(st.binary(min_size=8, max_size=8)))
            obj_type = blf.CAN_ERROR_EXT
        else:
            payload = data.draw(st.binary(max_size=40))
            obj_type = data.draw(st.sampled_from([blf.GLOBAL_MARKER, 65, 115]))
        parts.append(obj(obj_type, payload, ticks, version=version, ten_us=ten_us,
                         padding=padding))
    stream = b"".join(parts)
    cuts = data.draw(st.lists(st.integers(0, max(len(stream), 1)), max_size=6))
    methods = data.draw(st.lists(st.sampled_from([0, 2]), min_size=1, max_size=3))
    start = data.draw(st.sampled_from([(2023, 11, 2, 14, 22, 13, 20, 250), (0,) * 8,
                                       (1999, 1, 5, 1, 0, 0, 59, 999)]))
    assert_same(blf_file(tmp_path / "h.blf", stream, cuts, methods=methods, start=start))


@given(ticks=st.integers(0, 2**64 - 1), ten_us=st.booleans(),
       start=st.floats(0, 4e9, allow_nan=False))
def test_times_are_python_cans_to_the_bit(ticks: int, ten_us: bool, start: float) -> None:
    """``ticks / 10**5`` is ``float(Decimal(ticks) * Decimal("1e-5"))``: both are the
    correctly rounded quotient (and so for nanoseconds)."""
    factor = blf.TIME_TEN_MICS_FACTOR if ten_us else blf.TIME_ONE_NANS_FACTOR
    expected = float(Decimal(ticks) * factor) + start
    assert (ticks / 100_000 if ten_us else ticks / 1_000_000_000) + start == expected


# -- damaged files -------------------------------------------------------------------------

def test_truncated_anywhere(tmp_path: Path) -> None:
    """Cut short anywhere, a capture yields the frames python-can's reader yields before it
    ends or fails, and fails where it fails."""
    whole = write(tmp_path / "w.blf", sample_messages()[:120], max_container_size=700)
    data = whole.read_bytes()
    cut_path = tmp_path / "cut.blf"
    for cut in [*range(blf.FILE_HEADER_SIZE, len(data), 37), len(data) - 1]:
        cut_path.write_bytes(data[:cut])
        assert_same(cut_path)


def test_corrupt_bytes(tmp_path: Path) -> None:
    """A byte changed in an uncompressed container: the same frames, the same failure."""
    whole = write(tmp_path / "w.blf", sample_messages()[:60], max_container_size=500,
                  compression_level=0)
    data = whole.read_bytes()
    bad = tmp_path / "bad.blf"
    for at in range(blf.FILE_HEADER_SIZE + 40, len(data), 23):
        for value in (0x00, 0x4C, 0xFF):
            if value == 0 and data[at - 8:at - 4] == b"LOBJ":
                continue  # an object of 0 bytes: python-can's loop never ends (see below)
            changed = bytearray(data)
            changed[at] = value
            bad.write_bytes(bytes(changed))
            slow, fast = read_both(bad)
            if slow and slow[-1] == "error":
                assert fast[-1] == "BLFParseError"  # python-can raises struct.error there
                slow, fast = slow[:-1], fast[:-1]
            assert [f if isinstance(f, str) else fields(f) for f in fast] == \
                [f if isinstance(f, str) else fields(f) for f in slow]


def test_failure_names_the_byte_and_the_file(tmp_path: Path) -> None:
    """The fast reader's failure says how far into the file it had read; read_capture names
    the file."""
    whole = write(tmp_path / "w.blf", sample_messages()[:60], max_container_size=500,
                  compression_level=0)
    data = bytearray(whole.read_bytes())
    at = data.index(b"LOBJ", data.index(b"LOBJ") + 40)  # an object inside the first container
    data[at:at + 4] = b"XXXX"
    bad = tmp_path / "bad.blf"
    bad.write_bytes(bytes(data))
    with pytest.raises(blf.BLFParseError, match=r"Could not find next object \(before byte \d+\)"):
        list(FastBLFReader(bad))
    with pytest.raises(CaptureError, match=r"bad\.blf: offset \d+: damaged \(Could not find"):
        list(read_capture(bad, plain_frames=True))


def test_an_object_of_no_bytes_fails(tmp_path: Path) -> None:
    """python-can's loop would read an object that says it has 0 bytes forever."""
    good = obj(blf.CAN_MESSAGE, can_msg(1, 0, 8, 0x123, bytes(8)), 1_000)
    empty = bytearray(good)
    struct.pack_into("<L", empty, 8, 0)
    path = blf_file(tmp_path / "z.blf", good + bytes(empty) + good, [], methods=[0])
    frames = []
    with pytest.raises(blf.BLFParseError, match="object of 0 bytes"):
        frames.extend(FastBLFReader(path))
    assert len(frames) == 1


def test_read_capture_plain_frames(tmp_path: Path) -> None:
    """Only asked for, and only for BLF, does read_capture give PlainFrames."""
    msgs = sample_messages()
    path = write(tmp_path / "r.BLF", msgs)
    plain = list(read_capture(path, plain_frames=True))
    assert any(isinstance(f, PlainFrame) for f in plain)
    assert all(isinstance(m, can.Message) for m in read_capture(path))
    assert [fields(f) for f in plain] == [fields(m) for m in read_capture(path)]


def test_another_python_can_falls_back_to_its_reader(tmp_path: Path, monkeypatch) -> None:
    """Where python-can's reader lacks the methods the fast one builds on, its own reads."""
    from pdcp_studio.bus.trace.files import blf as blf_read

    path = write(tmp_path / "f.blf", sample_messages())
    assert blf_read.COMPATIBLE
    monkeypatch.setattr(blf_read, "COMPATIBLE", False)
    assert all(isinstance(m, can.Message) for m in read_capture(path, plain_frames=True))
