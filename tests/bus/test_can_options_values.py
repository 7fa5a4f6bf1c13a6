"""Contracts §2: a ``--bus`` URL whose option value the interface refuses is bad input —
exit 2 before anything opens, one line naming the option, the interface and what it takes.
The types are read from python-can's own source (the bus class's ``__init__``), so these
cases use real interfaces; good values still pass and open python-can's virtual bus."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pdcp_studio.bus.session.can_options import bad_value, option_types
from pdcp_studio.bus.session.urls import BusUrlError, check_bus_url, open_spec, parse_bus_url

ROOT = Path(__file__).resolve().parents[2]

REFUSED = [
    ("can:slcan:/dev/ttyS0?tty_baudrate=abc",
     "the slcan interface's option 'tty_baudrate' takes a whole number above 0, not 'abc'"),
    ("can:slcan:/dev/ttyS0?tty_baudrate=-3",
     "the slcan interface's option 'tty_baudrate' takes a whole number above 0, not '-3'"),
    ("can:slcan:/dev/ttyS0?tty_baudrate=0", "'tty_baudrate' takes a whole number above 0"),
    ("can:slcan:/dev/ttyS0?tty_baudrate=1152.5", "not '1152.5'"),
    ("can:slcan:/dev/ttyS0?timeout=nan", "option 'timeout' takes a number of 0 or more"),
    ("can:slcan:/dev/ttyS0?timeout=-0.5", "not '-0.5'"),
    ("can:slcan:/dev/ttyS0?rtscts=maybe", "option 'rtscts' takes true or false"),
    ("can:serial:/dev/ttyS0?baudrate=xyz",
     "the serial interface's option 'baudrate' takes a whole number above 0, not 'xyz'"),
    ("can:virtual:x?rx_queue_size=abc",
     "the virtual interface's option 'rx_queue_size' takes a whole number of 0 or more"),
    ("can:virtual:x?rx_queue_size=-1", "not '-1'"),
    ("can:virtual:x?receive_own_messages=yes",
     "the virtual interface's option 'receive_own_messages' takes true or false, not 'yes'"),
    ("can:virtual:x?preserve_timestamps=2", "takes true or false, not '2'"),
    ("can:pcan:PCAN_USBBUS1?device_id=first", "the pcan interface's option 'device_id'"),
    ("can:udp_multicast:239.74.163.2?hop_limit=far", "option 'hop_limit' takes a whole number"),
    ("can:robotell:/dev/ttyS0?ttyBaudrate=fast", "'ttyBaudrate' takes a whole number above 0"),
    ("can:socketcan:vcan0?local_loopback=on", "'local_loopback' takes true or false"),
    ("can:virtual:x?data_bitrate=-2000000", "'data_bitrate' takes a whole number above 0"),
]


@pytest.mark.parametrize(("url", "words"), REFUSED)
def test_a_value_the_interface_refuses_is_bad_input(url, words):
    with pytest.raises(BusUrlError) as caught:
        check_bus_url(url)
    assert words in str(caught.value)
    assert url in str(caught.value)  # the URL as given, once


ACCEPTED = [
    "can:virtual:x?rx_queue_size=10&preserve_timestamps=1",
    "can:virtual:x?receive_own_messages=true",
    "can:virtual:x?receive_own_messages=False&rx_queue_size=0",
    "can:slcan:/dev/ttyS0@1000000?tty_baudrate=115200",
    "can:slcan:/dev/ttyS0?timeout=0.5&sleep_after_open=2&rtscts=true",
    "can:serial:/dev/ttyS0?baudrate=115200&timeout=1",
    "can:pcan:PCAN_USBBUS1?device_id=3&receive_own_messages=0",
    "can:udp_multicast:239.74.163.2?port=43200&hop_limit=2&fd=false",
    "can:socketcan:vcan0?local_loopback=0",
    "can:vector:0?app_name=CANalyzer&rx_queue_size=16384",
    "can:virtual:x?data_bitrate=2000000&fd=true",
]


@pytest.mark.parametrize("url", ACCEPTED)
def test_good_values_are_still_accepted(url):
    assert check_bus_url(url).options


def test_values_are_read_as_python_can_reads_its_configuration():
    import can.util

    spec = parse_bus_url("can:slcan:/dev/ttyS0?timeout=0.5&tty_baudrate=+115200&rtscts=TRUE"
                         "&x=abc")
    assert dict(spec.options) == {"timeout": 0.5, "tty_baudrate": 115200, "rtscts": True,
                                  "x": "abc"}
    for key, value in spec.options:  # the same conversion, so the check judges what is passed
        assert can.util.cast_from_string({"timeout": "0.5", "tty_baudrate": "+115200",
                                          "rtscts": "TRUE", "x": "abc"}[key]) == value


def test_the_types_come_from_python_cans_source():
    slcan = option_types("slcan")
    assert slcan is not None
    assert slcan["tty_baudrate"] == {"int"} and slcan["timeout"] == {"float"}
    assert slcan["rtscts"] == {"bool"}
    vector = option_types("vector")
    assert vector is not None and "app_name" not in vector  # a string: any value
    assert option_types("no-such-plugin") is None  # a plug-in is not checked
    assert bad_value("no-such-plugin", {"anything": "abc"}) is None


def test_good_options_open_python_cans_virtual_bus():
    import can

    spec = check_bus_url("can:virtual:pdcp-values-test?rx_queue_size=10"
                         "&receive_own_messages=true&preserve_timestamps=false")
    bus = open_spec(spec)
    try:
        bus.send(can.Message(arbitration_id=0x123, data=b"\x01"))
        echoed = bus.recv(timeout=2)  # receive_own_messages=true reached python-can
        assert echoed is not None and echoed.arbitration_id == 0x123
    finally:
        bus.shutdown()


@pytest.mark.parametrize(("argv", "option"), [
    (["scan", "--bus", "can:slcan:/dev/ttyS0?tty_baudrate=abc"], "'tty_baudrate'"),
    (["scan", "--bus", "can:slcan:/dev/ttyS0?tty_baudrate=-3"], "'tty_baudrate'"),
    (["scan", "--bus", "can:serial:/dev/ttyS0?baudrate=xyz"], "'baudrate'"),
    (["scan", "--bus", "can:virtual:x?rx_queue_size=abc"], "'rx_queue_size'"),
    (["monitor", "--bus", "can:virtual:x?rx_queue_size=abc", "--seconds", "0.1"],
     "'rx_queue_size'"),
])
def test_the_cli_exits_2_naming_the_option(argv, option):
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", *argv], capture_output=True,
                          text=True, timeout=60, cwd=ROOT)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and option in lines[0] and "takes" in lines[0], done.stderr
    assert "cannot open" not in done.stderr and "Traceback" not in done.stderr
