"""One arbitrator per bus (reference §5, issue 10 item 1): the pure claim decisions, then the
arbitrator on a virtual bus — a second arbitrator on a settled transradial bus sends nothing,
one that appears later makes ours stop writing at once, and a replaced arbitrator's bus
(thesis test 5) is still taken over."""

from __future__ import annotations

import threading
import time

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.claim import (
    ARBITRATOR_BEACON_S,
    LISTEN_S,
    BusClaim,
    Decision,
    Phase,
    Stray,
)
from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.session.in_process import OtherArbitratorError, open_can_session
from pdcp_studio.bus.session.sim import open_sim_session
from pdcp_studio.bus.session.urls import open_can_bus, parse_bus_url, unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.rigs import TEST2_LINKS, load_prosthesis
from pdcp_studio.cli.main import main
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    GetParameter,
    GetParameterResponse,
    Mode,
    Reset,
    ResponseCode,
)
from tests.bus.stray_frames import (
    BeaconingArbitrator,
    is_arbitrator_beacon,
    single_mode_1_frames,
)


def frame(message):
    return message.encode()


# -- the pure decisions -----------------------------------------------------------------------
def test_listening_then_arbitrating_when_nobody_else_is_heard():
    claim = BusClaim(100.0, listen_s=1.0)
    assert claim.phase is Phase.LISTENING and not claim.may_write
    assert claim.listen_s >= 2 * ARBITRATOR_BEACON_S
    assert not claim.beacon_due(100.5)  # no beacon while listening: it would be heard
    assert claim.tick(100.99) is None
    decision = claim.tick(101.0)
    assert decision.phase is Phase.ARBITRATING and decision.takeover == ()
    assert claim.may_write and claim.tick(102.0) is None


BEACON_BA = frame(Beacon(0, mode=Mode.ARBITRATOR))


def test_one_mode_1_frame_while_listening_is_a_stray_frame_not_an_arbitrator():
    claim = BusClaim(0.0, listen_s=1.0)
    aid, data = frame(GetParameter(7, 9, 0))  # one request, from nobody known
    stray = claim.heard(aid, data, 0.3)
    assert isinstance(stray, Stray) and "ignored" in stray.message
    assert "0x307 [03 09 00]" in stray.message
    assert claim.tick(1.0).phase is Phase.ARBITRATING and claim.may_write


def test_two_arbitrator_beacons_while_listening_mean_never_arbitrate():
    claim = BusClaim(0.0, listen_s=1.1)
    assert claim.heard(*BEACON_BA, 0.1) is None  # one beacon alone: not yet
    decision = claim.heard(*BEACON_BA, 0.6)
    assert decision.phase is Phase.YIELDED and not decision.later
    assert "another bus arbitrator" in decision.message and "beacons" in decision.message
    assert claim.tick(5.0) is None and not claim.may_write and not claim.beacon_due(5.0)
    assert claim.heard(*BEACON_BA, 6.0) is None  # said once
    assert claim.tick(60.0) is None  # heard on start: never taken back


def test_one_beacon_heard_while_listening_keeps_it_listening_for_a_second():
    claim = BusClaim(0.0, listen_s=1.1)
    assert claim.heard(*BEACON_BA, 1.0) is None
    assert claim.tick(1.2) is None and claim.phase is Phase.LISTENING  # a second is due
    assert claim.tick(2.4) is None
    assert claim.tick(2.6).phase is Phase.ARBITRATING  # none came within 3 intervals


def test_beacons_further_apart_than_three_intervals_are_strays():
    claim = BusClaim(0.0, listen_s=0.0)
    for t in (1.0, 2.6, 4.2, 5.8):  # 1.6 s apart: more than 3 × 500 ms
        assert claim.heard(*BEACON_BA, t) is None
        assert claim.lone_beacon(t + 1.4) is None  # its second may still come …
        stray = claim.lone_beacon(t + 1.55)  # … it did not: a stray frame, told once
        assert isinstance(stray, Stray) and "0x100 [0A]" in stray.message
        assert claim.lone_beacon(t + 1.56) is None
    assert claim.may_write


def test_lone_beacons_far_apart_on_the_bus_handled_together_are_still_strays():
    """A busy PC handles a backlog late: two beacons 5 s apart on the bus (their own time
    stamps) handled 10 ms apart are not two beacons within three intervals."""
    claim = BusClaim(0.0, listen_s=0.0)
    assert claim.heard(*BEACON_BA, 20.00, bus_time=1000.0) is None
    assert claim.heard(*BEACON_BA, 20.01, bus_time=1005.0) is None
    assert claim.may_write


def test_one_beacon_and_an_answer_nobody_here_asked_for_is_an_arbitrator():
    claim = BusClaim(0.0, listen_s=1.1)
    claim.heard(*frame(Beacon(7)), 0.05)  # a device beacons on node 7
    answer = frame(GetParameterResponse(7, ResponseCode.SUCCESS, 9, 0, b"\x01\x00"))
    assert claim.heard(*answer, 0.1) is None  # an answer alone: nothing said
    decision = claim.heard(*BEACON_BA, 0.3)
    assert decision.phase is Phase.YIELDED and "did not send" in decision.message


def test_an_answer_to_our_own_request_is_no_evidence():
    claim = BusClaim(0.0, listen_s=0.0)
    claim.heard(*frame(Beacon(7)), 0.05)
    claim.sent(*frame(GetParameter(7, 9, 0)), 0.1)
    claim.heard(*frame(GetParameterResponse(7, ResponseCode.SUCCESS, 9, 0, b"\x01\x00")), 0.2)
    assert claim.heard(*BEACON_BA, 0.3) is None and claim.may_write


def test_an_arbitrator_appearing_later_stops_the_writing():
    claim = BusClaim(0.0, listen_s=0.0)
    assert claim.may_write and claim.beacon_due(0.0)
    assert claim.heard(*BEACON_BA, 3.0) is None and claim.may_write
    decision = claim.heard(*BEACON_BA, 3.5)
    assert decision.later and "stopped writing" in decision.message and not claim.may_write
    assert claim.tick(60.0) is None and not claim.may_write  # without take_back: for good


def test_taken_back_when_the_others_beacons_are_gone_five_intervals():
    claim = BusClaim(0.0, listen_s=0.0, take_back=True, jitter=lambda: 0.0)
    claim.heard(*BEACON_BA, 3.0)
    decision = claim.heard(*BEACON_BA, 3.5)
    assert decision.later and "read-only" in decision.message and "2.5 s" in decision.message
    for t in (4.0, 4.5, 5.0):  # it keeps beaconing: the bus stays its
        assert claim.heard(*BEACON_BA, t) is None and claim.tick(t + 0.4) is None
    assert claim.tick(7.4) is None  # 2.4 s since its last beacon
    assert claim.tick(7.6, caught_up=False) is None  # frames still waiting: not judged
    back = claim.tick(7.6)
    assert back.phase is Phase.ARBITRATING and back.taken_back and claim.may_write
    assert "2.6 s" in back.message and claim.beacon_due(7.6)


def test_two_arbitrators_that_stepped_aside_for_each_other_do_not_come_back_together():
    """Buses joined: each heard the other and stepped aside; their random waits differ, so
    one takes the bus back first, beacons, and the other stays aside."""
    waits = iter([0.1, 0.9])
    a, b = (BusClaim(0.0, listen_s=0.0, take_back=True, jitter=lambda: next(waits))
            for _ in range(2))
    for claim in (a, b):
        claim.heard(*BEACON_BA, 1.0)
        assert claim.heard(*BEACON_BA, 1.5).later
    assert 2.5 <= a.take_back_wait_s < b.take_back_wait_s <= 5.0
    t = 1.5
    while not a.may_write:
        t += 0.01
        a.tick(t)
        assert b.tick(t) is None
    assert t - 1.5 == pytest.approx(a.take_back_wait_s, abs=0.02)
    for step in range(10):  # a beacons; b hears it and stays aside
        now = t + 0.5 * step
        assert b.heard(*BEACON_BA, now) is None and b.tick(now) is None and b.yielded


def test_every_single_mode_1_frame_is_a_stray_never_a_reason_to_leave():
    claim = BusClaim(0.0, listen_s=0.0, take_back=True)
    t = 0.0
    for aid, data in single_mode_1_frames():
        t += 2.0  # one at a time: never two beacons within three intervals
        decision = claim.heard(aid, data, t)
        if is_arbitrator_beacon(aid, data):  # told once no second came in time
            assert decision is None and isinstance(claim.lone_beacon(t + 1.6), Stray)
        else:
            assert isinstance(decision, Stray), (hex(aid), data.hex())
        assert claim.may_write and claim.tick(t) is None


def test_devices_beaconing_unheard_of_nodes_are_a_replaced_arbitrators_bus():
    claim = BusClaim(0.0, listen_s=1.0)
    claim.heard(*frame(Beacon(12)), 0.2)
    claim.heard(*frame(Beacon(5)), 0.4)
    claim.heard(*frame(BindRequest(3, 2, 2, 4)), 0.5)  # binding: not a bound device
    decision = claim.tick(1.0)
    assert decision.takeover == (5, 12) and "takes it over" in decision.message


def test_our_beacon_every_interval_never_in_a_burst():
    claim = BusClaim(0.0, listen_s=0.0)
    due = [t / 100 for t in range(0, 300) if claim.beacon_due(t / 100)]
    assert due == [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]
    assert claim.beacon_due(10.0) and not claim.beacon_due(10.1)  # after a stall: one


# -- on a bus ------------------------------------------------------------------------------------
class Tap:
    """Every frame on a virtual channel (a third bus object)."""

    def __init__(self, channel: str) -> None:
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.frames: list[can.Message] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.is_set():
            msg = self.bus.recv(0.05)
            if msg is not None:
                self.frames.append(msg)

    def close(self) -> None:
        self._stop.set()
        self._thread.join(2)
        self.bus.shutdown()


def test_a_second_arbitrator_on_a_settled_transradial_bus_sends_nothing():
    channel = unique_virtual_channel("pdcp-claim")
    first = open_sim_session("transradial", channel=channel)
    tap = Tap(channel)
    try:
        links = first.system().links
        sent_before = first.arbitrator.conn.sent
        states: list[ev.BusState] = []
        second = Arbitrator(open_can_bus("virtual", channel), name="second", listen_s=LISTEN_S)
        second.subscribe(lambda e: states.append(e) if isinstance(e, ev.BusState) else None)
        try:
            assert not second.wait_claimed(LISTEN_S + 2)
            assert second.yielded and second.bus_state == "yielded"
            time.sleep(3.0)  # a settled bus: beacons and data; the second stays silent
            assert second.conn.sent == 0
        finally:
            second.close()
        time.sleep(0.1)
        ours = first.arbitrator.conn.sent - sent_before
        mode1 = [m for m in tap.frames if m.arbitration_id >> 8 & 1]
        intrusion = len(mode1) - ours  # mode-1 frames the first arbitrator did not send
        assert intrusion == 0, f"{intrusion} intrusion frames"
        assert any(m.arbitration_id == 0x100 for m in mode1)  # the first one beacons
        assert [s.state for s in states] == ["yielded"]
        assert first.system().links == links and all(
            d.present for d in first.system().devices.values())
        assert first.host.bad_frames == 0  # devices take the arbitrator's beacon in stride
    finally:
        tap.close()
        first.close()


def test_a_session_and_the_cli_on_a_taken_bus_say_so_in_one_line(capsys):
    channel = unique_virtual_channel("pdcp-claim-cli")
    first = open_sim_session("thesis-test2", channel=channel)
    try:
        with pytest.raises(OtherArbitratorError, match="another bus arbitrator"):
            open_can_session(parse_bus_url(f"can:virtual:{channel}"))
        code = main(["arbitrator", "--bus", f"can:virtual:{channel}", "--seconds", "6"])
        out, err = capsys.readouterr()
        assert code == 1
        assert err.count("\n") == 1 and "another bus arbitrator is on this bus" in err
        assert main(["scan", "--bus", f"can:virtual:{channel}", "--json"]) == 1
        out, err = capsys.readouterr()
        assert out == "" and err.count("\n") == 1 and "another bus arbitrator" in err
    finally:
        first.close()


def _devices(channel: str, name: str) -> DeviceHost:
    system = load_prosthesis(name)
    host = DeviceHost(open_can_bus("virtual", channel),
                      [SimulatedDevice(d) for d in system.devices.values()], name="devices",
                      plugged=False)
    for device in system.devices.values():
        if device.present:
            host.plug(device.key)
    return host


def test_an_arbitrator_appearing_later_stops_ours_writing_at_once():
    channel = unique_virtual_channel("pdcp-claim-later")
    host = _devices(channel, "thesis-test2")
    ours = Arbitrator(open_can_bus("virtual", channel), name="ours", listen_s=0.6,
                      startup_quiet_s=0.2)
    states: list[ev.BusState] = []
    ours.subscribe(lambda e: states.append(e) if isinstance(e, ev.BusState) else None)
    other = BeaconingArbitrator(channel)
    try:
        assert ours.wait_claimed(3) and ours.wait_settled(10)
        assert sorted(ours.system().links) == sorted(TEST2_LINKS)
        other.start()  # it beacons every 500 ms: heard at its second beacon
        assert ours.wait_for(lambda: ours.yielded, 10.0)
        assert other.sent >= 2
        sent = ours.conn.sent
        with pytest.raises(Exception, match="not writing"):
            ours.reset_device(next(iter(ours.devices_present())))
        time.sleep(1.5)  # beacons, presence, duty cycle: nothing more is written
        assert ours.conn.sent == sent
        assert [s.state for s in states] == ["arbitrating", "yielded"]
        assert "stopped writing" in states[-1].message
    finally:
        other.close()
        ours.close()
        host.close()


def test_a_replaced_arbitrators_bus_is_taken_over_thesis_test_5():
    channel = unique_virtual_channel("pdcp-claim-takeover")
    host = _devices(channel, "thesis-test5")
    first = Arbitrator(open_can_bus("virtual", channel), name="first", startup_quiet_s=0.2)
    try:
        assert first.wait_settled(10)
        assert sorted(first.system().links) == sorted(TEST2_LINKS)
    finally:
        first.close()  # the arbitrator is replaced; the devices stay bound and beaconing
    tap = Tap(channel)
    new = Arbitrator(open_can_bus("virtual", channel), name="new", listen_s=LISTEN_S,
                     startup_quiet_s=0.2)
    try:
        assert new.wait_claimed(LISTEN_S + 2)
        assert "takes it over" in new.bus_message
        assert new.wait_settled(15)
        assert sorted(new.system().links) == sorted(TEST2_LINKS)
        resets = [m for m in tap.frames if m.arbitration_id >> 8 & 1
                  and bytes(m.data) == Reset(0).encode()[1]]
        assert resets  # the devices were reset and bound again
    finally:
        new.close()
        tap.close()
        host.close()


# -- our own frames handed back by an echoing bus (can:udp_multicast) -------------------------
def test_the_copy_of_our_own_frame_is_ours_however_late():
    claim = BusClaim(0.0, listen_s=0.0, own_echoes=True)
    beacon = frame(Beacon(0, mode=Mode.ARBITRATOR))
    for t in (0.0, 0.5, 1.0):
        assert claim.beacon_due(t)
        claim.sent(*beacon, t)
    claim.sent(*frame(Reset(0)), 0.0)
    assert claim.is_own_echo(*beacon, 0.01)  # on time
    assert claim.is_own_echo(*beacon, 9.0)  # 8.5 s late: still one of ours
    assert claim.is_own_echo(*frame(Reset(0)), 9.0)
    assert claim.is_own_echo(*beacon, 9.1)
    assert not claim.is_own_echo(*beacon, 9.2)  # a fourth copy of three beacons:
    assert claim.heard(*beacon, 9.2) is None  # someone else's: one beacon …
    decision = claim.heard(*beacon, 9.7)  # … and its next: another arbitrator
    assert isinstance(decision, Decision) and decision.later and not claim.may_write


def test_without_echoes_every_mode_1_frame_is_anothers():
    claim = BusClaim(0.0, listen_s=0.0)  # a bus that never hands our frames back
    claim.sent(*frame(Beacon(0, mode=Mode.ARBITRATOR)), 0.0)
    assert not claim.is_own_echo(*frame(Beacon(0, mode=Mode.ARBITRATOR)), 0.01)


def test_an_echo_that_never_came_masks_one_foreign_frame_at_most():
    beacon = frame(Beacon(0, mode=Mode.ARBITRATOR))
    claim = BusClaim(0.0, listen_s=0.0, own_echoes=True)
    claim.sent(*beacon, 0.0)  # its copy was lost
    assert claim.is_own_echo(*beacon, 1.0)  # taken for the lost copy
    assert not claim.is_own_echo(*beacon, 1.5)  # the other arbitrator's next beacon
    claim = BusClaim(0.0, listen_s=0.0, own_echoes=True)
    claim.sent(*beacon, 0.0)
    assert not claim.is_own_echo(*beacon, 31.0)  # outstanding for too long: forgotten
    assert not claim.is_own_echo(*frame(GetParameter(7, 9, 0)), 0.1)  # never sent


class LateEcho(can.BusABC):
    """A virtual bus that hands every frame it sends back to its own reader ``delay`` seconds
    later, as a loaded ``can:udp_multicast`` receiver does."""

    def __init__(self, channel: str, delay: float) -> None:
        self.inner = can.Bus(interface="virtual", channel=channel)
        self.delay = delay
        self._late: list[tuple[float, can.Message]] = []
        self._lock = threading.Lock()
        super().__init__(channel=channel)

    def send(self, msg, timeout=None):
        self.inner.send(msg, timeout)
        with self._lock:
            self._late.append((time.monotonic() + self.delay, msg))

    def _recv_internal(self, timeout):
        with self._lock:
            if self._late and self._late[0][0] <= time.monotonic():
                return self._late.pop(0)[1], False
        return self.inner.recv(min(timeout, 0.01) if timeout is not None else 0.01), False

    def shutdown(self):
        super().shutdown()
        self.inner.shutdown()


def test_an_arbitrator_is_not_scared_off_by_its_own_late_beacons():
    channel = unique_virtual_channel()
    bus = LateEcho(channel, delay=2.6)  # later than the connection's echo filter waits (2 s)
    tap = can.Bus(interface="virtual", channel=channel)
    with Arbitrator(bus, profile_layer=False, drop_own=True, listen_s=0.0) as arb:
        deadline = time.monotonic() + 4.0
        while time.monotonic() < deadline:
            assert not arb.yielded, arb.bus_message
            time.sleep(0.05)
        assert arb.bus_state == "arbitrating"
        # Another arbitrator beaconing every 500 ms: while copies of ours are on their way
        # its beacons may pass for them, but within a few of its beacons it is heard.
        aid, data = frame(Beacon(0, mode=Mode.ARBITRATOR))
        deadline = time.monotonic() + 8.0
        while not arb.yielded and time.monotonic() < deadline:
            tap.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))
            time.sleep(ARBITRATOR_BEACON_S)
        assert arb.yielded and "appeared" in arb.bus_message
    tap.shutdown()
