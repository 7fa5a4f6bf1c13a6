"""Another arbitrator is known by its beacons, never by one frame (issue 28 item 1, reference
§5 "Decision (revised)").

Every single-frame arbitrator-mode pattern — every function code, node IDs 0, 1, 0x7F, 0xAC,
0xFE, 0xFF, five DLCs, the issue's ``0x3AC 0E 00`` first — is replayed against a running
arbitrator: it never stops arbitrating, and says so in a few rate-limited lines. Then a real
second arbitrator beacons: ours stops writing at once and, being the headless kind
(``take_back``), stays up read-only; when the other's beacons have been gone for five beacon
intervals it takes the bus back. The same through the command line and the host link."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.claim import ARBITRATOR_BEACON_S, TAKE_BACK_INTERVALS
from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.rigs import load_prosthesis
from pdcp_studio.errors import PdcpError
from tests.bus.hostlink_rig import wait_for
from tests.bus.stray_frames import (
    ISSUE_FRAME,
    BeaconingArbitrator,
    is_arbitrator_beacon,
    single_mode_1_frames,
)

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
TAKE_BACK_S = TAKE_BACK_INTERVALS * ARBITRATOR_BEACON_S
#: Longer than three beacon intervals: frames this far apart are never heard together.
APART_S = 3 * ARBITRATOR_BEACON_S + 0.5


def _send(bus: can.BusABC, aid: int, data: bytes) -> None:
    bus.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))


def replay_every_single_frame(bus: can.BusABC) -> int:
    """The arbitrator beacon pattern alone, then (apart from it) every other pattern."""
    frames = list(single_mode_1_frames())
    beacons = [f for f in frames if is_arbitrator_beacon(*f)]
    assert len(beacons) == 1 and frames[0] == ISSUE_FRAME
    _send(bus, *ISSUE_FRAME)
    _send(bus, *beacons[0])
    time.sleep(APART_S)
    for n, frame in enumerate(frames[1:]):
        if not is_arbitrator_beacon(*frame):
            _send(bus, *frame)
        if n % 500 == 499:
            time.sleep(0.01)  # the virtual bus's queues are bounded
    return len(frames)


@pytest.fixture
def devices():
    channel = unique_virtual_channel("pdcp-stray")
    system = load_prosthesis("thesis-test1")
    host = DeviceHost(open_can_bus("virtual", channel),
                      [SimulatedDevice(d) for d in system.devices.values()], name="devices",
                      plugged=False)
    for device in system.devices.values():
        if device.present:
            host.plug(device.key)
    yield channel, system
    host.close()


def test_no_single_frame_stops_it_beacons_make_it_read_only_and_it_takes_the_bus_back(devices):
    channel, system = devices
    arb = Arbitrator(open_can_bus("virtual", channel), name="ours", listen_s=0.6,
                     startup_quiet_s=0.2, take_back=True)
    events: list[object] = []
    arb.subscribe(lambda e: events.append(e) if isinstance(e, ev.BusState | ev.BusError)
                  else None)
    tap = can.Bus(interface="virtual", channel=channel)
    other = BeaconingArbitrator(channel)
    try:
        assert arb.wait_claimed(10) and arb.wait_settled(20)
        sent = replay_every_single_frame(tap)
        assert arb.wait_for(lambda: arb.claim.strays >= sent - 1, 30.0), arb.claim.strays
        assert arb.bus_state == "arbitrating" and not arb.yielded
        states = [e.state for e in events if isinstance(e, ev.BusState)]
        assert states == ["arbitrating"], states
        strays = [e.message for e in events
                  if isinstance(e, ev.BusError) and e.kind == "stray_frame"]
        assert "0x3AC [0E 00]" in strays[0] and "ignored" in strays[0]
        assert len(strays) <= 30, len(strays)  # thousands of frames, a few lines
        beacons_before = arb.conn.sent
        assert arb.wait_for(lambda: arb.conn.sent > beacons_before, 5.0)  # still beaconing
        # (The simulated devices took the broadcast writes among the frames as a device
        # would: what they do now is theirs; the arbitrator's hold on the bus is the point.)

        other.start()  # a real second arbitrator: its beacons every 500 ms
        assert arb.wait_for(lambda: arb.yielded, 10.0)
        assert arb.read_only and "read-only" in arb.bus_message
        assert "stopped writing" in arb.bus_message and f"{TAKE_BACK_S:g} s" in arb.bus_message
        with pytest.raises(PdcpError, match="not writing"):
            arb.reset_device(next(iter(system.devices)))
        quiet_from = arb.conn.sent
        time.sleep(2 * TAKE_BACK_S)  # the other beacons on: ours writes nothing, stays yielded
        assert arb.yielded and arb.conn.sent == quiet_from and not arb.closed
        other.stop()
        stopped = time.monotonic()
        assert arb.wait_for(lambda: arb.bus_state == "arbitrating", TAKE_BACK_S + 20.0)
        assert time.monotonic() - stopped >= TAKE_BACK_S - 2 * ARBITRATOR_BEACON_S
        assert "takes the bus back and writes again" in arb.bus_message
        assert arb.wait_for(lambda: arb.conn.sent > quiet_from, 5.0)  # beaconing again
        states = [e.state for e in events if isinstance(e, ev.BusState)]
        assert states == ["arbitrating", "yielded", "arbitrating"], states
    finally:
        other.close()
        tap.shutdown()
        arb.close()


class _Lines:
    """A command's stdout, read line by line on a thread of its own as the run goes on."""

    def __init__(self, stream) -> None:
        self.lines: list[str] = []
        self._thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self._thread.start()

    def _read(self, stream) -> None:
        for line in stream:
            self.lines.append(line.rstrip("\n"))

    def has(self, text: str) -> bool:
        return any(text in line for line in list(self.lines))


def test_the_headless_arbitrator_outlives_the_issues_frame_and_takes_the_bus_back(
        tmp_path, multicast_url):
    """``pdcp-studio arbitrator`` as a process: the frame ``0x3AC 0E 00`` made it exit with
    "another bus arbitrator appeared on this bus"; now it logs it and arbitrates on, yields to
    real beacons read-only and takes the bus back when they are gone."""
    import subprocess
    import sys

    from pdcp_studio.bus.session.urls import open_spec, parse_bus_url

    url = multicast_url("239.74.163.28", 44000)
    run = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus", url, "--memory",
         str(tmp_path / "memory.json"), "--seconds", "120"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    out = _Lines(run.stdout)
    tap = open_spec(parse_bus_url(url))
    other = BeaconingArbitrator(open_spec(parse_bus_url(url)))
    try:
        assert wait_for(lambda: out.has("arbitrating: no other bus arbitrator heard"), 60.0), \
            out.lines
        _send(tap, *ISSUE_FRAME)  # one frame made it exit with "another bus arbitrator …"
        assert wait_for(lambda: out.has("stray arbitrator-mode frame 0x3AC [0E 00]"), 20.0), \
            out.lines
        time.sleep(APART_S)
        assert run.poll() is None and not out.has("appeared")
        other.start()
        assert wait_for(lambda: out.has("another arbitrator: not writing: another bus "
                                        "arbitrator appeared"), 20.0), out.lines
        assert out.has("read-only") and run.poll() is None
        time.sleep(TAKE_BACK_S)
        assert run.poll() is None and not out.has("takes the bus back and writes again")
        other.stop()
        assert wait_for(lambda: out.has("takes the bus back and writes again"), TAKE_BACK_S + 30.0), out.lines
        assert run.poll() is None
    finally:
        other.close()
        tap.shutdown()
        run.terminate()
        rest, err = run.communicate(timeout=30)
    assert run.returncode == 0, err
    # The last lines reach either the reader thread or communicate(), whichever read first.
    assert wait_for(lambda: out.has("arbitrator stopped")
                    or "arbitrator stopped" in (rest or ""), 10.0), out.lines
    assert "another bus arbitrator" not in err  # no error line: it never left


def test_the_prosthesis_is_kept_while_read_only_and_after_the_bus_is_taken_back(devices):
    """No reset on taking back: the parts stay bound and linked through it all."""
    channel, system = devices
    arb = Arbitrator(open_can_bus("virtual", channel), name="ours", listen_s=0.6,
                     startup_quiet_s=0.2, take_back=True)
    left: list[object] = []
    arb.subscribe(lambda e: left.append(e) if isinstance(e, ev.DeviceLeft) else None)
    other = BeaconingArbitrator(channel)
    try:
        assert arb.wait_claimed(10) and arb.wait_settled(20)
        links = sorted(arb.system().links)
        assert links
        other.start()
        assert arb.wait_for(lambda: arb.yielded, 10.0)
        time.sleep(TAKE_BACK_S)
        other.stop()
        assert arb.wait_for(lambda: not arb.yielded, 2 * TAKE_BACK_S + 20.0)
        time.sleep(3 * ARBITRATOR_BEACON_S)  # presence judged again, links read back
        assert arb.wait_settled(20)
        assert left == [] and len(arb.devices_present()) == len(
            [d for d in system.devices.values() if d.present])
        assert sorted(arb.system().links) == links
    finally:
        other.close()
        arb.close()
