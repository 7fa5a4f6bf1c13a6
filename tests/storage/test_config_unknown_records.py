"""Unknown codes are kept (reference §3): on the declaration they appear in, in order, and
written back in place, so decode → encode gives the same records with only the checksum
added or recomputed — at every level and every position of a file."""

from __future__ import annotations

import json
import struct

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.model.configuration import UnknownRecord
from pdcp_studio.storage import config_codec as cc
from tests.storage.test_config_codec import FIG410_RECORDS, records, with_checksum

UNKNOWN_CODES = st.sampled_from([0, 17, 0x20, 99, 128, 200, 255])
u16 = st.integers(0, 0xFFFF)


def _insert(base: list[tuple[int, int]], inserts: list[tuple[int, int, int]]):
    """Put (position, code, value) records into ``base`` (positions before End)."""
    pairs = list(base)
    order = sorted(range(len(inserts)), key=lambda i: (-inserts[i][0], -i))  # list order kept
    for i in order:
        position, code, value = inserts[i]
        pairs.insert(position, (code, value))
    return pairs


def _all_unknown(coll) -> list[UnknownRecord]:
    out = list(coll.unknown)
    for cfg in coll.configurations:
        out += cfg.unknown
        for lk in cfg.links:
            out += [*lk.unknown, *lk.input.unknown, *lk.output.unknown]
    return out


def _json_round_trip(coll) -> bytes:
    """decode --json → encode, as the CLI does it."""
    return cc.dumps(cc.from_json(json.loads(json.dumps(cc.to_json(coll)))))


def test_the_issue_case_a_0x20_record_in_a_channel_survives():
    pairs = _insert(FIG410_RECORDS, [(13, 0x20, 0x1234)])  # end of link 1's input channel
    data = records(pairs)
    collection = cc.loads(data)
    channel = collection.configurations[0].links[0].input
    assert channel.unknown == (UnknownRecord(0x20, 0x1234, None),)
    assert cc.dumps(collection) == with_checksum(data)


@pytest.mark.parametrize("position", range(len(FIG410_RECORDS)))  # every place before End
def test_one_unknown_record_at_every_position_is_written_back_in_place(position):
    data = records(_insert(FIG410_RECORDS, [(position, 0x20, 4660)]))
    decoded = cc.decode(data)
    assert decoded.unknown_records == 1
    assert cc.dumps(decoded.collection) == with_checksum(data)
    # Through the contract JSON the record keeps its object and order; at the end of its
    # declaration (where writers append) even its byte position.
    again = _json_round_trip(decoded.collection)
    assert cc.to_json(cc.loads(again)) == cc.to_json(decoded.collection)
    if all(r.after is None for r in _all_unknown(decoded.collection)):
        assert again == with_checksum(data)


def test_each_declaration_gets_its_own_records_in_file_order():
    # collection: before and after the count; configuration 1: between 2 and 3 and after 3;
    # link 1: after 4; input channel of link 1: after 5 and after profile; configuration 2's
    # last output channel: at its end (right before End).
    inserts = [(0, 200, 1), (1, 201, 2), (2, 202, 3), (3, 203, 4), (3, 204, 5),
               (4, 205, 6), (5, 206, 7), (7, 207, 8), (len(FIG410_RECORDS) - 1, 208, 9)]
    data = records(_insert(FIG410_RECORDS, inserts))
    coll = cc.loads(data)
    cfg1, cfg2 = coll.configurations
    link1 = cfg1.links[0]
    assert coll.unknown == (UnknownRecord(200, 1, 0), UnknownRecord(201, 2))
    assert cfg1.unknown == (UnknownRecord(202, 3, 2), UnknownRecord(203, 4),
                            UnknownRecord(204, 5))
    assert link1.unknown == (UnknownRecord(205, 6),)
    assert link1.input.unknown == (UnknownRecord(206, 7, 5), UnknownRecord(207, 8, 8))
    assert cfg2.links[0].output.unknown == (UnknownRecord(208, 9),)
    assert cfg2.unknown == () and link1.output.unknown == ()
    doc = cc.to_json(coll)
    assert doc["unknown_records"] == [{"code": 200, "value": 1}, {"code": 201, "value": 2}]
    assert doc["configurations"][0]["links"][0]["input"]["unknown_records"] == [
        {"code": 206, "value": 7}, {"code": 207, "value": 8}]
    assert doc["configurations"][0]["links"][0]["unknown_records"] == [
        {"code": 205, "value": 6}]
    assert "unknown_records" not in doc["configurations"][1]
    assert cc.dumps(coll) == with_checksum(data)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.integers(0, len(FIG410_RECORDS) - 1), UNKNOWN_CODES, u16),
                max_size=12))
def test_any_unknown_records_anywhere_round_trip_through_bytes_and_json(inserts):
    data = records(_insert(FIG410_RECORDS, inserts))
    decoded = cc.decode(data)
    assert decoded.unknown_records == len(inserts)
    assert cc.dumps(decoded.collection) == with_checksum(data)
    doc = json.loads(json.dumps(cc.to_json(decoded.collection)))
    assert cc.to_json(cc.loads(cc.dumps(cc.from_json(doc)))) == doc
    # Writing again what the program wrote changes nothing, checksum included.
    assert cc.dumps(cc.loads(with_checksum(data))) == with_checksum(data)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(UNKNOWN_CODES, u16), min_size=1, max_size=4), st.data())
def test_an_edited_channel_keeps_its_unknown_records(extra, data):
    position = data.draw(st.integers(5, 12))  # somewhere in link 1's input channel
    inserts = [(position, code, value) for code, value in extra]
    coll = cc.loads(records(_insert(FIG410_RECORDS, inserts)))
    link = coll.configurations[0].links[0]
    from dataclasses import replace

    edited = replace(link.input, profile=0x2110, owner_type=None, owner_profile=None)
    coll.configurations[0].links[0] = replace(link, input=edited)
    again = cc.loads(cc.dumps(coll)).configurations[0].links[0].input
    assert [(r.code, r.value) for r in again.unknown] == extra
    assert again.profile == 0x2110


@pytest.mark.parametrize("item, words", [
    ({"code": 9, "value": 1}, "unknown_records[0].code: 9 is a known code (Channel index)"),
    ({"code": 16, "value": 1}, "is a known code (Checksum)"),
    ({"code": 256, "value": 1}, "unknown_records[0].code"),
    ({"code": 32, "value": 65536}, "unknown_records[0].value"),
    ({"code": 32}, "unknown_records[0].value: missing"),
    ({"code": 32, "value": 1, "after": 300}, "unknown_records[0].after"),
    ("x", "unknown_records[0]: expected an object"),
])
def test_json_unknown_records_are_checked_and_named(item, words):
    doc = cc.to_json(cc.loads(records(FIG410_RECORDS)))
    doc["configurations"][0]["links"][1]["input"]["unknown_records"] = [item]
    with pytest.raises(ConfigFormatError) as err:
        cc.from_json(doc)
    assert "configurations[0].links[1].input.unknown_records" in err.value.reason
    assert words in err.value.reason


def test_writer_refuses_a_known_code_as_an_unknown_record():
    coll = cc.loads(records(FIG410_RECORDS))
    coll.unknown = (UnknownRecord(15, 0),)
    with pytest.raises(ConfigFormatError, match=r"collection.unknown_records\[0\].code: 15"):
        cc.dumps(coll)


def test_unknown_record_between_checksum_and_end_is_still_refused_with_its_offset():
    body = cc.dumps(cc.loads(records(FIG410_RECORDS)))
    data = body[:-3] + struct.pack("<BH", 0x20, 1) + body[-3:]
    with pytest.raises(ConfigFormatError) as err:
        cc.loads(data)
    assert err.value.offset == len(body) - 3 and "only End" in err.value.reason


def test_a_value_record_outside_a_channel_is_still_refused_next_to_unknown_ones():
    pairs = _insert(FIG410_RECORDS, [(3, 0x20, 1)])
    pairs.insert(4, (9, 1))  # a Channel index right after the link record
    with pytest.raises(ConfigFormatError) as err:
        cc.loads(records(pairs))
    assert err.value.offset == 12 and "outside a channel declaration" in err.value.reason


def test_json_after_pins_a_record_inside_its_declaration():
    """``config encode`` takes an optional ``"after": CODE`` (decode --json never prints it)."""
    doc = cc.to_json(cc.loads(records(FIG410_RECORDS)))
    doc["configurations"][1]["links"][0]["input"]["unknown_records"] = [
        {"code": 32, "value": 4660, "after": 7}, {"code": 33, "value": 1}]
    data = cc.dumps(cc.from_json(doc))
    pairs = list(cc._RECORD.iter_unpack(data))
    at = pairs.index((32, 4660))
    assert pairs[at - 1] == (7, 13) and pairs[at + 1] == (8, 23)
    assert pairs[pairs.index((33, 1)) - 1] == (12, 53)  # the end of that channel
    assert cc.to_json(cc.loads(data)) == json.loads(json.dumps(cc.to_json(cc.from_json(doc))))
