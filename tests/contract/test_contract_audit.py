"""Contracts §1–§3 checked line by line through ``main``: exit statuses, one JSON document on
stdout, the exact keys, loader rejections naming the JSON path, bus URLs that are bad input."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdcp_studio.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "resources" / "systems"
FIG410 = ROOT / "resources" / "configs" / "fig410.pdcfg"
OTHER_CFG = ROOT / "resources" / "configs" / "transradial-hand-and-hook.pdcfg"


@pytest.fixture(autouse=True)
def _private_history(tmp_path, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "history.db"))
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "audit")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_json(out: str):
    doc, end = json.JSONDecoder().raw_decode(out.lstrip())
    assert out.lstrip()[end:].strip() == "", "something besides the JSON document on stdout"
    return doc


# -- §2 listings, sim, doctor --------------------------------------------------------------
def test_sim_list_names_the_contract_prostheses_one_a_line(capsys):
    code, out, _ = run(capsys, "sim", "list")
    assert code == 0
    names = out.split()
    for name in ("thesis-test1", "thesis-test2", "thesis-test3", "thesis-test4",
                 "thesis-test5", "transradial", "large", "full"):
        assert name in names


def test_scan_json_has_node_ids_on_devices_and_output_channels_only(capsys):
    code, out, _ = run(capsys, "scan", "--bus", "sim:transradial", "--json")
    doc = one_json(out)
    assert code == 0 and doc["format"] == "pdcp-system/1" and "links" in doc
    for device in doc["devices"]:
        assert "node_id" in device
        for channel in device["channels"]:
            assert ("node_id" in channel) == (channel["direction"] == "output")


def test_doctor_json_has_the_contract_keys(capsys):
    code, out, _ = run(capsys, "doctor", "--json")
    doc = one_json(out)
    assert code == 0
    assert {"version", "modules", "can_interfaces", "resources", "history"} <= set(doc)
    assert all(isinstance(v, bool) for v in doc["modules"].values())
    for entry in doc["can_interfaces"].values():
        assert isinstance(entry["driver"], bool)


def test_print_and_info_accept_a_bus(capsys):
    for command in ("print", "info"):
        code, out, _ = run(capsys, command, "--bus", "sim:thesis-test1")
        assert code == 0 and "2/2/4" in out


# -- §2 config -----------------------------------------------------------------------------
def test_config_decode_json_keys_and_a_bad_file_names_the_offset(capsys, tmp_path):
    code, out, _ = run(capsys, "config", "decode", FIG410, "--json")
    doc = one_json(out)
    link = doc["configurations"][0]["links"][0]
    assert code == 0 and link["index"] == 1
    assert set(link["input"]) >= {"type", "profile", "index", "vid", "pid", "serial"}
    assert link["input"]["type"] == "0x000A" and link["input"]["profile"] == "0x0014"
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(b"\x00\x01garbage that is no configuration")
    code, out, err = run(capsys, "config", "decode", bad, "--json")
    assert code == 2 and out == "" and "offset " in err and "bad.pdcfg" in err


def test_config_diff_exit_0_when_equal_3_when_different(capsys):
    code, out, _ = run(capsys, "config", "diff", FIG410, FIG410, "--json")
    assert code == 0
    assert all(c["only_in_a"] == c["only_in_b"] == c["changed"] == []
               for c in one_json(out)["configurations"])
    code, out, _ = run(capsys, "config", "diff", FIG410, OTHER_CFG, "--json")
    doc = one_json(out)
    assert code == 3
    assert {"index", "only_in_a", "only_in_b", "changed"} <= set(doc["configurations"][0])


def test_config_write_to_a_bus_needs_yes_and_writes_nothing_without(capsys, tmp_path):
    code, _, err = run(capsys, "config", "write", FIG410, "--bus", "sim:thesis-test1")
    assert code != 0 and "--yes" in err


# -- §2 apply, policy, history -------------------------------------------------------------
def test_apply_without_yes_writes_nothing_and_exits_0(capsys):
    code, out, _ = run(capsys, "apply", "clear", "--bus", "sim:thesis-test1", "--json")
    plan = one_json(out)
    assert code == 0 and plan["mode"] == "clear" and plan["links"] == []
    assert [a["op"] for a in plan["actions"]] == ["remove"]
    code, out, _ = run(capsys, "history", "list", "--json")
    assert code == 0 and one_json(out) == {"entries": []}


def test_apply_with_yes_is_recorded_with_the_contract_fields(capsys):
    code, out, _ = run(capsys, "apply", "clear", "--bus", "sim:thesis-test1", "--yes", "--json")
    one_json(out)
    assert code == 0
    code, out, _ = run(capsys, "history", "list", "--json")
    entry = one_json(out)["entries"][0]
    assert {"id", "time", "operator", "bus", "action", "devices", "links_before",
            "links_after", "config_crc_before", "config_crc_after", "verified",
            "interlock"} <= set(entry)
    assert entry["operator"] == "audit" and entry["bus"] == "sim:thesis-test1"
    assert entry["action"] == "apply clear" and entry["links_after"] == []
    assert entry["time"].endswith("Z") and entry["verified"] is True
    crc = entry["config_crc_before"]  # None: the fresh arbitrator stores nothing yet
    assert crc is None or (crc.startswith("0x") and len(crc) == 6)
    assert run(capsys, "history", "verify")[0] == 0
    code, out, _ = run(capsys, "history", "show", str(entry["id"]), "--json")
    assert code == 0 and one_json(out)["id"] == entry["id"]


def test_policy_json_shows_autoconfigure(capsys):
    code, out, _ = run(capsys, "policy", "--bus", "sim:thesis-test1", "--json")
    assert code == 0 and one_json(out)["autoconfigure"] is True


# -- §2 monitor ----------------------------------------------------------------------------
def test_a_short_capture_of_another_bus_is_called_not_pdcp(capsys, tmp_path):
    log = tmp_path / "obd.log"
    log.write_text("(1700000000.000000) can0 7E8#0102030405060708\n"
                   "(1700000000.010000) can0 18DAF110#02100300000000\n"
                   "(1700000000.020000) can0 7E8#01\n")
    code, _, err = run(capsys, "monitor", "--replay", log)
    head = err.splitlines()[0]
    assert code == 0 and "not PDCP" in head and "undecodable" not in head


def test_a_pdcp_capture_with_some_garbage_counts_undecodable(capsys, tmp_path):
    log = tmp_path / "mixed.log"
    log.write_text("(1700000000.000000) can0 001#0A\n"
                   "(1700000000.010000) can0 7FF#FFFFFFFFFFFFFFFF\n")
    code, _, err = run(capsys, "monitor", "--replay", log)
    assert code == 0 and "1 undecodable" in err and "not PDCP" not in err


@pytest.mark.parametrize("value", ["nan", "inf", "-1"])
def test_monitor_seconds_not_finite_or_negative_is_exit_2_naming_the_option(capsys, value):
    with pytest.raises(SystemExit) as exc:
        main(["monitor", "--bus", "sim:thesis-test1", "--seconds", value])
    assert exc.value.code == 2 and "--seconds" in capsys.readouterr().err


# -- §3 bus URLs ---------------------------------------------------------------------------
@pytest.mark.parametrize("url", ["serial:/dev/ttyUSB0@fast", "serial:/dev/ttyUSB0@-5",
                                 "serial:COM3@0", "can:pcan:PCAN_USBBUS1@fast",
                                 "can:nosuchinterface:x", "sim:no-such-prosthesis",
                                 "bogus:foo", "can:virtual:bus0?bitrate=abc",
                                 "can:virtual:bus0?bitrate=500000", "can:virtual:bus0?url=x"])
def test_a_malformed_bus_url_is_exit_2_naming_it(capsys, url):
    code, out, err = run(capsys, "scan", "--bus", url, "--json")
    assert code == 2 and out == "" and url in err


def test_serial_url_default_baud_and_pyserial_urls_keep_their_at_signs():
    from pdcp_studio.bus.session.urls import parse_bus_url

    assert parse_bus_url("serial:COM3").baud == 128000
    spec = parse_bus_url("serial:/dev/ttyUSB0@57600")
    assert (spec.port, spec.baud) == ("/dev/ttyUSB0", 57600)
    spec = parse_bus_url("serial:socket://user@127.0.0.1:7000")
    assert (spec.port, spec.baud) == ("socket://user@127.0.0.1:7000", 128000)
    spec = parse_bus_url("can:virtual:bus0@500000?receive_own_messages=1")
    assert (spec.interface, spec.channel, spec.bitrate) == ("virtual", "bus0", 500000)


# -- §1 system file loader -----------------------------------------------------------------
BASE = {"format": "pdcp-system/1", "devices": [
    {"vid": 2, "pid": 2, "serial": 5, "channels": [
        {"index": 1, "direction": "input", "type": "0x7200", "profile": "0x2200"},
        {"index": 3, "direction": "output", "type": "0x5000", "profile": "0x1100",
         "required_inputs": [1]}]},
    {"vid": 2, "pid": 2, "serial": 4, "channels": [
        {"index": 1, "direction": "output", "type": "0x5000", "profile": "0x2200"}]}],
    "links": [{"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
               "input": {"vid": 2, "pid": 2, "serial": 5, "index": 1}}]}
TEXT = json.dumps(BASE, separators=(",", ":"))

REJECTIONS = [
    ("dup-key", TEXT.replace('"vid":2,"pid":2,"serial":5', '"vid":2,"vid":2,"pid":2,"serial":5'),
     "devices[0].vid"),
    ("null-profile", TEXT.replace('"profile":"0x2200"}', '"profile":"0x0000"}', 1),
     "devices[0].channels[0].profile"),
    ("required-output", TEXT.replace('"required_inputs":[1]', '"required_inputs":[3]'),
     "devices[0].channels[1].required_inputs[0]"),
    ("desired-missing", TEXT.replace('"required_inputs":[1]', '"desired_inputs":[9]'),
     "devices[0].channels[1].desired_inputs[0]"),
    ("link-reversed", TEXT.replace('"serial":4,"index":1},"input":{"vid":2,"pid":2,"serial":5',
                                   '"serial":5,"index":1},"input":{"vid":2,"pid":2,"serial":4'),
     "links[0]"),
    ("format", TEXT.replace("pdcp-system/1", "pdcp-system/2"), "format"),
    ("index-256", TEXT.replace('"index":3', '"index":256'), "devices[0].channels[1].index"),
    ("dup-channel", TEXT.replace('"index":3', '"index":1'), "devices[0].channels[1]"),
    ("vid-range", TEXT.replace('"vid":2,"pid":2,"serial":4', '"vid":70000,"pid":2,"serial":4'),
     "devices[1].vid"),
    ("deep", TEXT[:-1] + ',"x":' + "[" * 500 + "]" * 500 + "}", "deep"),
]


@pytest.mark.parametrize(("name", "text", "where"), REJECTIONS, ids=[r[0] for r in REJECTIONS])
def test_the_loader_rejects_naming_the_json_path(capsys, tmp_path, name, text, where):
    assert text != TEXT
    path = tmp_path / f"{name}.json"
    path.write_text(text)
    code, out, err = run(capsys, "info", "--system", path)
    assert code == 2 and out == "" and f"{name}.json" in err and where in err, err


def test_the_loader_accepts_the_base_and_refuses_an_oversized_pipe(capsys, tmp_path):
    ok = tmp_path / "ok.json"
    ok.write_text(TEXT)
    assert run(capsys, "info", "--system", ok)[0] == 0
    big = tmp_path / "big.json"
    big.write_text(TEXT[:-1] + ',"x":"' + "a" * (8 << 20) + '"}')
    code, _, err = run(capsys, "info", "--system", big)
    assert code == 2 and "big.json" in err


# -- §2 config decode/encode: unknown records and omitted owner records ---------------------
def test_unknown_records_and_omitted_owner_records_round_trip(capsys, tmp_path):
    code, out, _ = run(capsys, "config", "decode", FIG410, "--json")
    doc = one_json(out)
    link = doc["configurations"][0]["links"][0]
    del link["input"]["owner_type"], link["input"]["owner_profile"]
    doc["unknown_records"] = [{"code": 32, "value": 4660}]
    doc["configurations"][0]["unknown_records"] = [{"code": 33, "value": 1}]
    link["unknown_records"] = [{"code": 34, "value": 2}]
    link["output"]["unknown_records"] = [{"code": 35, "value": 3}, {"code": 36, "value": 4}]
    source = tmp_path / "unknown.json"
    source.write_text(json.dumps(doc))
    target = tmp_path / "unknown.pdcfg"
    assert run(capsys, "config", "encode", source, "-o", target)[0] == 0
    code, out, _ = run(capsys, "config", "decode", target, "--json")
    again = one_json(out)
    assert code == 0 and again == doc
    assert "owner_type" not in again["configurations"][0]["links"][0]["input"]


# -- §2 history verify -----------------------------------------------------------------------
def test_history_verify_exit_1_names_the_first_edited_entry(capsys, tmp_path):
    import sqlite3

    for bus in ("sim:thesis-test1", "sim:thesis-test2"):
        assert run(capsys, "apply", "clear", "--bus", bus, "--yes")[0] == 0
    db = tmp_path / "history.db"
    with sqlite3.connect(db) as con:
        con.execute("UPDATE entries SET body = replace(body, 'audit', 'mallory') WHERE id = 2")
    con.close()
    code, _, err = run(capsys, "history", "verify")
    assert code == 1 and "entry 2" in err


# -- §2 arbitrator --no-autoconfigure: the policy is kept in the memory -------------------------
def test_arbitrator_no_autoconfigure_sets_the_stored_policy_which_then_holds(capsys, tmp_path):
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    from pdcp_studio.bus.session.urls import unique_virtual_channel

    memory = tmp_path / "memory.json"
    bus = f"can:virtual:{unique_virtual_channel('audit')}"
    assert run(capsys, "arbitrator", "--bus", bus, "--memory", memory, "--seconds", "0.1",
               "--startup-quiet", "0.1")[0] == 0
    assert MemoryStore(memory).read_policy()["autoconfigure"] is True
    assert run(capsys, "arbitrator", "--bus", bus, "--memory", memory, "--seconds", "0.1",
               "--startup-quiet", "0.1", "--no-autoconfigure")[0] == 0
    assert MemoryStore(memory).read_policy()["autoconfigure"] is False
    assert run(capsys, "arbitrator", "--bus", bus, "--memory", memory, "--seconds", "0.1",
               "--startup-quiet", "0.1")[0] == 0
    assert MemoryStore(memory).read_policy()["autoconfigure"] is False


# -- reference §3 decisions ------------------------------------------------------------------
def _records(*pairs: tuple[int, int]) -> bytes:
    return b"".join(bytes([code]) + value.to_bytes(2, "little") for code, value in pairs)


def _channel(code: int) -> list[tuple[int, int]]:
    return [(code, 0), (7, 10), (8, 20), (9, 1), (10, 30), (11, 40), (12, 50)]


THESIS_ERA = _records((1, 1), (2, 1), (3, 1), (4, 1), *_channel(5), *_channel(6), (15, 0))


def test_a_thesis_era_file_gains_a_checksum_and_a_mismatch_is_refused():
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec

    written = config_codec.dumps(config_codec.loads(THESIS_ERA + b"\xff" * 9))
    assert written[-6] == 16 and written[-3:] == b"\x0f\x00\x00"
    assert config_codec.dumps(config_codec.loads(written)) == written
    tampered = bytearray(written)
    tampered[-5] ^= 1
    with pytest.raises(ConfigFormatError, match="offset"):
        config_codec.loads(bytes(tampered))


@pytest.mark.parametrize("data", [
    THESIS_ERA[:-3],                                              # no End
    THESIS_ERA[:-4] + b"\x0f\x00",                                # a truncated record
    _records((1, 2), (2, 1), (3, 1), (4, 1), *_channel(5), *_channel(6), (15, 0)),
    _records((1, 1), (2, 1), (3, 1), (4, 1), (7, 5), *_channel(5), *_channel(6), (15, 0)),
    _records((1, 1), (2, 1), (3, 1), (4, 1), *_channel(5), (15, 0)),
], ids=["no-end", "truncated", "count", "outside-channel", "one-channel"])
def test_the_stored_configuration_reader_rejects_with_the_offset(data):
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec

    with pytest.raises(ConfigFormatError, match=r"offset \d+"):
        config_codec.loads(data)


# -- reference §5: one arbitrator per bus, said in one line ------------------------------------
def test_a_second_arbitrator_says_so_in_one_line_and_exits_1(tmp_path, multicast_url):
    import subprocess
    import sys

    url = multicast_url("239.74.163.13", 46000)
    first = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus", url, "--memory",
         str(tmp_path / "first.json"), "--seconds", "30"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        while "arbitrating" not in (line := first.stdout.readline()):
            assert line, "the first arbitrator ended before it arbitrated"
        second = subprocess.run(
            [sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus", url, "--memory",
             str(tmp_path / "second.json"), "--seconds", "5"],
            capture_output=True, text=True, timeout=60)
    finally:
        first.terminate()
        first.communicate(timeout=10)
    assert second.returncode == 1
    lines = second.stderr.splitlines()
    assert len(lines) == 1 and "another bus arbitrator" in lines[0], second.stderr
