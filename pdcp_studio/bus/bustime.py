"""How long PDCP frames occupy a real 1 Mbit/s CAN bus, so a simulation can quote bus time.

PDCP uses CAN 2.0A base data frames (11-bit identifier, 0–8 data bytes). A frame is:

    SOF 1 · identifier 11 · RTR 1 · IDE 1 · r0 1 · DLC 4 · data 8n · CRC 15   (34 + 8n bits,
        subject to bit stuffing)
    CRC delimiter 1 · ACK slot 1 · ACK delimiter 1 · EOF 7 · intermission 3    (13 bits, never
        stuffed)

Bit stuffing (ISO 11898-1): after five equal bits in a row the sender inserts one of the opposite
value, which itself starts the next run. A stuffed region of ``L`` bits gets at most
``floor((L - 1) / 4)`` stuff bits (the first after 5 bits, then every 4 when the stuff bits
themselves continue the pattern), so the worst case for a base frame is

    47 + 8n + floor((34 + 8n - 1) / 4) bits          (55 bits for n = 0, 135 for n = 8)

— the formula of R. I. Davis, A. Burns, R. J. Bril, J. J. Lukkien, "Controller Area Network
(CAN) schedulability analysis: Refuted, revisited and revised", Real-Time Systems 35 (2007),
eq. (1) with g = 34, and the value Linux's ``can_frame_bits()`` (include/linux/can/length.h)
gives for classical base frames. ``frame_bits(..., worst_case=False)`` counts the stuff bits a
given frame really gets, computing its CRC-15 (polynomial 0x4599, initial value 0), as
can-utils' ``canframelen.c`` (CFL_EXACT mode) does. The 3-bit intermission is included in both,
so back-to-back frames add up to the bus time they take.
"""

from __future__ import annotations

from dataclasses import dataclass

#: PDCP runs CAN at 1 Mbit/s (reference §1).
BITRATE = 1_000_000
#: Bits after the CRC that are never stuffed: CRC delimiter, ACK slot and delimiter, EOF, IFS.
TRAILER_BITS = 13
#: Bits from SOF to the end of the DLC in a base frame (SOF, ID 11, RTR, IDE, r0, DLC 4).
HEADER_BITS = 19
CRC_BITS = 15
CRC15_POLY = 0x4599
MAX_DATA = 8


def _check(arbitration_id: int, data: bytes) -> bytes:
    if not 0 <= arbitration_id <= 0x7FF:
        raise ValueError(f"arbitration ID 0x{arbitration_id:X} is not an 11-bit base identifier")
    data = bytes(data)
    if len(data) > MAX_DATA:
        raise ValueError(f"{len(data)} data bytes (a classical CAN frame has 0–8)")
    return data


def worst_case_bits(dlc: int) -> int:
    """Bits a base data frame with ``dlc`` bytes takes at most (Davis et al. 2007, eq. 1)."""
    if not 0 <= dlc <= MAX_DATA:
        raise ValueError(f"DLC {dlc} is out of range (0–8)")
    stuffed_region = HEADER_BITS + 8 * dlc + CRC_BITS
    return stuffed_region + TRAILER_BITS + (stuffed_region - 1) // 4


def crc15(bits: list[int]) -> int:
    """The CAN CRC-15 of a bit sequence (SOF through the last data bit)."""
    crc = 0
    for bit in bits:
        feedback = bit ^ (crc >> 14 & 1)
        crc = crc << 1 & 0x7FFF
        if feedback:
            crc ^= CRC15_POLY
    return crc


def _bits(value: int, width: int) -> list[int]:
    return [value >> shift & 1 for shift in range(width - 1, -1, -1)]


def frame_bitstream(arbitration_id: int, data: bytes, *, remote: bool = False) -> list[int]:
    """The unstuffed bits from SOF through the CRC of a base frame (0 dominant, 1 recessive)."""
    data = _check(arbitration_id, data)
    bits = [0, *_bits(arbitration_id, 11), int(remote), 0, 0, *_bits(len(data), 4)]
    if not remote:
        for byte in data:
            bits += _bits(byte, 8)
    return bits + _bits(crc15(bits), CRC_BITS)


def stuff_bit_count(bits: list[int]) -> int:
    """Stuff bits a sender inserts into ``bits`` (a stuff bit starts the next run)."""
    stuffed = 0
    last, run = -1, 0
    for bit in bits:
        if bit == last:
            run += 1
        else:
            last, run = bit, 1
        if run == 5:
            stuffed += 1
            last, run = 1 - bit, 1
    return stuffed


def frame_bits(arbitration_id: int, data: bytes, worst_case: bool = False) -> int:
    """Bits a base data frame occupies on the bus, including the 3-bit intermission.

    ``worst_case`` ignores the actual bits and assumes maximal stuffing (for planning);
    otherwise the frame's own bits and CRC decide how many stuff bits it gets.
    """
    data = _check(arbitration_id, data)
    if worst_case:
        return worst_case_bits(len(data))
    stream = frame_bitstream(arbitration_id, data)
    return len(stream) + stuff_bit_count(stream) + TRAILER_BITS


def frame_time_us(arbitration_id: int, data: bytes, worst_case: bool = False,
                  bitrate: int = BITRATE) -> float:
    """Microseconds the frame occupies the bus at ``bitrate`` (1 µs per bit at 1 Mbit/s)."""
    return frame_bits(arbitration_id, data, worst_case) * 1e6 / bitrate


@dataclass
class BusTimeMeter:
    """Adds up the bus time of frames; with timestamps, the load over the observed span.

    A monitor or a simulation feeds every frame; ``load()`` is busy time over elapsed time.
    """

    worst_case: bool = False
    bitrate: int = BITRATE
    frames: int = 0
    bits: int = 0
    first_timestamp: float | None = None
    last_timestamp: float | None = None

    def add(self, arbitration_id: int, data: bytes, timestamp: float | None = None) -> int:
        """Count one frame; returns its length in bits."""
        n = frame_bits(arbitration_id, data, self.worst_case)
        self.frames += 1
        self.bits += n
        if timestamp is not None:
            if self.first_timestamp is None:
                self.first_timestamp = timestamp
            self.last_timestamp = timestamp
        return n

    @property
    def bus_time_s(self) -> float:
        """Total time the counted frames occupy the bus, in seconds."""
        return self.bits / self.bitrate

    @property
    def bus_time_us(self) -> float:
        return self.bits * 1e6 / self.bitrate

    @property
    def span_s(self) -> float:
        """Seconds from the first to the last timestamped frame (0 if fewer than two)."""
        if self.first_timestamp is None or self.last_timestamp is None:
            return 0.0
        return max(0.0, self.last_timestamp - self.first_timestamp)

    def load(self, elapsed_s: float | None = None) -> float | None:
        """Fraction of ``elapsed_s`` (default: the timestamp span) the bus was busy.

        None when there is no time to compare with; may exceed 1 for simulated captures whose
        timestamps are denser than a real bus allows.
        """
        elapsed = self.span_s if elapsed_s is None else elapsed_s
        if elapsed <= 0:
            return None
        return self.bus_time_s / elapsed

    def reset(self) -> None:
        self.frames = self.bits = 0
        self.first_timestamp = self.last_timestamp = None
