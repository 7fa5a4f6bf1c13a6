"""Recognising host link version 1 on the line, so each end can refuse the other clearly.

Version 1 (PDCP Studio's early builds) framed JSON messages as
``0xA5 | id (u8) | length (u16 LE) | payload | CRC-16/CCITT-FALSE (u16 LE)`` with request IDs
in threes (request n, success n + 1, failure n + 2; PING was 0x10). It has no 0x00 delimiter,
so version 2 readers see it as garbage. :class:`V1Sniffer` watches the raw bytes for a whole,
CRC-valid version-1 frame; the arbitrator then answers a version-1 PC with a version-1
failure reply that says why, and a version-2 PC that hears a version-1 reply tells the user
which versions the two ends speak. Pure.
"""

from __future__ import annotations

import struct

from pdcp_studio.protocol.crc import crc16_ccitt_false

SYNC = 0xA5
PING = 0x10
#: Version-1 frames longer than this are not looked for (a PING and its reply are short).
LARGEST = 512
# after SYNC: message id, payload length
_HEADER = struct.Struct("<BH")
_CRC = struct.Struct("<H")


def encode_v1(msg_id: int, payload: bytes = b"") -> bytes:
    body = _HEADER.pack(msg_id, len(payload)) + payload
    return bytes([SYNC]) + body + _CRC.pack(crc16_ccitt_false(body))


class V1Sniffer:
    """Finds whole version-1 frames in a stream (bounded memory)."""

    def __init__(self) -> None:
        self._buf = bytearray()

    def feed(self, data: bytes) -> list[tuple[int, bytes]]:
        """(id, payload) of each CRC-valid version-1 frame completed by ``data``."""
        self._buf += data
        found: list[tuple[int, bytes]] = []
        start = 0
        while True:
            at = self._buf.find(SYNC, start)
            if at < 0 or len(self._buf) - at < 1 + _HEADER.size:
                break
            msg_id, length = _HEADER.unpack_from(self._buf, at + 1)
            end = at + 1 + _HEADER.size + length + _CRC.size
            if length > LARGEST or end > len(self._buf):
                if length > LARGEST:
                    start = at + 1
                    continue
                break
            body = bytes(self._buf[at + 1:end - _CRC.size])
            (crc,) = _CRC.unpack_from(self._buf, end - _CRC.size)
            if crc == crc16_ccitt_false(body):
                found.append((msg_id, body[_HEADER.size:]))
                start = end
            else:
                start = at + 1
        keep = max(start, len(self._buf) - (1 + _HEADER.size + LARGEST + _CRC.size))
        del self._buf[:keep]
        return found
