"""python-can's failures to open a bus, each in one line with the fix (issue 10 item 6,
issue 15 item 3): every kind of exception python-can and its drivers raise is injected into
``can.Bus`` and the CLI's answer checked — exit 2 for a URL python-can refuses, exit 1 with
the fix for a missing driver or adapter — and the same from every command that takes --bus.
"""

from __future__ import annotations

import errno
import logging
import socket

import can
import pytest
import serial

from pdcp_studio.bus.session.can_interfaces import (
    DRIVER_FIX,
    AdapterMissingError,
    DriverMissingError,
    explain_open_error,
)
from pdcp_studio.bus.session.urls import (
    BusUrlError,
    bitrate_warning,
    check_bus_url,
    known_interfaces,
    open_can_bus,
    open_spec,
    parse_bus_url,
)
from pdcp_studio.cli.main import main

#: (what python-can raised, the exception PDCP Studio raises, words the line must carry)
INJECTED = [
    (can.CanInterfaceNotImplementedError("Cannot import module can.interfaces.gs_usb for CAN "
                                         "interface 'gs_usb': No module named 'usb'"),
     DriverMissingError, "pip install gs_usb"),
    (can.CanInterfaceNotImplementedError('Unknown interface type "gs_usb"'), BusUrlError,
     "python-can has no interface"),
    (ImportError("Please install python-ics"), DriverMissingError, "pip install gs_usb"),
    (NameError("name 'canGetNumberOfChannels' is not defined"), DriverMissingError,
     "pip install gs_usb"),
    (AttributeError("module 'ctypes' has no attribute 'windll'"), DriverMissingError,
     "pip install gs_usb"),
    (OSError("pcanbasic library not found."), DriverMissingError, "pip install gs_usb"),
    (OSError(errno.EAFNOSUPPORT, "Address family not supported by protocol"),
     DriverMissingError, "pip install gs_usb"),
    (OSError(errno.ENODEV, "No such device"), AdapterMissingError, "plug the adapter in"),
    (serial.SerialException(errno.ENOENT, "could not open port /dev/ttyX"), AdapterMissingError,
     "plug the adapter in"),
    (OSError(errno.EACCES, "Permission denied"), AdapterMissingError, "dialout"),
    (can.CanInitializationError("could not open port"), AdapterMissingError,
     "plug the adapter in"),
    (can.CanOperationError("the adapter did not answer"), AdapterMissingError,
     "plug the adapter in"),
    (TypeError("getaddrinfo() argument 1 must be string or None"), BusUrlError,
     "expected a gs_usb channel"),
    (ValueError("Port config must be inside 0-65535 range!"), BusUrlError,
     "expected a gs_usb channel"),
    (OverflowError("bind(): port must be 0-65535."), BusUrlError, "expected"),
    (socket.gaierror(-2, "Name or service not known"), BusUrlError, "expected"),
    (RuntimeError("something else entirely"), Exception, "RuntimeError"),
]


@pytest.mark.parametrize(("raised", "kind", "says"), INJECTED,
                         ids=[type(r).__name__ for r, _, _ in INJECTED])
def test_each_exception_python_can_raises_becomes_one_line(monkeypatch, raised, kind, says):
    def refuse(**kwargs):
        raise raised

    monkeypatch.setattr(can, "Bus", refuse)
    with pytest.raises(kind) as caught:
        open_can_bus("gs_usb", "0", url="can:gs_usb:0")
    text = str(caught.value)
    assert "\n" not in text and "can:gs_usb:0" in text and says in text
    assert caught.value.__traceback__ is not None  # raised by us, not leaked
    assert not isinstance(caught.value, can.CanError | OSError)


@pytest.mark.parametrize(("raised", "kind", "says"), INJECTED[:-1],
                         ids=[type(r).__name__ for r, _, _ in INJECTED[:-1]])
def test_the_cli_gives_exit_2_for_refusals_and_1_with_the_fix(monkeypatch, capsys, raised,
                                                              kind, says):
    monkeypatch.setattr(can, "Bus", lambda **kw: (_ for _ in ()).throw(raised))
    code = main(["scan", "--bus", "can:gs_usb:0", "--json"])
    out, err = capsys.readouterr()
    assert code == (2 if kind is BusUrlError else 1)
    assert out == "" and err.count("\n") == 1 and says in err and "Traceback" not in err


def test_every_interface_has_a_fix_and_kvaser_without_canlib_is_not_a_traceback(capsys):
    assert set(known_interfaces()) <= set(DRIVER_FIX)
    # This machine has no Kvaser CANlib: python-can's kvaser raises NameError.
    assert main(["scan", "--bus", "can:kvaser:0", "--json"]) == 1
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and "Kvaser CANlib" in err and "Traceback" not in err


@pytest.mark.parametrize("interface", ["gs_usb", "vector", "ixxat", "pcan"])
def test_a_missing_driver_is_not_called_an_unknown_interface(capsys, interface):
    try:
        bus = can.Bus(interface=interface, channel="0")
    except Exception:
        pass
    else:  # pragma: no cover - a machine with the driver and an adapter
        bus.shutdown()
        pytest.skip(f"{interface} opens here")
    assert main(["scan", "--bus", f"can:{interface}:0", "--json"]) == 1
    _, err = capsys.readouterr()
    assert "has no interface" not in err and "fix: install" in err and err.count("\n") == 1


BAD = ["can:nosuch:0", "can:udp_multicast:0", "can:udp_multicast:239.74.163.2?port=99999",
       "can:udp_multicast:239.74.163.2?port=x", "can:slcan:/dev/ttyS0?state=bogus",
       "sim:nosuch", "can:virtual", "bogus:x"]
COMMANDS = [
    ["scan", "--json", "--bus"],
    ["monitor", "--seconds", "0.2", "--bus"],
    ["gui", "--bus"],
    ["arbitrator", "--seconds", "0.2", "--bus"],
    ["sim", "devices", "transradial", "--seconds", "0.2", "--bus"],
    ["config", "read", "-o", "never.pdcfg", "--bus"],
    ["print", "--bus"],
    ["info", "--bus"],
    ["apply", "clear", "--bus"],
    ["config", "save", "--bus"],
    ["config", "diff", "empty.pdcfg", "--bus"],
    ["policy", "--bus"],
    ["history", "restore", "1", "--bus"],
]


@pytest.mark.parametrize("url", BAD)
def test_a_bad_bus_url_is_the_same_exit_2_line_from_every_command(capsys, url, tmp_path,
                                                                   monkeypatch):
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.storage import config_codec

    monkeypatch.chdir(tmp_path)
    (tmp_path / "empty.pdcfg").write_bytes(config_codec.dumps(ConfigCollection([])))
    lines = set()
    for command in COMMANDS:
        if url.startswith("sim:") and command[0] in ("arbitrator", "sim"):
            continue  # these take can: buses only and say so
        try:
            code = main([*command, url])
        except SystemExit as exit_:  # argparse: a command this build does not have
            code = exit_.code
        out, err = capsys.readouterr()
        if code == 2 and err.startswith("usage:"):
            continue  # argparse: this build's command has no --bus yet
        assert code == 2, (command, err)
        assert out == "" and err.count("\n") == 1, (command, err)
        if not url.startswith(("can:virtual", "bogus")):
            lines.add(err)
    assert len(lines) <= 1, lines
    assert not (tmp_path / "never.pdcfg").exists()


def test_check_bus_url_accepts_good_urls():
    for url in ["sim:transradial", "can:virtual:bus0", "can:udp_multicast:239.74.163.2?port=43200",
                "can:udp_multicast:ff15:7079:7468:6f6e:6465:6d6f:6d63:6173",
                "can:slcan:/dev/ttyACM0@1000000?tty_baudrate=115200", "serial:COM3"]:
        assert check_bus_url(url).url == url


def test_a_bitrate_other_than_1_mbit_is_warned_about(caplog):
    assert bitrate_warning(parse_bus_url("can:socketcan:can0@500000")).count("1000000") == 1
    assert bitrate_warning(parse_bus_url("can:socketcan:can0@1000000")) == ""
    assert bitrate_warning(parse_bus_url("can:socketcan:can0")) == ""
    assert bitrate_warning(parse_bus_url("can:virtual:x@500000")) == ""
    with caplog.at_level(logging.WARNING, logger="pdcp_studio.bus.session.urls"), \
            pytest.raises(Exception):  # noqa: B017 - no SocketCAN here or no can9
        open_spec(parse_bus_url("can:socketcan:can9@500000"))
    assert any("not PDCP's 1000000 bit/s" in r.getMessage() for r in caplog.records)


def test_python_can_s_own_log_lines_stay_off_stderr(capsys):
    with pytest.raises(DriverMissingError):
        open_can_bus("kvaser", "0", url="can:kvaser:0")
    assert "canlib" not in capsys.readouterr().err.lower()


def test_explain_keeps_the_url_and_channel_form():
    err = explain_open_error("can:slcan:/dev/nope", "slcan", "/dev/nope",
                             can.CanInitializationError("could not open port /dev/nope"))
    assert isinstance(err, AdapterMissingError) and "tty_baudrate" in str(err)
