"""`serial:` bus URLs end to end: three processes, as in a fitting room.

Simulated devices in one process and a headless arbitrator in another share a CAN bus
(python-can udp_multicast on loopback); the arbitrator serves its host link on a new
pseudo-terminal; this process runs CLI commands against `serial:/dev/pts/N`.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.storage import config_codec

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")


@pytest.fixture
def serial_url(tmp_path, multicast_url):
    url = multicast_url("239.74.163.4", 43000)
    cmd = [sys.executable, "-m", "pdcp_studio"]
    devices = subprocess.Popen([*cmd, "sim", "devices", "transradial", "--bus", url,
                                "--seconds", "60"], stderr=subprocess.PIPE, text=True)
    arbitrator = subprocess.Popen([*cmd, "arbitrator", "--bus", url, "--host-serial", "pty",
                                   "--memory", str(tmp_path / "memory.bin"), "--seconds", "60"],
                                  stdout=subprocess.PIPE, text=True)
    try:
        assert "simulating 4 device(s)" in devices.stderr.readline()
        line = arbitrator.stdout.readline()
        assert line.startswith("host link on /dev/"), line
        yield "serial:" + line.split(" on ", 1)[1].strip()
    finally:
        for proc in (arbitrator, devices):
            proc.terminate()
        for proc in (arbitrator, devices):
            proc.wait(10)
        arbitrator.stdout.close()
        devices.stderr.close()


def test_scan_over_the_host_link_prints_the_contracts_system(serial_url, capsys):
    assert main(["scan", "--bus", serial_url, "--json", "--settle", "5"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["format"] == "pdcp-system/1"
    assert len(doc["devices"]) == 4
    assert all(d.get("node_id") for d in doc["devices"])


def test_config_write_over_the_host_link_is_verified(serial_url, tmp_path, capsys):
    good = tmp_path / "fig410.pdcfg"
    src = os.path.join(os.path.dirname(__file__), "..", "..", "resources", "configs",
                       "fig410.pdcfg")
    config_codec.save_path(config_codec.load_path(src), good)
    assert main(["config", "write", str(good), "--bus", serial_url, "--yes"]) == 0
    out = tmp_path / "back.pdcfg"
    assert main(["config", "read", "--bus", serial_url, "-o", str(out)]) == 0
    assert out.read_bytes() == good.read_bytes()


def test_monitor_over_the_host_link_shows_frames_and_counts_channel_data(serial_url, capsys):
    # The line cannot carry a busy CAN bus: protocol frames come in full, channel data as
    # counts per output, and the monitor says so instead of "0 frames".
    assert main(["monitor", "--bus", serial_url, "--seconds", "4"]) == 0
    out, err = capsys.readouterr()
    assert "channel data counted by the arbitrator over" in out, out[-2000:]
    assert "channel data frame(s) counted by the arbitrator" in err, err
