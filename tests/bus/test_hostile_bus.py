"""A hostile device on a simulated bus against the arbitrator (issue 15), kept in CI.

Random frames, a bind flood of made-up devices beyond the 254 node IDs, unsolicited
responses, bulk transfers that lie about their size and Update Data Channel floods, at about
4,000 frames a second: the legitimate devices stay bound and linked, a new device still binds
afterwards, every bad frame is counted, and the log gets a few lines a second, not thousands.
"""

from __future__ import annotations

import logging
import random
import resource
import struct
import threading
import time

import can

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.core import ERROR_BURST
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import Direction
from pdcp_studio.model.system import Channel, Device
from pdcp_studio.protocol import (
    BindRequest,
    FunctionCode,
    GetParameterResponse,
    ResponseCode,
    UpdateDataChannel,
    make_id,
)
from tests.bus.test_arbitrator_rig import Rig, key, load

RATE_HZ = 4000
#: Beacons every 200 ms (gone after 0.7 s): the flood is the test, not a loaded machine's
#: scheduling delays (the rig's 50 ms leaves 175 ms).
BEACON_MS = 200


def _frame(aid: int, data: bytes) -> can.Message:
    return can.Message(arbitration_id=aid, data=data, is_extended_id=False)


def _paced(bus: can.BusABC, frames, rate_hz: float = RATE_HZ) -> int:
    """Send ``frames`` at about ``rate_hz`` (in bursts of 40, as a busy adapter would)."""
    start = time.perf_counter()
    sent = 0
    for msg in frames:
        bus.send(msg)
        sent += 1
        if sent % 40 == 0:
            ahead = start + sent / rate_hz - time.perf_counter()
            if ahead > 0:
                time.sleep(ahead)
    return sent


def _garbage(rng: random.Random, bound: list[int], n: int):
    """Undecodable frames from bound nodes: reserved function codes, truncated responses."""
    for i in range(n):
        node = bound[i % len(bound)]
        code = rng.choice([0x55, 0x60, 0x7F, 0xA0, 0xC5])  # reserved function codes
        yield _frame(make_id(1, 0, node), bytes([code]) + rng.randbytes(rng.randint(0, 7)))


def _random_frames(rng: random.Random, n: int):
    """Random identifiers and bytes, as a device sends them (mode 0: a device cannot be
    told from the arbitrator on CAN, so frames posing as the arbitrator are another attack)."""
    for _ in range(n):
        yield _frame(rng.randrange(0x800) & ~0x100, rng.randbytes(rng.randint(0, 8)))


def _bind_flood(n: int):
    for serial in range(n):
        yield _frame(*BindRequest(1 + serial % 254, 0xBAD, 1, serial).encode())


def _unsolicited(bound: list[int], n: int):
    for i in range(n):
        msg = GetParameterResponse(bound[i % len(bound)], ResponseCode.SUCCESS,
                                   P.DEVICE_CHANNEL_COUNT, 0, bytes([i % 256]))
        yield _frame(*msg.encode())


def _lying_bulk(bound: list[int], n: int):
    """A bulk response announcing 65,535 bytes, then packets out of order and too long."""
    for i in range(n):
        node = bound[i % len(bound)]
        if i % 3 == 0:
            data = struct.pack("<BBBBH", FunctionCode.CONFIGURE_GET_BULK_RESPONSE,
                               ResponseCode.SUCCESS, P.DEVICE_DESCRIPTOR, 0, 0xFFFF)
        else:
            data = bytes([FunctionCode.BULK_DATA, (i * 7) % 256]) + b"\xAA" * 6
        yield _frame(make_id(1, 0, node), data)


def _update_flood(bound: list[int], n: int):
    for i in range(n):
        yield _frame(*UpdateDataChannel(bound[i % len(bound)], 1 + i % 3).encode())


def _late_device() -> SimulatedDevice:
    d = Device(0x77, 1, 1, name="late sensor")
    d.beacon_interval, d.bind_timeout = BEACON_MS, 60
    d.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4600))
    return SimulatedDevice(d, data_rate_hz=0)


def test_a_hostile_device_leaves_the_legitimate_links_intact_and_the_log_readable(caplog):
    rng = random.Random(15)
    with Rig(load("appendix-d", beacon_ms=BEACON_MS), data_rate_hz=0) as rig:
        rig.settle()
        arb = rig.arb
        links = arb.system().links
        legit = set(arb.devices_present())
        bound = sorted(arb.node_id_of(k) for k in legit)
        attacker = rig.bus()
        caplog.set_level(logging.WARNING, logger="pdcp_studio")
        caplog.clear()
        errors_before = len(rig.of(ev.BusError))
        bad_before = arb.bad_frames
        cpu0, wall0 = resource.getrusage(resource.RUSAGE_SELF), time.monotonic()
        try:
            garbage = _paced(attacker, _garbage(rng, bound, 8000))  # 2 s of undecodable frames
            sent = garbage + _paced(attacker, _random_frames(rng, 4000))
            sent += _paced(attacker, _bind_flood(400))  # made-up devices, beyond 254 node IDs
            sent += _paced(attacker, _unsolicited(bound, 2000))
            sent += _paced(attacker, _lying_bulk(bound, 2000))
            sent += _paced(attacker, _update_flood(bound, 2000))
        finally:
            attacker.shutdown()
        wall = time.monotonic() - wall0
        cpu1 = resource.getrusage(resource.RUSAGE_SELF)
        cpu = (cpu1.ru_utime + cpu1.ru_stime) - (cpu0.ru_utime + cpu0.ru_stime)
        assert rig.wait(lambda: arb.bad_frames - bad_before >= garbage, 10)  # all counted
        lines = len(caplog.records)
        shown = len(rig.of(ev.BusError)) - errors_before
        # A few lines a second: a burst per kind of error, then one line and one summary a
        # second per kind (a handful of kinds) — not one per frame (18,400 frames sent).
        kinds = {r.getMessage().split(":")[1] for r in caplog.records}
        print(f"hostile bus: {sent} frames in {wall:.1f} s, {lines} log lines "
              f"({lines / wall:.1f}/s), {shown} error events, CPU {cpu:.1f} s")
        assert lines <= len(kinds) * ERROR_BURST + 2 * 6 * (wall + 2), (lines, wall)
        assert shown <= lines
        assert cpu < 1.8 * wall, (cpu, wall)  # no thread spins (two cores: 2.0 is flat out)
        # The legitimate devices never left and keep their links; the fakes go away.
        assert rig.wait(lambda: set(arb.devices_present()) == legit, 15), arb.devices_present()
        assert not [e for e in rig.of(ev.DeviceLeft) if e.key in legit]
        assert set(links) <= set(arb.system().links)
        assert arb.get_parameter(key(5), P.DEVICE_CHANNEL_COUNT) == b"\x05"
        # A new device still binds and is set up.
        late = _late_device()
        rig.host.add(late)
        assert rig.wait(lambda: late.key in arb.devices_present(), 15), arb.devices_present()
        assert set(links) <= set(arb.system().links)


class LyingDevice(SimulatedDevice):
    """Honest until told to lie; then its bulk answers lie about their size, in turn:
    60,000 bytes announced and two packets sent; 8 announced and 12 sent; 12 announced and
    packet 1 sent over and over."""

    lying = False
    answers = 0

    def handle(self, msg) -> None:
        from pdcp_studio.protocol import BulkData, ConfigureGetBulk, ConfigureGetBulkResponse
        from pdcp_studio.protocol.identifier import Mode

        if not (self.lying and isinstance(msg, ConfigureGetBulk)):
            super().handle(msg)
            return
        LyingDevice.answers += 1
        size, ids = [(60_000, [1, 2]), (8, [1, 2]), (12, [1] * 40)][LyingDevice.answers % 3]
        self.send(ConfigureGetBulkResponse(self.node_id, ResponseCode.SUCCESS, msg.param,
                                           msg.channel, size))
        for packet_id in ids:
            self.send(BulkData(self.node_id, packet_id, b"\x55" * 6, mode=Mode.DEVICE))


def test_bulk_transfers_that_lie_about_their_size_fail_alone_and_fast():
    from pdcp_studio.errors import PdcpError

    system = load("appendix-d", beacon_ms=BEACON_MS)
    liar_model = Device(0x66, 6, 6, name="liar", descriptor="a descriptor long enough for bulk")
    liar_model.beacon_interval, liar_model.bind_timeout = BEACON_MS, 60
    liar_model.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4600))
    system.add_device(liar_model)
    with Rig(system, data_rate_hz=0) as rig:
        rig.settle()
        arb = rig.arb
        links = arb.system().links
        rig.host.remove(liar_model.key)  # replaced by one that lies from now on
        lying = LyingDevice(liar_model, data_rate_hz=0)
        lying.lying = True
        rig.host.add(lying)
        assert rig.wait(lambda: liar_model.key in arb.devices_present(), 15)
        for _ in range(6):
            started = time.monotonic()
            try:
                value = arb.get_parameter(liar_model.key, P.DEVICE_DESCRIPTOR)
            except PdcpError:
                pass
            else:
                raise AssertionError(f"a lying transfer was accepted: {value!r}")
            assert time.monotonic() - started < 5  # refused or timed out, never stuck
        # The others are not affected: requests answered, links intact.
        assert arb.get_parameter(key(5), P.DEVICE_CHANNEL_COUNT) == b"\x05"
        assert set(links) <= set(arb.system().links)


class _Gate:
    """Stands between the Notifier and the arbitrator's queue; while ``held`` it blocks the
    Notifier's thread, as a stalled process does (frames wait in the driver, unseen)."""

    def __init__(self, target) -> None:
        self.target = target
        self.held = threading.Event()

    def put(self, item) -> None:
        while self.held.is_set():
            time.sleep(0.001)
        self.target.put(item)

    def qsize(self) -> int:
        return self.target.qsize()


def test_a_stalled_arbitrator_process_does_not_take_its_own_pause_for_silent_devices():
    """A loaded clinic PC can stop the arbitrator's process for longer than three beacons;
    when it runs again the beacons are still in the driver's buffer: no device has left."""
    with Rig("appendix-d", data_rate_hz=0) as rig:  # beacons every 50 ms: gone after 175 ms
        rig.settle()
        arb = rig.arb
        present = set(arb.devices_present())
        gate = _Gate(arb.conn._listener._target)
        arb.conn._listener._target = gate

        def stall() -> None:  # the dispatch thread and the Notifier both stop for 0.6 s
            gate.held.set()
            time.sleep(0.6)
            gate.held.clear()

        for _ in range(3):
            arb.conn.post(stall)
            time.sleep(1.0)
        assert set(arb.devices_present()) == present
        assert not rig.of(ev.DeviceLeft)
