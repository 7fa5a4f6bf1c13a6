"""Channel data: synthetic signals for simulated outputs, and the bytes ↔ number codec.

A simulated output streams something a person recognises on a live plot: an EMG envelope for
EMG sensors, a joystick axis, a push button, a grip set point; an output that computes from
its device's required inputs forwards what they receive, so data visibly flows down a chain.
The codec follows the Channel Type (reference §1): 4/8-bit values take one byte, 12/16-bit
two, little-endian; signed is two's complement; float (format unspecified) is IEEE half in
16 bits and a 0…1 fraction otherwise; boolean is false iff all bits are 0.
"""

from __future__ import annotations

import math
import struct

from pdcp_studio.model.channel_type import ChannelType, DataType
from pdcp_studio.model.system import Channel

_HALF = struct.Struct("<e")


def _width(ctype: ChannelType) -> int:
    return 1 if ctype.bits <= 8 else 2


def encode_sample(type_value: int, x: float) -> bytes:
    """``x`` in −1…1 (signed) or 0…1 (others) → the channel's data bytes."""
    ctype = ChannelType(type_value)
    bits, width = ctype.bits, _width(ctype)
    if ctype.data_type is DataType.BOOLEAN:
        return (1 if x >= 0.5 else 0).to_bytes(width, "little")
    if ctype.data_type is DataType.FLOAT and bits == 16:
        return _HALF.pack(max(-65504.0, min(65504.0, x)))
    if ctype.data_type is DataType.SIGNED:
        top = (1 << (bits - 1)) - 1
        n = round(max(-1.0, min(1.0, x)) * top)
        return (n & ((1 << bits) - 1)).to_bytes(width, "little")
    top = (1 << bits) - 1
    return round(max(0.0, min(1.0, x)) * top).to_bytes(width, "little")


def decode_sample(type_value: int, data: bytes) -> float:
    """The inverse of :func:`encode_sample`; tolerant of a short or long frame (0.0 if empty)."""
    ctype = ChannelType(type_value)
    bits, width = ctype.bits, _width(ctype)
    if not data:
        return 0.0
    raw = int.from_bytes(bytes(data[:width]).ljust(width, b"\0"), "little")
    if ctype.data_type is DataType.BOOLEAN:
        return 1.0 if raw else 0.0
    if ctype.data_type is DataType.FLOAT and bits == 16:
        return float(_HALF.unpack(raw.to_bytes(2, "little"))[0])
    raw &= (1 << bits) - 1
    if ctype.data_type is DataType.SIGNED:
        top = (1 << (bits - 1)) - 1
        if raw & (1 << (bits - 1)):
            raw -= 1 << bits
        return raw / top
    return raw / ((1 << bits) - 1)


def decode_raw(type_value: int, data: bytes) -> float:
    """A data frame's value in the type's own numbers (what the channel sent: unsigned
    0…2^bits−1, signed two's complement, a half float, a flag 0/1) — what a person reads on
    an axis that spans the type's range (``model/value_axis.py``)."""
    ctype = ChannelType(type_value)
    fraction = decode_sample(type_value, data)
    if ctype.data_type is DataType.UNSIGNED:
        return float(round(fraction * ((1 << ctype.bits) - 1)))
    if ctype.data_type is DataType.SIGNED:
        return float(round(fraction * ((1 << (ctype.bits - 1)) - 1)))
    return fraction


def _emg(t: float, phase: float) -> float:
    """A muscle contracting every ~2 s: a smooth burst plus a little tremor."""
    cycle = (t + phase) % 2.0
    burst = math.sin(math.pi * cycle / 0.8) ** 2 if cycle < 0.8 else 0.0
    return min(1.0, 0.05 + 0.85 * burst + 0.05 * math.sin(37.0 * t + phase))


def synthetic_value(channel: Channel, t: float, phase: float = 0.0) -> float:
    """The value a simulated output shows at time ``t`` (0…1, or −1…1 for signed types)."""
    ctype = channel.ctype
    root, second = channel.profile >> 12, channel.profile >> 8 & 0xF
    if ctype.data_type is DataType.BOOLEAN or (root == 2 and second == 2 and channel.profile
                                               & 0xFF == 0):
        return 1.0 if (t + phase) % 2.0 < 0.5 else 0.0  # a push button
    if root == 4 and second == 2:
        value = _emg(t, phase)
    elif root == 2 and second == 1:
        value = 0.5 + 0.5 * math.sin(2 * math.pi * 0.25 * t + phase)  # a joystick axis
    elif root == 2:
        tri = ((t + phase) / 3.0) % 2.0
        value = tri if tri < 1.0 else 2.0 - tri  # a grip set point closing and opening
    else:
        value = 0.5 + 0.5 * math.sin(2 * math.pi * 0.5 * t + phase)
    return value * 2.0 - 1.0 if ctype.data_type is DataType.SIGNED else value
