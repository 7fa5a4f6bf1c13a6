"""A test rig: simulated devices and an arbitrator on one python-can virtual channel.

Imported by the other arbitrator / fault tests; its own tests check the rig's lossy bus.
Devices beacon every 50 ms here (gone after ~175 ms) and retry binding every 60 ms, so a
whole rig settles in a few hundred milliseconds.
"""

from __future__ import annotations

import random
import threading
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import can

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.storage import system_file

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
BEACON_MS = 50
BIND_TIMEOUT_MS = 60
STARTUP_QUIET_S = 0.15
SETTLE_S = 5.0


def load(name: str, *, beacon_ms: int = BEACON_MS, bind_ms: int = BIND_TIMEOUT_MS) -> System:
    """A shipped system with short beacon and bind intervals."""
    system = system_file.load_path(SYSTEMS / f"{name}.json")
    for device in system.devices.values():
        device.beacon_interval = beacon_ms
        device.bind_timeout = bind_ms
    return system


def ref(serial: int, index: int, vid: int = 2, pid: int = 2) -> ChannelRef:
    return ChannelRef(vid, pid, serial, index)


def key(serial: int, vid: int = 2, pid: int = 2) -> DeviceKey:
    return DeviceKey(vid, pid, serial)


def link(out: tuple[int, int], inp: tuple[int, int]) -> Link:
    return Link(ref(*out), ref(*inp))


class LossyBus(can.BusABC):
    """Wraps a bus and drops a seeded random fraction of the frames sent and received.

    ``spare(msg)`` true keeps a frame whatever the dice say (the fault tests spare beacons:
    at 5 % loss three in a row go missing once in ~8,000, a correct but unwanted departure).
    """

    def __init__(self, inner: can.BusABC, drop: float, seed: int = 1,
                 spare: Callable[[can.Message], bool] | None = None) -> None:
        self.inner = inner
        self.drop = drop
        self.spare = spare
        self.rng = random.Random(seed)
        self.rng_lock = threading.Lock()
        self.dropped = 0
        self.passed = 0
        super().__init__(channel=getattr(inner, "channel_info", "lossy"))

    def _lose(self) -> bool:
        with self.rng_lock:
            lost = self.rng.random() < self.drop
            if lost:
                self.dropped += 1
            else:
                self.passed += 1
            return lost

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        if (self.spare is not None and self.spare(msg)) or not self._lose():
            self.inner.send(msg, timeout)

    def _recv_internal(self, timeout: float | None) -> tuple[can.Message | None, bool]:
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            msg = self.inner.recv(left)
            if msg is None or (self.spare is not None and self.spare(msg)) or not self._lose():
                return msg, False
            if deadline is not None and time.monotonic() >= deadline:
                return None, False

    def shutdown(self) -> None:
        self.inner.shutdown()
        super().shutdown()


class Rig:
    """Devices (one DeviceHost) plus an arbitrator, on a fresh virtual channel."""

    def __init__(self, system: System | str, *, arbitrator: bool = True,
                 plug: Iterable[DeviceKey] | None = None, data_rate_hz: float = 20.0,
                 packet_gap_s: float = 0.0, lossy: float = 0.0,
                 spare: Callable[[can.Message], bool] | None = None,
                 **arb_options: Any) -> None:
        self.system = load(system) if isinstance(system, str) else system
        self.channel = unique_virtual_channel("pdcp-arb-test")
        self.events: list[Any] = []
        self.values = 0
        self._lock = threading.Lock()
        self.arb: Arbitrator | None = None
        self.lossy: LossyBus | None = None
        self.host: DeviceHost | None = None
        try:
            if arbitrator:
                self.start_arbitrator(lossy=lossy, spare=spare, **arb_options)
            devices = [SimulatedDevice(d, data_rate_hz=data_rate_hz, packet_gap_s=packet_gap_s)
                       for d in self.system.devices.values()]
            self.host = DeviceHost(self.bus(), devices, plugged=False, name="test devices")
            keys = plug if plug is not None else [d.key for d in self.system.devices.values()
                                                  if d.present]
            self.plugged = len(list(keys))
            for k in keys:
                self.host.plug(k)
        except BaseException:
            self.close()
            raise

    def bus(self) -> can.BusABC:
        return can.Bus(interface="virtual", channel=self.channel)

    def start_arbitrator(self, *, lossy: float = 0.0, seed: int = 7,
                         spare: Callable[[can.Message], bool] | None = None,
                         **options: Any) -> Arbitrator:
        options.setdefault("startup_quiet_s", STARTUP_QUIET_S)
        bus = self.bus()
        if lossy:
            bus = self.lossy = LossyBus(bus, lossy, seed, spare)
        self.arb = Arbitrator(bus, **options)
        self.arb.subscribe(self._on_event)
        return self.arb

    def _on_event(self, event: Any) -> None:
        with self._lock:
            if isinstance(event, ev.ChannelValue):
                self.values += 1
            else:
                self.events.append(event)

    def of(self, kind: type) -> list[Any]:
        with self._lock:
            return [e for e in self.events if isinstance(e, kind)]

    def wait(self, predicate: Callable[[], bool], timeout: float = 3.0) -> bool:
        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() >= deadline:
                return False
            time.sleep(0.005)
        return True

    def settle(self, timeout: float = SETTLE_S, devices: int | None = None) -> Rig:
        """Wait until ``devices`` (default: all plugged at the start) have joined and the
        arbitrator has settled."""
        assert self.arb is not None
        want = self.plugged if devices is None else devices
        assert self.wait(lambda: len(self.arb.devices_present()) >= want, timeout), \
            f"only {self.arb.devices_present()} joined"
        assert self.arb.wait_settled(timeout), "the arbitrator did not settle"
        return self

    def device(self, k: DeviceKey) -> SimulatedDevice:
        assert self.host is not None
        return self.host.device(k)

    def nv(self, k: DeviceKey, param: int, channel: int = 0) -> bytes:
        """A parameter as the simulated device holds it (read on the host thread)."""
        assert self.host is not None
        return self.host.call(lambda: self.device(k).nv[param, channel])

    def close(self) -> None:
        if self.arb is not None:
            self.arb.close()
        if self.host is not None:
            self.host.close()

    def __enter__(self) -> Rig:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def test_lossy_bus_drops_the_seeded_fraction_both_ways():
    channel = unique_virtual_channel("pdcp-lossy")
    peer = can.Bus(interface="virtual", channel=channel)
    lossy = LossyBus(can.Bus(interface="virtual", channel=channel), 0.05, seed=3)
    try:
        for n in range(2000):
            peer.send(can.Message(arbitration_id=0x100, data=n.to_bytes(2, "little"),
                                  is_extended_id=False))
        got = 0
        while lossy.recv(0.05) is not None:
            got += 1
        assert 1850 < got < 1950  # ~5 % of 2000 lost
        assert lossy.dropped == 2000 - got
        for _ in range(1000):
            lossy.send(can.Message(arbitration_id=0x101, data=b"x", is_extended_id=False))
        heard = 0
        while peer.recv(0.05) is not None:
            heard += 1
        assert 920 < heard < 985
    finally:
        peer.shutdown()
        lossy.shutdown()


def test_same_seed_drops_the_same_frames():
    def pattern(seed: int) -> list[bool]:
        bus = LossyBus(can.Bus(interface="virtual", channel=unique_virtual_channel()), 0.05, seed)
        try:
            return [bus._lose() for _ in range(500)]
        finally:
            bus.shutdown()

    assert pattern(11) == pattern(11)
    assert pattern(11) != pattern(12)
