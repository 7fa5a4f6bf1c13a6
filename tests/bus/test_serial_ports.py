"""Contracts §2: a serial port that is missing is exit 1 "with the fix in one line". The
failures here are pyserial's own (real paths that do not exist, a file that is not a serial
port, a TCP port nobody serves, a real pseudo-terminal that has gone); the ports a fix names
are given, so each wording is checked whatever this computer has."""

from __future__ import annotations

import errno
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest
import serial

from pdcp_studio.bus.hostlink.port import PtyPort, open_port
from pdcp_studio.bus.session.serial_ports import (
    PORTS_SHOWN,
    open_failure,
    seen_ports,
    unknown_protocol,
    url_protocols,
)
from pdcp_studio.bus.session.urls import BusUrlError, check_bus_url
from pdcp_studio.errors import TransportError

ROOT = Path(__file__).resolve().parents[2]


def _pyserial_error(name: str) -> BaseException:
    try:
        serial.serial_for_url(name, timeout=0.05).close()
    except (serial.SerialException, ValueError, OSError) as err:
        return err
    raise AssertionError(f"{name} opened")


def test_a_missing_device_names_the_ports_this_computer_has():
    err = _pyserial_error("/dev/ttyNONE")
    line = open_failure("serial:/dev/ttyNONE", "/dev/ttyNONE", err, ["/dev/ttyUSB1"])
    assert line == ("serial:/dev/ttyNONE: serial port '/dev/ttyNONE' not found; fix: plug the "
                    "serial cable in and name one of this computer's ports: "
                    "serial:/dev/ttyUSB1")


def test_a_port_named_without_a_url_is_shown_the_same_way():
    err = _pyserial_error("/dev/ttyNONE")  # arbitrator --host-serial PORT
    line = open_failure("host link", "/dev/ttyNONE", err, ["/dev/ttyUSB1"])
    assert line.endswith("name one of this computer's ports: /dev/ttyUSB1")
    assert open_failure("host link", "/dev/ttyNONE", err, [], "linux").endswith(
        "(e.g. /dev/ttyUSB0)")


@pytest.mark.parametrize(("platform", "example"), [
    ("linux", "serial:/dev/ttyUSB0"), ("win32", "serial:COM3"),
    ("darwin", "serial:/dev/cu.usbserial-1410")])
def test_with_no_port_plugged_in_the_fix_says_so_and_how_to_name_one(platform, example):
    err = _pyserial_error("COM3")  # on this system: a file name that is not there
    line = open_failure("serial:COM3", "COM3", err, [], platform)
    assert "not found; fix: no serial port is plugged in" in line
    assert line.endswith(f"(e.g. {example})") and "\n" not in line


def test_many_ports_are_named_a_few_at_a_time():
    ports = [f"/dev/ttyUSB{i}" for i in range(PORTS_SHOWN + 3)]
    line = open_failure("serial:/dev/x", "/dev/x", _pyserial_error("/dev/x-none"), ports)
    assert line.count("serial:/dev/ttyUSB") == PORTS_SHOWN and line.endswith("and 3 more")


def test_a_file_that_is_not_a_serial_port():
    line = open_failure("serial:/dev/null", "/dev/null", _pyserial_error("/dev/null"), [])
    assert "(Inappropriate ioctl for device)" in line
    assert "fix: /dev/null is not a serial port; no serial port is plugged in" in line


def test_a_network_port_nobody_serves():
    with socket.socket() as sock:  # a port that was free a moment ago: refused
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    name = f"socket://127.0.0.1:{port}"
    line = open_failure(f"serial:{name}", name, _pyserial_error(name), ["/dev/ttyS0"])
    assert "(Connection refused)" in line
    assert line.endswith(f"fix: check that the arbitrator serves its host link at 127.0.0.1:"
                         f"{port} and that this computer can reach it")


@pytest.mark.parametrize(("code", "fix"), [
    (errno.EACCES, "fix: add your user to the group that owns the port (dialout"),
    (errno.EBUSY, "fix: close the other program that has the port open"),
])
def test_permission_and_busy_as_pyserial_raises_them(code, fix):
    # pyserial's own form (serialposix: SerialException(errno, "could not open port …")):
    # a root test run cannot be refused a file, and a busy port needs a real adapter.
    err = serial.SerialException(code, f"could not open port /dev/ttyUSB0: "
                                       f"[Errno {code}] {os.strerror(code)}: '/dev/ttyUSB0'")
    line = open_failure("serial:/dev/ttyUSB0", "/dev/ttyUSB0", err, ["/dev/ttyUSB0"])
    assert f"({os.strerror(code)}); {fix}" in line


def test_windows_wording_of_a_missing_port_is_read_too():
    err = serial.SerialException("could not open port 'COM7': FileNotFoundError(2, 'The "
                                 "system cannot find the file specified.', None, 2)")
    line = open_failure("serial:COM7", "COM7", err, ["COM1"], "win32")
    assert line.endswith("serial port 'COM7' not found; fix: plug the serial cable in "
                         "and name one of this computer's ports: serial:COM1")


def test_a_pseudo_terminal_opens_and_once_gone_says_not_found():
    pty = PtyPort()
    path = pty.slave_path
    port = open_port(path, where=f"serial:{path}")  # a real pseudo-terminal: it opens
    port.close()
    pty.close()
    if os.path.exists(path):
        pytest.skip("this system keeps a closed pseudo-terminal's name")  # not on Linux
    with pytest.raises(TransportError) as caught:
        open_port(path, where=f"serial:{path}")
    assert str(caught.value).startswith(f"serial:{path}: serial port {path!r} not found; "
                                        "fix: ")


def test_an_unknown_pyserial_url_is_bad_input_before_opening():
    assert {"socket", "rfc2217", "loop"} <= set(url_protocols())
    assert unknown_protocol("/dev/ttyUSB0") is None
    assert unknown_protocol("socket://127.0.0.1:7000") is None
    with pytest.raises(BusUrlError, match="pyserial has no 'foo' URL"):
        check_bus_url("serial:foo://x")


@pytest.mark.parametrize("argv", [
    ["scan", "--bus", "serial:/dev/ttyNONE"],
    ["scan", "--bus", "serial:COM3"],
    ["hostlink-test", "--bus", "serial:/dev/nonexistent"],
    ["info", "--bus", "serial:/dev/ttyNONE@9600"],
])
def test_the_cli_exits_1_with_the_fix_in_one_line(argv):
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", *argv], capture_output=True,
                          text=True, timeout=60, cwd=ROOT)
    assert done.returncode == 1, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "not found; fix: " in lines[0], done.stderr
    ports = seen_ports()
    if ports:
        assert f"serial:{ports[0]}" in lines[0]
    else:
        assert "no serial port is plugged in" in lines[0]
    assert done.stdout == ""


def test_the_cli_exits_2_for_a_url_pyserial_does_not_have():
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "hostlink-test", "--bus",
                           "serial:foo://x"], capture_output=True, text=True, timeout=60,
                          cwd=ROOT)
    assert done.returncode == 2 and "pyserial has no 'foo' URL" in done.stderr


def test_arbitrator_host_serial_on_a_missing_port_exits_1_with_the_fix(tmp_path):
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus",
                           f"can:virtual:clifix-{os.getpid()}", "--memory",
                           str(tmp_path / "memory.json"), "--host-serial", "/dev/ttyNONE",
                           "--seconds", "1"], capture_output=True, text=True, timeout=60,
                          cwd=ROOT)
    assert done.returncode == 1, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "serial port '/dev/ttyNONE' not found; fix: " in lines[0]
    assert "serial:/dev" not in lines[0]  # --host-serial takes the port without serial:
