"""Bus URLs (contracts §3) and opening python-can buses from them."""

from __future__ import annotations

import re

import pytest

from pdcp_studio.bus.session.urls import (
    DEFAULT_BAUD,
    BusUrlError,
    check_bus_url,
    open_can_bus,
    open_spec,
    parse_bus_url,
    unique_virtual_channel,
)
from pdcp_studio.errors import TransportError


@pytest.mark.parametrize("url, fields", [
    ("sim:thesis-test1", {"kind": "sim", "name": "thesis-test1"}),
    ("can:socketcan:can0", {"kind": "can", "interface": "socketcan", "channel": "can0",
                            "bitrate": None}),
    ("can:pcan:PCAN_USBBUS1@1000000", {"interface": "pcan", "channel": "PCAN_USBBUS1",
                                       "bitrate": 1_000_000}),
    ("can:virtual:bus0", {"interface": "virtual", "channel": "bus0"}),
    ("can:udp_multicast:ff15:7079:7468:6f6e:6465:6d6f:6d63:6173",
     {"channel": "ff15:7079:7468:6f6e:6465:6d6f:6d63:6173"}),
    ("can:udp_multicast:239.74.163.2?port=43200&fd=false",
     {"channel": "239.74.163.2", "options": (("port", 43200), ("fd", False))}),
    ("serial:/dev/ttyUSB0@128000", {"kind": "serial", "port": "/dev/ttyUSB0", "baud": 128000}),
    ("serial:COM3", {"port": "COM3", "baud": DEFAULT_BAUD}),
    ("serial:socket://127.0.0.1:7000", {"port": "socket://127.0.0.1:7000"}),
])
def test_parse(url, fields):
    spec = parse_bus_url(url)
    assert spec.url == url
    for name, value in fields.items():
        assert getattr(spec, name) == value


@pytest.mark.parametrize("url, says", [
    ("nothing", "is not one of"),
    ("tcp:host", "unknown scheme"),
    ("sim:", "needs a prosthesis name"),
    ("sim:a b", "needs a prosthesis name"),
    ("can:socketcan", "expected can:INTERFACE:CHANNEL"),
    ("can::can0", "expected can:INTERFACE:CHANNEL"),
    ("can:pcan:X@fast", "bitrate 'fast' is not a number"),
    ("can:pcan:X@0", "must be positive"),
    ("can:pcan:@500000", "the channel is empty"),
    ("can:virtual:x?port", "is not NAME=VALUE"),
    ("serial:", "needs a port"),
])
def test_bad_urls_say_what_is_wrong(url, says):
    with pytest.raises(BusUrlError, match=says):
        parse_bus_url(url)


def test_unique_virtual_channels_differ():
    names = {unique_virtual_channel() for _ in range(100)}
    assert len(names) == 100


def test_open_virtual_and_missing_interfaces():
    spec = parse_bus_url(f"can:virtual:{unique_virtual_channel()}@500000")
    bus = open_spec(spec)  # the bitrate is not passed to the virtual interface
    bus.shutdown()
    with pytest.raises(BusUrlError, match=r"can:nosuch:x.*has no interface"):
        open_can_bus("nosuch", "x", url="can:nosuch:x")  # bad input (contracts §2): exit 2
    with pytest.raises(TransportError, match="not a can: bus"):
        open_spec(parse_bus_url("sim:thesis-test1"))


@pytest.mark.parametrize("url, says", [
    ("can:virtual:bus0?bogus=3", "the virtual interface has no option 'bogus'"),
    ("can:virtual:bus0?recieve_own_messages=1", "did you mean 'receive_own_messages'?"),
    ("can:pcan:PCAN_USBBUS1?fclock=80", "did you mean 'f_clock'?"),
    ("can:slcan:/dev/ttyACM0?tty_baud=115200", "the slcan interface has no option"),
])
def test_an_option_the_interface_does_not_know_is_refused(url, says):
    """python-can would drop it silently and open another bus than the one asked for."""
    with pytest.raises(BusUrlError, match=re.escape(says)):
        check_bus_url(url)


@pytest.mark.parametrize("url", [
    "can:virtual:bus0?rx_queue_size=10&preserve_timestamps=1",
    "can:slcan:/dev/ttyACM0?tty_baudrate=115200",
    "can:pcan:PCAN_USBBUS1?f_clock_mhz=80",  # read from **kwargs by python-can's pcan
    "can:udp_multicast:239.74.163.2?port=43200&hop_limit=2",
    "can:socketcan:vcan0?local_loopback=0",
    "can:vector:0?app_name=CANalyzer",
])
def test_options_python_can_reads_pass(url):
    assert check_bus_url(url).options


def test_known_options_are_read_from_python_cans_source_not_a_list():
    from pdcp_studio.bus.session.can_options import known_options

    virtual = known_options("virtual")
    assert virtual is not None and {"rx_queue_size", "preserve_timestamps"} <= virtual
    assert "tty_baudrate" not in virtual
    assert known_options("no-such-plugin") is None  # a plug-in is not checked


def test_scan_exits_2_on_an_unknown_option(tmp_path):
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "scan", "--bus",
                           "can:virtual:bus0?bogus=3"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2
    assert "no option 'bogus'" in done.stderr and "Traceback" not in done.stderr
