"""``can-bridge``: an SLCAN line (here a pseudo-terminal standing in for the firmware's UART1)
joined to a python-can bus (udp_multicast on loopback): frames go both ways, the line's
commands are answered by the firmware side only, and the bus's echoes of the bridge's own
sends do not come back to the line."""

from __future__ import annotations

import os
import threading
import time

import can
import pytest

from pdcp_studio.bus.session.urls import check_bus_url, open_spec
from pdcp_studio.cli.main import main

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")


def _read_lines(fd: int, seconds: float) -> list[str]:
    os.set_blocking(fd, False)
    data = b""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            data += os.read(fd, 1024)
        except BlockingIOError:
            time.sleep(0.02)
    return [line for line in data.decode().split("\r") if line]


def test_frames_cross_both_ways_and_own_echoes_stay_away(multicast_url):
    url = multicast_url("239.74.163.25", 45000)
    master, slave = os.openpty()
    path = os.ttyname(slave)
    done: list[int] = []
    bridge = threading.Thread(target=lambda: done.append(main(
        ["can-bridge", "--serial", path, "--bus", url, "--seconds", "4"])))
    bus = open_spec(check_bus_url(url))
    try:
        bridge.start()
        opened = _read_lines(master, 1.0)  # python-can opens the line: S8, O
        assert "O" in opened
        os.write(master, b"t123211AB\r")  # the firmware sends a frame
        got = bus.recv(2.0)
        assert got is not None and (got.arbitration_id, bytes(got.data)) == (0x123, b"\x11\xab")
        bus.send(can.Message(arbitration_id=0x245, data=b"\x0a", is_extended_id=False))
        lines = _read_lines(master, 1.0)
        assert "t24510A" in lines
        assert not any(line.startswith("t123") for line in lines)  # its own echo stayed away
    finally:
        bridge.join(10)
        bus.shutdown()
        os.close(master)
        os.close(slave)
    assert done == [0]


def test_a_bus_that_is_not_can_is_bad_input(capsys):
    assert main(["can-bridge", "--serial", "/dev/null", "--bus", "sim:thesis-test1"]) == 2
    assert "can-bridge joins a can: bus" in capsys.readouterr().err
