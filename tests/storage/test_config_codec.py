"""The stored-configuration codec against thesis figure 4.10 and every rejection rule.

Figure 4.10 in the thesis OCR shows link 1 of configuration 1 in full, but only the
declaration records of link 2 (``5 0`` / ``6 0``) and of configuration 2's single link;
their values are elided. The golden file fills them in systematically (each further
channel adds 1 to every figure value, the index counts on) and leaves owner type and
profile out of configuration 2 to cover the optional records:

- configuration 1, link 2: input type 11, profile 21, index 2, VID 31, PID 41, serial 51,
  owner type 61, owner profile 71; output 12, 22, 3, 32, 42, 52, 62, 72
- configuration 2, link 1: input 13, 23, 4, 33, 43, 53; output 14, 24, 5, 34, 44, 54
"""

from __future__ import annotations

import io
import struct
from pathlib import Path

import pytest

from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec as cc

ROOT = Path(__file__).resolve().parents[2]
THESIS_FILE = ROOT / "tests" / "data" / "fig410-thesis.pdcfg"
RESOURCE_FILE = ROOT / "resources" / "configs" / "fig410.pdcfg"


def records(pairs: list[tuple[int, int]]) -> bytes:
    return b"".join(struct.pack("<BH", code, value) for code, value in pairs)


def chan(code: int, *values: int) -> list[tuple[int, int]]:
    """A channel declaration: code 5/6, then values for codes 7, 8, 9, … in order."""
    return [(code, 0), *((7 + i, v) for i, v in enumerate(values))]


# Figure 4.10, record by record (values of the elided parts: see the module docstring).
FIG410_RECORDS = [
    (1, 2),                      # 2 configurations
    (2, 1), (3, 2),              # configuration 1 has 2 links
    (4, 1),                      # link 1
    *chan(5, 10, 20, 1, 30, 40, 50, 60, 70),
    *chan(6, 10, 20, 1, 30, 40, 50, 60, 70),
    (4, 2),                      # link 2
    *chan(5, 11, 21, 2, 31, 41, 51, 61, 71),
    *chan(6, 12, 22, 3, 32, 42, 52, 62, 72),
    (2, 2), (3, 1),              # configuration 2 has 1 link
    (4, 1),
    *chan(5, 13, 23, 4, 33, 43, 53),
    *chan(6, 14, 24, 5, 34, 44, 54),
    (15, 0),                     # End
]


def ch(t: int, p: int, i: int, v: int, pid: int, s: int, ot=None, op=None) -> StoredChannel:
    return StoredChannel(index=i, vid=v, pid=pid, serial=s, type=t, profile=p,
                         owner_type=ot, owner_profile=op)


FIG410 = ConfigCollection([
    StoredConfiguration(1, [
        StoredLink(ch(10, 20, 1, 30, 40, 50, 60, 70), ch(10, 20, 1, 30, 40, 50, 60, 70), 1),
        StoredLink(ch(11, 21, 2, 31, 41, 51, 61, 71), ch(12, 22, 3, 32, 42, 52, 62, 72), 2),
    ]),
    StoredConfiguration(2, [
        StoredLink(ch(13, 23, 4, 33, 43, 53), ch(14, 24, 5, 34, 44, 54), 1),
    ]),
])


def with_checksum(body: bytes) -> bytes:
    """Thesis-era bytes (ending in End) → the writer's form, checksum before End."""
    assert body[-3:] == b"\x0f\x00\x00"
    head = body[:-3]
    return head + records([(16, cc.crc16_ccitt_false(head)), (15, 0)])


# -- golden files ---------------------------------------------------------------------------
def test_thesis_golden_file_is_the_figure_byte_for_byte():
    assert THESIS_FILE.read_bytes() == records(FIG410_RECORDS)


def test_thesis_file_decodes_to_the_figure_and_has_no_checksum():
    decoded = cc.decode(THESIS_FILE.read_bytes())
    assert decoded.collection == FIG410
    assert decoded.checksum is None
    assert decoded.unknown_records == 0 and decoded.trailing_bytes == 0


def test_resource_file_is_the_writer_output_with_checksum():
    expected = with_checksum(records(FIG410_RECORDS))
    assert cc.dumps(FIG410) == expected
    assert RESOURCE_FILE.read_bytes() == expected
    decoded = cc.decode(expected)
    assert decoded.collection == FIG410
    assert decoded.checksum == cc.crc16_ccitt_false(expected[:-6])


def test_reencoding_is_identical_and_thesis_file_gains_a_checksum():
    written = RESOURCE_FILE.read_bytes()
    assert cc.dumps(cc.loads(written)) == written
    thesis = THESIS_FILE.read_bytes()
    assert cc.dumps(cc.loads(thesis)) == written


def test_crc16_ccitt_false_check_value():
    assert cc.crc16_ccitt_false(b"123456789") == 0x29B1
    assert cc.crc16_ccitt_false(b"") == 0xFFFF


def test_file_object_and_path_tiers(tmp_path):
    assert cc.load(io.BytesIO(RESOURCE_FILE.read_bytes())) == FIG410
    assert cc.load_path(RESOURCE_FILE) == FIG410
    buffer = io.BytesIO()
    cc.dump(FIG410, buffer)
    assert buffer.getvalue() == RESOURCE_FILE.read_bytes()
    target = tmp_path / "out.pdcfg"
    cc.save_path(FIG410, target)
    assert target.read_bytes() == RESOURCE_FILE.read_bytes()
    assert [p.name for p in tmp_path.iterdir()] == ["out.pdcfg"]


def test_contract_json_of_the_figure():
    doc = cc.to_json(FIG410)
    first = {"type": "0x000A", "profile": "0x0014", "index": 1, "vid": 30, "pid": 40,
             "serial": 50, "owner_type": 60, "owner_profile": 70}
    assert doc["configurations"][0]["index"] == 1
    assert doc["configurations"][0]["links"][0] == {"index": 1, "input": first, "output": first}
    assert doc["configurations"][1]["links"][0]["input"] == {
        "type": "0x000D", "profile": "0x0017", "index": 4, "vid": 33, "pid": 43, "serial": 53}
    assert cc.from_json(doc) == FIG410


# -- tolerated input ------------------------------------------------------------------------
ONE_LINK = [(1, 1), (2, 1), (3, 1), (4, 1), *chan(5, 0x10, 0x20, 1, 1, 2, 3),
            *chan(6, 0x11, 0x21, 2, 4, 5, 6), (15, 0)]
ONE = ConfigCollection([StoredConfiguration(1, [StoredLink(
    ch(0x10, 0x20, 1, 1, 2, 3), ch(0x11, 0x21, 2, 4, 5, 6), 1)])])


@pytest.mark.parametrize("tail", [b"", b"\xff", b"\xff\xff", b"\xff" * 4096, b"\x01\x02",
                                  records([(1, 1), (9, 0)]), b"\x0f\x00\x00" * 5])
def test_bytes_after_end_are_ignored(tail):
    decoded = cc.decode(records(ONE_LINK) + tail)
    assert decoded.collection == ONE
    assert decoded.trailing_bytes == len(tail)


def test_unknown_codes_are_kept_anywhere_and_written_back_in_place():
    pairs = list(ONE_LINK)
    for position, unknown in ((18, (0, 1)), (12, (17, 0xFFFF)), (5, (99, 7)), (4, (255, 0)),
                              (2, (200, 2)), (0, (42, 42))):
        pairs.insert(position, unknown)
    decoded = cc.decode(records(pairs))
    assert decoded.unknown_records == 6
    assert cc.to_json(decoded.collection) != cc.to_json(ONE)  # they are there
    assert cc.dumps(decoded.collection) == with_checksum(records(pairs))


def test_output_channel_first_missing_type_and_nonzero_declaration_values():
    pairs = [(1, 1), (2, 1), (3, 1), (4, 1), (6, 9), (9, 2), (10, 4), (11, 5), (12, 6),
             (5, 0xFFFF), (7, 0x10), (8, 0x20), (9, 1), (10, 1), (11, 2), (12, 3), (15, 7)]
    link = cc.loads(records(pairs)).configurations[0].links[0]
    assert link.input == ch(0x10, 0x20, 1, 1, 2, 3)
    assert link.output == ch(0, 0, 2, 4, 5, 6)


def test_empty_collection_and_empty_configuration():
    assert cc.loads(records([(1, 0), (15, 0)])) == ConfigCollection([])
    empty = ConfigCollection([StoredConfiguration(1, [])])
    assert cc.loads(records([(1, 1), (2, 1), (3, 0), (15, 0)])) == empty
    assert cc.loads(cc.dumps(empty)) == empty


# -- rejections, each with the offset of the offending record ---------------------------------
def replace(pairs, position, new):
    return [*pairs[:position], *new, *pairs[position + 1:]]


REJECTIONS = [
    # (id, bytes, offset, words in the reason)
    ("truncated", records(ONE_LINK[:-1]) + b"\x0f\x00", 54, "truncated record"),
    ("truncated-1", records(ONE_LINK[:3]) + b"\x04", 9, "truncated record"),
    ("empty", b"", 0, "missing End"),
    ("missing-end", records(ONE_LINK[:-1]), 54, "missing End"),
    ("padding-no-end", records(ONE_LINK[:-1]) + b"\xff" * 30, 84, "missing End"),
    ("count-1-high", records(replace(ONE_LINK, 0, [(1, 2)])), 0, "says 2, but 1 follow"),
    ("count-1-low", records(replace(ONE_LINK, 0, [(1, 0)])), 0, "says 0, but 1 follow"),
    ("count-3-high", records(replace(ONE_LINK, 2, [(3, 2)])), 6, "says 2, but 1 follow"),
    ("count-3-low", records(replace(ONE_LINK, 2, [(3, 0)])), 6, "says 0, but 1 follow"),
    ("value-after-link", records(replace(ONE_LINK, 3, [(4, 1), (7, 5)])), 12,
     "outside a channel declaration"),
    ("value-first", records([(9, 1), *ONE_LINK]), 0, "outside a channel declaration"),
    ("value-in-config", records(replace(ONE_LINK, 2, [(3, 1), (12, 1)])), 9,
     "outside a channel declaration"),
    ("no-index", records(replace(ONE_LINK, 7, [])), 12, "Channel index"),
    ("no-vid", records(replace(ONE_LINK, 15, [])), 33, "Owner VID"),
    ("no-pid", records(replace(ONE_LINK, 9, [])), 12, "Owner PID"),
    ("no-serial", records(replace(ONE_LINK, 17, [])), 33, "Owner serial number"),
    ("no-output", records([*ONE_LINK[:11], (15, 0)]), 9, "has no output channel"),
    ("no-input", records([*ONE_LINK[:4], *ONE_LINK[11:]]), 9, "has no input channel"),
    ("no-channels", records([*ONE_LINK[:4], (15, 0)]), 9, "has no input channel"),
    ("two-inputs", records([*ONE_LINK[:11], *ONE_LINK[4:11], (15, 0)]), 33,
     "second input channel"),
    ("two-outputs", records([*ONE_LINK[:18], *ONE_LINK[11:18], (15, 0)]), 54,
     "second output channel"),
    ("duplicate-value", records(replace(ONE_LINK, 6, [(8, 1), (8, 2)])), 21,
     "second Channel profile"),
    ("channel-index-0", records(replace(ONE_LINK, 7, [(9, 0)])), 21, "out of range 1…255"),
    ("channel-index-256", records(replace(ONE_LINK, 14, [(9, 256)])), 42, "out of range"),
    ("config-index-0", records(replace(ONE_LINK, 1, [(2, 0)])), 3, "counts from 1"),
    ("link-index-0", records(replace(ONE_LINK, 3, [(4, 0)])), 9, "counts from 1"),
    ("duplicate-config", records([(1, 2), *ONE_LINK[1:-1], *ONE_LINK[1:]]), 54,
     "configuration index 1 is a duplicate"),
    ("duplicate-link", records([*replace(ONE_LINK, 2, [(3, 2)])[:-1], *ONE_LINK[3:]]), 54,
     "link index 1 in configuration 1 is a duplicate"),
    ("config-before-count", records(ONE_LINK[1:]), 0, "before the # of configurations"),
    ("count-twice", records(replace(ONE_LINK, 3, [(1, 1), (4, 1)])), 9, "first record"),
    ("end-before-count", records([(15, 0)]), 0, "End before"),
    ("no-link-count", records(replace(ONE_LINK, 2, [])), 6, "before the # of links"),
    ("no-link-count-empty", records([(1, 1), (2, 1), (15, 0)]), 3, "has no # of links"),
    ("link-count-late", records(replace(ONE_LINK, 18, [(3, 1), (15, 0)])), 54,
     "must directly follow"),
    ("link-outside-config", records([(1, 0), (4, 1), (15, 0)]), 3, "outside a configuration"),
    ("channel-outside-link", records([(1, 1), (2, 1), (3, 0), (5, 0), (15, 0)]), 9,
     "outside a channel link"),
    ("too-many-configs-declared", records([(1, 256), (15, 0)]), 0, "exceed the limit 255"),
    ("too-many-links-declared", records([(1, 1), (2, 1), (3, 16385), (15, 0)]), 6,
     "exceed the limit 16384"),
    ("too-large", b"\xff" * (cc.MAX_INPUT_BYTES + 1), cc.MAX_INPUT_BYTES, "larger than"),
]


@pytest.mark.parametrize(("data", "offset", "reason"), [r[1:] for r in REJECTIONS],
                         ids=[r[0] for r in REJECTIONS])
def test_rejections_name_the_offending_record(data, offset, reason):
    with pytest.raises(ConfigFormatError) as info:
        cc.loads(data)
    assert info.value.offset == offset, info.value
    assert reason in info.value.reason
    assert f"offset {offset}: " in str(info.value)


def test_checksum_mismatch_is_refused():
    good = cc.dumps(ONE)
    assert cc.loads(good) == ONE
    bad_crc = good[:-5] + bytes([good[-5] ^ 0x01]) + good[-4:]
    with pytest.raises(ConfigFormatError, match="checksum mismatch") as info:
        cc.loads(bad_crc)
    assert info.value.offset == len(good) - 6
    tampered = bytearray(good)
    tampered[2 * 3 + 1] ^= 0x40  # a value the checksum covers
    with pytest.raises(ConfigFormatError, match="checksum mismatch"):
        cc.loads(bytes(tampered))


def test_checksum_must_be_followed_by_end():
    good = cc.dumps(ONE)
    late = good[:-3] + records([(99, 0), (15, 0)])
    with pytest.raises(ConfigFormatError, match="only End may follow") as info:
        cc.loads(late)
    assert info.value.offset == len(good) - 3


def test_more_configurations_than_the_limit():
    pairs = [(1, 255)] + [pair for i in range(1, 257) for pair in ((2, i), (3, 0))] + [(15, 0)]
    with pytest.raises(ConfigFormatError, match="more than 255 configurations") as info:
        cc.loads(records(pairs))
    assert info.value.offset == 3 + 255 * 6


def test_more_links_than_the_limit():
    link = [*chan(5, 0, 0, 1, 1, 1, 1), *chan(6, 0, 0, 1, 2, 2, 2)]
    pairs = [(1, 1), (2, 1), (3, 16384)]
    for i in range(1, cc.MAX_LINKS + 2):
        pairs += [(4, i), *link]
    data = records([*pairs, (15, 0)])
    assert len(data) < cc.MAX_INPUT_BYTES
    with pytest.raises(ConfigFormatError, match="more than 16384 links") as info:
        cc.loads(data)
    assert info.value.offset == 9 + cc.MAX_LINKS * 45


# -- the writer -----------------------------------------------------------------------------
def link(i: int, index: int = 0) -> StoredLink:
    return StoredLink(ch(1, 2, i, 3, 4, 5), ch(6, 7, i, 8, 9, 10), index)


def test_writer_keeps_a_permutation_of_indices_and_renumbers_anything_else():
    permuted = ConfigCollection([StoredConfiguration(2, [link(1, 2), link(2, 1)]),
                                 StoredConfiguration(1, [])])
    assert cc.loads(cc.dumps(permuted)) == permuted
    odd = ConfigCollection([StoredConfiguration(5, [link(1, 3), link(2, 7)]),
                            StoredConfiguration(0, [link(3)])])
    back = cc.loads(cc.dumps(odd))
    assert [c.index for c in back.configurations] == [1, 2]
    assert [lk.index for lk in back.configurations[0].links] == [1, 2]
    assert [lk.index for lk in back.configurations[1].links] == [1]
    assert back.configurations[0].links[1].input.index == 2


def test_writer_omits_owner_records_only_when_none():
    zero = ConfigCollection([StoredConfiguration(1, [StoredLink(
        ch(1, 2, 1, 3, 4, 5, 0, None), ch(1, 2, 1, 3, 4, 5, None, 0), 1)])])
    data = cc.dumps(zero)
    codes = [data[i] for i in range(0, len(data), 3)]
    assert codes == [1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12, 13, 6, 7, 8, 9, 10, 11, 12, 14, 16, 15]
    assert cc.loads(data) == zero


@pytest.mark.parametrize(("channel", "words"), [
    (ch(1, 2, 0, 3, 4, 5), "input.index: 0 is out of range 1…255"),
    (ch(1, 2, 256, 3, 4, 5), "input.index: 256"),
    (ch(1, 2, 1, 70000, 4, 5), "input.vid: 70000"),
    (ch(-1, 2, 1, 3, 4, 5), "input.type: -1"),
    (ch(1, 2, 1, 3, 4, 5, 0x10000), "input.owner_type: 65536"),
    (ch(1, 2, 1, 3, 4, "5"), "input.serial: '5'"),
])
def test_writer_refuses_values_it_cannot_encode(channel, words):
    bad = ConfigCollection([StoredConfiguration(1, [StoredLink(channel, ch(1, 2, 1, 3, 4, 5))])])
    with pytest.raises(ConfigFormatError) as info:
        cc.dumps(bad)
    assert info.value.offset == -1
    assert f"configurations[0].links[0].{words}" in str(info.value)


def test_writer_enforces_the_limits():
    with pytest.raises(ConfigFormatError, match="more than 255"):
        cc.dumps(ConfigCollection([StoredConfiguration(i, []) for i in range(1, 257)]))
    big = StoredConfiguration(1, [link(1)] * (cc.MAX_LINKS + 1))
    with pytest.raises(ConfigFormatError, match="16385 links exceed"):
        cc.dumps(ConfigCollection([big]))


def test_largest_collection_within_limits_fits_the_input_limit():
    full = ch(0xFFFF, 0xFFFF, 255, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF)
    per = cc.MAX_LINKS // cc.MAX_CONFIGURATIONS
    configs = [StoredConfiguration(i, [StoredLink(full, full, j) for j in range(1, per + 1)])
               for i in range(1, cc.MAX_CONFIGURATIONS + 1)]
    configs[-1].links.extend(StoredLink(full, full, j) for j in range(per + 1, per + 1 + (
        cc.MAX_LINKS - per * cc.MAX_CONFIGURATIONS)))
    data = cc.dumps(ConfigCollection(configs))
    assert len(data) <= cc.MAX_INPUT_BYTES
    assert cc.loads(data) == ConfigCollection(configs)


# -- JSON input -------------------------------------------------------------------------------
def test_from_json_accepts_hex_strings_and_defaults():
    doc = {"configurations": [{"links": [{
        "input": {"type": "0x5300", "profile": "0x2120", "index": 1, "vid": "0x0002",
                  "pid": 2, "serial": 6, "owner_type": None},
        "output": {"index": 3, "vid": 2, "pid": 2, "serial": 5}}]}], "comment": "extra"}
    coll = cc.from_json(doc)
    assert coll == ConfigCollection([StoredConfiguration(1, [StoredLink(
        ch(0x5300, 0x2120, 1, 2, 2, 6), ch(0, 0, 3, 2, 2, 5), 1)])])


@pytest.mark.parametrize(("doc", "words"), [
    ([], "document: expected an object"),
    ({}, "configurations: expected a list"),
    ({"configurations": [3]}, "configurations[0]: expected an object"),
    ({"configurations": [{"links": [None]}]}, "configurations[0].links[0]: expected an object"),
    ({"configurations": [{"links": [{"output": {}}]}]}, "links[0].input: expected an object"),
    ({"configurations": [{"links": [{"input": {"index": 1}, "output": {}}]}]},
     "links[0].input.vid: missing"),
    ({"configurations": [{"links": [{"input": {"index": 0, "vid": 1, "pid": 1, "serial": 1}}]}]},
     "input.index: 0 is out of range 1…255"),
    ({"configurations": [{"links": [{"input": {"index": True, "vid": 1, "pid": 1,
                                               "serial": 1}}]}]}, "expected an integer"),
    ({"configurations": [{"links": [{"input": {"index": 1.5, "vid": 1, "pid": 1,
                                               "serial": 1}}]}]}, "expected an integer"),
    ({"configurations": [{"links": [{"input": {"index": 1, "vid": "0xZZ", "pid": 1,
                                               "serial": 1}}]}]}, "'0xZZ' is not a number"),
    ({"configurations": [{"index": 0, "links": []}]}, "configurations[0].index: 0"),
])
def test_from_json_errors_name_the_json_path(doc, words):
    with pytest.raises(ConfigFormatError) as info:
        cc.from_json(doc)
    assert info.value.offset == -1
    assert words in str(info.value)
