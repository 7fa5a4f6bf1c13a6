"""The change road in the arbitrator (reference §5): interlock, write, verify, restore, release.

Every test runs a real arbitrator and simulated devices on a python-can virtual bus; a frame
recorder listens on the same channel as any other node would.
"""

from __future__ import annotations

import threading
import time

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.api import BusSession, open_session, preview_change
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.transaction import (
    INTERLOCK_MS,
    Change,
    LinkAction,
    ParameterWrite,
    Policy,
    Status,
    TransactionResult,
)
from pdcp_studio.errors import TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import Release, SetParameter, Suspend
from pdcp_studio.storage.history import History
from tests.road_rigs import FrameRecorder

D1, D2, D3 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5), DeviceKey(2, 2, 6)
JOY = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))
BAR = Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 6, 1))
LED = Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 6, 2))
LINK_PARAMS = {P.CH_DATA_ENABLED, P.IN_SOURCE_NODE_IDS, P.IN_SOURCE_VID_PID,
               P.IN_SOURCE_SN_INDEX, P.IN_SOURCE_TYPE_PROFILE}


@pytest.fixture
def rig():
    channel = unique_virtual_channel("road-tx")
    recorder = FrameRecorder(channel)
    session = open_session("sim:thesis-test2", channel=channel)
    try:
        yield session, recorder
    finally:
        session.close()
        recorder.close()


def _link_writes(messages):
    return [i for i, m in enumerate(messages)
            if isinstance(m, SetParameter) and m.param in LINK_PARAMS]


def test_every_transport_implements_the_declared_session(rig):
    from pdcp_studio.bus.hostlink.client import HostLinkSession
    from pdcp_studio.bus.session.in_process import Session
    from pdcp_studio.bus.session.sim import SimSession

    session, _ = rig
    assert isinstance(session, BusSession)
    for cls in (Session, SimSession, HostLinkSession):
        for name in ("carry_out", "transact", "apply_plan", "read_policy", "system",
                     "read_configuration", "write_configuration", "save_configuration",
                     "subscribe", "preview", "scan", "close"):
            assert callable(getattr(cls, name)), (cls, name)


def test_interlock_suspends_before_the_first_link_write_and_releases_after_the_last(rig):
    session, recorder = rig
    start = len(recorder.messages())
    result = session.transact(Change.from_plan(session.preview("clear")), record=False)
    assert result.status is Status.APPLIED and result.verified, result.summary()
    time.sleep(0.1)
    msgs = recorder.messages()[start:]
    suspends = [i for i, m in enumerate(msgs) if isinstance(m, Suspend)]
    releases = [i for i, m in enumerate(msgs) if isinstance(m, Release)]
    writes = _link_writes(msgs)
    assert writes and suspends and releases
    assert suspends[0] < writes[0] and writes[-1] < releases[-1]
    assert all(msgs[i].ms == INTERLOCK_MS for i in suspends)
    # The control unit feeds the LED board's terminal inputs: it is the one held.
    assert result.held == [D2] and result.interlock == "held 1 device"
    assert {msgs[i].node_id for i in suspends} == {session.arbitrator.node_id_of(D2)}


def test_a_device_that_refuses_to_suspend_stops_the_change_before_any_write(rig):
    session, recorder = rig
    session.host.call(lambda: setattr(session.host.device(D2), "refuse_suspend", True))
    start = len(recorder.messages())
    result = session.transact(Change.from_plan(session.preview("clear")), record=False)
    assert result.status is Status.FAILED and result.step == "interlock"
    assert "2/2/5" in result.reason and "nothing was written" in result.reason
    assert result.interlock == "refused by 2/2/5"
    assert session.system().links == [JOY, BAR, LED]
    assert not _link_writes(recorder.messages()[start:])


def test_a_failed_write_is_rolled_back_and_names_the_step(rig, monkeypatch):
    session, _ = rig
    arb = session.arbitrator
    real = arb.requests.set
    calls = {"n": 0}

    def flaky(node_id, param, channel, value, **kw):
        calls["n"] += 1
        if calls["n"] == 6:  # in the middle of the second removal
            raise TransportError("no answer from the device (injected)")
        return real(node_id, param, channel, value, **kw)

    monkeypatch.setattr(arb.requests, "set", flaky)
    result = session.transact(Change.from_plan(session.preview("clear")), record=False)
    monkeypatch.setattr(arb.requests, "set", real)
    assert result.status is Status.ROLLED_BACK and result.step == "write"
    assert "injected" in result.reason and "restored" in result.reason
    assert sorted(session.system().links) == sorted([JOY, BAR, LED])
    assert sorted(result.links_after) == sorted(result.links_before)
    # and the devices agree with the model: every input listens again
    for link in (JOY, BAR, LED):
        assert session.get_parameter(link.input.device, P.CH_DATA_ENABLED,
                                     link.input.index) == b"\x01"


def test_a_mismatch_on_read_back_restores_the_stored_configuration(rig, monkeypatch):
    session, _ = rig
    before = session.read_configuration()
    saved = session.configuration_of_links()
    monkeypatch.setattr(session.arbitrator, "read_memory", lambda: before)
    result = session.carry_out(Change("config save", configuration=saved))
    monkeypatch.undo()
    assert result.status is Status.ROLLED_BACK and result.step == "verify"
    assert "does not verify" in result.reason
    assert session.read_configuration() == before


def test_the_suspension_is_renewed_while_a_long_change_runs(rig, monkeypatch):
    session, _ = rig
    arb = session.arbitrator
    monkeypatch.setattr(arb, "interlock_renew_s", 0.05)
    real = arb._do_link

    def slow(op, link):
        time.sleep(0.12)
        real(op, link)

    monkeypatch.setattr(arb, "_do_link", slow)
    device = session.host.device(D2)
    before = device.suspensions
    result = session.carry_out(Change.from_plan(session.preview("clear")))
    assert result.written
    assert device.suspensions - before >= 3  # the first Suspend plus renewals
    time.sleep(0.05)
    assert device.suspended_until is None  # released at the end


def test_a_simulated_device_holds_a_bounded_suspension_only_that_long(rig):
    session, _ = rig
    device = session.host.device(D2)
    session.arbitrator.suspend(D2, 150)
    assert device.suspended_until is not None
    time.sleep(0.3)
    assert session.host.call(lambda: (device._stream_tick(), device.suspended_until)[1]) is None


def test_an_impossible_change_fails_before_anything_is_written(rig):
    session, recorder = rig
    ghost = Link(ChannelRef(2, 2, 4, 1), ChannelRef(9, 9, 9, 1))
    start = len(recorder.messages())
    result = session.carry_out(Change("manual", links=[LinkAction("add", ghost)]))
    assert result.status is Status.FAILED and result.step == "preview"
    assert "nothing was written" in result.reason
    assert not [m for m in recorder.messages()[start:] if isinstance(m, Suspend | SetParameter)]


def test_a_parameter_write_is_verified_and_held(rig):
    session, _ = rig
    value = P.encode_value(P.device_parameter(P.DEVICE_BEACON_INTERVAL), 120)
    change = Change("set beacon interval", parameters=[ParameterWrite(D2, P.DEVICE_BEACON_INTERVAL,
                                                                      0, value)])
    result = session.carry_out(change)
    assert result.written and result.held == [D2]
    assert session.get_parameter(D2, P.DEVICE_BEACON_INTERVAL) == value


def test_transact_previews_asks_and_records(rig, tmp_path):
    session, _ = rig
    history = History(tmp_path / "h.sqlite3")
    seen = []
    change = Change.from_plan(session.preview("clear"))
    declined = session.transact(change, confirm=lambda p: seen.append(p) or False,
                                history=history)
    assert declined.status is Status.DECLINED and session.system().links == [JOY, BAR, LED]
    assert "- link 2/2/4#1 → 2/2/5#2" in "\n".join(seen[0].lines())
    assert history.entries() == []
    done = session.transact(change, confirm=lambda p: True, operator="A. Fitter",
                            patient="P-17", history=history)
    assert done.written and done.history_id == 1
    entry = history.get(1)
    assert entry["operator"] == "A. Fitter" and entry["patient"] == "P-17"
    assert entry["action"] == "apply clear" and entry["links_after"] == []
    assert [a["reason"] for a in entry["plan"]["actions"]] == ["clear: every link is removed"] * 3
    assert entry["interlock"] == "held 1 device" and entry["verified"] is True
    again = session.transact(change, history=history)  # nothing left to clear
    assert again.status is Status.NOTHING and len(history.entries()) == 1
    history.close()


def test_the_result_and_the_change_cross_the_host_link_as_json():
    change = Change("x", links=[LinkAction("add", JOY, "why")],
                    parameters=[ParameterWrite(D1, 10, 0, b"\x01\x02")],
                    policy=Policy(False))
    assert Change.from_json(change.to_json()).to_json() == change.to_json()
    result = TransactionResult(Status.ROLLED_BACK, "x", "verify", "because", [JOY], [JOY],
                               "0x1234", "0x1234", False, "held 1 device", [D2], [D1, D2],
                               Policy(True), Policy(True), 7, ["n"])
    assert TransactionResult.from_json(result.to_json()) == result


def test_preview_names_the_held_devices(rig):
    session, _ = rig
    preview = preview_change(session, Change.from_plan(session.preview("clear")))
    assert preview.held == [D2] and not preview.empty
    lines = preview.lines()
    held = next(ln for ln in lines if "held still" in ln)
    assert "Control unit board" in held and "2/2/5" not in held  # names in words
    assert any(ln.strip() == "held 2/2/5" for ln in lines)  # the code in the detail


def test_after_a_hot_swap_the_snapshot_agrees_with_the_devices():
    """Issue 8: the arbitrator's system after a hot-swap shows each channel's Data Transfer
    Enabled as the devices hold it (the app must take this snapshot, not patch its own)."""
    session = open_session("sim:thesis-test1")
    try:
        assert session.run_script("hot-swap").ok
        system = session.system()
        for key, device in system.devices.items():
            if not device.present:
                continue
            for ch in device.channels.values():
                real = session.get_parameter(key, P.CH_DATA_ENABLED, ch.index)
                assert ch.data_enabled == (real == b"\x01"), (key, ch.index)
        assert all(system.channel(lk.output).data_enabled and system.channel(lk.input).data_enabled
                   for lk in system.links)
    finally:
        session.close()


def test_transactions_and_the_duty_cycle_never_overlap(rig):
    """The transaction holds the plan lock: a hot-swap during it waits its turn."""
    session, _ = rig
    arb = session.arbitrator
    inside = threading.Event()
    real = arb._do_link

    def slow(op, link):
        inside.set()
        time.sleep(0.05)
        real(op, link)

    arb._do_link = slow
    try:
        t = threading.Thread(target=lambda: session.carry_out(
            Change.from_plan(session.preview("clear"))))
        t.start()
        assert inside.wait(5)
        assert not arb._state.wire_lock.acquire(timeout=0.01)
        t.join(10)
        assert arb._state.wire_lock.acquire(timeout=1)
        arb._state.wire_lock.release()
    finally:
        del arb._do_link


def test_transaction_events_reach_subscribers(rig):
    session, _ = rig
    got: list = []
    session.subscribe(got.append)
    session.carry_out(Change.from_plan(session.preview("clear")))
    time.sleep(0.05)
    assert [type(e) for e in got if isinstance(e, ev.LinkRemoved)] == [ev.LinkRemoved] * 3
    done = [e for e in got if isinstance(e, ev.TransactionDone)]
    assert len(done) == 1 and done[0].result.written


def test_single_edits_are_transactions_too(rig):
    """``add_link``/``remove_link``/``set_parameter`` on a session take the same road: held,
    verified; a refused edit is a ModelError and writes nothing."""
    from pdcp_studio.errors import ModelError

    session, recorder = rig
    start = len(recorder.messages())
    session.remove_link(JOY)
    msgs = recorder.messages()[start:]
    assert any(isinstance(m, Suspend) for m in msgs) and any(isinstance(m, Release) for m in msgs)
    assert JOY not in session.system().links
    with pytest.raises(ModelError):
        session.remove_link(JOY)
    with pytest.raises(ModelError):
        session.add_link(Link(ChannelRef(2, 2, 4, 1), ChannelRef(9, 9, 9, 1)))
    session.add_link(JOY)
    assert JOY in session.system().links


def test_a_rollback_beside_a_missing_part_leaves_every_output_sending_as_before(rig,
                                                                                monkeypatch):
    """The joystick still sends to the missing control unit; a change that links it to the
    LED board fails and is rolled back: taking that link out again must not turn the
    joystick's output off (it was on before the change)."""
    session, _ = rig
    arb = session.arbitrator
    session.host.call(lambda: session.host.unplug(D2))
    assert arb.wait_for(lambda: D2 not in arb.devices_present(), 20.0)
    assert session.get_parameter(D1, P.CH_DATA_ENABLED, 1) == b"\x01"
    new = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 6, 1))
    tx = arb.transactions
    monkeypatch.setattr(tx, "_verify", lambda change, after: ["injected mismatch"])
    result = session.transact(Change("add", links=[LinkAction("add", new)]), record=False)
    monkeypatch.undo()
    assert result.status is Status.ROLLED_BACK, result.summary()
    assert new not in session.system().links
    assert session.get_parameter(D1, P.CH_DATA_ENABLED, 1) == b"\x01"
