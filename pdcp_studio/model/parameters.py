"""The parameter catalog: what each (parameter ID, channel index) means and how it is laid out.

Reference §1 "Parameters" and its Decisions on value layouts. Device-wide parameters live
under channel index 0, channel *n* under index *n*; the same ID means different things for
input and output channels (ID 5: Source's VID and PID / Channel Node Id). The documents name
the parameters but give no layouts; the layouts here are the project's Decisions.

Multi-byte values are little-endian. Values longer than 4 bytes travel by bulk transfer.
"""

from __future__ import annotations

import struct
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any, Literal

from pdcp_studio.errors import ParameterError
from pdcp_studio.model.refs import Direction

Scope = Literal["device", "input", "output"]
Layout = Literal["u8", "u16", "u32", "pair16", "sn_index", "node_ids", "bitmap", "string"]

# Device parameters (channel index 0).
DEVICE_VID_PID = 1
DEVICE_SERIAL = 2
DEVICE_EAN_LOW = 3
DEVICE_EAN_HIGH = 4
DEVICE_VERSION = 5
DEVICE_TYPE_PROFILE = 6
DEVICE_DESCRIPTOR = 7
DEVICE_NODE_ID = 8
DEVICE_CHANNEL_COUNT = 9
DEVICE_BEACON_INTERVAL = 10
DEVICE_ACK_TIMEOUT = 11
DEVICE_BIND_TIMEOUT = 12
# Parameters of every channel.
CH_TYPE_PROFILE = 1
CH_DESCRIPTOR = 2
CH_TRANSFER_TYPE = 3
CH_DATA_ENABLED = 4
CH_REQUIRED_INPUTS = 9
CH_DESIRED_INPUTS = 10
# Input-channel parameters.
IN_SOURCE_VID_PID = 5
IN_SOURCE_SN_INDEX = 6
IN_SOURCE_NODE_IDS = 7
IN_SOURCE_TYPE_PROFILE = 8
IN_TERMINAL_PROFILE = 11
# Output-channel parameters.
OUT_NODE_ID = 5

#: A value of at most this many bytes fits a 0x83 / 0x84 frame.
MAX_INLINE_SIZE = 4
#: Bulk transfer carries at most 255 packets of 6 bytes (protocol.bulk.MAX_PAYLOAD).
MAX_BULK_SIZE = 255 * 6
#: Required / Desired Input Channels: 1–32 bytes, one bit per channel index 0–255.
MAX_BITMAP_SIZE = 32

_U8 = struct.Struct("<B")  # value
_U16 = struct.Struct("<H")  # value
_U32 = struct.Struct("<I")  # value
_PAIR16 = struct.Struct("<HH")  # X (VID / type / FW), Y (PID / profile / HW)
_SN_INDEX = struct.Struct("<HB")  # serial number, channel index
_NODE_IDS = struct.Struct("<BB")  # device node ID, output-channel node ID

_FIXED: dict[str, struct.Struct] = {
    "u8": _U8,
    "u16": _U16,
    "u32": _U32,
    "pair16": _PAIR16,
    "sn_index": _SN_INDEX,
    "node_ids": _NODE_IDS,
}


@dataclass(frozen=True)
class ParameterSpec:
    """One catalog entry. ``size`` is exact for fixed layouts, the maximum for bitmap/string."""

    id: int
    name: str
    scope: Scope
    layout: Layout
    size: int
    writable: bool
    unit: str = ""
    bulk: bool = False
    doc: str = ""

    @property
    def fixed_size(self) -> bool:
        return self.layout in _FIXED


def _spec(pid: int, name: str, scope: Scope, layout: Layout, writable: bool, unit: str = "",
          doc: str = "") -> ParameterSpec:
    if layout in _FIXED:
        size = _FIXED[layout].size
    else:
        size = MAX_BITMAP_SIZE if layout == "bitmap" else MAX_BULK_SIZE
    return ParameterSpec(pid, name, scope, layout, size, writable, unit, layout == "string", doc)


def _channel_specs(scope: Scope) -> list[ParameterSpec]:
    transfer = 1 if scope == "input" else 2
    return [
        _spec(CH_TYPE_PROFILE, "Channel Type and Profile", scope, "pair16", True,
              doc="Channel Type (16 flag bits) in bytes 0-1, profile in bytes 2-3"),
        _spec(CH_DESCRIPTOR, "Channel Descriptor", scope, "string", True,
              doc="human-readable name, NUL-terminated, by bulk transfer"),
        _spec(CH_TRANSFER_TYPE, "Transfer Type", scope, "u8", False,
              doc=f"1 = input, 2 = output (this one: {transfer})"),
        _spec(CH_DATA_ENABLED, "Data Transfer Enabled Flag", scope, "u8", True,
              doc="1 = the channel sends (output) or listens to its source (input)"),
        _spec(CH_REQUIRED_INPUTS, "Required Input Channels", scope, "bitmap", True,
              doc="bit string, MSB of byte 0 = channel 0; bulk when longer than 4 bytes"),
        _spec(CH_DESIRED_INPUTS, "Desired Input Channels", scope, "bitmap", True,
              doc="bit string, MSB of byte 0 = channel 0; bulk when longer than 4 bytes"),
    ]


_DEVICE: tuple[ParameterSpec, ...] = (
    _spec(DEVICE_VID_PID, "VID and PID", "device", "pair16", False),
    _spec(DEVICE_SERIAL, "Serial Number", "device", "u16", False),
    _spec(DEVICE_EAN_LOW, "EAN13 low", "device", "u32", False, doc="low 32 bits of the EAN-13"),
    _spec(DEVICE_EAN_HIGH, "EAN13 high", "device", "u32", False, doc="high bits of the EAN-13"),
    _spec(DEVICE_VERSION, "FW and HW version", "device", "pair16", False),
    _spec(DEVICE_TYPE_PROFILE, "Device Type and Profile", "device", "pair16", False,
          doc="unused by the profile layer"),
    _spec(DEVICE_DESCRIPTOR, "Device Descriptor", "device", "string", True,
          doc="human-readable name, NUL-terminated, by bulk transfer"),
    _spec(DEVICE_NODE_ID, "Device Node Id", "device", "u8", True),
    _spec(DEVICE_CHANNEL_COUNT, "Number of Data Channels", "device", "u8", False),
    _spec(DEVICE_BEACON_INTERVAL, "Beacon Interval", "device", "u16", True, "ms"),
    _spec(DEVICE_ACK_TIMEOUT, "Time to Wait for Acknowledgement", "device", "u16", True, "ms"),
    _spec(DEVICE_BIND_TIMEOUT, "Bind Request Timeout", "device", "u16", True, "ms"),
)

_INPUT: tuple[ParameterSpec, ...] = (
    *_channel_specs("input"),
    _spec(IN_SOURCE_VID_PID, "Source's VID and PID", "input", "pair16", True,
          doc="FFFF FFFF = not connected"),
    _spec(IN_SOURCE_SN_INDEX, "Source's SN and Channel Index", "input", "sn_index", True,
          doc="serial (2 bytes) then channel index; FFFF FF = not connected"),
    _spec(IN_SOURCE_NODE_IDS, "Source's Node Ids", "input", "node_ids", True,
          doc="source device node ID, then source output-channel node ID"),
    _spec(IN_SOURCE_TYPE_PROFILE, "Source's Type and Profile", "input", "pair16", True,
          doc="0 = not connected"),
    _spec(IN_TERMINAL_PROFILE, "Terminal Profile", "input", "u16", True,
          doc="profile of the set points of the terminal device this input controls"),
)

_OUTPUT: tuple[ParameterSpec, ...] = (
    *_channel_specs("output"),
    _spec(OUT_NODE_ID, "Channel Node Id", "output", "u8", True,
          doc="the node ID this output sends its data with"),
)

_CATALOG: dict[str, dict[int, ParameterSpec]] = {
    scope: {s.id: s for s in sorted(specs, key=lambda s: s.id)}
    for scope, specs in (("device", _DEVICE), ("input", _INPUT), ("output", _OUTPUT))
}


def _scope_of(scope: str | Direction) -> str:
    key = scope.value if isinstance(scope, Direction) else scope
    if key not in _CATALOG:
        raise ParameterError(f"unknown parameter scope {scope!r} (device, input or output)")
    return key


def parameters_for(scope: Scope | Direction) -> tuple[ParameterSpec, ...]:
    """Every parameter of a scope ('device', 'input', 'output' or a Direction), by ID."""
    return tuple(_CATALOG[_scope_of(scope)].values())


def device_parameter(param_id: int) -> ParameterSpec:
    """The device-wide parameter ``param_id`` (channel index 0); ParameterError if unknown."""
    try:
        return _CATALOG["device"][param_id]
    except KeyError:
        raise ParameterError(f"device parameter {param_id} is not in the catalog") from None


def channel_parameter(param_id: int, direction: Direction | str) -> ParameterSpec:
    """The parameter ``param_id`` of an input or output channel; ParameterError if unknown."""
    scope = _scope_of(direction)
    if scope == "device":
        raise ParameterError("a channel's direction is input or output, not device")
    try:
        return _CATALOG[scope][param_id]
    except KeyError:
        raise ParameterError(
            f"{scope} channel parameter {param_id} is not in the catalog"
        ) from None


def find_parameter(param_id: int, channel_index: int,
                   direction: Direction | str | None = None) -> ParameterSpec | None:
    """The spec addressed by a frame, or None if unknown or ambiguous (direction not known)."""
    if channel_index == 0:
        return _CATALOG["device"].get(param_id)
    if direction is not None:
        return _CATALOG[_scope_of(direction)].get(param_id)
    inp, out = _CATALOG["input"].get(param_id), _CATALOG["output"].get(param_id)
    if inp is not None and out is not None and inp.name == out.name:
        return inp  # same name and layout for both directions
    return inp if out is None else out if inp is None else None


def parameter_name(param_id: int, channel_index: int,
                   direction: Direction | str | None = None) -> str:
    """A display name; with an unknown direction a combined "input / output" name."""
    if channel_index == 0:
        spec = _CATALOG["device"].get(param_id)
        return spec.name if spec else f"Device Parameter {param_id}"
    if direction is not None:
        spec = _CATALOG[_scope_of(direction)].get(param_id)
        return spec.name if spec else f"Channel Parameter {param_id}"
    inp, out = _CATALOG["input"].get(param_id), _CATALOG["output"].get(param_id)
    names = [s.name for s in (inp, out) if s is not None]
    if not names:
        return f"Channel Parameter {param_id}"
    return names[0] if len(set(names)) == 1 else " / ".join(names)


def require_writable(spec: ParameterSpec) -> None:
    """Raise ParameterError if the arbitrator may not set ``spec``."""
    if not spec.writable:
        raise ParameterError(f"{spec.name} ({spec.scope} parameter {spec.id}) is read-only")


def needs_bulk(data: bytes) -> bool:
    """True if an encoded value is too long for a 0x83 / 0x84 frame."""
    return len(data) > MAX_INLINE_SIZE


# ---------------------------------------------------------------------------------------------
# Bit strings (Required / Desired Input Channels)


def bitmap_to_indices(data: bytes) -> tuple[int, ...]:
    """The channel indices whose bit is set; the MSB of byte 0 is channel 0."""
    return tuple(
        byte_no * 8 + bit
        for byte_no, byte in enumerate(data)
        for bit in range(8)
        if byte & (0x80 >> bit)
    )


def indices_to_bitmap(indices: Iterable[int], length: int | None = None) -> bytes:
    """The shortest bit string (≥1 byte) covering ``indices``, or exactly ``length`` bytes."""
    idx = sorted(set(indices))
    for i in idx:
        if not isinstance(i, int) or not 0 <= i < MAX_BITMAP_SIZE * 8:
            raise ParameterError(f"channel index {i!r} is out of range for a bit string (0–255)")
    needed = idx[-1] // 8 + 1 if idx else 1
    size = needed if length is None else length
    if not needed <= size <= MAX_BITMAP_SIZE:
        raise ParameterError(
            f"bit string length {size} cannot hold channel {idx[-1] if idx else 0} "
            f"(needs {needed}–{MAX_BITMAP_SIZE} bytes)"
        )
    out = bytearray(size)
    for i in idx:
        out[i // 8] |= 0x80 >> (i % 8)
    return bytes(out)


# ---------------------------------------------------------------------------------------------
# Values


def _int_in(spec: ParameterSpec, value: Any, limit: int, what: str = "value") -> int:
    if not isinstance(value, int):
        raise ParameterError(f"{spec.name}: {what} {value!r} is not an integer")
    if not 0 <= value <= limit:
        raise ParameterError(f"{spec.name}: {what} {value} is out of range (0–{limit})")
    return int(value)


def _pair(spec: ParameterSpec, value: Any) -> tuple[Any, Any]:
    if not isinstance(value, tuple | list) or len(value) != 2:
        raise ParameterError(f"{spec.name}: value {value!r} is not a pair")
    return value[0], value[1]


def encode_value(spec: ParameterSpec, value: Any) -> bytes:
    """Encode a Python value (int, pair, indices or str per layout) into parameter bytes."""
    layout = spec.layout
    if layout == "u8":
        return _U8.pack(_int_in(spec, value, 0xFF))
    if layout == "u16":
        return _U16.pack(_int_in(spec, value, 0xFFFF))
    if layout == "u32":
        return _U32.pack(_int_in(spec, value, 0xFFFF_FFFF))
    if layout == "pair16":
        x, y = _pair(spec, value)
        return _PAIR16.pack(_int_in(spec, x, 0xFFFF, "X"), _int_in(spec, y, 0xFFFF, "Y"))
    if layout == "sn_index":
        sn, index = _pair(spec, value)
        return _SN_INDEX.pack(_int_in(spec, sn, 0xFFFF, "serial"),
                              _int_in(spec, index, 0xFF, "channel index"))
    if layout == "node_ids":
        dev, chan = _pair(spec, value)
        return _NODE_IDS.pack(_int_in(spec, dev, 0xFF, "device node ID"),
                              _int_in(spec, chan, 0xFF, "channel node ID"))
    if layout == "bitmap":
        if isinstance(value, str | bytes) or not isinstance(value, Iterable):
            raise ParameterError(f"{spec.name}: value {value!r} is not a collection of indices")
        try:
            return indices_to_bitmap(value)
        except ParameterError as err:
            raise ParameterError(f"{spec.name}: {err}") from err
    if layout == "string":
        if not isinstance(value, str):
            raise ParameterError(f"{spec.name}: value {value!r} is not a string")
        if "\0" in value:
            raise ParameterError(f"{spec.name}: a descriptor cannot contain NUL")
        data = value.encode("utf-8") + b"\0"
        if len(data) > spec.size:
            raise ParameterError(
                f"{spec.name}: {len(data)} bytes with the terminator, at most {spec.size} fit"
            )
        return data
    raise ParameterError(f"{spec.name}: unknown layout {layout!r}")


def decode_value(spec: ParameterSpec, data: bytes) -> Any:
    """Decode parameter bytes into the Python value for the layout; ParameterError if malformed."""
    data = bytes(data)
    layout = spec.layout
    fixed = _FIXED.get(layout)
    if fixed is not None:
        if len(data) != fixed.size:
            raise ParameterError(
                f"{spec.name}: {len(data)} bytes, expected {fixed.size} ({layout})"
            )
        fields = fixed.unpack(data)
        return fields[0] if len(fields) == 1 else fields
    if layout == "bitmap":
        if not 1 <= len(data) <= MAX_BITMAP_SIZE:
            raise ParameterError(
                f"{spec.name}: {len(data)} bytes, expected 1–{MAX_BITMAP_SIZE} (bit string)"
            )
        return bitmap_to_indices(data)
    if layout == "string":
        if len(data) > spec.size:
            raise ParameterError(f"{spec.name}: {len(data)} bytes, at most {spec.size} expected")
        # Descriptors are NUL-terminated on the wire (001 §3.3.6); a device that sends
        # invalid UTF-8 still gets a readable name rather than an error in a monitor.
        return data.split(b"\0", 1)[0].decode("utf-8", errors="replace")
    raise ParameterError(f"{spec.name}: unknown layout {layout!r}")


def render_value(spec: ParameterSpec | None, data: bytes) -> str:
    """A short text for a monitor; falls back to hex when the bytes do not fit the layout."""
    hex_text = data.hex(" ").upper() if data else "(empty)"
    if spec is None:
        return hex_text
    try:
        value = decode_value(spec, data)
    except ParameterError:
        return f"{hex_text} (not a valid {spec.layout})"
    unit = f" {spec.unit}" if spec.unit else ""
    if spec.layout == "pair16":
        return f"0x{value[0]:04X} / 0x{value[1]:04X}"
    if spec.layout == "sn_index":
        return f"SN {value[0]}, channel {value[1]}"
    if spec.layout == "node_ids":
        return f"device node {value[0]}, channel node {value[1]}"
    if spec.layout == "bitmap":
        return "channels {" + ", ".join(map(str, value)) + "}"
    if spec.layout == "string":
        return repr(value)
    return f"{value}{unit}"
