"""Faults (issue 4): bad frames, unplugging mid-transfer, twins, an empty node-ID pool,
a lossy bus and a killed arbitrator. Each is reported and survived."""

from __future__ import annotations

import random
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.bus.arbitrator.reading.requests import TransferAbortedError
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.errors import NodeIdExhaustedError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.protocol import FunctionCode, make_id
from tests.bus.test_arbitrator_rig import Rig, key, link, load

APPENDIX_D = [link((4, 1), (5, 2)), link((5, 3), (6, 1)), link((5, 5), (6, 2))]


def _kinds(rig: Rig, kind: str) -> list[ev.BusError]:
    return [e for e in rig.of(ev.BusError) if e.kind == kind]


def test_undecodable_frames_are_counted_and_shown_never_fatal():
    with Rig("appendix-d") as rig:
        rig.settle()
        node = rig.arb.node_id_of(key(5))
        raw = rig.bus()

        def frame(aid: int, data: bytes = b"", **kw) -> can.Message:
            return can.Message(arbitration_id=aid, data=data, is_extended_id=False, **kw)

        garbage = [
            frame(make_id(1, 0, node), b"\x55\x01"),  # a reserved function code
            frame(make_id(1, 0, node), b"\x83\x01"),  # a response too short for its code
            frame(make_id(1, 0, node)),  # no function code at all
            frame(make_id(3, 0, 9), b"\x01\x02"),  # a bind request of 2 bytes
            can.Message(arbitration_id=0x1ABCDE, data=b"\x01", is_extended_id=True),
            frame(make_id(1, 0, node), is_remote_frame=True),
        ]
        foreign = [frame(make_id(1, 0, 200), b"\x55"), frame(make_id(1, 0, 200), b"\x56")]
        try:
            for msg in garbage + foreign:
                raw.send(msg)
            raw.send(can.Message(is_error_frame=True, is_extended_id=False))
        finally:
            raw.shutdown()
        total = len(garbage) + len(foreign)
        assert rig.wait(lambda: rig.arb.bad_frames == total, 2)
        assert rig.wait(lambda: rig.arb.error_frames == 1, 2)
        shown = _kinds(rig, "bad_frame")
        # Every bad frame from a bound device is shown; a node that is not bound here is
        # shown once (a device of an earlier arbitrator may stream data we cannot decode).
        assert len(shown) == len(garbage) + 1
        assert "0x55" in shown[0].message and "reserved" in shown[0].message
        assert "too short" in shown[1].message
        assert "node 200, which is not bound here" in shown[-1].message
        assert _kinds(rig, "error_frame")
        # Still working: requests, presence, links.
        assert rig.arb.get_parameter(key(5), P.DEVICE_CHANNEL_COUNT) == b"\x05"
        assert rig.arb.system().links == APPENDIX_D
        assert not rig.of(ev.DeviceLeft)


def test_unplugging_a_device_mid_bulk_aborts_only_that_transfer():
    long_text = ("EMG sensor, forearm flexor group, channel calibrated 2026-11-21 " * 3).encode()
    with Rig("appendix-d", packet_gap_s=0.02) as rig:
        rig.settle()
        arb = rig.arb
        arb.set_parameter(key(4), P.CH_DESCRIPTOR, 1, long_text + b"\0")  # 33 packets
        results: dict[str, object] = {}

        def read(name: str, k, param: int, channel: int) -> None:
            try:
                results[name] = arb.get_parameter(k, param, channel)
            except Exception as err:
                results[name] = err

        slow = threading.Thread(target=read, args=("slow", key(4), P.CH_DESCRIPTOR, 1))
        watch = rig.bus()  # the unplug comes a few bulk packets (0x0E) in, however loaded
        started = time.monotonic()
        slow.start()
        packets, deadline = 0, time.monotonic() + 10
        while packets < 3 and time.monotonic() < deadline:
            msg = watch.recv(0.1)
            if msg is not None and msg.data[:1] == b"\x0e":
                packets += 1
        watch.shutdown()
        assert packets == 3, "the transfer never started"
        started = time.monotonic()
        other = threading.Thread(target=read, args=("other", key(5), P.DEVICE_DESCRIPTOR, 0))
        other.start()
        rig.host.unplug(key(4))
        slow.join(5)
        other.join(5)
        assert isinstance(results["slow"], TransferAbortedError), results["slow"]
        assert time.monotonic() - started < 1.5
        assert results["other"] == b"Control unit board\0"
        assert arb.requests.stats.aborted >= 1
        # Everything else goes on: the departure is seen, the other devices still answer.
        assert rig.wait(lambda: rig.of(ev.DeviceLeft), 2)
        assert arb.get_parameter(key(6), P.DEVICE_VID_PID) == b"\x02\x00\x02\x00"


def _twin_host(rig: Rig, k) -> DeviceHost:
    return DeviceHost(rig.bus(), [SimulatedDevice(rig.system.devices[k])], plugged=False,
                      name="twin")


def test_a_second_device_with_the_same_identity_is_reported_and_not_bound():
    with Rig("appendix-d") as rig:
        rig.settle()
        twin = _twin_host(rig, key(4))
        try:
            twin.plug(key(4))
            assert rig.wait(lambda: _kinds(rig, "duplicate_device"), 2)
            time.sleep(0.3)
            assert twin.call(lambda: twin.device(key(4)).state.value) == "binding"
            assert rig.arb.wait_settled(1)  # its bind requests keep nothing waiting
        finally:
            twin.close()
        report = _kinds(rig, "duplicate_device")
        assert len(report) == 1  # reported once, although the twin keeps asking
        assert "VID 2, PID 2, serial 4" in report[0].message
        assert key(4) in rig.arb.duplicates
        # The first one keeps its node ID and its link.
        assert rig.arb.system().links == APPENDIX_D
        assert rig.arb.node_id_of(key(4)) == rig.device(key(4)).node_id
        assert not rig.of(ev.DeviceLeft)


def test_twins_that_bound_together_are_reported():
    system = load("appendix-d")
    with Rig(system, plug=[]) as rig:
        twin = _twin_host(rig, key(4))
        try:
            rig.host.plug(key(4))
            twin.plug(key(4))  # one bind answer binds both: the same node ID
            assert rig.wait(lambda: _kinds(rig, "duplicate_device"), 3)
        finally:
            twin.close()
        assert key(4) in rig.arb.duplicates


def test_node_id_exhaustion_is_reported_and_cleared_by_a_departure():
    with Rig("appendix-d", plug=[key(4), key(6)], node_ids=(1, 3),
             profile_layer=False) as rig:
        rig.settle()
        assert rig.arb._pool.free_count == 0  # SN4 + its output + SN6
        rig.host.plug(key(5))
        assert rig.wait(lambda: _kinds(rig, "node_ids_exhausted"), 2)
        first = _kinds(rig, "node_ids_exhausted")[0]
        assert "2/2/5 cannot bind" in first.message and "all 3 node IDs" in first.message
        time.sleep(0.2)
        assert len(_kinds(rig, "node_ids_exhausted")) == 1  # once, not per retry
        assert rig.arb.node_id_of(key(5)) is None
        rig.host.unplug(key(6))  # its ID goes back to the pool; SN5 (still asking) gets it
        assert rig.wait(lambda: key(5) in rig.arb.devices_present(), 3)
        outputs = _kinds(rig, "node_ids_exhausted")[1:]
        assert outputs and "gets no node ID" in outputs[0].message
        with pytest.raises(NodeIdExhaustedError):
            rig.arb.add_link(link((5, 3), (5, 2)))
        assert rig.arb.system().links == []


def test_requests_complete_through_retries_with_five_percent_of_frames_lost():
    def beacon(msg: can.Message) -> bool:
        return bool(msg.data) and msg.data[0] == FunctionCode.BEACON

    # 100 ms beacons: a starved test machine must not pass for a silent device here.
    # Retries: one attempt of the bulk write below crosses the lossy bus in 11 frames, so it
    # fails 43 % of the time, and all of the arbitrator's default 5 attempts once in 70 (a
    # 4-packet descriptor read, once in 800; the test makes ~20). The seed does not fix the
    # dice (data frames and threads interleave differently each run), so the test was
    # flaky at ~4 %. With 11 attempts a run fails once in ~10,000.
    with Rig(load("appendix-d", beacon_ms=100), lossy=0.05, spare=beacon, seed=2026,
             retries=10) as rig:
        rig.settle(timeout=10)
        arb = rig.arb
        assert arb.system().links == APPENDIX_D
        # Read back every parameter of every channel and compare with the devices.
        read = 0
        for device in rig.system.devices.values():
            k = device.key
            for (param, channel), value in rig.host.call(lambda k=k: dict(rig.device(k).nv)).items():
                assert arb.get_parameter(k, param, channel) == value, (k, param, channel)
                read += 1
        text = b"written through a lossy bus, by bulk transfer\0"
        arb.set_parameter(key(6), P.CH_DESCRIPTOR, 2, text)
        assert rig.nv(key(6), P.CH_DESCRIPTOR, 2) == text
        assert read > 50
        assert rig.lossy.dropped > 10
        assert arb.requests.stats.retries > 0
        assert not rig.of(ev.DeviceLeft)


_WRITER = textwrap.dedent("""
    import sys, time, can
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    sys.path.insert(0, {root!r})
    from tests.bus.test_faults import big
    steps = 0
    def slow(step):  # a slow memory, like an EEPROM: 1 ms per chunk
        global steps
        steps += 1
        if sys.argv[2] == "mid" and writes == 2 and steps == 20:
            print("mid", flush=True)  # halfway through the third write: kill me now
            time.sleep(30)
        time.sleep(0.001)
    memory = MemoryStore(sys.argv[1], step_hook=slow)
    arb = Arbitrator(can.Bus(interface="virtual", channel="pdcp-kill"), memory=memory,
                     profile_layer=False)
    writes = 0
    while True:
        steps = 0
        arb.write_memory(big(writes % 3))  # 3, so a slot never gets its own bytes again
        writes += 1
        if writes == 2:
            print("ready", flush=True)
""")


def big(tag: int) -> ConfigCollection:
    """A configuration of 1,500 links (about 75 kB): a write takes long enough to be hit."""
    return ConfigCollection([StoredConfiguration(1, [
        StoredLink(StoredChannel(1 + n % 200, 2, 2, 10 + tag, 0x5300, 0x1110),
                   StoredChannel(1 + n % 250, 2, 2, 500 + n, 0x5000, 0x1100 + tag), n + 1)
        for n in range(1500)
    ])])


def _kill_writer(path, mode: str, pause: float) -> None:
    script = _WRITER.format(root=str(Path(__file__).resolve().parents[2]))
    proc = subprocess.Popen([sys.executable, "-c", script, str(path), mode],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "ready", proc.stderr.read()
        if mode == "mid":
            assert proc.stdout.readline().strip() == "mid", proc.stderr.read()
        time.sleep(pause)
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait(10)
        proc.stdout.close()
        proc.stderr.close()


def test_killing_the_arbitrator_mid_write_leaves_the_previous_configuration(tmp_path):
    path = tmp_path / "arbitrator.mem"
    _kill_writer(path, "mid", 0.0)
    store = MemoryStore(path)
    assert store.read() == big(1)  # the second write; the third was cut halfway
    assert store.warnings and "damaged" in store.warnings[0]


def test_killing_the_arbitrator_at_random_during_writes_leaves_old_or_new(tmp_path):
    path = tmp_path / "arbitrator.mem"
    rng = random.Random(5)
    for _ in range(3):
        _kill_writer(path, "random", rng.uniform(0.01, 0.2))
        # The previous or the new configuration, never a mix.
        assert MemoryStore(path).read() in (big(0), big(1), big(2))


def test_a_request_to_a_silent_node_times_out_after_bounded_retries():
    with Rig("appendix-d", response_timeout=0.02, retries=2) as rig:
        rig.settle()
        arb = rig.arb
        before = arb.requests.stats.retries
        started = time.monotonic()
        with pytest.raises(TransportError, match="after 3 attempt"):
            arb.requests.get(250, P.DEVICE_VID_PID, 0)  # nobody has node 250
        assert time.monotonic() - started < 0.5
        assert arb.requests.stats.retries - before == 2


def test_a_device_that_never_takes_the_suggested_id_cannot_hold_start_up_forever():
    from pdcp_studio.protocol import BindRequest, Priority

    with Rig("thesis-test2", startup_max_wait_s=0.8) as rig:
        raw = rig.bus()
        stop = threading.Event()

        def rogue() -> None:  # asks for node 1 again and again, ignoring every answer
            aid, data = BindRequest(1, 9, 9, 9, priority=Priority.BINDING).encode()
            while not stop.wait(0.04):
                raw.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))

        thread = threading.Thread(target=rogue)
        thread.start()
        try:
            assert rig.wait(lambda: rig.arb.startup_done, 3)
            assert rig.arb.system().links == APPENDIX_D
            assert any("binding has not settled" in e.message for e in _kinds(rig, "setup"))
        finally:
            stop.set()
            thread.join(2)
            raw.shutdown()
