"""One frozen dataclass per function code, plus ``ChannelData`` for data-channel frames.

Their equality, hash and repr are :class:`~pdcp_studio.protocol.records.Record`'s, the same
as ``dataclass(frozen=True)`` generates, written once instead of per class (issue 11).

Every message knows its identifier fields (``node_id``, ``priority``, ``mode``) and encodes to
``(arbitration_id, data)``; ``decode()`` turns any frame back into a message or raises
FrameError naming the function and what is wrong. DLCs follow reference §1 (the restated,
authoritative table of 001 figure 3.1); multi-byte fields are little-endian.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, ClassVar, Self

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.codes import (
    DLC_RANGE,
    FUNCTION_CODES,
    FunctionCode,
    ResponseCode,
    describe_code,
)
from pdcp_studio.protocol.identifier import NODE_ID_MAX, Mode, Priority, make_id, split_id
from pdcp_studio.protocol.records import Record

if TYPE_CHECKING:
    from pdcp_studio.model.refs import Direction

#: A CAN 2.0A frame carries at most 8 data bytes.
MAX_DLC = 8

# Byte 0 of every struct is the function code.
_CODE_ONLY = struct.Struct("<B")  # code
_BIND_REQUEST = struct.Struct("<BHHH")  # code, VID, PID, serial
_BIND_RESPONSE = struct.Struct("<BBHHH")  # code, granted node ID, VID, PID, serial
_PARAM = struct.Struct("<BBB")  # code, parameter ID, channel index
_PARAM_RESPONSE = struct.Struct("<BBBB")  # code, response code, parameter ID, channel index
_SUSPEND = struct.Struct("<BH")  # code, time in ms (0 = indefinitely)
_SUSPEND_RESPONSE = struct.Struct("<BBH")  # code, response code, time in ms
_RESPONSE = struct.Struct("<BB")  # code, response code
_SET_BULK = struct.Struct("<BBBH")  # code, parameter ID, channel index, bulk size
_BULK_RESPONSE = struct.Struct("<BBBBH")  # code, response code, parameter ID, channel, size
_BULK_DATA = struct.Struct("<BB")  # code, packet ID (data follows: 1–6 bytes)
_CHANNEL = struct.Struct("<BB")  # code, channel index
_CHANNEL_RESPONSE = struct.Struct("<BBB")  # code, response code, channel index

# Field kinds → allowed range (checked on construction, so decode and encode share them).
_RANGES: dict[str, tuple[int, int]] = {
    "node": (0, NODE_ID_MAX),  # an identifier node ID: 0 broadcast, 1–254 assigned
    "granted": (1, NODE_ID_MAX),  # a node ID the arbitrator hands out
    "u8": (0, 0xFF),
    "u16": (0, 0xFFFF),
    "packet": (1, 0xFF),  # packet IDs count from 1
}
_SIDE = {Mode.DEVICE: "a device", Mode.ARBITRATOR: "the bus arbitrator"}


def _int_field(where: str, name: str, value: object, kind: str) -> int:
    """``value`` if it is an integer in ``kind``'s range; else FrameError naming the field
    (``name`` as a field is spelt, ``granted_node_id``, or as shown, ``node ID``)."""
    if not isinstance(value, int) or isinstance(value, bool):
        raise FrameError(f"{where}: {_shown(name)} {value!r} is not an integer")
    lo, hi = _RANGES[kind]
    if not lo <= value <= hi:
        raise FrameError(f"{where}: {_shown(name)} {value} is out of range ({lo}–{hi})")
    return value


def _shown(name: str) -> str:
    return name.replace("_", " ").replace(" id", " ID")


#: Each enum's members by value (``enum(value)`` for a value known to be in range, as one
#: dict look-up: every message built or decoded converts two or three fields).
_MEMBERS: dict[type, dict[int, object]] = {
    enum: {member.value: member for member in enum}
    for enum in (Priority, Mode, ResponseCode)
}


def _enum_field(where: str, name: str, value: object, enum: type, allowed: range) -> object:
    if isinstance(value, bool) or not isinstance(value, int) or value not in allowed:
        choices = ", ".join(f"{v} {enum(v).name}" for v in allowed)
        shown = int(value) if isinstance(value, int) and not isinstance(value, bool) else value
        raise FrameError(f"{where}: {name} {shown!r} is not one of {choices}")
    return _MEMBERS[enum][value]


def _dlc_text(lo: int, hi: int) -> str:
    return f"{lo} expected" if lo == hi else f"{lo}–{hi} expected"


@dataclass(frozen=True, eq=False, repr=False)
class _FunctionMessage(Record):
    """Shared encode / decode / validation, driven by each class's layout constants.

    ``priority`` (and ``mode``, where either side may send) are keyword-only fields.
    """

    CODE: ClassVar[FunctionCode]
    MODE: ClassVar[Mode | None]  # the sender's mode; None if either side sends it
    _HEAD: ClassVar[struct.Struct]
    _FIELDS: ClassVar[tuple[tuple[str, str], ...]] = ()  # (name, kind) after byte 0
    _TAIL: ClassVar[str | None] = None  # a trailing bytes field (its length from the DLC)

    node_id: int
    priority: Priority = field(default=Priority.NORMAL, kw_only=True)

    @property
    def function_code(self) -> FunctionCode:
        return self.CODE

    def __post_init__(self) -> None:
        where = self.CODE.label
        put = object.__setattr__
        put(self, "priority", _enum_field(where, "priority", self.priority, Priority, range(4)))
        if self.MODE is None:
            put(self, "mode", _enum_field(where, "mode", self.mode, Mode, range(2)))  # type: ignore[attr-defined]
        binding = self.CODE is FunctionCode.BIND_REQUEST
        if binding != (self.priority is Priority.BINDING):
            raise FrameError(
                f"{where}: priority {self.priority} ({self.priority.name}); "
                + ("a bind request is sent with priority 3 (BINDING)" if binding
                   else "priority 3 is reserved for the Bind Device Request")
            )
        _int_field(where, "node ID", self.node_id, "node")
        for name, kind in self._FIELDS:
            value = getattr(self, name)
            if kind in ("response", "response_bulk"):
                allowed = range(3) if kind == "response_bulk" else range(2)
                put(self, name, _enum_field(where, "response code", value, ResponseCode, allowed))
            else:
                if (not isinstance(value, int) or isinstance(value, bool)
                        or not _RANGES[kind][0] <= value <= _RANGES[kind][1]):
                    _int_field(where, name, value, kind)  # raises, naming the field
        if self._TAIL is not None:
            tail = getattr(self, self._TAIL)
            if not isinstance(tail, bytes | bytearray | memoryview):
                raise FrameError(f"{where}: {self._TAIL} {tail!r} is not bytes")
            tail = bytes(tail)
            lo, hi = (n - self._HEAD.size for n in DLC_RANGE[self.CODE])
            if not lo <= len(tail) <= hi:
                raise FrameError(
                    f"{where}: {self._TAIL} of {len(tail)} bytes ({lo}–{hi} bytes expected)"
                )
            put(self, self._TAIL, tail)

    def encode(self) -> tuple[int, bytes]:
        """``(arbitration_id, data)`` ready for a CAN frame."""
        head = self._HEAD.pack(self.CODE, *(getattr(self, name) for name, _ in self._FIELDS))
        tail = getattr(self, self._TAIL) if self._TAIL is not None else b""
        return make_id(self.priority, self.mode, self.node_id), head + tail  # type: ignore[attr-defined]

    @classmethod
    def decode(cls, arbitration_id: int, data: bytes) -> Self:
        """Decode a frame known to carry this function code; FrameError if it does not fit."""
        ident = split_id(arbitration_id)
        data = bytes(data)
        where = cls.CODE.label
        if not data or data[0] != cls.CODE:
            found = f"0x{data[0]:02X}" if data else "missing"
            raise FrameError(f"{where}: function code is {found}")
        lo, hi = DLC_RANGE[cls.CODE]
        if not lo <= len(data) <= hi:
            problem = "too short" if len(data) < lo else "too long"
            raise FrameError(f"{where}: DLC {len(data)} is {problem} ({_dlc_text(lo, hi)})")
        if cls.MODE is not None and ident.mode != cls.MODE:
            raise FrameError(
                f"{where}: sent in mode {ident.mode} ({ident.mode.name.lower()}), "
                f"but only {_SIDE[cls.MODE]} sends it (mode {cls.MODE})"
            )
        values = cls._HEAD.unpack_from(data)[1:]
        names = (name for name, _ in cls._FIELDS)
        kwargs: dict[str, object] = dict(zip(names, values, strict=True))
        if cls._TAIL is not None:
            kwargs[cls._TAIL] = data[cls._HEAD.size:]
        if cls.MODE is None:
            kwargs["mode"] = ident.mode
        return cls(node_id=ident.node_id, priority=ident.priority, **kwargs)


class _OneSided(_FunctionMessage):
    """A message only one side sends: ``mode`` comes from the class, not a field."""

    @property
    def mode(self) -> Mode:
        return self.MODE  # type: ignore[return-value]


_DEV, _BA = Mode.DEVICE, Mode.ARBITRATOR
_PARAM_FIELDS = (("param", "u8"), ("channel", "u8"))
_CODE_FIELD = (("code", "response"),)


@dataclass(frozen=True, eq=False, repr=False)
class BindRequest(_OneSided):
    """0x01: a device asks for ``node_id`` (the identifier's node ID), at priority 3."""

    CODE, MODE, _HEAD = FunctionCode.BIND_REQUEST, _DEV, _BIND_REQUEST
    _FIELDS = (("vid", "u16"), ("pid", "u16"), ("serial", "u16"))
    vid: int
    pid: int
    serial: int
    priority: Priority = field(default=Priority.BINDING, kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class BindResponse(_OneSided):
    """0x81: ``node_id`` is the ID the request used; ``granted_node_id`` (byte 1) the answer.

    The device is bound only when the two agree; otherwise it retries with the suggestion.
    """

    CODE, MODE, _HEAD = FunctionCode.BIND_RESPONSE, _BA, _BIND_RESPONSE
    _FIELDS = (("granted_node_id", "granted"), ("vid", "u16"), ("pid", "u16"), ("serial", "u16"))
    granted_node_id: int
    vid: int
    pid: int
    serial: int

    @property
    def accepted(self) -> bool:
        return self.granted_node_id == self.node_id


@dataclass(frozen=True, eq=False, repr=False)
class GetParameter(_OneSided):
    CODE, MODE, _HEAD, _FIELDS = FunctionCode.GET_PARAMETER, _BA, _PARAM, _PARAM_FIELDS
    param: int
    channel: int


@dataclass(frozen=True, eq=False, repr=False)
class GetParameterResponse(_OneSided):
    """0x83: ``value`` is 0–4 bytes (empty with USE_BULK or FAILURE)."""

    CODE, MODE, _HEAD = FunctionCode.GET_PARAMETER_RESPONSE, _DEV, _PARAM_RESPONSE
    _FIELDS, _TAIL = (("code", "response_bulk"), *_PARAM_FIELDS), "value"
    code: ResponseCode
    param: int
    channel: int
    value: bytes = b""


@dataclass(frozen=True, eq=False, repr=False)
class SetParameter(_OneSided):
    """0x04: ``value`` is 1–4 bytes; longer values go by Configure Set Bulk."""

    CODE, MODE, _HEAD = FunctionCode.SET_PARAMETER, _BA, _PARAM
    _FIELDS, _TAIL = _PARAM_FIELDS, "value"
    param: int
    channel: int
    value: bytes


@dataclass(frozen=True, eq=False, repr=False)
class SetParameterResponse(_OneSided):
    """0x84: echoes 1–4 value bytes whatever the response code (reference DLC 5–8)."""

    CODE, MODE, _HEAD = FunctionCode.SET_PARAMETER_RESPONSE, _DEV, _PARAM_RESPONSE
    _FIELDS, _TAIL = (("code", "response_bulk"), *_PARAM_FIELDS), "value"
    code: ResponseCode
    param: int
    channel: int
    value: bytes


@dataclass(frozen=True, eq=False, repr=False)
class Suspend(_OneSided):
    """0x08: stop transmitting for ``ms`` milliseconds (0 = until released)."""

    CODE, MODE, _HEAD, _FIELDS = FunctionCode.SUSPEND, _BA, _SUSPEND, (("ms", "u16"),)
    ms: int


@dataclass(frozen=True, eq=False, repr=False)
class SuspendResponse(_OneSided):
    CODE, MODE, _HEAD = FunctionCode.SUSPEND_RESPONSE, _DEV, _SUSPEND_RESPONSE
    _FIELDS = (*_CODE_FIELD, ("ms", "u16"))
    code: ResponseCode
    ms: int


@dataclass(frozen=True, eq=False, repr=False)
class Release(_OneSided):
    CODE, MODE, _HEAD = FunctionCode.RELEASE, _BA, _CODE_ONLY


@dataclass(frozen=True, eq=False, repr=False)
class ReleaseResponse(_OneSided):
    CODE, MODE, _HEAD, _FIELDS = FunctionCode.RELEASE_RESPONSE, _DEV, _RESPONSE, _CODE_FIELD
    code: ResponseCode


@dataclass(frozen=True, eq=False, repr=False)
class Beacon(_FunctionMessage):
    """0x0A: "still here", from a device (mode 0) or the arbitrator (mode 1).

    Defaults to HIGH priority, as in 001 §3.3.4.
    """

    CODE, MODE, _HEAD = FunctionCode.BEACON, None, _CODE_ONLY
    mode: Mode = field(default=Mode.DEVICE, kw_only=True)
    priority: Priority = field(default=Priority.HIGH, kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class Reset(_OneSided):
    CODE, MODE, _HEAD = FunctionCode.RESET, _BA, _CODE_ONLY


@dataclass(frozen=True, eq=False, repr=False)
class ResetResponse(_OneSided):
    CODE, MODE, _HEAD, _FIELDS = FunctionCode.RESET_RESPONSE, _DEV, _RESPONSE, _CODE_FIELD
    code: ResponseCode


@dataclass(frozen=True, eq=False, repr=False)
class ConfigureGetBulk(_OneSided):
    CODE, MODE, _HEAD, _FIELDS = FunctionCode.CONFIGURE_GET_BULK, _BA, _PARAM, _PARAM_FIELDS
    param: int
    channel: int


@dataclass(frozen=True, eq=False, repr=False)
class ConfigureGetBulkResponse(_OneSided):
    """0x8C: the device will send ``size`` bytes in 0x0E packets."""

    CODE, MODE, _HEAD = FunctionCode.CONFIGURE_GET_BULK_RESPONSE, _DEV, _BULK_RESPONSE
    _FIELDS = (*_CODE_FIELD, *_PARAM_FIELDS, ("size", "u16"))
    code: ResponseCode
    param: int
    channel: int
    size: int


@dataclass(frozen=True, eq=False, repr=False)
class ConfigureSetBulk(_OneSided):
    """0x0D: the arbitrator will send ``size`` bytes in 0x0E packets."""

    CODE, MODE, _HEAD = FunctionCode.CONFIGURE_SET_BULK, _BA, _SET_BULK
    _FIELDS = (*_PARAM_FIELDS, ("size", "u16"))
    param: int
    channel: int
    size: int


@dataclass(frozen=True, eq=False, repr=False)
class ConfigureSetBulkResponse(_OneSided):
    CODE, MODE, _HEAD = FunctionCode.CONFIGURE_SET_BULK_RESPONSE, _DEV, _BULK_RESPONSE
    _FIELDS = (*_CODE_FIELD, *_PARAM_FIELDS, ("size", "u16"))
    code: ResponseCode
    param: int
    channel: int
    size: int


@dataclass(frozen=True, eq=False, repr=False)
class BulkData(_FunctionMessage):
    """0x0E: one packet of 1–6 bytes; ``mode`` (keyword) says which side sends the data."""

    CODE, MODE, _HEAD = FunctionCode.BULK_DATA, None, _BULK_DATA
    _FIELDS, _TAIL = (("packet_id", "packet"),), "data"
    packet_id: int
    data: bytes
    mode: Mode = field(kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class BulkDataResponse(_FunctionMessage):
    """0x8E: sent by the receiver of the data after the last packet."""

    CODE, MODE, _HEAD, _FIELDS = FunctionCode.BULK_DATA_RESPONSE, None, _RESPONSE, _CODE_FIELD
    code: ResponseCode
    mode: Mode = field(kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class UpdateDataChannel(_OneSided):
    """0x0F: a device asks the arbitrator to (re)choose the source of input ``channel``."""

    CODE, MODE, _HEAD = FunctionCode.UPDATE_DATA_CHANNEL, _DEV, _CHANNEL
    _FIELDS = (("channel", "u8"),)
    channel: int


@dataclass(frozen=True, eq=False, repr=False)
class UpdateDataChannelResponse(_OneSided):
    CODE, MODE, _HEAD = FunctionCode.UPDATE_DATA_CHANNEL_RESPONSE, _BA, _CHANNEL_RESPONSE
    _FIELDS = (*_CODE_FIELD, ("channel", "u8"))
    code: ResponseCode
    channel: int


@dataclass(frozen=True, eq=False, repr=False)
class ChannelData(Record):
    """A data-channel frame: mode 0, an output channel's node ID, 0–8 bytes, no function code."""

    MODE: ClassVar[Mode] = Mode.DEVICE

    node_id: int
    data: bytes
    priority: Priority = field(default=Priority.NORMAL, kw_only=True)

    @property
    def mode(self) -> Mode:
        return Mode.DEVICE

    def __post_init__(self) -> None:
        where = "Channel data"
        prio = _enum_field(where, "priority", self.priority, Priority, range(3))
        object.__setattr__(self, "priority", prio)
        _int_field(where, "channel node ID", self.node_id, "granted")
        if not isinstance(self.data, bytes | bytearray | memoryview):
            raise FrameError(f"{where}: data {self.data!r} is not bytes")
        data = bytes(self.data)
        if len(data) > MAX_DLC:
            raise FrameError(f"{where}: {len(data)} bytes (0–8 expected)")
        object.__setattr__(self, "data", data)

    def encode(self) -> tuple[int, bytes]:
        return make_id(self.priority, Mode.DEVICE, self.node_id), self.data

    @classmethod
    def decode(cls, arbitration_id: int, data: bytes) -> Self:
        ident = split_id(arbitration_id)
        if ident.mode is not Mode.DEVICE:
            raise FrameError(
                f"Channel data: sent in mode {ident.mode}, but only outputs (mode 0) send it"
            )
        return cls(ident.node_id, bytes(data), priority=ident.priority)


Message = (
    BindRequest | BindResponse | GetParameter | GetParameterResponse | SetParameter
    | SetParameterResponse | Suspend | SuspendResponse | Release | ReleaseResponse | Beacon
    | Reset | ResetResponse | ConfigureGetBulk | ConfigureGetBulkResponse | ConfigureSetBulk
    | ConfigureSetBulkResponse | BulkData | BulkDataResponse | UpdateDataChannel
    | UpdateDataChannelResponse | ChannelData
)

#: Function code → message class.
MESSAGE_TYPES: dict[FunctionCode, type[_FunctionMessage]] = {
    cls.CODE: cls for cls in Message.__args__ if issubclass(cls, _FunctionMessage)
}


def decode(arbitration_id: int, data: bytes, *,
           channel_node_ids: frozenset[int] | set[int] = frozenset()) -> Message:
    """Decode any PDCP frame; FrameError (and nothing else) if it is not a valid one.

    A mode-0 frame below priority 3 whose node ID is in ``channel_node_ids`` is channel data;
    priority 3 is always a bind request (a device may ask for an ID an output uses).
    """
    ident = split_id(arbitration_id)
    if not isinstance(data, bytes | bytearray | memoryview):
        raise FrameError(f"frame data {data!r} is not bytes")
    data = bytes(data)
    if len(data) > MAX_DLC:
        raise FrameError(f"node {ident.node_id}: {len(data)} data bytes (a CAN frame has 0–8)")
    if (ident.mode is Mode.DEVICE and ident.priority is not Priority.BINDING
            and ident.node_id in channel_node_ids):
        return ChannelData.decode(arbitration_id, data)
    if not data:
        raise FrameError(f"{ident}: an empty frame has no function code")
    code = FUNCTION_CODES.get(data[0])
    if code is None:
        raise FrameError(f"{ident}: function code {describe_code(data[0])}")
    return MESSAGE_TYPES[code].decode(arbitration_id, data)  # type: ignore[return-value]


def describe(message: Message, direction: Direction | str | None = None) -> str:
    """One line for a bus monitor, e.g. "0x03 Get Device Parameter → node 5: …".

    ``direction`` (a model Direction) names channel parameters exactly when known.
    """
    # Imported here: the catalog lives in the model layer, which sits above the protocol.
    from pdcp_studio.model.parameters import find_parameter, parameter_name, render_value

    if isinstance(message, ChannelData):
        payload = message.data.hex(" ").upper() or "(empty)"
        return f"Channel data ← node {message.node_id}: {payload}"
    arrow = "←" if message.mode is Mode.DEVICE else "→"
    node = "all" if message.node_id == 0 and message.mode is Mode.ARBITRATOR else message.node_id
    head = f"{message.CODE.label} {arrow} node {node}"
    parts: list[str] = []
    values = {f.name: getattr(message, f.name) for f in fields(message)}
    if "code" in values:
        parts.append(values["code"].title)
    if isinstance(message, BindRequest | BindResponse):
        if isinstance(message, BindResponse):
            verdict = "granted" if message.accepted else "suggested"
            parts.append(f"node ID {message.granted_node_id} {verdict}")
        parts.append(f"VID 0x{message.vid:04X}, PID 0x{message.pid:04X}, SN {message.serial}")
    if "param" in values:
        name = parameter_name(values["param"], values["channel"], direction)
        parts.append(f"{name} (param {values['param']}, channel {values['channel']})")
    elif "channel" in values:
        parts.append(f"channel {values['channel']}")
    if values.get("value"):
        spec = find_parameter(values["param"], values["channel"], direction)
        parts[-1] += f" = {render_value(spec, values['value'])}"
    if "ms" in values:
        parts.append(f"{values['ms']} ms" if values["ms"] else "indefinitely")
    if "size" in values:
        parts.append(f"{values['size']} bytes")
    if isinstance(message, BulkData):
        parts.append(f"packet {message.packet_id}: {message.data.hex(' ').upper()}")
    return f"{head}: {', '.join(parts)}" if parts else head
