"""``pdcp-studio arbitrator``: headless on a virtual bus, its errors, the host-link option."""

from __future__ import annotations

import sys
import threading

import can

from pdcp_studio.bus.arbitrator.claim import LISTEN_S
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.cli.main import main
from tests.bus.test_arbitrator_rig import load


def test_runs_headless_and_logs_joins_plans_and_leaves(capsys, tmp_path):
    channel = unique_virtual_channel("pdcp-cli")
    system = load("appendix-d")
    host = DeviceHost(can.Bus(interface="virtual", channel=channel),
                      [SimulatedDevice(d) for d in system.devices.values()], plugged=False)
    result: list[int] = []
    run = threading.Thread(target=lambda: result.append(main([
        "arbitrator", "--bus", f"can:virtual:{channel}", "--memory", str(tmp_path / "m"),
        "--startup-quiet", "0.15", "--seconds", str(1.2 + LISTEN_S)])))
    try:
        run.start()  # it listens LISTEN_S for another arbitrator before it arbitrates
        for key in system.devices:
            host.plug(key)
        threading.Timer(0.7 + LISTEN_S, lambda: host.unplug(next(iter(system.devices)))).start()
        run.join(10)
    finally:
        host.close()
    assert result == [0]
    out = capsys.readouterr().out.splitlines()
    assert out[0] == f"arbitrator on can:virtual:{channel}, memory {tmp_path / 'm'}"
    assert out[1].startswith("arbitrating: no other bus arbitrator heard")
    assert {"joined 2/2/4", "joined 2/2/5", "joined 2/2/6"} <= set(out)
    assert "plan startup: 3 added, 0 removed, 3 links" in out
    assert "  add 2/2/4#1 → 2/2/5#2 (retrieved: input 2/2/5#2 stores source 2/2/4#1)" in out
    assert "left 2/2/4" in out
    assert out[-1] == "arbitrator stopped"


def test_bad_bus_urls_exit_2(capsys):
    assert main(["arbitrator", "--bus", "sim:thesis-test1"]) == 2
    assert "runs on a can: bus" in capsys.readouterr().err
    assert main(["arbitrator", "--bus", "can:nope"]) == 2
    assert "expected can:INTERFACE:CHANNEL" in capsys.readouterr().err


def test_a_missing_adapter_driver_exits_1(capsys):
    assert main(["arbitrator", "--bus", "can:no_such_interface:x", "--seconds", "0"]) == 2
    assert "can:no_such_interface:x" in capsys.readouterr().err
    assert main(["arbitrator", "--bus", "can:kvaser:0", "--seconds", "0"]) == 1
    assert "fix: install Kvaser CANlib" in capsys.readouterr().err


def test_host_serial_without_the_host_link_module_exits_2(capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "pdcp_studio.bus.hostlink.server", None)
    code = main(["arbitrator", "--bus", f"can:virtual:{unique_virtual_channel()}",
                 "--host-serial", "pty", "--seconds", "0"])
    assert code == 2
    assert "--host-serial needs the host-link server" in capsys.readouterr().err


def test_host_serial_serves_the_host_link_on_a_pty(capsys):
    code = main(["arbitrator", "--bus", f"can:virtual:{unique_virtual_channel()}",
                 "--host-serial", "pty", "--seconds", "0.3"])
    assert code == 0
    out = capsys.readouterr().out
    assert "host link on /dev/" in out
