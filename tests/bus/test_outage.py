"""A pulled and returned adapter (issue 10 item 2): one line and one event per outage, backoff
and no busy loop while it is away, the bus reopened and presence and links re-read when it is
back. The pure decisions first, then python-can's real slcan driver on a pseudo-terminal whose
far end is closed and reopened, and a bus whose reads and writes start raising."""

from __future__ import annotations

import itertools
import logging
import threading
import time

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.outage import BACKOFF_S, Outage
from pdcp_studio.bus.reopen import ReopeningBus
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.rigs import TEST2_LINKS, load_prosthesis
from tests.bus.slcan_rig import SlcanAdapter


# -- the pure decisions -----------------------------------------------------------------------
def test_one_line_per_outage_then_reminders_at_most_every_30_s():
    outage = Outage("can:slcan:/dev/x", remind_s=30.0)
    first = outage.failed(10.0, "device disconnected")
    assert "disconnected" in first and "reconnecting" in first
    assert outage.failed(10.001, "again") is None  # every further failed read: silent
    lines = [outage.attempt_failed(10.0 + t / 10, "no such port") for t in range(1, 900)]
    said = [line for line in lines if line]
    assert len(said) == 2 and "still disconnected" in said[0]  # 90 s: at 30 s and 60 s
    back = outage.reopened(100.0)
    assert "back after 90.0 s" in back and not outage.down
    assert outage.failed(200.0, "gone again") is not None and outage.outages == 2


def test_reopening_backs_off_and_is_never_a_busy_loop():
    outage = Outage("bus")
    outage.failed(0.0, "x")
    assert not outage.due(0.0) and outage.wait(0.0) == pytest.approx(BACKOFF_S[0])
    now, tries = 0.0, []
    while now < 20.0:
        now += outage.wait(now)
        assert outage.due(now)
        tries.append(now)
        outage.attempt_failed(now, "no adapter")
    gaps = [round(b - a, 6) for a, b in itertools.pairwise(tries)]
    assert gaps == sorted(gaps) and max(gaps) == BACKOFF_S[-1]
    assert len(tries) <= 20 / BACKOFF_S[-1] + len(BACKOFF_S)


# -- a bus whose reads and writes start failing ---------------------------------------------------
class Breakable(can.BusABC):
    """A virtual bus that raises CanOperationError on every call once broken."""

    broken = False

    def __init__(self, channel: str) -> None:
        self.inner = can.Bus(interface="virtual", channel=channel)
        super().__init__(channel=channel)

    def _recv_internal(self, timeout):
        if Breakable.broken:
            raise can.CanOperationError("Could not read from serial device")
        return self.inner.recv(timeout), True

    def send(self, msg, timeout=None):
        if Breakable.broken:
            raise can.CanOperationError("Could not write to serial device")
        self.inner.send(msg, timeout)

    def shutdown(self):
        self.inner.shutdown()
        super().shutdown()


def test_a_failing_bus_is_reported_once_and_reopened(caplog):
    channel = unique_virtual_channel("pdcp-outage")
    opens = []

    def opener():
        if Breakable.broken:
            opens.append("refused")
            raise can.CanInitializationError("could not open port")
        opens.append("opened")
        return Breakable(channel)

    states: list[tuple[str, str]] = []
    Breakable.broken = False
    bus = ReopeningBus(opener, name="test bus", on_state=lambda s, line: states.append((s, line)))
    peer = can.Bus(interface="virtual", channel=channel)
    try:
        with caplog.at_level(logging.DEBUG, logger="pdcp_studio"):
            peer.send(can.Message(arbitration_id=0x10A, data=b"\x0a", is_extended_id=False))
            assert bus.recv(1.0).arbitration_id == 0x10A
            Breakable.broken = True
            started, cpu = time.monotonic(), time.process_time()
            while time.monotonic() - started < 2.0:  # what python-can's Notifier does
                bus.recv(0.05)
            cpu = time.process_time() - cpu
            with pytest.raises(can.CanOperationError, match="disconnected"):
                bus.send(can.Message(arbitration_id=0x100, data=b"\x0a", is_extended_id=False))
            Breakable.broken = False
            deadline = time.monotonic() + 5
            while not bus.connected and time.monotonic() < deadline:
                bus.recv(0.05)
            assert bus.connected
            peer.send(can.Message(arbitration_id=0x10B, data=b"\x0a", is_extended_id=False))
            assert bus.recv(1.0).arbitration_id == 0x10B
    finally:
        bus.shutdown()
        peer.shutdown()
        Breakable.broken = False
    assert [s for s, _ in states] == ["disconnected", "reconnected"]
    warnings = [r for r in caplog.records if r.levelno >= logging.INFO]
    assert len(warnings) == 2, [r.getMessage() for r in warnings]
    assert 3 <= opens.count("refused") <= 12  # backoff: a handful of tries in 2 s
    assert cpu < 0.5, f"{cpu:.2f} s of CPU in a 2 s outage"


# -- python-can's slcan driver on a pseudo-terminal -------------------------------------------------
def test_a_pulled_slcan_adapter_is_said_once_reopened_and_its_links_re_read(tmp_path, caplog):
    channel = unique_virtual_channel("pdcp-slcan")
    adapter = SlcanAdapter(tmp_path / "ttyPDCP", channel)
    system = load_prosthesis("thesis-test2")
    host = DeviceHost(can.Bus(interface="virtual", channel=channel),
                      [SimulatedDevice(d) for d in system.devices.values()], plugged=False)
    for key in system.devices:
        host.plug(key)
    url = f"can:slcan:{tmp_path / 'ttyPDCP'}@1000000?sleep_after_open=0"
    events: list[ev.BusState] = []
    lock = threading.Lock()
    session = open_session(url, startup_quiet_s=0.2, settle_timeout=10)
    try:
        session.subscribe(lambda e: events.append(e) if isinstance(e, ev.BusState) else None)
        assert session.wait_settled(10)
        assert sorted(session.system().links) == sorted(TEST2_LINKS)
        with caplog.at_level(logging.INFO):
            caplog.clear()
            adapter.pull()
            started, cpu = time.monotonic(), time.process_time()
            time.sleep(4.0)  # 40 beacon intervals of the devices: nobody is declared gone
            cpu = time.process_time() - cpu
            elapsed = time.monotonic() - started
            outage_lines = [r.getMessage() for r in caplog.records
                            if r.name.startswith(("pdcp_studio", "can"))]
            assert session.state == "disconnected"
            assert all(d.present for d in session.system().devices.values())
            adapter.plug()
            deadline = time.monotonic() + 6
            while session.state != "reconnected" and time.monotonic() < deadline:
                time.sleep(0.02)
            assert session.state == "reconnected"
            time.sleep(1.0)
            assert session.wait_settled(10)
        print(f"\noutage of {elapsed:.1f} s: {len(outage_lines)} log line(s), "
              f"{cpu:.2f} s CPU (whole process, devices included)")
        with lock:
            states = [e.state for e in events]
        assert states == ["disconnected", "reconnected"]
        assert len(outage_lines) <= 2, outage_lines
        assert cpu < 0.25 * elapsed, f"{cpu:.2f} s CPU in {elapsed:.1f} s"
        assert sorted(session.system().links) == sorted(TEST2_LINKS)
        assert all(d.present for d in session.system().devices.values())
        # The bus works again: a parameter read through the reopened adapter.
        key = next(iter(system.devices))
        assert session.get_parameter(key, 1)
    finally:
        session.close()
        host.close()
        adapter.close()


def test_the_headless_arbitrator_prints_the_outage_lines():
    from pdcp_studio.cli.live.arbitrator import describe

    line = "can:slcan:/dev/x: the adapter is disconnected (EIO); reconnecting"
    assert describe(ev.BusState("disconnected", line)) == \
        f"disconnected — reconnecting: {line}"
    assert describe(ev.BusState("reconnected", "back")) == "reconnected: back"
    assert describe(ev.BusState("yielded", "another")) is None  # said on stderr, once
