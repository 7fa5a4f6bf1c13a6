"""Deterministic fuzzing: mutated valid encodings only ever decode or raise ConfigFormatError.

Each run mutates a few seed encodings (the figure 4.10 files, a larger generated one) with
bit flips, truncations, insertions, deletions, record swaps and duplications. Half of the
mutants whose checksum record is still in place get their checksum repaired, so that the
structural checks behind the checksum are exercised too, not just the CRC.
"""

from __future__ import annotations

import random
from pathlib import Path

from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    UnknownRecord,
)
from pdcp_studio.storage import config_codec as cc

ROOT = Path(__file__).resolve().parents[2]
MUTANTS = 12_000
SEED = 0x4_10


def _generated() -> bytes:
    rng = random.Random(7)

    def channel() -> StoredChannel:
        return StoredChannel(index=rng.randint(1, 255), vid=rng.randint(0, 9),
                             pid=rng.randint(0, 9), serial=rng.randint(0, 99),
                             type=rng.getrandbits(16), profile=rng.getrandbits(16),
                             owner_type=rng.choice([None, 1]), owner_profile=None,
                             unknown=unknown())

    def unknown() -> tuple[UnknownRecord, ...]:
        return tuple(UnknownRecord(rng.choice((0, 17, 0x20, 255)), rng.getrandbits(16),
                                   rng.choice((None, None, 7, 9)))
                     for _ in range(rng.choice((0, 0, 1, 2))))

    return cc.dumps(ConfigCollection([
        StoredConfiguration(i, [StoredLink(channel(), channel(), unknown=unknown())
                                for _ in range(i + 1)], unknown=unknown())
        for i in range(1, 4)], unknown=unknown()))


def _seeds() -> list[bytes]:
    return [
        (ROOT / "resources" / "configs" / "fig410.pdcfg").read_bytes(),
        (ROOT / "tests" / "data" / "fig410-thesis.pdcfg").read_bytes(),
        _generated(),
    ]


def _mutate(rng: random.Random, data: bytes) -> bytes:
    buf = bytearray(data)
    for _ in range(rng.choice((1, 1, 1, 2, 3))):
        records = len(buf) // 3
        kind = rng.randrange(9)
        if kind == 0 and buf:  # bit flip
            i = rng.randrange(len(buf))
            buf[i] ^= 1 << rng.randrange(8)
        elif kind == 1:  # truncation
            del buf[rng.randrange(len(buf) + 1):]
        elif kind == 2:  # random bytes inserted
            i = rng.randrange(len(buf) + 1)
            buf[i:i] = rng.randbytes(rng.randint(1, 4))
        elif kind == 3 and records >= 2:  # two records swapped
            a, b = rng.sample(range(records), 2)
            ra, rb = buf[3 * a:3 * a + 3], buf[3 * b:3 * b + 3]
            if len(ra) == len(rb) == 3:
                buf[3 * a:3 * a + 3], buf[3 * b:3 * b + 3] = rb, ra
        elif kind == 4 and records:  # a record deleted
            i = rng.randrange(records)
            del buf[3 * i:3 * i + 3]
        elif kind == 5 and records:  # a record duplicated
            i = rng.randrange(records)
            buf[3 * i:3 * i] = buf[3 * i:3 * i + 3]
        elif kind == 6 and records:  # a record's code replaced by any code
            buf[3 * rng.randrange(records)] = rng.choice((*range(17), rng.randrange(256)))
        elif kind == 7 and records:  # a value set to an edge value
            i = 3 * rng.randrange(records) + 1
            buf[i:i + 2] = rng.choice((0, 1, 255, 256, 0xFFFF)).to_bytes(2, "little")
        elif kind == 8:  # an unknown record inserted at a record boundary
            i = 3 * rng.randrange(records + 1)
            buf[i:i] = cc._RECORD.pack(rng.choice((0, 17, 0x20, 255)), rng.getrandbits(16))
    return bytes(buf)


def _unknown_records(data: bytes, end_offset: int) -> list[tuple[int, int]]:
    """The records before End whose codes the format does not define, in file order."""
    pairs = cc._RECORD.iter_unpack(data[:end_offset])
    return [(code, value) for code, value in pairs if not 1 <= code <= cc.CHECKSUM]


def _repair_checksum(data: bytes) -> bytes:
    """If a checksum record sits right before End at the end, make it match again."""
    if len(data) >= 6 and data[-6] == cc.CHECKSUM and data[-3] == cc.END:
        crc = cc.crc16_ccitt_false(data[:-6])
        return data[:-5] + crc.to_bytes(2, "little") + data[-3:]
    return data


def test_mutated_encodings_only_raise_config_format_error():
    rng = random.Random(SEED)
    seeds = _seeds()
    decoded = refused = 0
    for _ in range(MUTANTS):
        data = _mutate(rng, rng.choice(seeds))
        if rng.random() < 0.5:
            data = _repair_checksum(data)
        try:
            found = cc.decode(data)
        except ConfigFormatError as err:
            assert 0 <= err.offset <= len(data), (err, data.hex())
            assert err.reason
            refused += 1
        else:
            decoded += 1
            again = cc.dumps(found.collection)
            assert cc.dumps(cc.loads(again)) == again
            # Every unknown record survives, in order (the writer keeps them in place).
            kept = _unknown_records(data, found.end_offset)
            assert len(kept) == found.unknown_records
            assert _unknown_records(again, len(again) - 3) == kept, data.hex()
    assert decoded + refused == MUTANTS
    # Both outcomes must be common, or the mutations are not probing the format.
    assert decoded > MUTANTS // 50 and refused > MUTANTS // 2
