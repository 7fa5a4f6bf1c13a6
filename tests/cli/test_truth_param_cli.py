"""Parameters, --store and history restore from the command line over the host link (issue 26,
points 3 and 4; contracts §2 ``param``, ``--store``, ``effect``, ``next_power_on``,
``history restore``).

Three processes (tests/cli/truth_rig.py): simulated ``transradial`` devices, a headless
arbitrator with a fresh memory, and the CLI over ``serial:/dev/pts/N`` in this process,
recording in the test's own fitting history.
"""

from __future__ import annotations

import os
from typing import Any

import pytest

from pdcp_studio.bus.sim.rigs import resolve_prosthesis
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.storage import config_codec, system_file
from tests.cli.truth_rig import TruthRig, cli, cli_json

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not hasattr(os, "openpty"),
                                 reason="needs POSIX pseudo-terminals")]

HAND = "2641/769/301"
POWER_GRIP = f"{HAND}#1"
PART = {"vid": 2641, "pid": 769, "serial": 301}
FLEXOR_EMG = DeviceKey(2641, 257, 101)


@pytest.fixture
def rig(tmp_path, multicast_url):
    url = multicast_url("239.74.163.28", 46000)
    with TruthRig.running(url, tmp_path / "memory.bin", "transradial", count=4) as running:
        yield running


def stored(rig: TruthRig, path) -> bytes:
    code, out, err = cli("config", "read", "--bus", rig.url, "-o", str(path))
    assert code == 0, out + err
    return path.read_bytes()


def entries() -> list[dict[str, Any]]:
    code, doc = cli_json("history", "list")
    assert code == 0
    return list(doc["entries"])


def set_type(rig: TruthRig, value: str, *flags: str) -> dict[str, Any]:
    code, doc = cli_json("param", "set", "--bus", rig.url, POWER_GRIP, f"type={value}",
                         "--yes", *flags)
    assert code == 0 and doc["written"], doc.get("transaction")
    return doc


def test_param_get_json_is_the_contracts_document(rig):
    code, doc = cli_json("param", "get", "--bus", rig.url, POWER_GRIP)
    assert code == 0
    assert set(doc) == {"part", "channel", "parameters"}
    assert doc["part"] == PART and doc["channel"] == 1
    params = doc["parameters"]
    assert params["type"] == "0x9300" and params["profile"] == "0x2220"
    assert params["descriptor"] == "Power grip" and params["data-transfer"] in ("on", "off")
    assert all(isinstance(v, str) for v in params.values())

    code, doc = cli_json("param", "get", "--bus", rig.url, HAND)
    assert code == 0
    assert doc["part"] == PART and doc["channel"] is None
    assert doc["parameters"]["descriptor"] == "Multi-grip hand with wrist rotator"
    assert doc["parameters"]["beacon-interval"] == "100"


def test_param_set_no_store_shows_the_effect_and_leaves_the_stored_configuration(rig, tmp_path):
    assert cli("config", "save", "--bus", rig.url, "--yes")[0] == 0
    cfg_before = stored(rig, tmp_path / "before.pdcfg")
    doc = set_type(rig, "0x9700", "--no-store")
    [p] = doc["effect"]["parameters"]
    assert {k: p[k] for k in ("part", "channel", "name", "before", "after")} == {
        "part": PART, "channel": 1, "name": "type", "before": "0x9300", "after": "0x9700"}
    assert "control mode" in p["text"] and "0x" not in p["text"]  # words, not codes
    assert "Power grip" in p["text"]
    po = doc["next_power_on"]
    assert set(po) >= {"links_added", "links_removed", "text"} and po["text"]
    assert doc["store"] is False and not doc["effect"]["stored_configuration"]["changed"]
    # Read back: the part holds it, the stored configuration is as it was.
    code, got = cli_json("param", "get", "--bus", rig.url, POWER_GRIP)
    assert code == 0 and got["parameters"]["type"] == "0x9700"
    assert stored(rig, tmp_path / "after.pdcfg") == cfg_before


def test_param_set_store_stores_the_links_after(rig, tmp_path):
    doc = set_type(rig, "0x9700", "--store")
    assert doc["store"] is True and doc["effect"]["stored_configuration"]["changed"]
    stored(rig, tmp_path / "after.pdcfg")
    collection = config_codec.load_path(tmp_path / "after.pdcfg")
    [cfg] = collection.configurations
    links = rig.links()
    assert {(sl.output.ref, sl.input.ref) for sl in cfg.links} == {
        (lk.output, lk.input) for lk in links}
    # … with the channel as written: the hand's power grip stored as type 0x9700.
    grip = [sl.input for sl in cfg.links if str(sl.input.ref) == POWER_GRIP]
    assert grip and grip[0].type == 0x9700
    after = doc["effect"]["stored_configuration"]["links_after"]
    assert len(after) == len(links)


def test_history_restore_needing_an_absent_part_is_refused_before_anything_is_written(
        rig, tmp_path):
    set_type(rig, "0x9700", "--no-store")
    [entry] = [e for e in entries() if e["action"].startswith("param set")]
    # The flexor EMG electrode leaves the bus: the devices run again without it.
    system = resolve_prosthesis("transradial").load()
    system.remove_device(FLEXOR_EMG)
    for link in [lk for lk in system.links if lk.output.device == FLEXOR_EMG]:
        system.remove_link(link)
    reduced = tmp_path / "without-flexor.json"
    system_file.save_path(system, reduced)
    rig.start_devices(str(reduced), 3)
    rig.wait_set_up()
    links = rig.links()
    before = entries()
    cfg_before = stored(rig, tmp_path / "before.pdcfg")

    code, out, err = cli("history", "restore", str(entry["id"]), "--bus", rig.url, "--yes")
    assert code == 1, out + err
    assert str(FLEXOR_EMG) in err and "nothing was written" in err
    assert "EMG" in err  # the part by its name too
    assert entries() == before  # no new entry: nothing reached the prosthesis
    assert rig.links() == links
    assert stored(rig, tmp_path / "after.pdcfg") == cfg_before


def test_history_restore_of_a_control_mode_puts_it_back(rig):
    set_type(rig, "0x9700", "--no-store")
    [entry] = [e for e in entries() if e["action"].startswith("param set")]
    set_type(rig, "0x9300", "--no-store")
    code, doc = cli_json("param", "get", "--bus", rig.url, POWER_GRIP)
    assert code == 0 and doc["parameters"]["type"] == "0x9300"

    code, out, err = cli("history", "restore", str(entry["id"]), "--bus", rig.url)
    assert code == 0, out + err
    assert "nothing to change" not in out, out  # the trial's failure
    assert "control mode" in out
    code, doc = cli_json("history", "restore", str(entry["id"]), "--bus", rig.url, "--yes")
    assert code == 0 and doc["written"], doc.get("transaction")
    [p] = doc["effect"]["parameters"]
    assert (p["channel"], p["name"], p["before"], p["after"]) == (1, "type", "0x9300",
                                                                    "0x9700")
    code, got = cli_json("param", "get", "--bus", rig.url, POWER_GRIP)
    assert code == 0 and got["parameters"]["type"] == "0x9700"
    assert entries()[-1]["action"].startswith("history restore")
