"""``config diff A B [--json]`` and ``config diff A --bus URL`` (contracts §2): the one
configuration diff, exit 0 when equal and 3 when the configurations differ."""

from __future__ import annotations

import json
import struct
from dataclasses import replace
from pathlib import Path

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    UnknownRecord,
)
from pdcp_studio.storage import config_codec

ROOT = Path(__file__).resolve().parents[2]
FIG410 = ROOT / "resources" / "configs" / "fig410.pdcfg"

OUT = StoredChannel(1, 2, 2, 4, 0x5000, 0x2120)
IN = StoredChannel(2, 2, 2, 5, 0x5200, 0x2110)
OTHER_IN = StoredChannel(1, 2, 2, 6, 0x5300, 0x1110)


def _save(path: Path, *configs: list[StoredLink], unknown=()) -> Path:
    config_codec.save_path(ConfigCollection(
        [StoredConfiguration(i, links) for i, links in enumerate(configs, 1)], unknown), path)
    return path


def _diff(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(["config", "diff", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_a_file_equals_itself_and_a_copy_exit_0(capsys, tmp_path):
    copy = tmp_path / "copy.pdcfg"
    copy.write_bytes(FIG410.read_bytes())
    code, out, _ = _diff(capsys, str(FIG410), str(copy))
    assert code == 0 and "store the same configurations" in out
    code, out, _ = _diff(capsys, str(FIG410), str(copy), "--json")
    assert code == 0
    doc = json.loads(out)
    assert [c["index"] for c in doc["configurations"]] == [1, 2]
    assert all(not c["only_in_a"] and not c["only_in_b"] and not c["changed"]
               for c in doc["configurations"])


def test_links_only_on_one_side_and_changed_records_exit_3(capsys, tmp_path):
    a = _save(tmp_path / "a.pdcfg", [StoredLink(IN, OUT, 1), StoredLink(OTHER_IN, OUT, 2)])
    b = _save(tmp_path / "b.pdcfg", [StoredLink(replace(IN, profile=0x2100), OUT, 1)],
              [StoredLink(OTHER_IN, OUT, 1)])
    code, out, err = _diff(capsys, str(a), str(b), "--json")
    assert code == 3 and err == ""
    doc = json.loads(out)
    first, second = doc["configurations"]
    assert first["index"] == 1
    assert [(lk["output"]["serial"], lk["input"]["serial"]) for lk in first["only_in_a"]] == [
        (4, 6)]
    assert first["only_in_b"] == []
    (changed,) = first["changed"]
    assert changed["link"] == {"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
                               "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}}
    assert changed["a"]["input"]["profile"] == "0x2110"
    assert changed["b"]["input"]["profile"] == "0x2100"
    assert second["index"] == 2 and len(second["only_in_b"]) == 1 and not second["only_in_a"]
    code, out, _ = _diff(capsys, str(a), str(b))
    assert code == 3
    assert "configuration 1: link 2/2/4#1 → 2/2/6#1 is only in" in out
    assert "input profile 0x2110 → 0x2100" in out
    assert "configuration 2 is only in" in out


def test_unknown_records_count_as_a_difference(capsys, tmp_path):
    rec = UnknownRecord(0x20, 0x1234)
    a = _save(tmp_path / "a.pdcfg", [StoredLink(IN, OUT, 1)])
    b = _save(tmp_path / "b.pdcfg", [StoredLink(replace(IN, unknown=(rec,)), OUT, 1)])
    c = _save(tmp_path / "c.pdcfg", [StoredLink(IN, OUT, 1)], unknown=(rec,))
    code, out, _ = _diff(capsys, str(a), str(b), "--json")
    assert code == 3
    (changed,) = json.loads(out)["configurations"][0]["changed"]
    assert "unknown_records" not in changed["a"]["input"]
    assert changed["b"]["input"]["unknown_records"] == [{"code": 32, "value": 4660}]
    code, out, _ = _diff(capsys, str(a), str(c), "--json")
    assert code == 3
    assert json.loads(out)["unknown_records"] == {"a": [], "b": [{"code": 32, "value": 4660}]}
    code, out, _ = _diff(capsys, str(b), str(b))
    assert code == 0


def test_against_the_bus_stored_configuration(capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "history.sqlite"))
    memory = tmp_path / "arb.mem"
    stored = _save(tmp_path / "stored.pdcfg", [StoredLink(IN, OUT, 1)])
    other = _save(tmp_path / "other.pdcfg", [StoredLink(OTHER_IN, OUT, 1)])
    # A new arbitrator stores nothing: the file differs from it.
    code, out, _ = _diff(capsys, str(stored), "--bus", "sim:thesis-test3",
                         "--memory", str(memory), "--json")
    assert code == 3
    assert json.loads(out)["configurations"][0]["only_in_a"]
    assert main(["config", "write", str(stored), "--bus", "sim:thesis-test3",
                 "--memory", str(memory), "--yes"]) == 0
    capsys.readouterr()
    code, out, _ = _diff(capsys, str(stored), "--bus", "sim:thesis-test3",
                         "--memory", str(memory))
    assert code == 0 and "the arbitrator on sim:thesis-test3" in out
    code, out, _ = _diff(capsys, str(other), "--bus", "sim:thesis-test3",
                         "--memory", str(memory))
    assert code == 3 and "is only in the arbitrator on sim:thesis-test3" in out


def test_an_empty_file_equals_a_new_arbitrator(capsys, tmp_path):
    empty = _save(tmp_path / "empty.pdcfg")
    code, out, _ = _diff(capsys, str(empty), "--bus", "sim:thesis-test3", "--json")
    assert code == 0 and json.loads(out) == {"configurations": []}


@pytest.mark.parametrize("argv, words", [
    (["A"], "either a second file B or --bus"),
    (["A", "B", "--bus", "sim:thesis-test3"], "either a second file B or --bus"),
    (["A", "B", "--memory", "m.mem"], "--memory needs --bus"),
])
def test_wrong_arguments_are_bad_input(capsys, tmp_path, argv, words):
    names = {"A": str(FIG410), "B": str(FIG410)}
    code, out, err = _diff(capsys, *[names.get(x, x) for x in argv])
    assert code == 2 and words in err and out == ""


def test_a_bad_file_is_exit_2_with_its_offset(capsys, tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(struct.pack("<BHBH", 1, 1, 9, 1))
    code, out, err = _diff(capsys, str(FIG410), str(bad))
    assert code == 2 and "bad.pdcfg" in err and "offset 3" in err and out == ""
    code, _, err = _diff(capsys, str(tmp_path / "absent.pdcfg"), str(FIG410))
    assert code == 2 and "absent.pdcfg" in err


def test_an_unknown_prosthesis_is_bad_input(capsys, tmp_path):
    code, _, err = _diff(capsys, str(FIG410), "--bus", "sim:no-such-prosthesis")
    assert code == 2 and "no-such-prosthesis" in err
