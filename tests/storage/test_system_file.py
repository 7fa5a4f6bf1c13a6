"""System files (contracts §1): shipped examples load; bad files name the JSON path."""

import copy
import json

import pytest

from pdcp_studio.errors import SystemFileError
from pdcp_studio.model import ChannelRef, Link
from pdcp_studio.storage import system_file

EXAMPLE = {
    "format": "pdcp-system/1",
    "devices": [
        {"vid": 2, "pid": 2, "serial": 5, "name": "Control unit", "present": True,
         "channels": [
             {"index": 1, "direction": "input", "type": "0x7200", "profile": "0x2200",
              "terminal_profile": "0x0000", "required_inputs": [], "desired_inputs": [],
              "descriptor": "Button",
              "source": {"vid": 65535, "pid": 65535, "serial": 65535, "index": 255}},
             {"index": 2, "direction": "input", "type": "0x5200", "profile": "0x2110"},
             {"index": 3, "direction": "output", "type": "0x5000", "profile": "0x1100",
              "required_inputs": [2], "desired_inputs": []}]},
        {"vid": 2, "pid": 2, "serial": 4,
         "channels": [{"index": 1, "direction": "output", "type": 20480, "profile": "0x2120"}]},
    ],
    "links": [{"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
               "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}}],
}


def test_contract_example_loads():
    s = system_file.from_json(EXAMPLE)
    assert s.links == [Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))]
    cu = s.device((2, 2, 5))
    assert cu.name == "Control unit" and cu.present
    assert cu.channels[1].type == 0x7200 and not cu.channels[1].source.connected
    assert cu.channels[3].required_inputs == (2,)
    assert s.device((2, 2, 4)).channels[1].type == 0x5000  # integers accepted too


def test_writer_uses_hex_strings_for_type_profile_terminal_profile():
    doc = system_file.to_json(system_file.from_json(EXAMPLE))
    ch = doc["devices"][0]["channels"][0]
    assert ch["type"] == "0x7200" and ch["profile"] == "0x2200"
    assert ch["terminal_profile"] == "0x0000"
    assert doc["devices"][0]["vid"] == 2


def test_round_trip_is_stable():
    once = system_file.to_json(system_file.from_json(EXAMPLE))
    twice = system_file.to_json(system_file.from_json(once))
    assert once == twice


@pytest.mark.parametrize(
    ("mutate", "path"),
    [
        (lambda d: d.update(format="pdcp-system/2"), "format"),
        (lambda d: d["devices"].append(copy.deepcopy(d["devices"][0])), "devices[2]"),
        (lambda d: d["devices"][0]["channels"].append(dict(d["devices"][0]["channels"][0])),
         "devices[0].channels[3].index"),
        (lambda d: d["devices"][0]["channels"][0].update(index=256), "devices[0].channels[0].index"),
        (lambda d: d["devices"][0]["channels"][0].update(index=0), "devices[0].channels[0].index"),
        (lambda d: d["devices"][0]["channels"][1].update(profile="0x10000"),
         "devices[0].channels[1].profile"),
        (lambda d: d["devices"][0]["channels"][2].update(required_inputs=[3]),
         "devices[0].channels[2].required_inputs[0]"),
        (lambda d: d["devices"][0]["channels"][2].update(desired_inputs=[7]),
         "devices[0].channels[2].desired_inputs[0]"),
        (lambda d: d["links"][0].update(output=d["links"][0]["input"]), "links[0].output"),
        (lambda d: d["links"][0]["input"].update(index=3), "links[0].input"),
        (lambda d: d["devices"][1].update(vid=70000), "devices[1].vid"),
        (lambda d: d["devices"][0]["channels"][0].update(direction="both"),
         "devices[0].channels[0].direction"),
    ],
)
def test_loader_rejects_naming_the_json_path(mutate, path):
    doc = copy.deepcopy(EXAMPLE)
    mutate(doc)
    with pytest.raises(SystemFileError) as info:
        system_file.from_json(doc)
    assert info.value.path == path


def test_load_path_names_file_and_path(tmp_path):
    doc = copy.deepcopy(EXAMPLE)
    doc["devices"][0]["channels"][1]["profile"] = "zz"
    f = tmp_path / "bad.pdcpsys.json"
    f.write_text(json.dumps(doc))
    with pytest.raises(SystemFileError, match=r"bad\.pdcpsys\.json: devices\[0\]\.channels\[1\]\.profile"):
        system_file.load_path(f)


def test_corrupt_json_is_a_clear_error(tmp_path):
    f = tmp_path / "x.json"
    f.write_text("{not json")
    with pytest.raises(SystemFileError, match="not valid JSON"):
        system_file.load_path(f)


def test_shipped_examples_load(systems_dir):
    names = sorted(p.name for p in systems_dir.glob("*.json"))
    assert {"appendix-d.json", "transradial.json", *(f"thesis-test{i}.json" for i in range(1, 6))} <= set(names)
    for p in systems_dir.glob("*.json"):
        system_file.load_path(p).validate()


def test_save_is_atomic_and_reloads(tmp_path, systems_dir):
    s = system_file.load_path(systems_dir / "appendix-d.json")
    out = tmp_path / "saved.pdcpsys.json"
    system_file.save_path(s, out)
    again = system_file.load_path(out)
    assert again.links == s.links
    assert system_file.to_json(again) == system_file.to_json(s)
    assert [p.name for p in tmp_path.iterdir()] == ["saved.pdcpsys.json"]


def test_appendix_d_rig(systems_dir):
    s = system_file.load_path(systems_dir / "appendix-d.json")
    r = lambda sn, i: ChannelRef(2, 2, sn, i)  # noqa: E731
    assert s.links == sorted([Link(r(4, 1), r(5, 2)), Link(r(5, 3), r(6, 1)), Link(r(5, 5), r(6, 2))])
    assert s.channel(r(5, 2)).source.ref == r(4, 1)
    assert s.channel(r(6, 1)).terminal_profile == 0x1110
