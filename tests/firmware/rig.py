"""The reference firmware on QEMU, simulated devices and a host-link session, for the tests.

``Firmware`` starts ``firmware/run-qemu.sh --bus URL --memory FILE`` (QEMU's lm3s6965evb, its
CAN side bridged to a udp_multicast bus) and reads its ``host link on /dev/pts/N`` line;
``Devices`` hosts a prosthesis's simulated devices in this process on the same bus, so a test
can unplug and plug them; ``run_script`` carries out a simulator script's steps (settle,
save, unplug, plug, await, reset) against the firmware, as ``sim replay`` does against PDCP
Studio's own arbitrator.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
RUN_QEMU = ROOT / "firmware" / "run-qemu.sh"
TOOLS = ("qemu-system-arm", "arm-none-eabi-gcc", "make")


def missing_tools() -> str | None:
    """Why the firmware cannot run here (None when it can)."""
    gone = [t for t in TOOLS if shutil.which(t) is None]
    if gone:
        return (f"needs {', '.join(gone)} (Debian: apt-get install gcc-arm-none-eabi "
                "libnewlib-arm-none-eabi qemu-system-arm make)")
    if not hasattr(os, "openpty"):
        return "needs POSIX pseudo-terminals"
    return None


class Firmware:
    """The firmware on QEMU; ``serial_url`` reaches its host link."""

    starts = 0

    def __init__(self, bus_url: str, memory: Path) -> None:
        Firmware.starts += 1
        #: QEMU's output and the firmware's log lines (kept in the test's folder)
        self.log = memory.with_name(f"firmware-{Firmware.starts}.log")
        env = dict(os.environ, PDCP_STUDIO=f"{sys.executable} -m pdcp_studio",
                   PDCP_FW_LOG=str(self.log),
                   PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
        self.proc = subprocess.Popen([str(RUN_QEMU), "--bus", bus_url, "--memory", str(memory)],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                     env=env, cwd=ROOT)
        assert self.proc.stdout is not None
        line = self.proc.stdout.readline()
        if not line.startswith("host link on /dev/"):
            self.stop()
            raise AssertionError(f"run-qemu.sh did not start: {line!r} {self.stderr}")
        self.serial_url = "serial:" + line.split(" on ", 1)[1].strip()
        self.stderr = ""

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
        try:
            _, self.stderr = self.proc.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            _, self.stderr = self.proc.communicate()


class Devices:
    """A prosthesis's simulated devices on ``bus_url``, plugged as its system says."""

    def __init__(self, name: str, bus_url: str) -> None:
        from pdcp_studio.bus.session.urls import check_bus_url, open_spec
        from pdcp_studio.bus.sim.device import SimulatedDevice
        from pdcp_studio.bus.sim.device_host import DeviceHost
        from pdcp_studio.bus.sim.rigs import load_prosthesis

        self.system = load_prosthesis(name)
        devices = [SimulatedDevice(d) for d in self.system.devices.values()]
        self.host = DeviceHost(open_spec(check_bus_url(bus_url)), devices,
                               name=f"{name} devices", plugged=False)
        for key, device in self.system.devices.items():
            if device.present:
                self.host.plug(key)

    def plugged(self) -> list[Any]:
        return [k for k in self.host.keys() if self.host.is_plugged(k)]

    def close(self) -> None:
        self.host.close()


class DeviceProcess:
    """A prosthesis's simulated devices in a process of their own (``sim devices``): their
    beacons do not wait for this process's GIL while it runs a CLI command or the tester."""

    def __init__(self, name: str, bus_url: str, seconds: int = 300) -> None:
        from pdcp_studio.bus.sim.rigs import load_prosthesis

        self.keys = [k for k, d in load_prosthesis(name).devices.items() if d.present]
        env = dict(os.environ,
                   PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
        self.proc = subprocess.Popen([sys.executable, "-m", "pdcp_studio", "sim", "devices", name,
                                      "--bus", bus_url, "--seconds", str(seconds)],
                                     stderr=subprocess.PIPE, text=True, env=env)
        assert self.proc.stderr is not None
        line = self.proc.stderr.readline()
        if "simulating" not in line:
            self.close()
            raise AssertionError(f"sim devices did not start: {line!r}")

    def plugged(self) -> list[Any]:
        return list(self.keys)

    def close(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(15)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        if self.proc.stderr is not None:
            self.proc.stderr.close()


#: How long the tests' sessions wait for the firmware's reply on QEMU.
REPLY_TIMEOUT_S = 20.0


def open_session(serial_url: str, attempts: int = 3) -> Any:
    """A host-link session; greeted again when the first HELLO goes unacknowledged: QEMU's
    pty backend notices a newly opened pseudo-terminal only at its next 1 s poll, and on a
    loaded machine the PC's 8 sends over 2 s can all fall before it."""
    from pdcp_studio.bus.hostlink.client import open_hostlink_session
    from pdcp_studio.bus.session.urls import check_bus_url
    from pdcp_studio.errors import TransportError

    for attempt in range(attempts):
        try:
            # (QEMU, its bridge and the test's devices share the machine with the rest of the
            # suite: a reply may wait longer than the PC's default 6 s for the emulator)
            return open_hostlink_session(check_bus_url(serial_url), monitor=False,
                                         reply_timeout=REPLY_TIMEOUT_S)
        except TransportError:
            if attempt == attempts - 1:
                raise
            time.sleep(0.5)
    raise AssertionError("unreachable")


class Awake:
    """Hold the host link's pseudo-terminal open around a command that opens it itself.

    QEMU's pty backend stops serving a pseudo-terminal when its last user closes it and looks
    again only once a second; a PC that opens it meanwhile waits up to a second for its first
    reply — longer than the conformance suite's 1 s. Opened (and drained) here first, the pty
    stays served while the command opens and uses it; nothing is read here after that."""

    def __init__(self, serial_url: str) -> None:
        self.path = serial_url.split(":", 1)[1]

    def __enter__(self) -> Awake:
        self.fd = os.open(self.path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        end = time.monotonic() + 1.3
        while time.monotonic() < end:  # QEMU notices the open within a second
            try:
                os.read(self.fd, 4096)  # (what the firmware sent to nobody)
            except BlockingIOError:
                time.sleep(0.05)
        return self

    def __exit__(self, *exc: object) -> None:
        os.close(self.fd)


def wait_for(predicate: Any, timeout: float, what: str) -> None:
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.2)


def settle(session: Any, timeout: float = 60.0,
           devices: Devices | DeviceProcess | None = None) -> None:
    """Start-up done and nothing in progress (twice in a row, a second apart: a device that
    was just plugged needs a moment to bind), with every plugged device of ``devices`` on
    the bus."""
    def done() -> bool:
        if not session.wait_settled(1.0):
            return False
        if devices is None:
            return True
        system = session.system()
        return all((d := system.device(k)) is not None and d.present
                   for k in devices.plugged())

    wait_for(done, timeout, "the firmware to settle")
    time.sleep(1.0)
    wait_for(done, timeout, "the firmware to settle")


def present(session: Any, key: Any) -> bool:
    device = session.system().device(key)
    return device is not None and device.present


class Run:
    """A script's run against the firmware: the firmware (restarted by ``reset``), the devices
    and a session on its host link."""

    def __init__(self, name: str, bus_url: str, memory: Path) -> None:
        self.bus_url = bus_url
        self.memory = memory
        self.devices = Devices(name, bus_url)
        try:
            self.firmware = Firmware(bus_url, memory)
        except BaseException:
            self.devices.close()
            raise
        try:
            self.session = open_session(self.firmware.serial_url)
        except BaseException:
            self.firmware.stop()
            self.devices.close()
            raise

    def restart(self, keep_memory: bool) -> None:
        """A power cycle of the arbitrator (``keep_memory`` False: a new, empty memory)."""
        self.session.close()
        self.firmware.stop()
        if not keep_memory and self.memory.exists():
            self.memory.unlink()
        self.firmware = Firmware(self.bus_url, self.memory)
        self.session = open_session(self.firmware.serial_url)

    def close(self) -> None:
        try:
            if getattr(self, "session", None) is not None:
                self.session.close()
        finally:
            try:
                self.firmware.stop()
            finally:
                self.devices.close()

    def step(self, step: Any) -> None:
        from pdcp_studio.engine import configuration_from_system
        from pdcp_studio.model.configuration import ConfigCollection
        from pdcp_studio.storage import config_codec

        op = step.op
        if op == "settle":
            settle(self.session, devices=self.devices)
        elif op == "save":
            collection = ConfigCollection([configuration_from_system(self.session.system())])
            self.session.write_configuration_bytes(config_codec.dumps(collection))
        elif op == "unplug":
            self.devices.host.unplug(step.key)
        elif op == "plug":
            self.devices.host.plug(step.key)
        elif op == "await_left":
            wait_for(lambda: not present(self.session, step.key), 15, f"{step.key} to leave")
        elif op == "await_joined":
            wait_for(lambda: present(self.session, step.key), 15, f"{step.key} to join")
        elif op == "reset":
            self.restart(step.keep_memory)
        else:
            raise AssertionError(f"script step {op} is not supported here")

    def links(self) -> list[Any]:
        return sorted(self.session.system().links)
