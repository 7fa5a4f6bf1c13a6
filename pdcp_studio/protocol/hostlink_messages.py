"""Host link 2, the messages: requests, replies and events carried in DATA payloads.

A message is ``code (u8) | body (≤ 254 bytes)`` (docs/host-link.md §4). The host sends
requests (0x01…0x3F); the arbitrator answers each with ``code | 0x80`` and a status byte
first (0x00 OK, else an error code of :class:`Status` and a short UTF-8 reason), and pushes
events (0x40…0x5F) on its own. Multi-byte numbers are little-endian, as on the CAN bus.

The records here are what the arbitrator holds in its tables: devices with node IDs, a
device's channel table, links; values longer than one frame move in chunks with offsets
(canopen's segmented SDO), and error codes say exactly why (its abort codes). Pure.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from enum import IntEnum

from pdcp_studio.errors import FrameError
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, SourceInfo

#: The protocol version this module speaks (HELLO).
VERSION = 2
#: Body bytes of one message (the frame's 255 less the code byte).
MAX_BODY = 254
#: Bytes of a value, configuration or text chunk per message (room left for the headers).
CHUNK = 240
REPLY = 0x80


class Req(IntEnum):
    HELLO = 0x01
    STATUS = 0x02
    LIST_DEVICES = 0x03
    GET_DEVICE = 0x04
    GET_CHANNELS = 0x05
    LIST_LINKS = 0x06
    GET_PARAM = 0x07
    SET_PARAM = 0x08
    ADD_LINK = 0x09
    REMOVE_LINK = 0x0A
    SUSPEND = 0x0B
    RELEASE = 0x0C
    RESET_DEVICE = 0x0D
    CONFIG_INFO = 0x0E
    CONFIG_READ = 0x0F
    CONFIG_WRITE_BEGIN = 0x10
    CONFIG_WRITE_CHUNK = 0x11
    CONFIG_WRITE_COMMIT = 0x12
    TRANSACT_BEGIN = 0x13
    TRANSACT_CHUNK = 0x14
    GET_POLICY = 0x15
    TRANSACT_RUN = 0x16
    MONITOR = 0x17
    RESULT_READ = 0x18


class Event(IntEnum):
    DEVICE_JOINED = 0x41
    DEVICE_LEFT = 0x42
    LINK_MADE = 0x43
    LINK_REMOVED = 0x44
    OTHER_ARBITRATOR = 0x45
    BUS_ERROR = 0x46
    FRAMES = 0x47
    CHANNEL_COUNTS = 0x48
    EVENTS_LOST = 0x49
    TRANSACTION_DONE = 0x4A
    TERMINALS_UNCONNECTED = 0x4B


class Status(IntEnum):
    """Why a request failed (the reply's status byte); the reason text says more."""

    OK = 0x00
    UNKNOWN_REQUEST = 0x01
    BAD_LENGTH = 0x02
    NOT_GREETED = 0x03
    VERSION = 0x04
    UNKNOWN_DEVICE = 0x05
    DEVICE_ABSENT = 0x06
    DEVICE_REFUSED = 0x07
    DEVICE_TIMEOUT = 0x08
    MANAGED = 0x09
    BAD_LINK = 0x0A
    BAD_OFFSET = 0x0B
    TOO_LARGE = 0x0C
    CHECKSUM = 0x0D
    BAD_CONFIGURATION = 0x0E
    NO_TRANSFER = 0x0F
    BUSY = 0x10
    INTERLOCK = 0x11
    OTHER_ARBITRATOR = 0x12
    STORAGE = 0x13
    UNSUPPORTED = 0x14
    INTERNAL = 0x1F


#: Capability bits (HELLO): what the arbitrator offers beyond the core requests.
CAP_MONITOR = 0x0001
CAP_TRANSACTIONS = 0x0002
CAP_POLICY = 0x0004
CAP_PARAM_BULK = 0x0008

# -- structs (little-endian; fields in order) ---------------------------------------------------
# device key: vid, pid, serial
KEY = struct.Struct("<HHH")
# channel reference: vid, pid, serial, index
REF = struct.Struct("<HHHB")
# HELLO request/reply head: version, capabilities, largest payload
HELLO = struct.Struct("<BHB")
# STATUS reply: flags (bit0 settled, bit1 start-up done, bit2 other arbitrator), devices,
#   links, change counter, events lost
STATUS = struct.Struct("<BBHHH")
# LIST_DEVICES record: vid, pid, serial, node id (0 = none), flags (bit0 present), channels
DEVICE_ROW = struct.Struct("<HHHBBB")
# GET_DEVICE reply head: node id, flags, fw, hw, type, profile, beacon, ack, bind timeouts,
#   EAN low, EAN high, channel count, descriptor length (descriptor follows)
DEVICE_INFO = struct.Struct("<BBHHHHHHHIIBB")
# GET_CHANNELS record head: index, direction (1 in, 2 out), flags (bit0 data enabled), type,
#   profile, node id (outputs) — then inputs add TERMINAL_SOURCE; then required, desired,
#   descriptor, each as count/length u8 then items
CHANNEL_HEAD = struct.Struct("<BBBHHB")
# input channel: terminal profile, source vid, pid, serial, index, type, profile
INPUT_TAIL = struct.Struct("<HHHHBHH")
# parameter address: key (6), channel, parameter id
PARAM = struct.Struct("<HHHBB")
# offset and total of a chunked value
SPAN = struct.Struct("<HH")
# configuration info: length, CRC-16/CCITT-FALSE of the stored bytes
CONFIG_INFO = struct.Struct("<HH")
# a link event: output ref, input ref, output's channel node id
LINK_EVENT = struct.Struct("<HHHBHHHBB")
# a frame in a FRAMES event: time (ms, u32 wraps), identifier (11 bits), length, data
FRAME_HEAD = struct.Struct("<IHB")
# a CHANNEL_COUNTS record: channel node id, frames in the period
COUNT = struct.Struct("<BH")


def reply_code(request: int) -> int:
    return request | REPLY


class MessageError(FrameError):
    """A message body is too short or too long for its code."""


def need(body: bytes, size: int, what: str) -> None:
    if len(body) < size:
        raise MessageError(f"{what}: {len(body)} bytes, needs {size}")


def pack_key(key: DeviceKey) -> bytes:
    return KEY.pack(*key)


def unpack_key(body: bytes, offset: int = 0) -> DeviceKey:
    need(body, offset + KEY.size, "device key")
    return DeviceKey(*KEY.unpack_from(body, offset))


def pack_link(link: Link) -> bytes:
    return REF.pack(*link.output) + REF.pack(*link.input)


def unpack_link(body: bytes, offset: int = 0) -> Link:
    need(body, offset + 2 * REF.size, "link")
    return Link(ChannelRef(*REF.unpack_from(body, offset)),
                ChannelRef(*REF.unpack_from(body, offset + REF.size)))


def text(body: bytes) -> str:
    return bytes(body).decode("utf-8", errors="replace")


def short_text(message: str, limit: int = MAX_BODY - 1) -> bytes:
    """UTF-8 of ``message`` cut to ``limit`` bytes on a character boundary."""
    data = message.encode("utf-8")
    if len(data) <= limit:
        return data
    return data[:limit].decode("utf-8", errors="ignore").encode("utf-8")


def _lstr(value: str, limit: int = 64) -> bytes:
    data = short_text(value, limit)
    return bytes([len(data)]) + data


def _u16s(values: tuple[int, ...]) -> bytes:
    return bytes([len(values)]) + struct.pack(f"<{len(values)}H", *values)


# -- device rows and device info --------------------
def pack_device_row(device: Device) -> bytes:
    return DEVICE_ROW.pack(device.vid, device.pid, device.serial, device.node_id or 0,
                           1 if device.present else 0, len(device.channels))


@dataclass(frozen=True)
class DeviceRow:
    key: DeviceKey
    node_id: int | None
    present: bool
    channels: int


def unpack_device_rows(body: bytes) -> list[DeviceRow]:
    if len(body) % DEVICE_ROW.size:
        raise MessageError(f"device list: {len(body)} bytes is not whole rows")
    rows = []
    for off in range(0, len(body), DEVICE_ROW.size):
        vid, pid, serial, node, flags, count = DEVICE_ROW.unpack_from(body, off)
        rows.append(DeviceRow(DeviceKey(vid, pid, serial), node or None, bool(flags & 1),
                              count))
    return rows


def pack_device_info(device: Device) -> bytes:
    desc = short_text(device.descriptor, MAX_BODY - 2 - DEVICE_INFO.size)
    return DEVICE_INFO.pack(
        device.node_id or 0, 1 if device.present else 0, device.fw_version, device.hw_version,
        device.device_type, device.device_profile, device.beacon_interval, device.ack_timeout,
        device.bind_timeout, device.ean_low, device.ean_high, len(device.channels),
        len(desc)) + desc


def unpack_device_info(key: DeviceKey, body: bytes) -> tuple[Device, int, int]:
    """The device (no channels yet), how many channels it has, and the bytes read."""
    need(body, DEVICE_INFO.size, "device info")
    (node, flags, fw, hw, dtype, dprofile, beacon, ack, bind, ean_lo, ean_hi, count,
     length) = DEVICE_INFO.unpack_from(body)
    need(body, DEVICE_INFO.size + length, "device descriptor")
    desc = text(body[DEVICE_INFO.size:DEVICE_INFO.size + length])
    device = Device(key.vid, key.pid, key.serial, present=bool(flags & 1),
                    node_id=node or None, descriptor=desc, fw_version=fw, hw_version=hw,
                    device_type=dtype, device_profile=dprofile, beacon_interval=beacon,
                    ack_timeout=ack, bind_timeout=bind, ean_low=ean_lo, ean_high=ean_hi)
    return device, count, DEVICE_INFO.size + length


# -- channel tables --------------------
def pack_channel(ch: Channel) -> bytes:
    direction = 1 if ch.direction is Direction.INPUT else 2
    out = CHANNEL_HEAD.pack(ch.index, direction, 1 if ch.data_enabled else 0, ch.type,
                            ch.profile, ch.node_id or 0)
    if direction == 1:
        s = ch.source
        out += INPUT_TAIL.pack(ch.terminal_profile, s.vid, s.pid, s.serial, s.index, s.type,
                               s.profile)
    return (out + _u16s(tuple(ch.required_inputs)[:32]) + _u16s(tuple(ch.desired_inputs)[:32])
            + _lstr(ch.descriptor))


def unpack_channel(body: bytes, offset: int) -> tuple[Channel, int]:
    """One channel record at ``offset``; returns it and the offset after it."""
    need(body, offset + CHANNEL_HEAD.size, "channel record")
    index, direction, flags, ctype, profile, node = CHANNEL_HEAD.unpack_from(body, offset)
    offset += CHANNEL_HEAD.size
    if direction not in (1, 2):
        raise MessageError(f"channel {index}: direction {direction} is neither 1 nor 2")
    ch = Channel(index, Direction.from_transfer_type(direction), ctype, profile,
                 data_enabled=bool(flags & 1), node_id=node or None)
    if direction == 1:
        need(body, offset + INPUT_TAIL.size, "input channel record")
        term, svid, spid, sser, sidx, stype, sprof = INPUT_TAIL.unpack_from(body, offset)
        offset += INPUT_TAIL.size
        ch.terminal_profile = term
        ch.source = SourceInfo(svid, spid, sser, sidx, stype, sprof)
    lists = []
    for what in ("required inputs", "desired inputs"):
        need(body, offset + 1, what)
        n = body[offset]
        need(body, offset + 1 + 2 * n, what)
        lists.append(struct.unpack_from(f"<{n}H", body, offset + 1))
        offset += 1 + 2 * n
    ch.required_inputs, ch.desired_inputs = tuple(lists[0]), tuple(lists[1])
    need(body, offset + 1, "channel descriptor")
    n = body[offset]
    need(body, offset + 1 + n, "channel descriptor")
    ch.descriptor = text(body[offset + 1:offset + 1 + n])
    return ch, offset + 1 + n


def pack_channel_page(channels: list[Channel], start: int,
                      room: int = MAX_BODY - 1) -> tuple[bytes, int]:
    """Records of ``channels`` from list position ``start`` that fit ``room`` bytes (a reply
    less its status byte). Returns the page (next position u8, 0 when done, then records)
    and the next position; an empty page when not even one record fits (GET_DEVICE)."""
    records = b""
    pos = start
    while pos < len(channels):
        record = pack_channel(channels[pos])
        if 1 + len(records) + len(record) > room:
            break
        records += record
        pos += 1
    if pos == start and pos < len(channels) and room >= MAX_BODY - 1:
        raise MessageError(f"channel {channels[pos].index}'s record does not fit a frame")
    nxt = pos if pos < len(channels) else 0
    return bytes([nxt]) + records, nxt


def unpack_channel_page(body: bytes) -> tuple[list[Channel], int]:
    need(body, 1, "channel page")
    nxt, offset, out = body[0], 1, []
    while offset < len(body):
        ch, offset = unpack_channel(body, offset)
        out.append(ch)
    return out, nxt


# -- link events --------------------
def pack_link_event(link: Link, node_id: int | None) -> bytes:
    return LINK_EVENT.pack(*link.output, *link.input, node_id or 0)


def unpack_link_event(body: bytes) -> tuple[Link, int | None]:
    need(body, LINK_EVENT.size, "link event")
    f = LINK_EVENT.unpack_from(body)
    return Link(ChannelRef(*f[0:4]), ChannelRef(*f[4:8])), f[8] or None


# MONITOR reply: the bytes per second the arbitrator lets monitor traffic use
MONITOR_REPLY = struct.Struct("<H")
# FRAMES event head: frames dropped (over budget) since the last FRAMES event
FRAMES_HEAD = struct.Struct("<H")
# CHANNEL_COUNTS event head: the period it covers in ms
COUNTS_HEAD = struct.Struct("<H")


@dataclass(frozen=True)
class WireFrame:
    """A CAN frame passed through for the monitor."""

    time_ms: int
    arbitration_id: int
    data: bytes


def pack_frames(frames: list[WireFrame], dropped: int) -> bytes:
    out = bytes([Event.FRAMES]) + FRAMES_HEAD.pack(min(dropped, 0xFFFF))
    for f in frames:
        out += FRAME_HEAD.pack(f.time_ms & 0xFFFFFFFF, f.arbitration_id, len(f.data)) + f.data
    return out


def unpack_frames(body: bytes) -> tuple[list[WireFrame], int]:
    need(body, FRAMES_HEAD.size, "FRAMES")
    (dropped,) = FRAMES_HEAD.unpack_from(body)
    offset, out = FRAMES_HEAD.size, []
    while offset < len(body):
        need(body, offset + FRAME_HEAD.size, "frame record")
        t, aid, n = FRAME_HEAD.unpack_from(body, offset)
        offset += FRAME_HEAD.size
        if n > 8:
            raise MessageError(f"frame record of {n} data bytes (CAN has at most 8)")
        need(body, offset + n, "frame data")
        out.append(WireFrame(t, aid, bytes(body[offset:offset + n])))
        offset += n
    return out, dropped


def pack_counts(period_ms: int, counts: dict[int, int]) -> list[bytes]:
    """CHANNEL_COUNTS events (as many as the counts need)."""
    items = sorted(counts.items())
    per = (MAX_BODY - COUNTS_HEAD.size) // COUNT.size
    head = bytes([Event.CHANNEL_COUNTS]) + COUNTS_HEAD.pack(min(period_ms, 0xFFFF))
    return [head + b"".join(COUNT.pack(n, min(c, 0xFFFF)) for n, c in items[i:i + per])
            for i in range(0, len(items), per)] or [head]


def unpack_counts(body: bytes) -> tuple[int, dict[int, int]]:
    need(body, COUNTS_HEAD.size, "CHANNEL_COUNTS")
    (period,) = COUNTS_HEAD.unpack_from(body)
    rest = body[COUNTS_HEAD.size:]
    if len(rest) % COUNT.size:
        raise MessageError(f"channel counts: {len(rest)} bytes is not whole records")
    return period, {n: c for n, c in COUNT.iter_unpack(rest)}
