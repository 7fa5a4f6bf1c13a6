"""``pdcp-studio scan --bus URL [--json]`` (contracts §2)."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.rigs import load_prosthesis
from pdcp_studio.cli.main import main
from pdcp_studio.storage import system_file

TEST2_LINKS = [
    {"output": {"vid": 2, "pid": 2, "serial": 4, "index": 1},
     "input": {"vid": 2, "pid": 2, "serial": 5, "index": 2}},
    {"output": {"vid": 2, "pid": 2, "serial": 5, "index": 3},
     "input": {"vid": 2, "pid": 2, "serial": 6, "index": 1}},
    {"output": {"vid": 2, "pid": 2, "serial": 5, "index": 5},
     "input": {"vid": 2, "pid": 2, "serial": 6, "index": 2}},
]




def _check_contract(doc: dict) -> None:
    assert doc["format"] == "pdcp-system/1"
    assert doc["links"] == TEST2_LINKS
    for dev in doc["devices"]:
        assert isinstance(dev["node_id"], int) and 1 <= dev["node_id"] <= 254
        for ch in dev["channels"]:
            assert ("node_id" in ch) == (ch["direction"] == "output")
            assert ch["type"].startswith("0x") and len(ch["type"]) == 6
    system_file.from_json(doc)  # a loader accepts what scan prints


def test_scan_sim_json(capsys):
    assert main(["scan", "--bus", "sim:thesis-test2", "--json"]) == 0
    out, _ = capsys.readouterr()
    doc = json.loads(out)
    _check_contract(doc)
    cu = next(d for d in doc["devices"] if d["serial"] == 5)
    assert cu["descriptor"] == "Control unit board"
    out3 = next(c for c in cu["channels"] if c["index"] == 3)
    assert out3["profile"] == "0x1100" and out3["required_inputs"] == [2]


def test_scan_can_bus_binds_starts_up_and_scans(capsys, tmp_path):
    channel = unique_virtual_channel("pdcp-test-cli-scan")
    system = load_prosthesis("thesis-test2")
    host = DeviceHost(open_can_bus("virtual", channel),
                      [SimulatedDevice(d) for d in system.devices.values()], name="rig")
    try:
        code = main(["scan", "--bus", f"can:virtual:{channel}", "--json",
                     "--memory", str(tmp_path / "arb.mem"), "--settle", "5"])
    finally:
        host.close()
    assert code == 0
    _check_contract(json.loads(capsys.readouterr().out))


def test_scan_text_listing(capsys):
    assert main(["scan", "--bus", "sim:thesis-test1"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("2 device(s), 1 link(s)")
    # Names first (the app's: model/names.py), the numbers beside them in brackets.
    assert "link Joystick, Joystick X axis → LED terminal A, X axis LEDs  [2/2/4#1 → 2/2/5#1]" \
        in out
    assert "Joystick  [2/2/4, node 1]" in out


@pytest.mark.parametrize("argv, says", [
    (["scan", "--bus", "bogus"], "bus URL"),
    (["scan", "--bus", "sim:nope"], "no built-in prosthesis"),
    (["scan", "--bus", "sim:thesis-test2", "--window", "0"], "--window"),
    (["scan", "--bus", "serial:/dev/null", "--memory", "x"], "--memory"),
])
def test_scan_bad_input_is_exit_2(capsys, argv, says):
    assert main(argv) == 2
    assert says in capsys.readouterr().err


def test_scan_missing_adapter_is_exit_1(capsys):
    assert main(["scan", "--bus", "can:no_such_interface:can0"]) == 2  # not python-can's
    assert "can:no_such_interface:can0" in capsys.readouterr().err
    assert main(["scan", "--bus", "can:kvaser:0"]) == 1  # known, driver missing: the fix
    assert "fix: install Kvaser CANlib" in capsys.readouterr().err


def test_scan_of_devices_in_another_process_over_udp_multicast(capsys, multicast_url):
    import subprocess
    import sys

    url = multicast_url("239.74.163.3", 42000)
    devices = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "sim", "devices", "thesis-test2", "--bus", url,
         "--seconds", "20"], stderr=subprocess.PIPE, text=True)
    try:
        assert "simulating 3 device(s)" in devices.stderr.readline()
        assert main(["scan", "--bus", url, "--json", "--settle", "5"]) == 0
    finally:
        devices.terminate()
        devices.wait(5)
    _check_contract(json.loads(capsys.readouterr().out))
