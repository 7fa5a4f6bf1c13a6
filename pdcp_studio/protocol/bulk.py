"""Bulk data transfer: cutting a value into 0x0E packets and putting it back together.

001 §3.3.6–3.3.7: packet IDs count from 1, each packet carries 6 bytes, the last one fewer.
The packet ID is one byte, so at most 255 packets — 1530 bytes — fit one transfer, although
the size field of 0x0C / 0x0D is 16 bits.
"""

from __future__ import annotations

from typing import NamedTuple

from pdcp_studio.errors import FrameError

#: Data bytes per 0x0E packet (DLC 8 minus the code and packet-ID bytes).
PACKET_SIZE = 6
#: Packet IDs are 1…255.
MAX_PACKETS = 255
#: The most bytes one bulk transfer can carry.
MAX_PAYLOAD = MAX_PACKETS * PACKET_SIZE


class Packet(NamedTuple):
    """One 0x0E packet's content; wrap it in ``messages.BulkData`` to send it."""

    packet_id: int
    data: bytes


def packet_count(size: int) -> int:
    """How many packets a payload of ``size`` bytes takes."""
    return -(-size // PACKET_SIZE)


def _check_size(size: int) -> None:
    if not 0 <= size <= MAX_PAYLOAD:
        raise FrameError(
            f"bulk transfer of {size} bytes does not fit: at most {MAX_PAYLOAD} "
            f"({MAX_PACKETS} packets of {PACKET_SIZE} bytes)"
        )


def packetize(payload: bytes) -> list[Packet]:
    """Cut ``payload`` into packets 1, 2, … of 6 bytes (the last shorter); none if empty."""
    payload = bytes(payload)
    _check_size(len(payload))
    return [
        Packet(number + 1, payload[offset:offset + PACKET_SIZE])
        for number, offset in enumerate(range(0, len(payload), PACKET_SIZE))
    ]


class BulkReassembler:
    """Collects the packets of one transfer, in order, and checks them as they come.

    The size comes from the 0x8C / 0x0D frame. Packets must arrive in order with 6 bytes
    each except the last; a wrong packet ID, a short packet or extra bytes raise FrameError.
    """

    def __init__(self, expected_size: int) -> None:
        _check_size(expected_size)
        self.expected_size = expected_size
        self._buffer = bytearray()
        self._next_id = 1

    @property
    def next_packet_id(self) -> int:
        return self._next_id

    @property
    def received(self) -> int:
        """Bytes received so far."""
        return len(self._buffer)

    @property
    def complete(self) -> bool:
        return len(self._buffer) == self.expected_size

    def add(self, packet_id: int, data: bytes) -> bool:
        """Accept the next packet; returns ``complete``."""
        data = bytes(data)
        if self.complete:
            raise FrameError(
                f"bulk packet {packet_id}: the transfer of {self.expected_size} bytes "
                "is already complete"
            )
        if packet_id != self._next_id:
            raise FrameError(f"bulk packet {packet_id} arrived, packet {self._next_id} expected")
        remaining = self.expected_size - len(self._buffer)
        want = min(PACKET_SIZE, remaining)
        if len(data) != want:
            if len(data) > remaining:
                problem = "overflows the transfer"
            else:
                problem = "is too long" if len(data) > want else "is short"
            raise FrameError(
                f"bulk packet {packet_id} carries {len(data)} bytes and {problem} "
                f"({want} expected, {remaining} of {self.expected_size} still to come)"
            )
        self._buffer += data
        self._next_id += 1
        return self.complete

    def result(self) -> bytes:
        """The reassembled payload; FrameError if packets are still missing."""
        if not self.complete:
            raise FrameError(
                f"bulk transfer incomplete: {len(self._buffer)} of {self.expected_size} bytes"
            )
        return bytes(self._buffer)
