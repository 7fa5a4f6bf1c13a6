"""Host link 2, the messages: requests, replies and events carried in DATA payloads.

A message is ``code (u8) | body (≤ 254 bytes)`` (docs/host-link.md §4). The host sends
requests (0x01…0x3F); the arbitrator answers each with ``code | 0x80`` and a status byte
first (0x00 OK, else an error code of :class:`Status` and a short UTF-8 reason), and pushes
events (0x40…0x5F) on its own. Multi-byte numbers are little-endian, as on the CAN bus.

The record layouts here are what the arbitrator holds in its tables: devices with node IDs, a
device's channel table, links (their conversions to model objects are in
``bus/hostlink/records.py``); values longer than one frame move in chunks with offsets
(canopen's segmented SDO), and error codes say exactly why (its abort codes). Pure.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from enum import IntEnum

from pdcp_studio.errors import FrameError

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
    ANCHOR_READ = 0x19
    ANCHOR_WRITE = 0x1A


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
    DEVICE_REPLACED = 0x4C


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
#: The two profiles of docs/host-link.md §7, as HELLO declares them: the full one has every
#: capability; the lean one (an 8-bit MCU with 2 KB of RAM) none that costs RAM (it may add
#: CAP_POLICY, which costs nothing).
CAP_FULL = CAP_MONITOR | CAP_TRANSACTIONS | CAP_POLICY | CAP_PARAM_BULK
CAP_LEAN = 0x0000

# -- structs (little-endian; fields in order) ---------------------------------------------------
# device key: vid, pid, serial
KEY = struct.Struct("<HHH")
# DEVICE_LEFT event, after the key (optional): how long the device was not heard and its
#   beacon interval, in ms (0 = unknown; u16, saturating); the reason (UTF-8) follows
LEFT_TAIL = struct.Struct("<HH")
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


def text(body: bytes) -> str:
    return bytes(body).decode("utf-8", errors="replace")


def short_text(message: str, limit: int = MAX_BODY - 1) -> bytes:
    """UTF-8 of ``message`` cut to ``limit`` bytes on a character boundary."""
    data = message.encode("utf-8")
    if len(data) <= limit:
        return data
    return data[:limit].decode("utf-8", errors="ignore").encode("utf-8")


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
