"""Simulated devices, driven frame by frame from a bare python-can bus (no arbitrator)."""

from __future__ import annotations

import struct
import threading
import time

import can
import pytest

from pdcp_studio.bus.arbitrator.reading.requests import DeviceRefusedError, RequestEngine
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice, State
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.signals import decode_sample, encode_sample, synthetic_value
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Channel
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    BindResponse,
    ChannelData,
    Priority,
    Release,
    Reset,
    ResetResponse,
    ResponseCode,
    Suspend,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
)
from pdcp_studio.storage import system_file
from tests.bus.test_arbitrator_rig import SYSTEMS, load

D5 = DeviceKey(2, 2, 5)


class Bench:
    """One simulated device (appendix D's control unit) and a bare bus to talk to it."""

    def __init__(self, *, preferred: int = 9, data_rate_hz: float = 50.0) -> None:
        system = load("appendix-d")
        self.model = system.devices[D5]
        self.model.node_id = preferred
        self.channel = unique_virtual_channel("pdcp-bench")
        self.device = SimulatedDevice(self.model, data_rate_hz=data_rate_hz)
        self.host = DeviceHost(can.Bus(interface="virtual", channel=self.channel),
                               [self.device], plugged=False)
        self.bus = can.Bus(interface="virtual", channel=self.channel)
        self.frames: list[tuple[float, object]] = []
        self.engine = RequestEngine(self.send, response_timeout=0.1, retries=2)
        self._lock = threading.Lock()
        self.notifier = can.Notifier(self.bus, [self._on_frame], timeout=0.02)

    def _on_frame(self, msg: can.Message) -> None:
        try:
            m = decode(msg.arbitration_id, bytes(msg.data),
                       channel_node_ids=frozenset(range(40, 80)))
        except Exception:
            return
        with self._lock:
            self.frames.append((time.monotonic(), m))
        self.engine.feed(m)

    def send(self, message) -> None:
        aid, data = message.encode()
        self.bus.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))

    def got(self, kind: type, since: float = 0.0) -> list:
        with self._lock:
            return [m for t, m in self.frames if isinstance(m, kind) and t >= since]

    def wait(self, predicate, timeout: float = 2.0) -> bool:
        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() > deadline:
                return False
            time.sleep(0.005)
        return True

    def bind(self, node: int) -> None:
        self.host.plug(D5)
        assert self.wait(lambda: self.got(BindRequest))
        asked = self.got(BindRequest)[-1].node_id
        self.send(BindResponse(asked, node, 2, 2, 5))
        if asked != node:
            assert self.wait(lambda: any(r.node_id == node for r in self.got(BindRequest)))
            self.send(BindResponse(node, node, 2, 2, 5))
        assert self.wait(lambda: self.device.state is State.BOUND)

    def close(self) -> None:
        self.notifier.stop(timeout=1)
        self.bus.shutdown()
        self.host.close()


@pytest.fixture
def bench():
    b = Bench()
    yield b
    b.close()


def test_binds_with_its_preferred_id_then_the_suggested_one(bench):
    bench.host.plug(D5)
    assert bench.wait(lambda: bench.got(BindRequest))
    first = bench.got(BindRequest)[0]
    assert (first.node_id, first.vid, first.pid, first.serial) == (9, 2, 2, 5)
    assert first.priority is Priority.BINDING
    bench.send(BindResponse(9, 12, 2, 2, 5))  # 12 suggested
    assert bench.wait(lambda: any(r.node_id == 12 for r in bench.got(BindRequest)))
    assert bench.device.state is State.BINDING
    bench.send(BindResponse(12, 12, 2, 2, 5))  # request and answer agree: bound
    assert bench.wait(lambda: bench.device.state is State.BOUND)
    assert bench.device.node_id == 12
    assert bench.device.nv[P.DEVICE_NODE_ID, 0] == b"\x0c"
    # An answer for another device, or to another request, changes nothing.
    assert bench.wait(lambda: bench.got(Beacon))
    assert all(b.node_id == 12 for b in bench.got(Beacon))


def test_repeats_its_bind_request_every_bind_timeout_until_answered(bench):
    bench.host.plug(D5)
    time.sleep(0.33)  # bind timeout 60 ms
    asks = bench.got(BindRequest)
    assert 4 <= len(asks) <= 7
    assert {a.node_id for a in asks} == {9}


def test_beacons_at_its_beacon_interval(bench):
    bench.bind(12)
    start = time.monotonic()
    time.sleep(0.5)
    beacons = bench.got(Beacon, since=start)
    assert 8 <= len(beacons) <= 12  # every 50 ms
    bench.engine.set(12, P.DEVICE_BEACON_INTERVAL, 0, struct.pack("<H", 20))
    start = time.monotonic()
    time.sleep(0.4)
    assert 15 <= len(bench.got(Beacon, since=start)) <= 22


def test_update_data_channel_requests_until_answered(bench):
    bench.bind(12)
    assert bench.wait(lambda: len(bench.got(UpdateDataChannel)) >= 2)
    asked = {u.channel for u in bench.got(UpdateDataChannel)}
    assert asked == {1, 2}  # its two input channels
    for ch in (1, 2):
        bench.send(UpdateDataChannelResponse(12, ResponseCode.SUCCESS, ch))
    time.sleep(0.3)
    n = len(bench.got(UpdateDataChannel))
    time.sleep(0.3)
    assert len(bench.got(UpdateDataChannel)) == n  # answered: no more requests
    assert n <= 2 * 3  # and unanswered ones stop after their retries anyway


def test_get_set_and_bulk_both_ways(bench):
    bench.bind(12)
    e = bench.engine
    assert e.get(12, P.DEVICE_VID_PID, 0) == struct.pack("<HH", 2, 2)
    assert e.get(12, P.DEVICE_CHANNEL_COUNT, 0) == b"\x05"
    assert e.get(12, P.CH_TRANSFER_TYPE, 3) == b"\x02"
    assert e.get(12, P.CH_TYPE_PROFILE, 1) == struct.pack("<HH", 0x7200, 0x2200)
    assert e.get(12, P.DEVICE_DESCRIPTOR, 0) == b"Control unit board\0"  # bulk get
    text = b"a descriptor long enough to need several bulk packets\0"
    e.set(12, P.CH_DESCRIPTOR, 4, text)  # bulk set
    assert e.get(12, P.CH_DESCRIPTOR, 4) == text
    e.set(12, P.CH_REQUIRED_INPUTS, 4, b"\x60")  # inline set of a bit string
    assert bench.device.nv[P.CH_REQUIRED_INPUTS, 4] == b"\x60"
    with pytest.raises(DeviceRefusedError):
        e.set(12, P.DEVICE_VID_PID, 0, b"\1\0\1\0")  # read-only
    with pytest.raises(DeviceRefusedError):
        e.set(12, P.CH_TRANSFER_TYPE, 1, b"\x02")  # read-only
    with pytest.raises(DeviceRefusedError):
        e.get(12, P.CH_TYPE_PROFILE, 9)  # no such channel
    with pytest.raises(DeviceRefusedError):
        e.set(12, P.IN_SOURCE_NODE_IDS, 1, b"\x01")  # wrong layout (2 bytes expected)


def test_sources_are_non_volatile_node_ids_and_flags_are_not(bench):
    bench.bind(12)
    e = bench.engine
    e.set(12, P.IN_SOURCE_VID_PID, 1, struct.pack("<HH", 2, 2))
    e.set(12, P.IN_SOURCE_SN_INDEX, 1, struct.pack("<HB", 4, 1))
    e.set(12, P.IN_SOURCE_NODE_IDS, 1, b"\x03\x04")
    e.set(12, P.CH_DATA_ENABLED, 1, b"\x01")
    e.set(12, P.OUT_NODE_ID, 3, b"\x30")
    bench.host.unplug(D5)
    bench.host.plug(D5)  # re-plugged
    nv = bench.device.nv
    assert nv[P.IN_SOURCE_SN_INDEX, 1] == struct.pack("<HB", 4, 1)  # remembered
    assert nv[P.IN_SOURCE_VID_PID, 1] == struct.pack("<HH", 2, 2)
    assert nv[P.IN_SOURCE_NODE_IDS, 1] == b"\0\0"  # bus-session values start over
    assert nv[P.CH_DATA_ENABLED, 1] == b"\0"
    assert nv[P.OUT_NODE_ID, 3] == b"\0"
    assert bench.device.state is State.BINDING
    assert bench.device.preferred_node_id == 12  # it asks for its last node ID again
    assert bench.wait(lambda: bench.got(BindRequest)[-1].node_id == 12)


def test_streams_enabled_outputs_at_its_rate_keeps_inputs_and_obeys_suspend(bench):
    bench.bind(12)
    e = bench.engine
    e.set(12, P.OUT_NODE_ID, 4, b"\x41")
    time.sleep(0.1)
    assert not [d for d in bench.got(ChannelData) if d.node_id == 0x41]  # not enabled yet
    e.set(12, P.CH_DATA_ENABLED, 4, b"\x01")
    start = time.monotonic()
    time.sleep(0.4)
    data = [d for d in bench.got(ChannelData, since=start) if d.node_id == 0x41]
    assert 14 <= len(data) <= 24  # 50 Hz
    assert all(len(d.data) == 1 for d in data)  # type 0x5000: unsigned 8 bit
    # An enabled input keeps what its source sends.
    e.set(12, P.IN_SOURCE_NODE_IDS, 2, b"\x03\x50")
    e.set(12, P.CH_DATA_ENABLED, 2, b"\x01")
    bench.send(ChannelData(0x50, b"\x7f"))
    assert bench.wait(lambda: bench.device.received.get(2, (b"",))[0] == b"\x7f")
    assert 1 not in bench.device.received  # not enabled: nothing kept
    # Output 3 requires input 2 and forwards what it receives.
    e.set(12, P.OUT_NODE_ID, 3, b"\x42")
    e.set(12, P.CH_DATA_ENABLED, 3, b"\x01")
    assert bench.wait(lambda: any(d.node_id == 0x42 for d in bench.got(ChannelData)))
    # Suspend: data stops (beacons go on); release: it flows again.
    bench.send(Suspend(12, 0))
    time.sleep(0.1)
    start = time.monotonic()
    time.sleep(0.2)
    assert not bench.got(ChannelData, since=start)
    assert bench.got(Beacon, since=start)
    bench.send(Release(12))
    start = time.monotonic()
    assert bench.wait(lambda: bench.got(ChannelData, since=start))


def test_reset_answers_then_binds_again(bench):
    bench.bind(12)
    before = len(bench.got(BindRequest))
    bench.send(Reset(12))
    assert bench.wait(lambda: bench.got(ResetResponse))
    assert bench.got(ResetResponse)[0].code is ResponseCode.SUCCESS
    assert bench.wait(lambda: len(bench.got(BindRequest)) > before)
    assert bench.got(BindRequest)[-1].node_id == 12
    assert bench.device.state is State.BINDING


@pytest.mark.parametrize("path", sorted(SYSTEMS.glob("*.json")), ids=lambda p: p.stem)
def test_every_shipped_system_builds_simulated_devices(path):
    system = system_file.load_path(path)
    for device in system.devices.values():
        sim = SimulatedDevice(device)
        assert sim.nv[P.DEVICE_CHANNEL_COUNT, 0] == bytes([max(device.channels, default=0)])
        for ch in device.channels.values():
            assert sim.nv[P.CH_TRANSFER_TYPE, ch.index] == bytes([ch.direction.transfer_type])
            if ch.is_input:
                src = ch.source
                assert sim.nv[P.IN_SOURCE_SN_INDEX, ch.index] == struct.pack(
                    "<HB", src.serial, src.index)


@pytest.mark.parametrize("kind", [0x5000, 0x4000, 0xD000, 0xE000, 0x7000, 0x3000, 0x1000])
def test_samples_round_trip_through_the_channel_type(kind):
    signed = kind & 0x3000 == 0
    for x in ([-1.0, -0.5, 0.0, 0.25, 1.0] if signed else [0.0, 0.25, 0.5, 1.0]):
        data = encode_sample(kind, x)
        assert len(data) == (1 if kind >> 14 <= 1 else 2)
        tolerance = 0.2 if kind >> 14 == 0 else 0.01  # 4 bits are coarse
        if kind & 0x3000 == 0x3000:  # boolean
            assert decode_sample(kind, data) == (1.0 if x >= 0.5 else 0.0)
        else:
            assert abs(decode_sample(kind, data) - x) <= tolerance
    assert decode_sample(kind, b"") == 0.0


def test_synthetic_signals_stay_in_range():
    for profile in (0x4220, 0x2110, 0x2200, 0x2120, 0x1100):
        for kind in (0x5000, 0x4000, 0x7000):
            ch = Channel(1, Direction.OUTPUT, type=kind, profile=profile)
            for t in range(200):
                v = synthetic_value(ch, t * 0.05, 0.3)
                assert (-1.0 if kind & 0x3000 == 0 else 0.0) <= v <= 1.0
