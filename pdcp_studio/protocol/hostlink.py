"""The arbitrator's host link: framed request/response messages over a serial line.

The thesis's hardware arbitrator exposed a UART "Bus Arbitrator API" (thesis §5.2.1):
a message ID, a length and a variable payload; the host always initiates; IDs come
in threes — request *n*, success *n + 1*, failure *n + 2*. Its documentation is not
public, so PDCP Studio defines its own framing in that shape (docs/host-link.md):

    0xA5 | message id (u8) | length (u16 LE) | payload | CRC-16/CCITT-FALSE (u16 LE)

The CRC covers id, length and payload. ``FrameReader`` resynchronises on the next
0xA5 after garbage or a bad CRC, so a glitch on the line costs one message, not the link.
Pure: no I/O.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from enum import IntEnum

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.crc import crc16_ccitt_false

SYNC = 0xA5
MAX_PAYLOAD = 60_000
# header after SYNC: message id, payload length
_HEADER = struct.Struct("<BH")
_CRC = struct.Struct("<H")


class HostCommand(IntEnum):
    """Request IDs; ``+1`` is the success reply and ``+2`` the failure reply."""

    PING = 0x10  # → payload: JSON {"name", "version"}
    GET_SYSTEM = 0x13  # → JSON pdcp-system/1 with node IDs
    GET_PARAMETER = 0x16  # vid pid serial (u16 ×3) chan param → value bytes
    SET_PARAMETER = 0x19  # vid pid serial chan param value → value read back
    ADD_LINK = 0x1C  # output ref, input ref (u16 ×3 + u8 each)
    REMOVE_LINK = 0x1F  # output ref, input ref
    READ_CONFIGURATION = 0x22  # → stored-configuration bytes
    WRITE_CONFIGURATION = 0x25  # stored-configuration bytes → bytes read back
    POLL_EVENTS = 0x28  # → JSON list of events since the last poll
    PREVIEW_PLAN = 0x2B  # mode (ASCII) → JSON plan
    APPLY_PLAN = 0x2E  # mode (ASCII) → JSON plan applied
    RESET_DEVICE = 0x31  # vid pid serial
    # The change road (issue 8): one transaction carried out by the arbitrator.
    TRANSACT = 0x34  # JSON Change → JSON TransactionResult
    READ_POLICY = 0x37  # → JSON {"autoconfigure": bool}


def reply_ok(command: int) -> int:
    return command + 1


def reply_fail(command: int) -> int:
    return command + 2


@dataclass(frozen=True)
class HostMessage:
    msg_id: int
    payload: bytes = b""

    def encode(self) -> bytes:
        if not 0 <= self.msg_id <= 0xFF:
            raise FrameError(f"host-link message id {self.msg_id} is not a byte")
        if len(self.payload) > MAX_PAYLOAD:
            raise FrameError(f"host-link payload of {len(self.payload)} bytes > {MAX_PAYLOAD}")
        body = _HEADER.pack(self.msg_id, len(self.payload)) + self.payload
        return bytes([SYNC]) + body + _CRC.pack(crc16_ccitt_false(body))


class FrameReader:
    """Incremental decoder: feed bytes as they arrive, collect whole messages.

    ``errors`` counts frames dropped for a bad CRC, an oversize length or garbage.
    """

    def __init__(self) -> None:
        self._buf = bytearray()
        self.errors = 0
        self.last_error = ""

    def feed(self, data: bytes) -> list[HostMessage]:
        self._buf += data
        out: list[HostMessage] = []
        while True:
            start = self._buf.find(SYNC)
            if start < 0:
                if self._buf:
                    self._note(f"{len(self._buf)} bytes of garbage before a sync byte")
                self._buf.clear()
                return out
            if start:
                self._note(f"{start} bytes of garbage before a sync byte")
                del self._buf[:start]
            if len(self._buf) < 1 + _HEADER.size:
                return out
            msg_id, length = _HEADER.unpack_from(self._buf, 1)
            if length > MAX_PAYLOAD:
                self._note(f"length {length} > {MAX_PAYLOAD}")
                del self._buf[:1]
                continue
            total = 1 + _HEADER.size + length + _CRC.size
            if len(self._buf) < total:
                return out
            body = bytes(self._buf[1 : total - _CRC.size])
            (crc,) = _CRC.unpack_from(self._buf, total - _CRC.size)
            if crc != crc16_ccitt_false(body):
                self._note(f"bad CRC on message 0x{msg_id:02X}")
                del self._buf[:1]
                continue
            out.append(HostMessage(msg_id, body[_HEADER.size :]))
            del self._buf[:total]

    def _note(self, reason: str) -> None:
        self.errors += 1
        self.last_error = reason


# -- payload helpers ---------------------------------------------------------------
# device key: vid, pid, serial
_KEY = struct.Struct("<HHH")
# channel reference: vid, pid, serial, index
_REF = struct.Struct("<HHHB")
# parameter address: vid, pid, serial, channel index, parameter id
_PARAM = struct.Struct("<HHHBB")


def pack_key(vid: int, pid: int, serial: int) -> bytes:
    return _KEY.pack(vid, pid, serial)


def unpack_key(payload: bytes) -> tuple[int, int, int]:
    if len(payload) != _KEY.size:
        raise FrameError(f"a device key is {_KEY.size} bytes, not {len(payload)}")
    return _KEY.unpack(payload)


def pack_link(output: tuple[int, int, int, int], input_: tuple[int, int, int, int]) -> bytes:
    return _REF.pack(*output) + _REF.pack(*input_)


def unpack_link(payload: bytes) -> tuple[tuple[int, ...], tuple[int, ...]]:
    if len(payload) != 2 * _REF.size:
        raise FrameError(f"a link is {2 * _REF.size} bytes, not {len(payload)}")
    return _REF.unpack_from(payload, 0), _REF.unpack_from(payload, _REF.size)


def pack_param(
    vid: int, pid: int, serial: int, channel: int, param: int, value: bytes = b""
) -> bytes:
    return _PARAM.pack(vid, pid, serial, channel, param) + value


def unpack_param(payload: bytes) -> tuple[tuple[int, int, int, int, int], bytes]:
    if len(payload) < _PARAM.size:
        raise FrameError(f"a parameter address is {_PARAM.size} bytes, got {len(payload)}")
    return _PARAM.unpack_from(payload, 0), bytes(payload[_PARAM.size :])
