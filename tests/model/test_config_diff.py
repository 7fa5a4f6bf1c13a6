"""The one configuration diff (model/config_diff.py; contracts §2 ``config diff``)."""

from __future__ import annotations

from pdcp_studio.model.config_diff import diff_configurations, link_ends
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)


def ch(serial: int, index: int, ctype: int = 0x5000, profile: int = 0x2110,
       owner: int | None = None) -> StoredChannel:
    return StoredChannel(index, 2, 2, serial, ctype, profile, owner_type=owner)


def link(out: StoredChannel, inp: StoredChannel, n: int = 1) -> StoredLink:
    return StoredLink(inp, out, n)


A1 = link(ch(4, 1), ch(5, 2), 1)
A2 = link(ch(5, 3), ch(6, 1), 2)
A3 = link(ch(5, 5), ch(6, 2), 3)


def coll(*configs: list[StoredLink]) -> ConfigCollection:
    return ConfigCollection([StoredConfiguration(i, list(c)) for i, c in enumerate(configs, 1)])


def test_equal_collections_are_equal_even_with_other_link_indices():
    a = coll([A1, A2])
    b = coll([StoredLink(A2.input, A2.output, 1), StoredLink(A1.input, A1.output, 2)])
    diff = diff_configurations(a, b)
    assert diff.equal and diff.lines() == [] and diff.describe() == "no difference"
    assert diff.to_json() == {"configurations": [
        {"index": 1, "only_in_a": [], "only_in_b": [], "changed": []}]}


def test_links_only_in_one_side_and_changed_records():
    changed = link(ch(4, 1, profile=0x2120), ch(5, 2), 1)
    a, b = coll([A1, A2]), coll([changed, A3])
    diff = diff_configurations(a, b)
    assert not diff.equal
    doc = diff.to_json()["configurations"][0]
    assert [d["output"]["index"] for d in doc["only_in_a"]] == [3]
    assert [d["output"]["index"] for d in doc["only_in_b"]] == [5]
    assert doc["only_in_a"][0]["input"] == {"type": "0x5000", "profile": "0x2110", "index": 1,
                                            "vid": 2, "pid": 2, "serial": 6}
    (c,) = doc["changed"]
    assert c["link"] == {"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
                         "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}}
    assert c["a"]["output"]["profile"] == "0x2110" and c["b"]["output"]["profile"] == "0x2120"
    text = diff.describe("stored", "file")
    assert "link 2/2/5#3 → 2/2/6#1 is only in stored" in text
    assert "link 2/2/5#5 → 2/2/6#2 is only in file" in text
    assert "output profile 0x2110 → 0x2120" in text


def test_owner_records_count_as_a_change():
    b = coll([link(ch(4, 1, owner=60), ch(5, 2), 1)])
    diff = diff_configurations(coll([A1]), b)
    assert len(diff.configurations[0].changed) == 1
    assert "output owner type none → 0x003C" in diff.describe()


def test_a_configuration_on_one_side_only():
    diff = diff_configurations(coll([A1]), coll([A1], [A2]))
    assert not diff.equal
    second = diff.configurations[1]
    assert second.index == 2 and not second.in_a and second.only_in_b == [A2]
    assert diff.lines()[0] == "configuration 2 is only in B"
    assert diff_configurations(ConfigCollection(), ConfigCollection()).equal


def test_link_ends_of_every_configuration():
    ends = link_ends(coll([A1], [A2]))
    assert {(o.serial, i.serial) for o, i in ends} == {(4, 5), (5, 6)}
