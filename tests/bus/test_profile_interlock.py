"""The profile layer's own changes hold the prosthesis still (reference §5's motion interlock).

Start-up implements a stored configuration and the hot-swap duty cycle makes links on a
prosthesis that may be worn: the devices feeding a terminal channel before or after are
suspended (bounded) before the first link write and released after the last; one that refuses
to hold still stops the plan before anything is written.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.api import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.transaction import INTERLOCK_MS
from pdcp_studio.model import parameters as P
from pdcp_studio.protocol import Release, SetParameter, Suspend
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
