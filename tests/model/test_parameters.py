"""The parameter catalog (reference §1 "Parameters") and its value layouts."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.errors import ParameterError
from pdcp_studio.model import parameters as p
from pdcp_studio.model.refs import Direction


def test_id_constants() -> None:
    assert (p.DEVICE_VID_PID, p.DEVICE_SERIAL, p.DEVICE_EAN_LOW, p.DEVICE_EAN_HIGH) == (1, 2, 3, 4)
    assert (p.DEVICE_VERSION, p.DEVICE_TYPE_PROFILE, p.DEVICE_DESCRIPTOR, p.DEVICE_NODE_ID) == (5, 6, 7, 8)
    assert (p.DEVICE_CHANNEL_COUNT, p.DEVICE_BEACON_INTERVAL, p.DEVICE_ACK_TIMEOUT) == (9, 10, 11)
    assert p.DEVICE_BIND_TIMEOUT == 12
    assert (p.CH_TYPE_PROFILE, p.CH_DESCRIPTOR, p.CH_TRANSFER_TYPE, p.CH_DATA_ENABLED) == (1, 2, 3, 4)
    assert (p.IN_SOURCE_VID_PID, p.IN_SOURCE_SN_INDEX, p.IN_SOURCE_NODE_IDS) == (5, 6, 7)
    assert (p.IN_SOURCE_TYPE_PROFILE, p.OUT_NODE_ID, p.IN_TERMINAL_PROFILE) == (8, 5, 11)
    assert (p.CH_REQUIRED_INPUTS, p.CH_DESIRED_INPUTS) == (9, 10)


def test_catalog_matches_the_reference_table() -> None:
    assert [s.id for s in p.parameters_for("device")] == list(range(1, 13))
    assert [s.id for s in p.parameters_for(Direction.INPUT)] == list(range(1, 12))
    assert [s.id for s in p.parameters_for("output")] == [1, 2, 3, 4, 5, 9, 10]
    assert p.device_parameter(9).name == "Number of Data Channels"
    assert p.channel_parameter(5, Direction.INPUT).name == "Source's VID and PID"
    assert p.channel_parameter(5, "output").name == "Channel Node Id"
    assert p.channel_parameter(11, Direction.INPUT).name == "Terminal Profile"
    for scope in ("device", "input", "output"):
        assert all(s.scope == scope for s in p.parameters_for(scope))


@pytest.mark.parametrize(
    ("spec", "layout", "size"),
    [
        (p.device_parameter(p.DEVICE_VID_PID), "pair16", 4),
        (p.device_parameter(p.DEVICE_SERIAL), "u16", 2),
        (p.device_parameter(p.DEVICE_EAN_LOW), "u32", 4),
        (p.device_parameter(p.DEVICE_EAN_HIGH), "u32", 4),
        (p.device_parameter(p.DEVICE_VERSION), "pair16", 4),
        (p.device_parameter(p.DEVICE_DESCRIPTOR), "string", 1530),
        (p.device_parameter(p.DEVICE_NODE_ID), "u8", 1),
        (p.device_parameter(p.DEVICE_CHANNEL_COUNT), "u8", 1),
        (p.device_parameter(p.DEVICE_BEACON_INTERVAL), "u16", 2),
        (p.device_parameter(p.DEVICE_ACK_TIMEOUT), "u16", 2),
        (p.device_parameter(p.DEVICE_BIND_TIMEOUT), "u16", 2),
        (p.channel_parameter(p.CH_TYPE_PROFILE, "input"), "pair16", 4),
        (p.channel_parameter(p.CH_TRANSFER_TYPE, "output"), "u8", 1),
        (p.channel_parameter(p.CH_DATA_ENABLED, "output"), "u8", 1),
        (p.channel_parameter(p.IN_SOURCE_SN_INDEX, "input"), "sn_index", 3),
        (p.channel_parameter(p.IN_SOURCE_NODE_IDS, "input"), "node_ids", 2),
        (p.channel_parameter(p.IN_SOURCE_TYPE_PROFILE, "input"), "pair16", 4),
        (p.channel_parameter(p.IN_TERMINAL_PROFILE, "input"), "u16", 2),
        (p.channel_parameter(p.CH_REQUIRED_INPUTS, "output"), "bitmap", 32),
        (p.channel_parameter(p.OUT_NODE_ID, "output"), "u8", 1),
    ],
    ids=lambda v: getattr(v, "name", str(v)),
)
def test_layouts(spec: p.ParameterSpec, layout: str, size: int) -> None:
    assert (spec.layout, spec.size) == (layout, size)
    assert spec.bulk is (layout == "string")


def test_units_and_writability() -> None:
    timing = [p.DEVICE_BEACON_INTERVAL, p.DEVICE_ACK_TIMEOUT, p.DEVICE_BIND_TIMEOUT]
    assert all(p.device_parameter(i).unit == "ms" for i in timing)
    writable_device = {s.id for s in p.parameters_for("device") if s.writable}
    assert writable_device == {7, 8, 10, 11, 12}
    assert {s.id for s in p.parameters_for("input") if s.writable} == {1, 2, 4, 5, 6, 7, 8, 9, 10, 11}
    assert {s.id for s in p.parameters_for("output") if s.writable} == {1, 2, 4, 5, 9, 10}
    p.require_writable(p.channel_parameter(p.OUT_NODE_ID, "output"))
    with pytest.raises(ParameterError, match=r"Transfer Type \(input parameter 3\) is read-only"):
        p.require_writable(p.channel_parameter(p.CH_TRANSFER_TYPE, "input"))


def test_unknown_lookups() -> None:
    with pytest.raises(ParameterError, match="device parameter 13 is not in the catalog"):
        p.device_parameter(13)
    with pytest.raises(ParameterError, match="output channel parameter 6"):
        p.channel_parameter(6, Direction.OUTPUT)
    with pytest.raises(ParameterError, match="input or output"):
        p.channel_parameter(1, "device")
    with pytest.raises(ParameterError, match="unknown parameter scope"):
        p.parameters_for("sideways")  # type: ignore[arg-type]


def test_parameter_names() -> None:
    assert p.parameter_name(9, 0) == "Number of Data Channels"
    assert p.parameter_name(9, 0, Direction.INPUT) == "Number of Data Channels"  # index 0 wins
    assert p.parameter_name(1, 3) == "Channel Type and Profile"
    assert p.parameter_name(5, 1) == "Source's VID and PID / Channel Node Id"
    assert p.parameter_name(5, 1, Direction.OUTPUT) == "Channel Node Id"
    assert p.parameter_name(6, 2) == "Source's SN and Channel Index"
    assert p.parameter_name(0x37, 0) == "Device Parameter 55"
    assert p.parameter_name(40, 2) == "Channel Parameter 40"
    assert p.parameter_name(6, 2, "output") == "Channel Parameter 6"


def test_find_parameter() -> None:
    assert p.find_parameter(7, 0) is p.device_parameter(7)
    assert p.find_parameter(1, 2) is not None
    assert p.find_parameter(5, 2) is None  # ambiguous without a direction
    assert p.find_parameter(5, 2, Direction.OUTPUT) is p.channel_parameter(5, "output")
    assert p.find_parameter(11, 2) is p.channel_parameter(11, "input")
    assert p.find_parameter(99, 0) is None


def _spec(pid: int, scope: str = "device") -> p.ParameterSpec:
    return p.device_parameter(pid) if scope == "device" else p.channel_parameter(pid, scope)


@pytest.mark.parametrize(
    ("pid", "scope", "value", "data"),
    [
        (p.DEVICE_VID_PID, "device", (0x0001, 0x000A), "01 00 0A 00"),
        (p.DEVICE_SERIAL, "device", 4, "04 00"),
        (p.DEVICE_EAN_LOW, "device", 0x12345678, "78 56 34 12"),
        (p.DEVICE_NODE_ID, "device", 5, "05"),
        (p.DEVICE_CHANNEL_COUNT, "device", 1, "01"),  # 001 §3.3.2
        (p.DEVICE_BEACON_INTERVAL, "device", 100, "64 00"),
        (p.CH_TYPE_PROFILE, "input", (0x7300, 0x4620), "00 73 20 46"),
        (p.OUT_NODE_ID, "output", 6, "06"),  # 001 §3.3.3
        (p.IN_SOURCE_VID_PID, "input", (0xFFFF, 0xFFFF), "FF FF FF FF"),  # not connected
        (p.IN_SOURCE_SN_INDEX, "input", (0x0004, 2), "04 00 02"),
        (p.IN_SOURCE_SN_INDEX, "input", (0xFFFF, 0xFF), "FF FF FF"),
        (p.IN_SOURCE_NODE_IDS, "input", (5, 6), "05 06"),
        (p.IN_TERMINAL_PROFILE, "input", 0x2220, "20 22"),
        (p.CH_REQUIRED_INPUTS, "output", (1,), "40"),  # appendix D: 64 → input 1
        (p.CH_DESIRED_INPUTS, "output", (2,), "20"),  # appendix D: 32 → input 2
        (p.CH_REQUIRED_INPUTS, "input", (), "00"),
        (p.CH_REQUIRED_INPUTS, "input", (0, 8, 15), "80 81"),
        (p.DEVICE_DESCRIPTOR, "device", "Prototype PDCP Device Descriptor",
         b"Prototype PDCP Device Descriptor\0".hex()),  # 001 §3.3.6, 33 bytes
        (p.CH_DESCRIPTOR, "output", "", "00"),
    ],
)
def test_encode_decode_values(pid: int, scope: str, value: object, data: str) -> None:
    spec = _spec(pid, scope)
    raw = bytes.fromhex(data)
    assert p.encode_value(spec, value) == raw
    assert p.decode_value(spec, raw) == value


def test_list_pairs_are_accepted() -> None:
    assert p.encode_value(_spec(p.DEVICE_VID_PID), [1, 2]) == bytes.fromhex("01 00 02 00")


@pytest.mark.parametrize(
    ("pid", "scope", "value", "match"),
    [
        (p.DEVICE_NODE_ID, "device", 256, r"^Device Node Id: value 256 is out of range \(0–255\)$"),
        (p.DEVICE_SERIAL, "device", -1, r"Serial Number: value -1 is out of range"),
        (p.DEVICE_EAN_HIGH, "device", 2**32, r"EAN13 high: value 4294967296"),
        (p.DEVICE_BEACON_INTERVAL, "device", "100", r"Beacon Interval: value '100' is not an integer"),
        (p.DEVICE_VID_PID, "device", 1, r"VID and PID: value 1 is not a pair"),
        (p.DEVICE_VID_PID, "device", (1, 0x10000), r"VID and PID: Y 65536 is out of range"),
        (p.IN_SOURCE_SN_INDEX, "input", (1, 256), r"channel index 256 is out of range"),
        (p.IN_SOURCE_NODE_IDS, "input", (-1, 1), r"device node ID -1"),
        (p.CH_REQUIRED_INPUTS, "input", (256,), r"Required Input Channels: channel index 256"),
        (p.CH_DESIRED_INPUTS, "input", "12", r"not a collection of indices"),
        (p.DEVICE_DESCRIPTOR, "device", 5, r"Device Descriptor: value 5 is not a string"),
        (p.DEVICE_DESCRIPTOR, "device", "a\0b", r"cannot contain NUL"),
        (p.DEVICE_DESCRIPTOR, "device", "x" * 1530, r"1531 bytes with the terminator"),
    ],
)
def test_encode_rejects(pid: int, scope: str, value: object, match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        p.encode_value(_spec(pid, scope), value)


@pytest.mark.parametrize(
    ("pid", "scope", "data", "match"),
    [
        (p.DEVICE_SERIAL, "device", "04", r"^Serial Number: 1 bytes, expected 2 \(u16\)$"),
        (p.DEVICE_VID_PID, "device", "01 00 0A 00 00", r"5 bytes, expected 4 \(pair16\)"),
        (p.IN_SOURCE_SN_INDEX, "input", "", r"Source's SN and Channel Index: 0 bytes"),
        (p.CH_REQUIRED_INPUTS, "input", "", r"0 bytes, expected 1–32 \(bit string\)"),
        (p.CH_REQUIRED_INPUTS, "input", "00" * 33, r"33 bytes"),
    ],
)
def test_decode_rejects(pid: int, scope: str, data: str, match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        p.decode_value(_spec(pid, scope), bytes.fromhex(data))


def test_strings_decode_leniently() -> None:
    spec = _spec(p.DEVICE_DESCRIPTOR)
    assert p.decode_value(spec, b"Grip") == "Grip"  # no terminator
    assert p.decode_value(spec, b"Grip\0junk") == "Grip"
    assert p.decode_value(spec, "Größe".encode() + b"\0") == "Größe"
    assert p.decode_value(spec, b"\xff\0") == "\ufffd"
    with pytest.raises(ParameterError, match="at most 1530"):
        p.decode_value(spec, bytes(1531))


def test_bitmap_helpers() -> None:
    assert p.bitmap_to_indices(b"\x40") == (1,)
    assert p.bitmap_to_indices(b"\x20") == (2,)
    assert p.bitmap_to_indices(b"\x80\x01") == (0, 15)
    assert p.bitmap_to_indices(b"") == ()
    assert p.indices_to_bitmap([]) == b"\x00"
    assert p.indices_to_bitmap([0]) == b"\x80"
    assert p.indices_to_bitmap([8, 1, 1]) == b"\x40\x80"
    assert p.indices_to_bitmap([1], length=4) == b"\x40\x00\x00\x00"
    assert len(p.indices_to_bitmap([255])) == 32
    with pytest.raises(ParameterError, match="out of range"):
        p.indices_to_bitmap([256])
    with pytest.raises(ParameterError, match="needs 2–32 bytes"):
        p.indices_to_bitmap([8], length=1)
    with pytest.raises(ParameterError, match="bit string length 33"):
        p.indices_to_bitmap([], length=33)


@given(st.sets(st.integers(0, 255)))
def test_bitmap_round_trip(indices: set[int]) -> None:
    data = p.indices_to_bitmap(indices)
    assert 1 <= len(data) <= 32
    assert p.bitmap_to_indices(data) == tuple(sorted(indices))
    assert p.needs_bulk(data) is (len(data) > 4)


def test_needs_bulk() -> None:
    assert not p.needs_bulk(b"")
    assert not p.needs_bulk(b"1234")
    assert p.needs_bulk(b"12345")
    assert p.needs_bulk(p.encode_value(_spec(p.DEVICE_DESCRIPTOR), "abcd"))  # 5 with NUL
    assert p.needs_bulk(p.indices_to_bitmap([32]))


def test_render_value() -> None:
    assert p.render_value(_spec(p.DEVICE_BEACON_INTERVAL), b"\x64\x00") == "100 ms"
    assert p.render_value(_spec(p.DEVICE_VID_PID), bytes.fromhex("01000A00")) == "0x0001 / 0x000A"
    assert p.render_value(_spec(p.IN_SOURCE_SN_INDEX, "input"), b"\x04\x00\x02") == "SN 4, channel 2"
    assert p.render_value(_spec(p.IN_SOURCE_NODE_IDS, "input"), b"\x05\x06") == (
        "device node 5, channel node 6"
    )
    assert p.render_value(_spec(p.CH_REQUIRED_INPUTS, "output"), b"\x60") == "channels {1, 2}"
    assert p.render_value(_spec(p.DEVICE_DESCRIPTOR), b"Hi\0") == "'Hi'"
    assert p.render_value(_spec(p.DEVICE_SERIAL), b"\x01") == "01 (not a valid u16)"
    assert p.render_value(None, b"\x01\x02") == "01 02"
    assert p.render_value(None, b"") == "(empty)"
