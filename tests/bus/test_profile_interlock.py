"""The profile layer's own changes hold the prosthesis still (reference §5's motion interlock).

Start-up implements a stored configuration and the hot-swap duty cycle makes links on a
prosthesis that may be worn: the devices feeding a terminal channel before or after are
suspended (bounded) before the first link write and released after the last; one that refuses
to hold still stops the plan before anything is written.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.api import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.transaction import INTERLOCK_MS
from pdcp_studio.model import parameters as P
from pdcp_studio.protocol import GetParameter, Release, SetParameter, Suspend
from tests.road_rigs import FrameRecorder


def _link_writes(messages):
    """The writes that make a link carry data: an input given its source's node IDs, a
    channel's data enabled. (Cutting an input off when its source leaves — zeros — is the
    safe direction and needs no hold: the device that fed it is gone.)"""
    return [i for i, m in enumerate(messages)
            if isinstance(m, SetParameter) and (
                (m.param == P.IN_SOURCE_NODE_IDS and any(m.value))
                or (m.param == P.CH_DATA_ENABLED and m.value == b"\1"))]


def _held_around(msgs, writes):
    """Every link write happens while a device is held; the held are released after."""
    suspends = [i for i, m in enumerate(msgs) if isinstance(m, Suspend)]
    releases = [i for i, m in enumerate(msgs) if isinstance(m, Release)]
    assert suspends, "nothing was held"
    assert all(msgs[i].ms == INTERLOCK_MS for i in suspends)  # bounded: a dead PC frees it
    held: set[int] = set()
    write_at = set(writes)
    for i, m in enumerate(msgs):
        if isinstance(m, Suspend):
            held.add(m.node_id)
        elif isinstance(m, Release):
            held.discard(m.node_id)
        elif i in write_at:
            assert held, f"link write {m} while nothing was held"
    assert not held, f"never released: {held}"
    return {msgs[i].node_id for i in suspends}, {msgs[i].node_id for i in releases}


@contextmanager
def recorded(prosthesis: str) -> Iterator[tuple[object, FrameRecorder]]:
    """A simulated prosthesis on a virtual channel of its own, every frame recorded."""
    channel = unique_virtual_channel("profile-hold")
    recorder = FrameRecorder(channel)
    try:
        session = open_session(prosthesis, channel=channel)
        try:
            yield session, recorder
        finally:
            session.close()
    finally:
        recorder.close()


def test_start_up_holds_the_devices_feeding_terminal_channels_while_it_links():
    with recorded("sim:thesis-test2") as (session, recorder):
        assert session.system().links  # start-up autoconfigured appendix D's links
        time.sleep(0.1)
        msgs = recorder.messages()
        writes = _link_writes(msgs)
        assert writes
        held, released = _held_around(msgs, writes)
        assert held <= released  # every held device was let go again


def test_a_hot_swap_repair_holds_the_feeders_then_releases_them():
    with recorded("sim:thesis-test4") as (session, recorder):
        recorder.caught_up()  # start-up's last frames are in, not counted as the swap's
        start = len(recorder.messages())
        assert session.run_script("hot-swap").ok
        time.sleep(0.1)
        msgs = recorder.messages()[start:]
        writes = _link_writes(msgs)
        assert writes, "the duty cycle made no link"
        held, released = _held_around(msgs, writes)
        assert held <= released


def test_a_device_that_will_not_hold_still_stops_the_repair_before_any_write():
    errors: list[str] = []
    with recorded("sim:thesis-test4") as (session, recorder):
        assert session.wait_settled(10)
        before = session.system().links
        for key in session.host.keys():  # the new part too: nobody holds still
            session.host.call(lambda k=key: setattr(session.host.device(k), "refuse_suspend",
                                                    True))
        session.subscribe(
            lambda e: errors.append(e.message) if isinstance(e, ev.BusError) else None)
        recorder.caught_up()
        start = len(recorder.messages())
        session.run_script("hot-swap")  # ends without the repair: nobody would hold still
        time.sleep(0.2)
        msgs = recorder.messages()[start:]
        assert not _link_writes(msgs), "a link was written with a device not held"
        assert any("not written" in e and "did not suspend" in e for e in errors), errors
        assert session.system().links == before  # no replacement link was made


def test_a_plan_cut_off_by_closing_the_session_is_no_error(caplog):
    """Closing a session while the profile layer writes (a duty-cycle repair on a busy
    machine) stops the plan quietly: no warning for the writes and releases the closed bus
    refuses, and the result says the bus was closed."""
    import logging

    from pdcp_studio.engine.modes import plan_clear

    with recorded("sim:thesis-test4") as (session, _recorder):
        arb = session.arbitrator
        plan = plan_clear(arb.system())
        assert plan.actions
        arb.close()
        with caplog.at_level(logging.WARNING):
            result = arb.profile.apply_plan(plan)
    assert result.status.value == "failed"
    assert "the bus was closed after 0 of" in result.reason
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text


# -- issue 28 item 8: read back before release, renewed, and said in Bus events -----------------
def _read_back_then_released(msgs, writes):
    """After the last link write and before the held devices are let go, the inputs are read
    back (Source's Node Ids, Data Transfer Enabled): released after verify."""
    last_write = max(writes)
    releases = [i for i, m in enumerate(msgs) if isinstance(m, Release) and i > last_write]
    assert releases, "nothing released after the last write"
    reads = [i for i, m in enumerate(msgs[last_write:releases[0]], last_write)
             if isinstance(m, GetParameter)
             and m.param in (P.IN_SOURCE_NODE_IDS, P.CH_DATA_ENABLED)]
    assert reads, "the held devices were let go without reading the links back"


def _renewed(msgs):
    """A held device got its bounded suspension again before it was released."""
    counts: dict[int, int] = {}
    for m in msgs:
        if isinstance(m, Suspend):
            counts[m.node_id] = counts.get(m.node_id, 0) + 1
    return any(n >= 2 for n in counts.values())


def _own_plans(events):
    return [e for e in events if isinstance(e, ev.PlanApplied) and e.own]


def test_start_up_after_a_power_on_is_held_renewed_read_back_then_released_and_said(
        monkeypatch):
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.arbitrator.links import LinkWriter

    monkeypatch.setattr(Arbitrator, "interlock_renew_s", 0.005)  # renewals show in a short plan
    # After the reset, the plan's first link write waits (at most 5 s) until a held device
    # was suspended a second time: a slow bus, so the renewer's 5 ms turn comes inside the
    # hold however busy the machine (with two CPU burners the plan was once written before
    # the renewer thread ran at all). The renewal is still the renewer's own: without it the
    # write goes ahead after 5 s and the check below fails.
    suspended: dict[object, int] = {}
    renewed, pacing = threading.Event(), threading.Event()
    real_suspend, real_add = Arbitrator.suspend, LinkWriter.add

    def counted_suspend(self, key, ms=0):
        real_suspend(self, key, ms)
        suspended[key] = suspended.get(key, 0) + 1
        if suspended[key] >= 2:
            renewed.set()

    def paced_add(self, link):
        if pacing.is_set():
            pacing.clear()
            renewed.wait(5.0)
        real_add(self, link)

    monkeypatch.setattr(Arbitrator, "suspend", counted_suspend)
    monkeypatch.setattr(LinkWriter, "add", paced_add)
    with recorded("sim:thesis-test2") as (session, recorder):
        arb = session.arbitrator
        assert arb.wait_settled(20)
        events: list[object] = []
        arb.subscribe(events.append)
        recorder.caught_up()
        start = len(recorder.messages())
        suspended.clear()
        renewed.clear()
        pacing.set()
        arb.reset()  # every device resets and binds again: start-up as after a power-on
        assert arb.wait_for(lambda: bool(_own_plans(events)), 30.0)
        assert arb.wait_settled(20)
        recorder.caught_up()
        msgs = recorder.messages()[start:]
        writes = _link_writes(msgs)
        assert writes
        held, released = _held_around(msgs, writes)
        assert held <= released
        _read_back_then_released(msgs, writes)
        assert _renewed(msgs), "the suspension was never renewed"
        plan_event = next(e for e in _own_plans(events) if e.plan.mode == "startup")
        result = plan_event.result
        assert plan_event.plan.mode == "startup" and result.held and result.verified
        assert all(a.reason for a in plan_event.plan.actions)


def test_a_hot_swap_repair_is_read_back_before_release_and_said_in_bus_events():
    with recorded("sim:thesis-test4") as (session, recorder):
        events: list[object] = []
        session.arbitrator.subscribe(events.append)
        recorder.caught_up()
        start = len(recorder.messages())
        assert session.run_script("hot-swap").ok
        assert session.arbitrator.wait_for(lambda: bool(_own_plans(events)), 20.0)
        recorder.caught_up()
        msgs = recorder.messages()[start:]
        writes = _link_writes(msgs)
        assert writes, "the duty cycle made no link"
        _held_around(msgs, writes)
        _read_back_then_released(msgs, writes)
        plan_event = _own_plans(events)[-1]
        assert plan_event.plan.mode == "duty-cycle"
        assert plan_event.result.held and plan_event.result.verified
