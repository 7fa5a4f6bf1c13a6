"""The arbitrator's parts decide from ``now`` and frames, without threads or a bus (issue 10
item 7): the node table's bind decisions, the presence tracker's verdicts, the link writer's
writes, the profile driver's timing and the device reader shared by set-up and scan."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.arbitrator.common import (
    BEACON_WINDOW,
    BIND_HOLD_S,
    DUPLICATE_WINDOW,
    ECHOES_FOR_TWIN,
    FOREIGN_HOLD_S,
    MISSED_BEACONS,
    PRESENCE_GRACE,
    RESET_GRACE_S,
    SILENT_BUS_FACTOR,
    SILENT_BUS_S,
    UNKNOWN_RESET_S,
    _Node,
)
from pdcp_studio.bus.arbitrator.links import (
    link_writes,
    needs_remaking,
    unlink_writes,
    wanted_source,
)
from pdcp_studio.bus.arbitrator.nodes import BindDecision, NodeTable
from pdcp_studio.bus.arbitrator.presence import PresenceTracker
from pdcp_studio.bus.arbitrator.profile.driver import ProfileDriver
from pdcp_studio.bus.arbitrator.reading.device_reader import EVERYTHING, SETUP, DeviceReader
from pdcp_studio.bus.arbitrator.reading.requests import DeviceRefusedError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import NO_SOURCE, Channel, Device, Link, SourceInfo
from pdcp_studio.protocol import Beacon, BindRequest, GetParameterResponse, ResponseCode

K4, K5 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5)


def ask(key: DeviceKey, node_id: int) -> BindRequest:
    return BindRequest(node_id, key.vid, key.pid, key.serial)


def bind(table: NodeTable, key: DeviceKey, node_id: int, now: float = 0.0) -> _Node:
    decision = table.decide_bind(ask(key, node_id), now)
    assert decision.kind == "grant", decision
    node, _ = table.install(key, node_id, now, 0.1)
    node.set_up = True
    return node


# -- the node table -----------------------------------------------------------------------------
def test_a_free_id_is_granted_a_taken_one_suggests_the_lowest_free_held_a_while():
    table = NodeTable(1, 254)
    assert table.decide_bind(ask(K4, 7), 0.0) == BindDecision("grant", K4, 7, 7)
    suggestion = table.decide_bind(ask(K5, 7), 0.0)
    assert suggestion == BindDecision("suggest", K5, 7, 1)
    assert table.held == {K5: 0.0} and not table.pool.is_free(1)
    assert table.decide_bind(ask(K5, 7), 0.5).node_id == 1  # asks again: still its
    table.expire(0.5 + BIND_HOLD_S + 0.1)
    assert table.pool.is_free(1) and not table.held  # not taken up: back to the pool
    assert table.decide_bind(ask(K5, 1), 3.0) == BindDecision("grant", K5, 1, 1)


def test_no_free_id_is_said_once_per_device():
    table = NodeTable(1, 2)
    bind(table, K4, 1)
    bind(table, DeviceKey(2, 2, 9), 2)
    first = table.decide_bind(ask(K5, 1), 0.0)
    assert first.kind == "exhausted" and "cannot bind" in first.report
    assert table.decide_bind(ask(K5, 1), 0.1).report == ""  # its retries are not reported


def test_a_set_up_device_asking_again_is_deferred_for_its_twins_beacon():
    table = NodeTable(1, 254)
    node = bind(table, K4, 7)
    assert table.on_bind_request(ask(K4, 7), 1.0, set()).kind == "defer"
    assert table.resolve_deferred(1.01, set()) == []  # the window is still open
    node.last_beacon = 1.05  # the bound one beacons meanwhile: two devices, one key
    assert table.resolve_deferred(1.06, set()) == [(ask(K4, 7), True)]
    assert table.on_bind_request(ask(K4, 7), 2.0, {K4}).kind == "ignore"  # the twin
    table.on_bind_request(ask(K4, 7), 3.0, set())  # silence: it restarted
    deadline = 3.0 + DUPLICATE_WINDOW * node.beacon_interval
    assert table.resolve_deferred(deadline - 0.01, set()) == []
    assert table.resolve_deferred(deadline, set()) == [(ask(K4, 7), False)]


def test_an_id_heard_from_elsewhere_stays_out_of_the_pool_while_heard():
    table = NodeTable(1, 254)
    assert table.is_foreign(Beacon(3).encode()[0])
    table.hear_foreign(3, 0.0)
    assert table.decide_bind(ask(K5, 3), 0.1).kind == "grant"  # that very device, reset
    table.hear_foreign(4, 0.0)
    assert table.decide_bind(ask(K4, 3), 0.2) == BindDecision("suggest", K4, 3, 1)
    table.expire(FOREIGN_HOLD_S / 2)
    assert not table.pool.is_free(4)
    table.expire(FOREIGN_HOLD_S + 0.1)
    assert table.pool.is_free(4)
    assert not table.is_foreign(ask(K4, 5).encode()[0])  # a bind request is nobody's yet


def test_outputs_share_the_pool_and_leave_with_their_device():
    table = NodeTable(1, 4)
    node = bind(table, K4, 1)
    ids, refused, why = table.give_outputs(K4, [1, 2, 3, 4])
    assert ids == {1: 2, 2: 3, 3: 4} and refused == [4] and "node IDs are in use" in why
    assert table.channel_ids[3] == ChannelRef(2, 2, 4, 2) and 3 in table.channel_set
    assert not table.is_foreign(Beacon(3).encode()[0])  # an output's ID is not a stranger
    assert table.remove(node) and table.pool.free_count == 4 and not table.channel_ids
    assert not table.remove(node)  # once


# -- the presence tracker -----------------------------------------------------------------------
def test_a_device_is_gone_after_its_missed_beacons_at_now():
    presence = PresenceTracker()
    node = _Node(K4, 7, last_seen=10.0, beacon_interval=0.1)
    limit = 0.1 * (MISSED_BEACONS + PRESENCE_GRACE)
    assert presence.absent([node], 10.0 + limit - 0.01, by_bus=False) == []
    assert [g.node for g in presence.absent([node], 10.0 + limit + 0.01, by_bus=False)] \
        == [node]


def _part(node_id: int, last_seen: float, last_bus: float, beacons: tuple[float, float] = (),
          interval: float = 0.5) -> _Node:
    node = _Node(DeviceKey(2, 2, node_id), node_id, last_seen=last_seen,
                 beacon_interval=interval, last_bus=last_bus)
    if beacons:
        node.prev_beacon_bus, node.last_beacon_bus = beacons
    return node


def test_presence_is_judged_by_the_bus_not_by_a_starved_clock():
    """Issue 28 item 6: a part leaves only after missed beacons measured against frames
    actually received (their bus times), never because the checker or the reader was not
    scheduled."""
    presence = PresenceTracker()
    limit = 0.5 * (MISSED_BEACONS + PRESENCE_GRACE)  # 1.75 s
    # The process was starved for 3 s: by the clock the part is long silent, but no other
    # part beaconed since its last beacon (bus time 1000.0): not gone.
    node = _part(7, last_seen=10.0, last_bus=1000.0, beacons=(999.5, 1000.0))
    other = _part(8, last_seen=13.0, last_bus=1000.2, beacons=(999.7, 1000.2))
    assert presence.absent([node, other], 13.0, smooth_s=0.5) == []
    # A backlog handled late, or a sender starved mid-burst: the other beaconed once past
    # the deadline (one overdue beacon sent first) — not yet evidence.
    other = _part(8, last_seen=13.0, last_bus=1002.0, beacons=(1000.2, 1002.0))
    assert presence.absent([node, other], 13.0, smooth_s=0.5) == []
    # The other beaconed twice past its deadline: the bus moved on; gone, saying why.
    other = _part(8, last_seen=13.0, last_bus=1002.4, beacons=(1001.9, 1002.4))
    gone = presence.absent([node, other], 13.0, smooth_s=0.5)
    assert [g.node for g in gone] == [node]
    assert gone[0].why.startswith("no beacon for 1.9 s, 3 beacon intervals"), gone[0].why
    assert "other parts beaconed on" in gone[0].why
    assert gone[0].silent_s == pytest.approx(1.9)
    assert limit < gone[0].silent_s


def test_a_bus_gone_quiet_still_loses_its_parts_after_a_long_silence_of_a_running_checker():
    presence = PresenceTracker()
    node = _part(7, last_seen=10.0, last_bus=1000.0, beacons=(999.5, 1000.0))
    quiet = max(SILENT_BUS_FACTOR * 0.5 * (MISSED_BEACONS + PRESENCE_GRACE), SILENT_BUS_S)
    assert presence.absent([node], 10.0 + quiet - 0.1, smooth_s=60.0) == []
    assert presence.absent([node], 10.0 + quiet + 0.1, smooth_s=1.0) == []  # it stalled
    gone = presence.absent([node], 10.0 + quiet + 0.1, smooth_s=60.0)
    assert [g.node for g in gone] == [node] and "no other part beaconed" in gone[0].why


def test_twins_beacon_twice_as_often():
    presence = PresenceTracker()
    node = _Node(K4, 7, 0.0, beacon_interval=0.1, set_up=True)
    verdicts = [presence.beacon(node, t * 0.1) for t in range(BEACON_WINDOW + 1)]
    assert not any(verdicts)  # one beacon an interval: alone
    verdicts = [presence.beacon(node, 1.0 + t * 0.05) for t in range(2 * BEACON_WINDOW + 1)]
    assert any("beacons" in v for v in verdicts)
    assert presence.beacon(node, 5.0, caught_up=False) == ""  # after a backlog: no verdict


def test_twins_answer_each_request_twice():
    presence = PresenceTracker()
    node = _Node(K4, 7, 0.0)
    aid, data = GetParameterResponse(7, ResponseCode.SUCCESS, 1, 0, b"\x01").encode()
    whys = []
    for n in range(ECHOES_FOR_TWIN):
        node.last_request = n + 0.0
        assert presence.response(node, aid, data, n + 0.01, 0.2) == (False, "")
        echo, why = presence.response(node, aid, data, n + 0.02, 0.2)
        assert echo
        whys.append(why)
    assert whys[-1] == "node 7 answers requests twice" and not any(whys[:-1])
    presence.report(K4, whys[-1])
    assert K4 in presence.duplicates


def test_strangers_are_reset_at_most_once_a_second_and_shown_once():
    presence = PresenceTracker()
    assert presence.may_reset_stranger(9, 0.0)
    assert not presence.may_reset_stranger(9, UNKNOWN_RESET_S / 2)
    assert presence.may_reset_stranger(9, UNKNOWN_RESET_S)
    assert [presence.bad_stranger_frame(9, 0.0) for _ in range(3)] == ["show", "count", "count"]
    presence.forget([20, 21], 10.0)  # a reset: 20 and 21 were our outputs
    assert presence.bad_stranger_frame(20, 10.5) == "stale"
    assert presence.bad_stranger_frame(20, 10.0 + RESET_GRACE_S + 0.1) == "show"
    assert presence.stale_data_frames == 1 and presence.may_reset_stranger(9, 10.0)


# -- the link writer ----------------------------------------------------------------------------
LINK = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 6, 2))
OUT = Channel(1, Direction.OUTPUT, 0x5001, 0x2220)


def test_what_to_write_for_a_link_on_a_fresh_input():
    want = wanted_source(LINK, OUT)
    assert want == SourceInfo(2, 2, 4, 1, 0x5001, 0x2220)
    writes = link_writes(LINK, 12, 10, 11, NO_SOURCE, want)
    assert [(w.node_id, w.param, w.channel) for w in writes] == [
        (12, P.IN_SOURCE_NODE_IDS, 2), (12, P.IN_SOURCE_VID_PID, 2),
        (12, P.IN_SOURCE_SN_INDEX, 2), (12, P.IN_SOURCE_TYPE_PROFILE, 2),
        (12, P.CH_DATA_ENABLED, 2), (10, P.CH_DATA_ENABLED, 1)]
    assert writes[0].value == bytes([10, 11])
    assert [w.then for w in writes] == ["", "", "", "source", "input_on", "output_on"]


def test_an_input_that_knows_its_source_gets_only_the_node_ids():
    want = wanted_source(LINK, OUT)
    writes = link_writes(LINK, 12, 10, 11, want, want)
    assert [(w.param, w.then) for w in writes] == [
        (P.IN_SOURCE_NODE_IDS, "source"), (P.CH_DATA_ENABLED, "input_on"),
        (P.CH_DATA_ENABLED, "output_on")]


def test_what_to_write_to_undo_a_link():
    both = unlink_writes(LINK, 12, 10)
    assert [(w.node_id, w.param) for w in both] == [
        (12, P.CH_DATA_ENABLED), (12, P.IN_SOURCE_NODE_IDS), (12, P.IN_SOURCE_VID_PID),
        (12, P.IN_SOURCE_SN_INDEX), (12, P.IN_SOURCE_TYPE_PROFILE), (10, P.CH_DATA_ENABLED)]
    assert both[-2].then == "input_cleared" and both[-1].value == b"\0"
    assert [w.node_id for w in unlink_writes(LINK, None, 10)] == [10]  # input has another
    assert unlink_writes(LINK, None, None) == []


def test_a_link_lost_in_an_outage_is_seen_in_what_the_input_reads_back():
    assert not needs_remaking(10, 11, bytes([10, 11]), b"\x01")
    assert needs_remaking(10, 11, bytes([10, 11]), b"\x00")
    assert needs_remaking(10, 11, b"\0\0", b"\x01")


# -- the profile driver's timing ----------------------------------------------------------------
def driver(now: float = 0.0, listen_until: float = 0.0) -> ProfileDriver:
    return ProfileDriver(None, now, quiet_s=0.5, duty_quiet_s=0.05,  # type: ignore[arg-type]
                         max_wait_s=10.0, listen_until=listen_until)


def test_start_up_waits_for_quiet_binding_but_not_for_ever():
    profile = driver()
    assert profile.startup_due(0.4, False, False, True) == ""
    assert profile.startup_due(0.5, False, False, True) == "due"
    assert profile.startup_due(0.6, False, False, False) == ""  # frames still to handle
    profile.last_bind = 3.0
    assert profile.startup_due(3.4, False, False, True) == ""
    assert profile.startup_due(9.0, True, False, True) == ""  # binding goes on
    assert profile.startup_due(10.0, True, False, True) == "late"  # … too long
    assert profile.startup_due(10.0, True, True, True) == ""  # but not mid-set-up
    assert driver(listen_until=2.0).startup_due(1.0, False, False, True) == ""  # listening


def test_the_duty_cycle_follows_changes_after_start_up():
    profile = driver()
    profile.duty_needed = True
    assert not profile.duty_due(1.0, False)  # start-up first
    profile.startup_done, profile.last_change = True, 1.0
    assert not profile.duty_due(1.01, False) and profile.duty_due(1.05, False)
    assert not profile.duty_due(2.0, True)
    profile.restart(3.0)
    assert not profile.startup_done and not profile.duty_needed and profile.started == 3.0


def _driver_on(state: object) -> ProfileDriver:
    """A profile driver on ``state`` whose other ports do nothing (policy: unreadable)."""
    from pdcp_studio.bus.arbitrator.profile.driver import ProfilePorts

    def no_policy() -> object:
        raise OSError("no memory in this test")

    profile = ProfileDriver(ProfilePorts(  # type: ignore[arg-type]
        state=state, add_link=lambda link: None, remove_link=lambda link: None,
        interlock=None, read_memory=list, read_policy=no_policy,
        error=lambda *a: None, emit=lambda event: None, closed=lambda: False, name="test"),
        0.0, quiet_s=0.5, duty_quiet_s=0.05, max_wait_s=10.0, listen_until=0.0)
    profile.startup_done, profile.duty_needed = True, True
    return profile


def test_a_duty_cycle_under_way_is_not_settled_before_its_plan_is_written():
    """From the moment the duty cycle takes what it owes until it is done, the bus is not
    settled: a script waiting for "settled" once closed the session between the two (the
    duty cycle was still planning, under two CPU burners) and its plan was never written."""
    from pdcp_studio.bus.arbitrator.state import SystemState

    state = SystemState()
    seen: list[bool] = []
    profile = _driver_on(state)
    assert not profile.settled(True)  # a duty cycle is owed

    taken = state.snapshot

    def snapshot_while_planning() -> object:
        seen.append(profile.settled(True))  # what a waiting script sees while it plans
        return taken()

    state.snapshot = snapshot_while_planning  # type: ignore[method-assign]
    profile.run_duty_cycle()
    assert seen == [False]
    assert profile.settled(True) and profile.plan_running == 0  # and settled once done


def test_a_duty_cycle_whose_plan_fails_leaves_what_it_owes_owed(monkeypatch):
    """A plan that could not be made writes nothing and forgets nothing: the channels that
    left are planned for at the next join or leave; the bus is not left looking busy."""
    import pdcp_studio.engine as engine
    from pdcp_studio.bus.arbitrator.state import SystemState

    profile = _driver_on(SystemState())
    owed = {ChannelRef(2, 2, 5, 1)}
    profile.last_present = set(owed)

    def fails(*args: object, **kwargs: object) -> None:
        raise RuntimeError("the plan could not be made")

    monkeypatch.setattr(engine, "plan_duty_cycle", fails)
    with pytest.raises(RuntimeError):
        profile.run_duty_cycle()
    assert profile.last_present == owed and profile.plan_running == 0


# -- one device reader for set-up and scan -------------------------------------------------------
class TableDevice:
    """A device's parameter table answering Get Parameter (refusing what it lacks)."""

    def __init__(self, device: Device, lacks: set[tuple[int, int]] = frozenset()) -> None:
        self.table = param_fields.parameter_table(device)
        self.lacks = lacks
        self.asked: list[tuple[int, int, bool]] = []

    def get(self, node_id: int, param: int, channel: int, *, timeout: float | None = None,
            bulk_first: bool = False) -> bytes:
        self.asked.append((param, channel, bulk_first))
        if (param, channel) in self.lacks or (param, channel) not in self.table:
            raise DeviceRefusedError(f"parameter {param} of channel {channel} refused")
        return self.table[param, channel]


def _device() -> Device:
    device = Device(2, 2, 4, descriptor="Sensor", beacon_interval=200)
    device.add_channel(Channel(1, Direction.OUTPUT, 0x5001, 0x2220, node_id=9,
                               data_enabled=True))
    device.add_channel(Channel(2, Direction.INPUT, terminal_profile=0x3000,
                               source=SourceInfo(2, 2, 5, 1, 0x5001, 0x2220)))
    return device


@pytest.mark.parametrize("what", [SETUP, EVERYTHING], ids=["set-up", "scan"])
def test_the_reader_reads_what_it_is_told_and_the_mapping_builds_the_device(what):
    device = _device()
    bus = TableDevice(device, lacks={(P.DEVICE_EAN_HIGH, 0)})
    reader = DeviceReader(bus, descriptor_bulk=what is EVERYTHING)
    values: param_fields.Values = {}
    reader.read_device(K4, 7, what, values)
    assert reader.identity_problem(K4, 7, values) == ""
    reader.read_channels(K4, 7, what, values)
    assert len(bus.asked) == what.count([Direction.OUTPUT, Direction.INPUT])
    assert values[P.DEVICE_EAN_HIGH, 0] is None  # refused: left at its default
    assert ((P.DEVICE_DESCRIPTOR, 0, True) in bus.asked) == (what is EVERYTHING)
    built = param_fields.device_from_values(K4, values, node_id=7)
    assert (built.descriptor, built.beacon_interval) == ("Sensor", 200)
    assert built.channels[2].source == device.channels[2].source
    assert built.channels[2].terminal_profile == 0x3000
    if what is SETUP:  # not the bus-session values the set-up sets itself
        assert (P.OUT_NODE_ID, 1) not in values and (P.CH_DATA_ENABLED, 1) not in values
    else:
        assert built.channels[1].node_id == 9 and built.channels[1].data_enabled


def test_the_reader_names_a_device_that_answers_as_another():
    bus = TableDevice(_device())
    reader = DeviceReader(bus)
    values: param_fields.Values = {}
    reader.read_device(K5, 7, SETUP, values)
    assert reader.identity_problem(K5, 7, values) == "node 7 answered as 2/2/4, not 2/2/5"
    problems: list[str] = []
    values[P.DEVICE_CHANNEL_COUNT, 0] = b"\x01"
    bus.table[P.CH_TRANSFER_TYPE, 1] = b"\x07"
    reader.read_channels(K5, 7, SETUP, values, problems.append)
    assert problems and "neither input" in problems[0]


def test_a_first_start_up_with_every_expected_device_does_not_wait_out_the_quiet_time():
    """A simulated prosthesis knows its parts: once they have all joined and nothing is
    being set up, start-up is due at once; a restart waits the quiet time again."""
    from pdcp_studio.bus.arbitrator.profile.driver import ProfileDriver
    from pdcp_studio.model.refs import DeviceKey

    a, b = DeviceKey(1, 1, 1), DeviceKey(1, 1, 2)
    driver = ProfileDriver(None, 0.0, quiet_s=0.2, duty_quiet_s=0.1, max_wait_s=10.0,  # type: ignore[arg-type]
                           listen_until=0.0)
    driver.last_bind = 0.05
    assert driver.startup_due(0.1, False, False, True, {a, b}) == ""  # nothing expected
    driver.expect({a, b})
    assert driver.startup_due(0.1, False, False, True, {a}) == ""  # b has not joined
    assert driver.startup_due(0.1, True, False, True, {a, b}) == ""  # still setting up
    assert driver.startup_due(0.1, False, False, False, {a, b}) == ""  # frames unread
    assert driver.startup_due(0.1, False, False, True, {a, b}) == "due"
    driver.restart(1.0)
    assert driver.startup_due(1.1, False, False, True, {a, b}) == ""  # quiet time again
    assert driver.startup_due(1.25, False, False, True, {a, b}) == "due"
