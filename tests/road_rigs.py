"""Rigs for the change-road tests: a simulated thesis prosthesis reached over the host link,
and a recorder of every frame on a simulated bus.

``served(name, memory)`` runs the built-in prosthesis's devices and a real arbitrator (with its
profile layer and memory) on one python-can virtual channel and serves the host link on a new
pseudo-terminal; the URL ``serial:/dev/pts/N`` reaches it exactly as ``/dev/ttyUSB0`` would.
``FrameRecorder`` listens on a virtual channel like any other node on the bus.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import can

from pdcp_studio.protocol import Message, decode


@contextlib.contextmanager
def served(name: str, memory: Path, **arbitrator_options: Any) -> Iterator[tuple[Any, Any, str]]:
    """(arbitrator, device host, serial URL) of a simulated prosthesis behind a host link."""
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.hostlink.server import HostLinkServer
    from pdcp_studio.bus.session.urls import unique_virtual_channel
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import resolve_prosthesis

    system = resolve_prosthesis(name).load()
    channel = unique_virtual_channel(f"road-{name}")
    arb_bus = can.Bus(interface="virtual", channel=channel)
    dev_bus = can.Bus(interface="virtual", channel=channel)
    host = DeviceHost(dev_bus, [SimulatedDevice(d) for d in system.devices.values()],
                      plugged=False)
    arbitrator_options.setdefault("startup_quiet_s", 0.2)
    arbitrator = Arbitrator(arb_bus, memory=memory, **arbitrator_options)
    server = None
    try:
        for dev in system.devices.values():
            if dev.present:
                host.plug(dev.key)
        assert arbitrator.wait_for(lambda: len(arbitrator.devices_present()) == sum(
            d.present for d in system.devices.values()), 10.0)
        assert arbitrator.wait_settled(10.0)
        server = HostLinkServer(arbitrator, "pty")
        yield arbitrator, host, f"serial:{server.slave_path}"
    finally:
        if server is not None:
            server.close()
        arbitrator.close()
        host.close()
        for bus in (arb_bus, dev_bus):
            bus.shutdown()


class FrameRecorder:
    """Every frame on a virtual channel, decoded where it decodes (thread-safe)."""

    def __init__(self, channel: str) -> None:
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.frames: list[can.Message] = []
        self._lock = threading.Lock()
        self._notifier = can.Notifier(self.bus, [self._on])

    def _on(self, msg: can.Message) -> None:
        with self._lock:
            self.frames.append(msg)

    def caught_up(self, quiet_s: float = 0.03, timeout: float = 2.0) -> int:
        """Wait until no frame came for ``quiet_s`` (the frames sent so far are all here, not
        still in the recorder's queue); the number recorded."""
        deadline = time.monotonic() + timeout
        with self._lock:
            count = len(self.frames)
        while time.monotonic() < deadline:
            time.sleep(quiet_s)
            with self._lock:
                now = len(self.frames)
            if now == count:
                break
            count = now
        return count

    def messages(self) -> list[Message]:
        with self._lock:
            frames = list(self.frames)
        out = []
        for f in frames:
            try:
                out.append(decode(f.arbitration_id, bytes(f.data)))
            except Exception:  # channel data and other undecodable frames
                continue
        return out

    def close(self) -> None:
        self._notifier.stop()
        self.bus.shutdown()


def fitted_twice(tmp_path: Path, monkeypatch: Any, bus: str = "sim:transradial"
                 ) -> tuple[Path, Path]:
    """(archive, memory file) of a simulated prosthesis after two changes through the change
    road (``apply clear``), each recorded in a fresh SQLite archive and anchored; the second
    on the prosthesis re-opened, which starts up and autoconfigures it again."""
    from pdcp_studio.cli.main import main

    archive = tmp_path / "history.sqlite"
    memory = tmp_path / "m.img"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(archive))
    monkeypatch.delenv("PDCP_STUDIO_ARCHIVE", raising=False)
    for _ in range(2):
        assert main(["apply", "clear", "--bus", bus, "--memory", str(memory), "--yes"]) == 0
    return archive, memory
