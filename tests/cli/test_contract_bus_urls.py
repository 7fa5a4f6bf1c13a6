"""Contracts §3, ``--bus`` URLs, through the command line: ``sim:NAME``,
``can:INTERFACE:CHANNEL[@BITRATE]`` (PDCP Studio is the arbitrator there) and
``serial:PORT[@BAUD]`` including pyserial URLs, default 128000 baud. A URL that does not
parse is bad input (exit 2); a bus that cannot be opened is any other failure (exit 1).
"""

from __future__ import annotations

import json

import pytest
import serial

from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.cli.main import main


def test_can_virtual_bus_with_nobody_on_it_scans_to_an_empty_system(capsys):
    url = f"can:virtual:{unique_virtual_channel('contract-url')}@1000000"
    assert main(["scan", "--bus", url, "--json", "--settle", "0.3"]) == 0
    out, _ = capsys.readouterr()
    assert json.loads(out) == {"format": "pdcp-system/1", "devices": [], "links": []}


@pytest.mark.parametrize(("url", "port", "baud"), [
    ("serial:socket://127.0.0.1:7000", "socket://127.0.0.1:7000", 128000),
    ("serial:/dev/ttyUSB0@128000", "/dev/ttyUSB0", 128000),
    ("serial:COM3", "COM3", 128000),
    ("serial:rfc2217://localhost:7000@57600", "rfc2217://localhost:7000", 57600),
])
def test_serial_urls_open_the_pyserial_port_at_the_baud_rate(capsys, monkeypatch, url, port,
                                                             baud):
    opened = []

    def refuse(port, **kwargs):
        opened.append((port, kwargs.get("baudrate")))
        raise serial.SerialException("no such port here")

    monkeypatch.setattr(serial, "serial_for_url", refuse)
    assert main(["scan", "--bus", url, "--json"]) == 1
    out, err = capsys.readouterr()
    assert opened == [(port, baud)]
    assert out == "" and url in err


@pytest.mark.parametrize("url", ["", "bogus", "bogus:x", "sim:", "can:", "can:virtual",
                                 "can:virtual:bus0@fast", "can:virtual:bus0@0", "serial:",
                                 "serial:@9600"])
def test_a_url_that_does_not_parse_is_exit_2(capsys, url):
    assert main(["scan", "--bus", url, "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.startswith("pdcp-studio: ") and "bus" in err.lower()


def test_sim_bus_of_each_thesis_test_and_transradial_scans(capsys):
    for name in [f"thesis-test{n}" for n in range(1, 6)] + ["transradial"]:
        assert main(["scan", "--bus", f"sim:{name}", "--json"]) == 0
        doc = json.loads(capsys.readouterr().out)
        assert doc["format"] == "pdcp-system/1" and doc["devices"]
