"""Host link 2, the frame layer: COBS-delimited binary frames with a sequence number and a CRC.

A frame on the line (docs/host-link.md §2) is the COBS encoding of

    kind (u8) | seq (u8) | len (u8) | payload (len bytes, ≤ 255) | CRC-16/CCITT-FALSE (u16 BE)

followed by one 0x00 delimiter. COBS (Consistent Overhead Byte Stuffing) removes every zero
from the frame, so a reader that meets garbage or a flipped bit resynchronises at the next
0x00: a glitch costs one frame, never the link, and the longest frame on the line is
263 bytes. The CRC (poly 0x1021, init 0xFFFF — the stored configuration's checksum) covers
kind, seq, len and payload.

Pure: no I/O, no clocks. The link state machine is in ``hostlink_link``; the messages carried
in DATA payloads are in ``hostlink_messages``.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from enum import IntEnum

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.crc import crc16_ccitt_false

__all__ = ["MAX_PAYLOAD", "MAX_WIRE", "Frame", "FrameReader", "Kind", "cobs_decode",
           "cobs_encode", "crc16_ccitt_false"]

#: Largest DATA payload (one message: code byte + up to 254 bytes of body).
MAX_PAYLOAD = 255
# kind, seq, len
_HEADER = struct.Struct(">BBB")
# CRC-16/CCITT-FALSE over header + payload, big-endian
_CRC = struct.Struct(">H")
#: Largest unencoded frame: header + payload + CRC.
MAX_RAW = _HEADER.size + MAX_PAYLOAD + _CRC.size
#: Largest frame on the line: COBS adds one byte per 254 (2 here) plus the 0x00 delimiter.
MAX_WIRE = MAX_RAW + (MAX_RAW + 253) // 254 + 1
DELIMITER = 0x00


class Kind(IntEnum):
    """What a frame is; only DATA carries a payload."""

    DATA = 0x01  # a message; the receiver answers ACK (or NAK)
    ACK = 0x02  # seq = the DATA frame received
    NAK = 0x03  # seq = the DATA frame expected next: "resend it now"
    RESET = 0x04  # seq 0: both directions start again at seq 0 (sent by the host)


def cobs_encode(data: bytes) -> bytes:
    """COBS: no 0x00 in the result; one code byte per run of up to 254 non-zero bytes."""
    out = bytearray()
    block = bytearray()
    for byte in data:
        if byte == 0:
            out.append(len(block) + 1)
            out += block
            block.clear()
        else:
            block.append(byte)
            if len(block) == 254:
                out.append(255)
                out += block
                block.clear()
    out.append(len(block) + 1)
    out += block
    return bytes(out)


def cobs_decode(data: bytes) -> bytes:
    """Undo :func:`cobs_encode`; FrameError when a code byte points past the end or is 0."""
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        code = data[i]
        if code == 0:
            raise FrameError(f"COBS: a zero byte at {i} inside a frame")
        end = i + code
        if end > n:
            raise FrameError(f"COBS: code {code} at {i} runs past the frame's {n} bytes")
        out += data[i + 1:end]
        i = end
        if code != 255 and i < n:
            out.append(0)
    return bytes(out)


@dataclass(frozen=True)
class Frame:
    kind: Kind
    seq: int
    payload: bytes = b""

    def encode(self) -> bytes:
        """The frame as it goes on the line, delimiter included."""
        if not 0 <= self.seq <= 0xFF:
            raise FrameError(f"host-link sequence number {self.seq} is not a byte")
        if len(self.payload) > MAX_PAYLOAD:
            raise FrameError(f"host-link payload of {len(self.payload)} bytes > {MAX_PAYLOAD}")
        raw = _HEADER.pack(self.kind, self.seq, len(self.payload)) + bytes(self.payload)
        return cobs_encode(raw + _CRC.pack(crc16_ccitt_false(raw))) + b"\x00"


def parse_frame(encoded: bytes) -> Frame:
    """One frame from the bytes between two delimiters; FrameError says why not."""
    if len(encoded) > MAX_WIRE - 1:
        raise FrameError(f"oversize frame: {len(encoded)} bytes > {MAX_WIRE - 1}")
    raw = cobs_decode(encoded)
    if len(raw) < _HEADER.size + _CRC.size:
        raise FrameError(f"short frame: {len(raw)} bytes")
    body, (crc,) = raw[:-_CRC.size], _CRC.unpack_from(raw, len(raw) - _CRC.size)
    if crc != crc16_ccitt_false(body):
        raise FrameError(f"bad CRC 0x{crc:04X} (computed 0x{crc16_ccitt_false(body):04X})")
    kind, seq, length = _HEADER.unpack_from(body)
    if length != len(body) - _HEADER.size:
        raise FrameError(f"length byte {length} but {len(body) - _HEADER.size} payload bytes")
    try:
        return Frame(Kind(kind), seq, bytes(body[_HEADER.size:]))
    except ValueError as err:
        raise FrameError(f"unknown frame kind 0x{kind:02X}") from err


class FrameReader:
    """Incremental decoder: feed bytes as they arrive, get whole frames.

    Bytes are collected up to the next 0x00; a run longer than the largest frame is dropped
    at once (bounded memory, as on the microcontroller). ``errors`` counts dropped frames
    and ``last_error`` says why the last one was dropped.
    """

    def __init__(self) -> None:
        self._buf = bytearray()
        self._overflow = False
        self.errors = 0
        self.last_error = ""

    def discard(self) -> None:
        """Forget a frame begun but not ended (the link was reset)."""
        self._buf.clear()
        self._overflow = False

    def feed(self, data: bytes) -> list[Frame | FrameError]:
        """Whole frames in ``data`` (with what came before); a dropped one as its FrameError."""
        out: list[Frame | FrameError] = []
        start = 0
        while True:
            end = data.find(b"\x00", start)
            if end < 0:
                self._take(data[start:])
                return out
            self._take(data[start:end])
            start = end + 1
            if self._overflow:
                out.append(self._note(FrameError(f"oversize frame: more than {MAX_WIRE - 1} "
                                                 "bytes before a delimiter")))
            elif self._buf:
                try:
                    out.append(parse_frame(bytes(self._buf)))
                except FrameError as err:
                    out.append(self._note(err))
            self._buf.clear()
            self._overflow = False

    def _take(self, chunk: bytes) -> None:
        if self._overflow or not chunk:
            return
        if len(self._buf) + len(chunk) > MAX_WIRE - 1:
            self._overflow = True
            self._buf.clear()
        else:
            self._buf += chunk

    def _note(self, err: FrameError) -> FrameError:
        self.errors += 1
        self.last_error = str(err)
        return err
