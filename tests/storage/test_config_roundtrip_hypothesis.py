"""Property tests: any collection round-trips through bytes and JSON; any bytes give either a
collection or ConfigFormatError."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.errors import ConfigFormatError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    UnknownRecord,
)
from pdcp_studio.storage import config_codec as cc

u16 = st.integers(0, 0xFFFF)
# Records of codes this program does not know, at the end of any declaration (reference §3).
unknown = st.lists(st.builds(UnknownRecord, code=st.sampled_from([0, 17, 0x20, 255]),
                             value=u16), max_size=2).map(tuple)
channels = st.builds(
    StoredChannel, index=st.integers(1, 255), vid=u16, pid=u16, serial=u16, type=u16,
    profile=u16, owner_type=st.none() | u16, owner_profile=st.none() | u16, unknown=unknown,
)
links = st.builds(StoredLink, input=channels, output=channels, index=st.integers(0, 8),
                  unknown=unknown)
configurations = st.builds(StoredConfiguration, index=st.integers(0, 6),
                           links=st.lists(links, max_size=6), unknown=unknown)
collections = st.builds(ConfigCollection, configurations=st.lists(configurations, max_size=5),
                        unknown=unknown)


def canonical(coll: ConfigCollection) -> ConfigCollection:
    """What the writer does to indices: keep a permutation of 1…n, else number 1…n."""
    def fix(indices: list[int]) -> list[int]:
        n = len(indices)
        return indices if sorted(indices) == list(range(1, n + 1)) else list(range(1, n + 1))

    configs = []
    for cfg, cidx in zip(coll.configurations, fix([c.index for c in coll.configurations]),
                         strict=True):
        renumbered = [StoredLink(lk.input, lk.output, i, lk.unknown)
                      for lk, i in zip(cfg.links, fix([lk.index for lk in cfg.links]), strict=True)]
        configs.append(StoredConfiguration(cidx, renumbered, cfg.unknown))
    return ConfigCollection(configs, coll.unknown)


@settings(max_examples=200, deadline=None)
@given(collections)
def test_bytes_round_trip(coll):
    data = cc.dumps(coll)
    decoded = cc.decode(data)
    assert decoded.collection == canonical(coll)
    assert decoded.checksum is not None
    assert cc.dumps(decoded.collection) == data


# JSON indices count from 1 (from_json refuses 0) but need not be unique or consecutive.
json_links = st.builds(StoredLink, input=channels, output=channels, index=st.integers(1, 0xFFFF),
                       unknown=unknown)
json_collections = st.builds(ConfigCollection, configurations=st.lists(st.builds(
    StoredConfiguration, index=st.integers(1, 0xFFFF), links=st.lists(json_links, max_size=5),
    unknown=unknown), max_size=4), unknown=unknown)


@settings(max_examples=200, deadline=None)
@given(json_collections)
def test_json_round_trip(coll):
    doc = cc.to_json(coll)
    assert cc.from_json(json.loads(json.dumps(doc))) == coll
    assert cc.to_json(cc.loads(cc.dumps(coll))) == cc.to_json(canonical(coll))


@settings(max_examples=200, deadline=None)
@given(collections)
def test_json_of_decoded_bytes_round_trips(coll):
    decoded = cc.loads(cc.dumps(coll))
    assert cc.from_json(json.loads(json.dumps(cc.to_json(decoded)))) == decoded


@settings(max_examples=200, deadline=None)
@given(collections, st.binary(max_size=64))
def test_trailing_bytes_never_matter(coll, tail):
    assert cc.loads(cc.dumps(coll) + tail) == canonical(coll)


@settings(max_examples=500, deadline=None)
@given(st.binary(max_size=300))
def test_any_bytes_give_a_collection_or_config_format_error(data):
    try:
        coll = cc.loads(data)
    except ConfigFormatError as err:
        assert 0 <= err.offset <= len(data)
    else:
        assert cc.loads(cc.dumps(coll)) == canonical(coll)


record = st.tuples(st.sampled_from([*range(1, 17), 0, 99]), st.integers(0, 300))


@settings(max_examples=500, deadline=None)
@given(st.lists(record, max_size=40))
def test_any_record_sequence_gives_a_collection_or_config_format_error(pairs):
    data = b"".join(cc._RECORD.pack(code, value) for code, value in pairs)
    try:
        coll = cc.loads(data)
    except ConfigFormatError as err:
        assert 0 <= err.offset <= len(data)
        assert err.offset % 3 == 0
    else:
        assert cc.loads(cc.dumps(coll)) == canonical(coll)
