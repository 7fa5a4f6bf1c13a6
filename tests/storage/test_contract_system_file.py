"""Contracts §1, the ``pdcp-system/1`` system file, clause by clause.

"Numbers in JSON may be written as integers or as strings "0x…"" · "A loader rejects, naming
the JSON path: unknown format, duplicate device or channel, an index out of 1…255, a link
whose ends are not an output and an input, a required/desired index that is not an input
channel of that device, a value out of range." · CLI: exit 2, stderr names file and where.
"""

from __future__ import annotations

import copy
import json

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.errors import SystemFileError
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.storage import system_file

CONTRACT_EXAMPLE = {
    "format": "pdcp-system/1",
    "devices": [
        {"vid": 2, "pid": 2, "serial": 4, "channels": [
            {"index": 1, "direction": "output", "type": "0x5000", "profile": "0x2110"}]},
        {"vid": 2, "pid": 2, "serial": 5, "name": "Control unit", "present": True, "channels": [
            {"index": 1, "direction": "input", "type": "0x7200", "profile": "0x2200",
             "terminal_profile": "0x0000", "required_inputs": [], "desired_inputs": [],
             "descriptor": "Button",
             "source": {"vid": 65535, "pid": 65535, "serial": 65535, "index": 255}},
            {"index": 2, "direction": "input", "type": "0x5200", "profile": "0x2110"},
            {"index": 3, "direction": "output", "type": "0x5000", "profile": "0x1100",
             "required_inputs": [2], "desired_inputs": []}]},
    ],
    "links": [{"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
               "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}}],
}


def _doc(mutate=None) -> dict:
    doc = copy.deepcopy(CONTRACT_EXAMPLE)
    if mutate is not None:
        mutate(doc)
    return doc


def _cu(doc: dict) -> dict:
    return doc["devices"][1]


def test_numbers_may_be_integers_or_0x_strings_in_any_field():
    as_hex = _doc(lambda d: (_cu(d).update(vid="0x0002", serial="0X5"),
                             _cu(d)["channels"][2].update(index="0x3", required_inputs=["0x02"]),
                             d["links"][0]["input"].update(serial="0x5", index="0x02")))
    as_int = _doc(lambda d: _cu(d)["channels"][0].update(type=0x7200, profile=8704,
                                                         terminal_profile=0))
    for doc in (as_hex, as_int):
        s = system_file.from_json(doc)
        cu = s.device((2, 2, 5))
        assert cu.channels[3].required_inputs == (2,)
        assert cu.channels[1].type == 0x7200 and cu.channels[1].profile == 0x2200
        assert [lk.input for lk in s.links] == [ChannelRef(2, 2, 5, 2)]


@pytest.mark.parametrize("text", ["2200", "5", "0b1", "0o7", "1_0", " 0x10", "0x", "0xZZ", ""])
def test_a_string_that_is_not_0x_hex_is_refused_not_read_as_decimal(text):
    doc = _doc(lambda d: _cu(d)["channels"][0].update(profile=text))
    with pytest.raises(SystemFileError) as info:
        system_file.from_json(doc)
    assert info.value.path == "devices[1].channels[0].profile"


def test_defaults_present_true_and_empty_input_lists_and_an_empty_system_loads():
    s = system_file.from_json(_doc())
    joystick = s.device((2, 2, 4))
    assert joystick.present is True
    assert joystick.channels[1].required_inputs == () == joystick.channels[1].desired_inputs
    assert not system_file.from_json({"format": "pdcp-system/1"}).devices
    assert not system_file.from_json({"format": "pdcp-system/1", "devices": [],
                                      "links": []}).links


def test_extra_fields_are_welcome():
    doc = _doc(lambda d: (d.update(comment="x"), _cu(d).update(colour="red"),
                          _cu(d)["channels"][0].update(note=[1, 2])))
    assert len(system_file.from_json(doc).links) == 1


REJECTIONS = [
    # unknown format
    (lambda d: d.pop("format"), "format"),
    (lambda d: d.update(format="pdcp-system/2"), "format"),
    # duplicate device or channel (the same number in another form is the same)
    (lambda d: d["devices"].append({"vid": "0x2", "pid": 2, "serial": 4}), "devices[2]"),
    (lambda d: _cu(d)["channels"].append({"index": "0x2", "direction": "output"}),
     "devices[1].channels[3].index"),
    # an index out of 1…255
    (lambda d: _cu(d)["channels"][0].update(index=0), "devices[1].channels[0].index"),
    (lambda d: _cu(d)["channels"][0].update(index=256), "devices[1].channels[0].index"),
    (lambda d: d["links"][0]["output"].update(index=0), "links[0].output.index"),
    (lambda d: d["links"][0]["input"].update(index="0x100"), "links[0].input.index"),
    # a link whose ends are not an output and an input
    (lambda d: d["links"].__setitem__(0, {"output": d["links"][0]["input"],
                                          "input": d["links"][0]["output"]}), "links[0].output"),
    (lambda d: d["links"][0].update(input={"vid": 2, "pid": 2, "serial": 5, "index": 3}),
     "links[0].input"),
    (lambda d: d["links"][0].update(output={"vid": 9, "pid": 9, "serial": 9, "index": 1}),
     "links[0].output"),
    (lambda d: d["links"][0].pop("input"), "links[0]"),
    # a required/desired index that is not an input channel of that device
    (lambda d: _cu(d)["channels"][2].update(required_inputs=[3]),
     "devices[1].channels[2].required_inputs[0]"),
    (lambda d: _cu(d)["channels"][2].update(desired_inputs=[2, 9]),
     "devices[1].channels[2].desired_inputs[1]"),
    (lambda d: d["devices"][0]["channels"][0].update(required_inputs=[1]),
     "devices[0].channels[0].required_inputs[0]"),
    # a value out of range
    (lambda d: _cu(d).update(vid=65536), "devices[1].vid"),
    (lambda d: _cu(d).update(serial=-1), "devices[1].serial"),
    (lambda d: _cu(d)["channels"][0].update(type="0x10000"), "devices[1].channels[0].type"),
    (lambda d: _cu(d)["channels"][0].update(terminal_profile=70000),
     "devices[1].channels[0].terminal_profile"),
    (lambda d: _cu(d)["channels"][0]["source"].update(index=256),
     "devices[1].channels[0].source.index"),
    # wrong types
    (lambda d: _cu(d)["channels"][0].update(profile=1.5), "devices[1].channels[0].profile"),
    (lambda d: _cu(d)["channels"][0].update(profile=True), "devices[1].channels[0].profile"),
    (lambda d: _cu(d)["channels"][0].update(direction="in"), "devices[1].channels[0].direction"),
    (lambda d: _cu(d)["channels"][0].pop("direction"), "devices[1].channels[0].direction"),
    (lambda d: _cu(d).update(present="yes"), "devices[1].present"),
    (lambda d: _cu(d).update(name=5), "devices[1].name"),
    (lambda d: _cu(d)["channels"][0].update(descriptor=["Button"]),
     "devices[1].channels[0].descriptor"),
    (lambda d: _cu(d)["channels"][2].update(required_inputs=2),
     "devices[1].channels[2].required_inputs"),
    (lambda d: d.update(devices={}), "devices"),
]


@pytest.mark.parametrize(("mutate", "path"), REJECTIONS)
def test_loader_rejects_naming_the_json_path(mutate, path):
    with pytest.raises(SystemFileError) as info:
        system_file.from_json(_doc(mutate))
    assert info.value.path == path


@pytest.mark.parametrize(("mutate", "path"), REJECTIONS[::4])
def test_cli_exits_2_naming_the_file_and_the_json_path(tmp_path, capsys, mutate, path):
    bad = tmp_path / "bad.pdcpsys.json"
    bad.write_text(json.dumps(_doc(mutate)))
    for command in ("info", "print"):
        assert main([command, "--system", str(bad)]) == 2
        out, err = capsys.readouterr()
        assert out == ""
        assert f"{bad}: {path}: " in err


@pytest.mark.parametrize("content", [None, "", "{", "[]", b"\xff\xfe{"])
def test_missing_directory_or_unparsable_file_is_bad_input(tmp_path, capsys, content):
    target = tmp_path / "s.json"
    if content is None:
        target.mkdir()
    elif isinstance(content, bytes):
        target.write_bytes(content)
    else:
        target.write_text(content)
    for path in (target, tmp_path / "absent.json"):
        assert main(["plan", "autoconfigure", "--system", str(path), "--json"]) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.startswith(f"pdcp-studio: {path}: ")


def test_writer_writes_type_profiles_as_0x_strings_and_everything_else_as_integers():
    doc = system_file.to_json(system_file.from_json(_doc()))
    cu = doc["devices"][1]
    button = cu["channels"][0]
    assert (button["type"], button["profile"], button["terminal_profile"]) == (
        "0x7200", "0x2200", "0x0000")
    assert "terminal_profile" not in cu["channels"][2]  # inputs only
    assert cu["channels"][2]["required_inputs"] == [2]
    assert button["source"] == {"vid": 65535, "pid": 65535, "serial": 65535, "index": 255}
    assert all(isinstance(cu[k], int) for k in ("vid", "pid", "serial"))
    assert doc["links"] == CONTRACT_EXAMPLE["links"]
