"""Contracts §2, the command line, as written: exit 0 / 2 / 1, ``--json`` = one JSON document
on stdout and nothing else, ``plan MODE --system FILE [--config CFG] [--json]`` for every
MODE, ``links`` sorted by output then input, and the thesis tests of reference §4 ending in
the reference's links through ``sim replay thesis-testN --json`` and ``plan``.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.storage import config_codec, system_file

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "resources" / "systems"
MODES = ("autoconfigure", "replacements", "implement", "startup", "enforce", "clear")


def _ref(serial: int, index: int) -> dict:
    return {"vid": 2, "pid": 2, "serial": serial, "index": index}


def _link(out: tuple[int, int], inp: tuple[int, int]) -> dict:
    return {"output": _ref(*out), "input": _ref(*inp)}


# Appendix D: SN4.O1→SN5.I2, SN5.O3→SN6.I1, SN5.O5→SN6.I2 (reference §4, tests 2, 3 and 5).
TEST2_LINKS = [_link((4, 1), (5, 2)), _link((5, 3), (6, 1)), _link((5, 5), (6, 2))]




def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _one_json_document(out: str) -> dict:
    doc, end = json.JSONDecoder().raw_decode(out)
    assert out[end:].strip() == "", "something besides the JSON document on stdout"
    return doc


# -- plan ---------------------------------------------------------------------------------
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("system", ["thesis-test2.json", "appendix-d.json"])
def test_plan_every_mode_without_config_prints_the_contract_json(capsys, mode, system):
    code, out, err = run(capsys, "plan", mode, "--system", str(SYSTEMS / system), "--json")
    assert (code, err) == (0, "")
    doc = _one_json_document(out)
    assert list(doc)[:3] == ["mode", "actions", "links"] and doc["mode"] == mode
    for action in doc["actions"]:
        assert action["op"] in ("add", "remove")
        assert set(action) >= {"op", "output", "input", "similarity", "reason"}
    key = [(lk["output"]["vid"], lk["output"]["pid"], lk["output"]["serial"],
            lk["output"]["index"], lk["input"]["vid"], lk["input"]["pid"],
            lk["input"]["serial"], lk["input"]["index"]) for lk in doc["links"]]
    assert key == sorted(key)
    if system == "appendix-d.json":  # already configured: only clear changes it
        assert doc["links"] == ([] if mode == "clear" else TEST2_LINKS)
    else:  # no links yet: autoconfigure and start-up (retrieving nothing) make appendix D's
        assert doc["links"] == (TEST2_LINKS if mode in ("autoconfigure", "startup") else [])


def test_plan_links_are_sorted_by_output_then_input(capsys):
    # Transradial has outputs feeding several inputs and links across all its devices.
    code, out, _ = run(capsys, "plan", "autoconfigure", "--system",
                       str(SYSTEMS / "transradial.json"), "--json")
    links = _one_json_document(out)["links"]
    assert code == 0 and len(links) >= 2

    def key(lk: dict) -> tuple:
        return tuple(lk[end][k] for end in ("output", "input")
                     for k in ("vid", "pid", "serial", "index"))

    assert [key(lk) for lk in links] == sorted(key(lk) for lk in links)


@pytest.mark.parametrize("mode", ["replacements", "implement", "startup"])
def test_a_stored_configuration_holding_no_configuration_is_not_bad_input(capsys, tmp_path,
                                                                           mode):
    # What `config read` saves from an arbitrator whose memory is empty.
    empty = tmp_path / "empty.pdcfg"
    config_codec.save_path(config_codec.from_json({"configurations": []}), empty)
    code, out, err = run(capsys, "plan", mode, "--system", str(SYSTEMS / "thesis-test2.json"),
                         "--config", str(empty), "--json")
    assert (code, err) == (0, "")
    doc = _one_json_document(out)
    assert doc["links"] == (TEST2_LINKS if mode == "startup" else [])


def test_unknown_mode_is_exit_2_with_a_message_on_stderr(capsys):
    with pytest.raises(SystemExit) as info:
        main(["plan", "reboot", "--system", str(SYSTEMS / "thesis-test2.json"), "--json"])
    out, err = capsys.readouterr()
    assert info.value.code == 2 and out == "" and "reboot" in err


# -- reference §4: the thesis's tests -----------------------------------------------------
THESIS_FINAL_LINKS = {
    "thesis-test1": [_link((4, 1), (6, 1))],  # D1.O1 → D3.I1
    "thesis-test2": TEST2_LINKS,
    "thesis-test3": TEST2_LINKS,  # the links before the reset
    "thesis-test4": [_link((5, 2), (6, 2))],  # D2.O2 → D3.I2
    "thesis-test5": TEST2_LINKS,  # the links before the reset
}


@pytest.mark.parametrize("name", sorted(THESIS_FINAL_LINKS))
def test_sim_replay_thesis_test_ends_in_the_references_links(capsys, name):
    code, out, _ = run(capsys, "sim", "replay", name, "--json")
    assert code == 0
    doc = _one_json_document(out)
    assert doc["format"] == "pdcp-system/1"
    assert doc["links"] == THESIS_FINAL_LINKS[name]
    system_file.from_json(doc)  # a loader takes what replay prints
    for device in doc["devices"]:
        if device["present"]:
            assert 1 <= device["node_id"] <= 254
            for ch in device["channels"]:
                assert ("node_id" in ch) == (ch["direction"] == "output")


@pytest.mark.parametrize(("name", "gone", "joins"), [("thesis-test1", 5, 6),
                                                     ("thesis-test4", 4, 5)])
def test_plan_startup_and_replacements_repair_a_replaced_device(capsys, tmp_path, name, gone,
                                                                joins):
    """Tests 1 and 4 offline: link, store, swap the device, start up with the stored links."""
    system = SYSTEMS / f"{name}.json"
    _, out, _ = run(capsys, "plan", "autoconfigure", "--system", str(system), "--json")
    before = _one_json_document(out)["links"]
    doc = json.loads(system.read_text())
    (tmp_path / "stored.json").write_text(json.dumps({**doc, "links": before}))
    for device in doc["devices"]:
        device["present"] = {gone: False, joins: True}.get(device["serial"], device["present"])
    doc["devices"] = [d for d in doc["devices"] if d["serial"] != gone]  # "the system lacks"
    (tmp_path / "after.json").write_text(json.dumps(doc))
    for mode in ("startup", "replacements"):
        code, out, err = run(capsys, "plan", mode, "--system", str(tmp_path / "after.json"),
                             "--config", str(tmp_path / "stored.json"), "--json")
        assert (code, err) == (0, "")
        assert _one_json_document(out)["links"] == THESIS_FINAL_LINKS[name]


# -- sim list -----------------------------------------------------------------------------
def test_sim_list_names_at_least_the_thesis_tests_and_transradial_one_a_line(capsys):
    code, out, err = run(capsys, "sim", "list")
    assert (code, err) == (0, "")
    names = out.splitlines()
    assert {f"thesis-test{n}" for n in range(1, 6)} | {"transradial"} <= set(names)
    assert all(name == name.strip() and name for name in names)


# -- --memory FILE: bad input, before any bus opens ---------------------------------------
@pytest.mark.parametrize("argv", [
    ["scan", "--bus", "sim:thesis-test3", "--json"],
    ["config", "read", "--bus", "sim:thesis-test3", "-o", "{tmp}/out.pdcfg"],
    ["arbitrator", "--bus", "can:virtual:contract-memory", "--seconds", "0.1"],
])
@pytest.mark.parametrize("memory", ["{tmp}", "{tmp}/no/such/folder/memory.bin"])
def test_a_memory_that_is_a_directory_or_in_no_folder_is_exit_2(capsys, tmp_path, argv,
                                                                  memory):
    memory = memory.format(tmp=tmp_path)
    argv = [a.format(tmp=tmp_path) for a in argv]
    code, out, err = run(capsys, *argv, "--memory", memory)
    assert (code, out) == (2, "")
    assert err.startswith(f"pdcp-studio: --memory {memory}: ")
