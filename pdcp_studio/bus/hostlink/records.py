"""Host link 2 records ↔ model objects: device keys, links, device rows and info, channels.

The byte layouts are ``protocol/hostlink_messages.py``'s structs (docs/host-link.md §5.2);
this module turns them into the model's DeviceKey, Link, Device and Channel and back.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, SourceInfo
from pdcp_studio.protocol.hostlink_messages import (
    CHANNEL_HEAD,
    DEVICE_INFO,
    DEVICE_ROW,
    INPUT_TAIL,
    KEY,
    LEFT_TAIL,
    LINK_EVENT,
    MAX_BODY,
    REF,
    MessageError,
    need,
    short_text,
    text,
)
from pdcp_studio.storage.archive.chain import ANCHOR_SIZE as _ANCHOR_SIZE
from pdcp_studio.storage.archive.chain import Anchor
from pdcp_studio.storage.archive.chain import pack_anchor as _pack_anchor
from pdcp_studio.storage.archive.chain import unpack_anchor as _unpack_anchor


def pack_key(key: DeviceKey) -> bytes:
    return KEY.pack(*key)


def unpack_key(body: bytes, offset: int = 0) -> DeviceKey:
    need(body, offset + KEY.size, "device key")
    return DeviceKey(*KEY.unpack_from(body, offset))


@dataclass(frozen=True)
class Left:
    """A DEVICE_LEFT event's body: the device and why it left (0 and "" when not said)."""

    key: DeviceKey
    silent_s: float = 0.0
    interval_s: float = 0.0
    why: str = ""


def _ms16(seconds: float) -> int:
    return min(max(round(seconds * 1000), 0), 0xFFFF)


def pack_left(key: DeviceKey, silent_s: float, interval_s: float, why: str,
              limit: int = 200) -> bytes:
    """DEVICE_LEFT's body: key, silent ms, beacon interval ms (saturating u16), reason cut
    to ``limit`` bytes (docs/host-link.md §5.7)."""
    return (KEY.pack(*key) + LEFT_TAIL.pack(_ms16(silent_s), _ms16(interval_s))
            + short_text(why, limit))


def unpack_left(body: bytes) -> Left:
    """The key alone (an arbitrator from before reasons), or key, times and reason. A tail
    too short for the two times is ignored; the reason is read leniently, any length."""
    key = unpack_key(body)
    tail = body[KEY.size:]
    if len(tail) < LEFT_TAIL.size:
        return Left(key)
    silent, interval = LEFT_TAIL.unpack_from(tail)
    return Left(key, silent / 1000.0, interval / 1000.0, text(tail[LEFT_TAIL.size:]))


def pack_link(link: Link) -> bytes:
    return REF.pack(*link.output) + REF.pack(*link.input)


def unpack_link(body: bytes, offset: int = 0) -> Link:
    need(body, offset + 2 * REF.size, "link")
    return Link(ChannelRef(*REF.unpack_from(body, offset)),
                ChannelRef(*REF.unpack_from(body, offset + REF.size)))


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




# -- the fitting history's anchor (ANCHOR_READ / ANCHOR_WRITE, issue 28) ------------------
#: An anchor's bytes: entry id u64, SHA-256 (32 bytes), announced token (32 ASCII bytes).
ANCHOR_SIZE = _ANCHOR_SIZE


def pack_anchor(anchor: Anchor | None) -> bytes:
    """The anchor as a reply's body; empty when the arbitrator keeps none."""
    return b"" if anchor is None else _pack_anchor(anchor)


def unpack_anchor(body: bytes) -> Anchor:
    """The anchor in a request's or reply's body (MessageError when it is not one)."""
    try:
        return _unpack_anchor(body)
    except ValueError as err:
        raise MessageError(str(err)) from None


def unpack_optional_anchor(body: bytes) -> Anchor | None:
    """ANCHOR_READ's reply: None when empty (the arbitrator keeps none)."""
    return None if not body else unpack_anchor(body)
