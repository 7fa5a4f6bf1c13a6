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

A monitor counts every frame of a saturated bus, so ``frame_bits`` does not build a bit list:
it walks the data 16 bits at a time through tables that carry the stuffing state (the value of
the last bit and the length of its run) and the CRC register from chunk to chunk (see
``_Tables``). ``frame_bitstream`` and ``stuff_bit_count`` are the plain bit-by-bit definition
the tables are tested against.
"""

from __future__ import annotations

from array import array
from functools import cache

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
    if worst_case:
        data = _check(arbitration_id, data)
        return worst_case_bits(len(data))
    if not 0 <= arbitration_id <= 0x7FF or len(data) > MAX_DATA:
        _check(arbitration_id, data)  # raises with the reason
    return _tables().exact_bits(arbitration_id, bytes(data))


def plain_frame_bits(arbitration_id: int, data: bytes) -> int:
    """``frame_bits`` the slow, obvious way: build the stream, count its stuff bits."""
    stream = frame_bitstream(arbitration_id, data)
    return len(stream) + stuff_bit_count(stream) + TRAILER_BITS


def _stuff_step(state: int, value: int, width: int) -> tuple[int, int]:
    """Feed ``width`` bits (MSB first) to a stuffer in ``state``; (stuff bits, new state).

    A state is ``last_bit * 4 + run - 1`` for a run of 1–4 equal bits (a fifth equal bit
    makes a stuff bit, which starts a run of 1 of the opposite value).
    """
    last, run, stuffed = state >> 2, (state & 3) + 1, 0
    for shift in range(width - 1, -1, -1):
        bit = value >> shift & 1
        if bit == last:
            run += 1
        else:
            last, run = bit, 1
        if run == 5:
            stuffed += 1
            last, run = 1 - bit, 1
    return stuffed, last * 4 + run - 1


def _crc_chunk(crc: int, value: int, width: int) -> int:
    for shift in range(width - 1, -1, -1):
        feedback = (value >> shift & 1) ^ (crc >> 14 & 1)
        crc = crc << 1 & 0x7FFF
        if feedback:
            crc ^= CRC15_POLY
    return crc


#: Bits of a base frame that are never stuff bits, beside its 8 bits per data byte.
_FIXED_BITS = HEADER_BITS + CRC_BITS + TRAILER_BITS


class _Tables:
    """Lookup tables for exact frame lengths, built once (≈ 0.1 s, under 1 MB).

    ``stuff16[state << 16 | chunk]`` = stuff bits × 16 + next state for a 16-bit chunk (at
    most 4 stuff bits, so a byte holds it), ``stuff8`` the same for a lone byte, and
    ``tail[state << 15 | crc]`` the stuff bits the 15 CRC bits get. ``crc16[x]`` is the CRC
    register after 16 bits ``x`` from 0; since the register is 15 bits wide, the register
    ``c`` before a chunk ``v`` folds in as ``crc16[v ^ c << 1]``. Headers (SOF to DLC: the
    identifier and length only) are few, so they are memoised by (identifier, length).
    """

    def __init__(self) -> None:
        states = range(8)
        step8 = [[_stuff_step(s, v, 8) for v in range(256)] for s in states]
        self.stuff8 = bytes(n << 4 | t for row in step8 for n, t in row)
        # 16 bits = high byte then low byte: the low byte's row of the state after the high
        # byte, with the high byte's stuff bits added (a translate per (state, high byte)).
        add = [bytes(min(255, x + 16 * k) for x in range(256)) for k in range(3)]
        rows = [self.stuff8[256 * s:256 * s + 256] for s in states]
        self.stuff16 = b"".join(rows[t].translate(add[n])
                                for row in step8 for n, t in row)
        step7 = [[_stuff_step(s, v, 7) for v in range(128)] for s in states]
        counts = [bytes(x >> 4 for x in row) for row in rows]
        add_count = [bytes(min(255, x + k) for x in range(256)) for k in range(3)]
        self.tail = b"".join(counts[t].translate(add_count[n])
                             for row in step7 for n, t in row)
        crc8 = [_crc_chunk(0, v, 8) for v in range(256)]
        crc16 = array("H", bytes(2 * 65536))
        for hi in range(256):
            c1 = crc8[hi]
            base = (c1 << 8) & 0x7FFF
            top = c1 >> 7
            for lo in range(256):
                crc16[hi << 8 | lo] = base ^ crc8[(top ^ lo) & 0xFF]
        self.crc8, self.crc16 = crc8, crc16
        self.headers: dict[int, tuple[int, int, int]] = {}

    def header(self, key: int) -> tuple[int, int, int]:
        """(stuff bits, stuffer state, CRC) after SOF … DLC for ``key = id << 4 | dlc``."""
        bits = [0, *_bits(key >> 4, 11), 0, 0, 0, *_bits(key & 15, 4)]
        stuffed, last, run = 0, -1, 0
        for bit in bits:
            if bit == last:
                run += 1
            else:
                last, run = bit, 1
            if run == 5:
                stuffed += 1
                last, run = 1 - bit, 1
        state = (stuffed, last * 4 + run - 1, crc15(bits))
        self.headers[key] = state
        return state

    def exact_bits(self, arbitration_id: int, data: bytes) -> int:
        n = len(data)
        key = arbitration_id << 4 | n
        stuffed, state, crc = self.headers.get(key) or self.header(key)
        stuff16, crc16 = self.stuff16, self.crc16
        i = 0
        while i + 1 < n:  # 16 bits at a time
            chunk = data[i] << 8 | data[i + 1]
            step = stuff16[state << 16 | chunk]
            crc = crc16[chunk ^ crc << 1]
            stuffed += step >> 4
            state = step & 15
            i += 2
        if i < n:  # one byte left
            byte = data[i]
            step = self.stuff8[state << 8 | byte]
            crc = (crc << 8 & 0x7FFF) ^ self.crc8[(crc >> 7 ^ byte) & 0xFF]
            stuffed += step >> 4
            state = step & 15
        return _FIXED_BITS + 8 * n + stuffed + self.tail[state << 15 | crc]


@cache
def _tables() -> _Tables:
    return _Tables()


def frame_time_us(arbitration_id: int, data: bytes, worst_case: bool = False,
                  bitrate: int = BITRATE) -> float:
    """Microseconds the frame occupies the bus at ``bitrate`` (1 µs per bit at 1 Mbit/s)."""
    return frame_bits(arbitration_id, data, worst_case) * 1e6 / bitrate


#: Frames a meter gathers before it counts their bits in one vectorised pass.
BATCH = 4096


class _BatchCounter:
    """The tables as numpy arrays: exact bits of many frames at once (a monitor's hot path).

    Per frame the caller only appends the identifier and data; every ``BATCH`` frames the
    header, the 16-bit data chunks, a lone last byte and the CRC tail go through the same
    tables as ``_Tables.exact_bits``, for all frames of the batch together.
    """

    def __init__(self, tables: _Tables) -> None:
        import numpy as np

        self.np = np
        i64 = np.int64
        # Small element types keep the tables in cache; gathers index them with int64.
        self.stuff16 = np.frombuffer(tables.stuff16, np.uint8)
        self.stuff8 = np.frombuffer(tables.stuff8, np.uint8)
        self.tail = np.frombuffer(tables.tail, np.uint8)
        self.crc16 = np.frombuffer(tables.crc16, np.uint16)
        self.crc8 = np.array(tables.crc8, np.uint16)
        # Every header at once: SOF (a 0: state "0, run 1", CRC 0), then 18 bits
        # id << 7 | dlc as a 2-bit chunk and a 16-bit chunk.
        keys = np.arange(1 << 15, dtype=i64)
        value = (keys >> 4) << 7 | (keys & 15)
        top, low = value >> 16, value & 0xFFFF
        step2 = np.array([_stuff_step(0, v, 2) for v in range(4)], i64)
        crc = np.array([_crc_chunk(0, v, 2) for v in range(4)], i64)[top]
        stuffed, state = step2[top, 0], step2[top, 1]
        step = self.stuff16[state << 16 | low].astype(i64)
        self.h_stuff = stuffed + (step >> 4)
        self.h_state = step & 15
        self.h_crc = self.crc16[low ^ crc << 1].astype(i64)

    def bits(self, ids: list[int], payloads: list[bytes]) -> int:
        np = self.np
        n = len(ids)
        dlc = np.fromiter(map(len, payloads), np.int64, n)
        flat = np.frombuffer(b"".join(payloads) + bytes(8), np.uint8).astype(np.int64)
        start = np.cumsum(dlc) - dlc  # byte k of frame i is flat[start[i] + k]
        key = np.array(ids, np.int64) << 4 | dlc
        stuffed, state, crc = self.h_stuff[key], self.h_state[key], self.h_crc[key]
        for j in range(4):
            active = dlc >= 2 * j + 2
            if not active.any():
                break
            chunk = flat[start + 2 * j] << 8 | flat[start + 2 * j + 1]
            step = self.stuff16[state << 16 | chunk].astype(np.int64)
            new_crc = self.crc16[chunk ^ crc << 1].astype(np.int64)
            stuffed = stuffed + np.where(active, step >> 4, 0)
            state = np.where(active, step & 15, state)
            crc = np.where(active, new_crc, crc)
        odd = (dlc & 1) == 1
        if odd.any():
            byte = flat[start + np.maximum(dlc - 1, 0)]
            step = self.stuff8[state << 8 | byte].astype(np.int64)
            new_crc = (crc << 8 & 0x7FFF) ^ self.crc8[(crc >> 7 ^ byte) & 0xFF].astype(np.int64)
            stuffed = stuffed + np.where(odd, step >> 4, 0)
            state = np.where(odd, step & 15, state)
            crc = np.where(odd, new_crc, crc)
        stuffed = stuffed + self.tail[state << 15 | crc].astype(np.int64)
        return int(n * _FIXED_BITS + 8 * dlc.sum() + stuffed.sum())


@cache
def _batch_counter() -> _BatchCounter:
    return _BatchCounter(_tables())


class BusTimeMeter:
    """Adds up the bus time of frames; with timestamps, the load over the observed span.

    A monitor or a simulation feeds every frame; ``load()`` is busy time over elapsed time.
    ``add`` only queues a frame (cheap enough for a saturated bus); ``bits`` counts what is
    queued first, so every figure read from the meter is exact.
    """

    def __init__(self, worst_case: bool = False, bitrate: int = BITRATE) -> None:
        self.worst_case, self.bitrate = worst_case, bitrate
        self.frames = 0
        self._bits = 0
        self.first_timestamp: float | None = None
        self.last_timestamp: float | None = None
        self._ids: list[int] = []
        self._payloads: list[bytes] = []

    def add(self, arbitration_id: int, data: bytes, timestamp: float | None = None) -> None:
        """Count one classical base frame; ValueError (counting nothing) if it is not one."""
        if not 0 <= arbitration_id <= 0x7FF or len(data) > MAX_DATA:
            _check(arbitration_id, data)
        self.frames += 1
        if self.worst_case:
            self._bits += worst_case_bits(len(data))
        else:
            self._ids.append(arbitration_id)
            self._payloads.append(bytes(data))
            if len(self._ids) >= BATCH:
                self._count()
        if timestamp is not None:
            if self.first_timestamp is None:
                self.first_timestamp = timestamp
            self.last_timestamp = timestamp

    def add_base(self, arbitration_id: int, data: bytes, timestamp: float) -> None:
        """``add`` for a caller that knows the frame is a base frame of 0–8 bytes (``data``
        being ``bytes``): the monitor's hot path."""
        self.frames += 1
        ids = self._ids
        ids.append(arbitration_id)
        self._payloads.append(data)
        if len(ids) >= BATCH:
            self._count()
        if self.first_timestamp is None:
            self.first_timestamp = timestamp
        self.last_timestamp = timestamp

    def add_batch(self, ids: list[int], payloads: list[bytes], last_timestamp: float) -> None:
        """``add_base`` for many frames at once (the lists are taken over, not copied)."""
        if not ids:
            return
        self.frames += len(ids)
        if self.worst_case:
            self._bits += sum(worst_case_bits(len(data)) for data in payloads)
        elif self._ids:
            self._ids += ids
            self._payloads += payloads
        else:
            self._ids, self._payloads = ids, payloads
        if len(self._ids) >= BATCH:
            self._count()
        if self.first_timestamp is None:
            self.first_timestamp = last_timestamp
        self.last_timestamp = last_timestamp

    def _count(self) -> None:
        if self._ids:
            ids, payloads = self._ids, self._payloads
            if max(ids) > 0x7FF or max(map(len, payloads)) > MAX_DATA:
                # A capture from another tool may hold frames no base frame can be (a 29-bit
                # ID marked standard, more than 8 data bytes): counted at their worst case
                # as extended frames (20 more header bits), never indexed into the tables.
                odd = [n for n, (i, p) in enumerate(zip(ids, payloads, strict=True))
                       if i > 0x7FF or len(p) > MAX_DATA]
                skip = set(odd)
                self._bits += sum(worst_case_bits(min(len(payloads[n]), MAX_DATA)) + 20
                                  for n in odd)
                ids = [i for n, i in enumerate(ids) if n not in skip]
                payloads = [p for n, p in enumerate(payloads) if n not in skip]
            if ids:
                self._bits += _batch_counter().bits(ids, payloads)
            self._ids, self._payloads = [], []

    @property
    def bits(self) -> int:
        """Bits the counted frames occupy, intermissions included."""
        self._count()
        return self._bits

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
        self.frames = self._bits = 0
        self._ids, self._payloads = [], []
        self.first_timestamp = self.last_timestamp = None
