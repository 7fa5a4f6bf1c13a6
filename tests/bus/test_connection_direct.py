"""A simulation's connections take frames straight from python-can's virtual bus (issue 11).

Real parts: python-can's ``virtual`` interface, the Connection, the simulated prosthesis.
The fast path must give the consumer exactly what a Notifier would (order, content, the flood
bound, posted callables), must not engage on any other bus, and must close at once.
"""

from __future__ import annotations

import threading
import time

import can
import pytest
from can.interfaces.virtual import VirtualBus

from pdcp_studio.bus import connection
from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.session.urls import unique_virtual_channel


def _frame(i: int) -> can.Message:
    return can.Message(arbitration_id=0x100 + (i % 0x80), data=i.to_bytes(2, "little"),
                       is_extended_id=False)


def _notifier_threads(channel: str) -> list[str]:
    return [t.name for t in threading.enumerate() if channel in t.name]


@pytest.fixture
def channel() -> str:
    return unique_virtual_channel("pdcp-direct")


def test_frames_from_another_bus_arrive_in_order_without_a_notifier_thread(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    conn = Connection(can.Bus(interface="virtual", channel=channel), name="direct",
                      direct=True)
    try:
        assert conn.direct
        assert _notifier_threads(channel) == []
        for i in range(200):
            sender.send(_frame(i))
        got = [conn.get(1.0) for _ in range(200)]
        assert [bytes(m.data) for m in got] == [i.to_bytes(2, "little") for i in range(200)]
        assert all(m.arbitration_id == 0x100 + (i % 0x80) for i, m in enumerate(got))
        assert all(m.is_rx and m.channel == channel for m in got)
        assert conn.received == 200 and conn.get(0.01) is None
    finally:
        conn.close()
        sender.shutdown()


def test_own_frames_reach_the_others_but_not_itself(channel):
    other = Connection(can.Bus(interface="virtual", channel=channel), name="other",
                       direct=True)
    conn = Connection(can.Bus(interface="virtual", channel=channel), name="direct",
                      direct=True)
    try:
        conn.send(0x123, b"\x01\x02")
        got = other.get(1.0)
        assert got is not None and got.arbitration_id == 0x123 and bytes(got.data) == b"\x01\x02"
        assert conn.get(0.05) is None
    finally:
        conn.close()
        other.close()


def test_frames_waiting_before_the_connection_attached_are_passed_on_first(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    bus = can.Bus(interface="virtual", channel=channel)
    sender.send(_frame(1))
    sender.send(_frame(2))
    conn = Connection(bus, name="direct", direct=True)
    try:
        sender.send(_frame(3))
        got = [conn.get(1.0) for _ in range(3)]
        assert [int.from_bytes(m.data, "little") for m in got] == [1, 2, 3]
    finally:
        conn.close()
        sender.shutdown()


def test_a_flood_is_bounded_and_counted_as_with_a_notifier(monkeypatch, channel):
    monkeypatch.setattr(connection, "INBOUND_MAX", 100)
    sender = can.Bus(interface="virtual", channel=channel)
    conn = Connection(can.Bus(interface="virtual", channel=channel), name="flooded",
                      direct=True)
    try:
        for i in range(300):
            sender.send(_frame(i))  # never blocks nor fails: the surplus is dropped
        assert conn.inbound.qsize() == 100 and conn.dropped == 200
        conn.post(lambda: None)  # the consumer's own requests always get through
        assert conn.inbound.qsize() == 101
    finally:
        conn.close()
        sender.shutdown()


def test_posted_callables_and_wake_reach_the_consumer(channel):
    conn = Connection(can.Bus(interface="virtual", channel=channel), name="direct",
                      direct=True)
    try:
        def job() -> None:
            pass

        conn.post(job)
        assert conn.get(1.0) is job
        threading.Timer(0.05, conn.wake).start()
        t0 = time.monotonic()
        assert conn.get(5.0) is None
        assert time.monotonic() - t0 < 2.0
    finally:
        conn.close()


def test_close_is_immediate_and_leaves_the_channel(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    bus = can.Bus(interface="virtual", channel=channel)
    conn = Connection(bus, name="direct", direct=True)
    t0 = time.perf_counter()
    conn.close()
    assert time.perf_counter() - t0 < connection.NOTIFIER_POLL_S
    assert len(sender.channel) == 1  # only the sender's own queue is left
    sender.send(_frame(1))  # nobody listens: python-can delivers to no one, no error
    assert conn.inbound.qsize() == 1 and conn.inbound.get_nowait() is None  # close's wake
    sender.shutdown()


def test_a_stray_recv_on_the_attached_bus_waits_and_finds_nothing(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    bus = can.Bus(interface="virtual", channel=channel)
    conn = Connection(bus, name="direct", direct=True)
    try:
        sender.send(_frame(7))
        t0 = time.monotonic()
        assert bus.recv(0.05) is None
        assert time.monotonic() - t0 >= 0.04
        assert conn.get(1.0) is not None  # the frame went to the connection, not lost
    finally:
        conn.close()
        sender.shutdown()


def test_without_direct_a_virtual_bus_is_read_by_a_notifier_as_before(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    conn = Connection(can.Bus(interface="virtual", channel=channel), name="notified")
    try:
        assert not conn.direct
        assert _notifier_threads(channel)
        sender.send(_frame(5))
        got = conn.get(1.0)
        assert got is not None and bytes(got.data) == b"\x05\x00"
    finally:
        conn.close()
        sender.shutdown()


class _SubclassedVirtualBus(VirtualBus):
    """Not python-can's own class: its internals are not ours to assume."""


def test_direct_falls_back_to_a_notifier_on_any_bus_but_python_cans_virtual(channel):
    sender = can.Bus(interface="virtual", channel=channel)
    conn = Connection(_SubclassedVirtualBus(channel=channel), name="sub", direct=True)
    try:
        assert not conn.direct
        sender.send(_frame(9))
        got = conn.get(1.0)
        assert got is not None and bytes(got.data) == b"\x09\x00"
    finally:
        conn.close()
        sender.shutdown()


def test_a_virtual_bus_laid_out_otherwise_is_left_alone(channel):
    bus = can.Bus(interface="virtual", channel=channel)
    listener = connection._Enqueue(__import__("queue").SimpleQueue())
    saved = bus.queue
    bus.queue = None  # a python-can that keeps its receive queue elsewhere
    try:
        assert connection.attach_direct(bus, listener) is None
        assert saved in bus.channel
    finally:
        bus.queue = saved
        bus.shutdown()


def test_a_simulated_prosthesis_runs_without_notifier_threads():
    from pdcp_studio.bus.session.opening import open_session

    channel = unique_virtual_channel("pdcp-sim-direct")
    with open_session("sim:thesis-test2", channel=channel) as session:
        assert session.arbitrator.conn.direct and session.host.conn.direct  # type: ignore[attr-defined]
        assert _notifier_threads(channel) == []
        assert len(session.system().links) == 3  # appendix D's links: it works end to end
        assert session.host.bad_frames == 0 and session.arbitrator.bad_frames == 0  # type: ignore[attr-defined]


# -- the device host answers on the sender's thread (direct mode) ---------------------------
def _next(conn: Connection, kind: type, timeout: float = 2.0):
    from pdcp_studio.protocol import decode

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        item = conn.get(max(0.0, deadline - time.monotonic()))
        if isinstance(item, can.Message):
            message = decode(item.arbitration_id, bytes(item.data))
            if isinstance(message, kind):
                return message
    raise AssertionError(f"no {kind.__name__} within {timeout} s")


def test_devices_answer_on_the_senders_thread_and_their_timers_still_run(monkeypatch, channel):
    from pdcp_studio.bus.sim import device_host
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.model.system import Device
    from pdcp_studio.protocol import (
        Beacon,
        BindRequest,
        BindResponse,
        GetParameter,
        GetParameterResponse,
        Reset,
        ResetResponse,
        decode,
    )

    # The host thread would sleep 5 s between timers: only the wake-up of a frame handled
    # on another thread brings a timer that frame set (the reset's power-on) in time.
    monkeypatch.setattr(device_host, "IDLE_WAKE_S", 5.0)
    arb = Connection(can.Bus(interface="virtual", channel=channel), name="arb", direct=True)
    quiet = Device(0x0A51, 0x0101, 77, name="quiet", beacon_interval=60000)
    host = DeviceHost(can.Bus(interface="virtual", channel=channel), [SimulatedDevice(quiet)],
                      name="devices", direct=True)
    try:
        assert host.inline and host.conn.direct
        req = _next(arb, BindRequest)
        arb.send(*BindResponse(req.node_id, req.node_id, req.vid, req.pid, req.serial).encode())
        _next(arb, Beacon)  # bound
        while arb.get(0.05) is not None:  # bind retries sent before the answer
            pass
        arb.send(*GetParameter(req.node_id, 1, 0).encode())
        answer = arb.inbound.get_nowait()  # already there when send() returned
        assert isinstance(decode(answer.arbitration_id, bytes(answer.data)),
                          GetParameterResponse)
        deadline = time.monotonic() + 5.0  # until the host thread sleeps its long sleep
        while host._wake_at - time.monotonic() < 2.0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert host._wake_at - time.monotonic() >= 2.0
        arb.send(*Reset(req.node_id).encode())
        answer = arb.inbound.get_nowait()
        assert isinstance(decode(answer.arbitration_id, bytes(answer.data)), ResetResponse)
        t0 = time.monotonic()
        again = _next(arb, BindRequest, timeout=1.5)  # power-on 2 ms after the reset
        assert again.serial == 77 and time.monotonic() - t0 < 1.5
        assert host.conn.received == 3 and host.failures == 0
    finally:
        host.close()
        arb.close()


def test_a_simulated_prosthesis_on_a_channel_already_in_use_is_read_with_notifiers():
    """Two simulated prostheses on one channel: the second's parts have Notifiers (its
    devices could otherwise answer on the first's host thread while that one answers on
    theirs), and both work."""
    from pdcp_studio.bus.connection import virtual_channel_in_use
    from pdcp_studio.bus.session.sim import open_sim_session

    channel = unique_virtual_channel("pdcp-sim-shared")
    assert not virtual_channel_in_use(channel)
    tap = can.Bus(interface="virtual", channel=channel)
    try:
        assert virtual_channel_in_use(channel)
        with open_sim_session("thesis-test2", channel=channel) as session:
            assert not session.arbitrator.conn.direct and not session.host.inline
            assert _notifier_threads(channel)
            assert len(session.system().links) == 3
    finally:
        tap.shutdown()
    assert not virtual_channel_in_use(channel)
