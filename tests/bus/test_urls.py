"""Bus URLs (contracts §3) and opening python-can buses from them."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.urls import (
    DEFAULT_BAUD,
    BusUrlError,
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
