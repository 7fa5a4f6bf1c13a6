"""A replaced part is no longer missing (issue 26 item 6): on ``sim:transradial`` the hand is
unplugged and the spare plugged in; once the replacement goes through a verified transaction
the arbitrator forgets the hand, says "replaced by", and the fitting history records it."""

from __future__ import annotations

import time

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND
from pdcp_studio.bus.transaction import Change, ParameterWrite
from pdcp_studio.engine import configuration_from_system
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.storage.history import History, replaced_from_notes, replaced_note

KEY = {"vid": 2641, "pid": 769}


def _until(condition, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.05)
    return False


def _missing(system):
    return [k for k, d in system.devices.items() if not d.present]


def _stored_live(system):
    """The configuration of the links whose both ends are on the bus (as the wizard stores)."""
    live = system.copy()
    for link in list(live.links):
        if not (live.is_present(link.output) and live.is_present(link.input)):
            live.remove_link(link)
    return ConfigCollection([configuration_from_system(live)])


def _swap(session):
    session.unplug(HAND)
    assert _until(lambda: not session.system().devices[HAND].present)
    session.plug(SPARE_HAND)
    assert _until(lambda: SPARE_HAND in session.system().devices
                  and session.system().devices[SPARE_HAND].present)


@pytest.fixture
def heard():
    return []


def _last_entry():
    with History.open() as h:
        return h.entries()[-1]


def _replaced_and_recorded(session, result, heard):
    assert result.written and result.verified, result.summary()
    assert replaced_note(HAND, SPARE_HAND) in result.notes
    assert _missing(session.system()) == []
    assert HAND not in session.system().devices  # forgotten: nothing needs it now
    assert ev.DeviceReplaced(HAND, SPARE_HAND) in heard
    assert _last_entry()["replaced"] == [{"old": {**KEY, "serial": 301},
                                          "new": {**KEY, "serial": 302}}]


def test_replacements_through_the_transaction_leave_nothing_missing(heard):
    """No profile layer: the hand's links stay dead until ``apply replacements`` is written."""
    with open_session("sim:transradial", frame_events=False, profile_layer=False) as session:
        session.subscribe(heard.append)
        assert session.transact(Change.from_plan(session.preview("autoconfigure"))).written
        assert session.save_configuration().configurations
        _swap(session)
        assert _missing(session.system()) == [HAND]
        plan = session.preview("replacements")
        assert {a.op.value for a in plan.actions} == {"add", "remove"}
        _replaced_and_recorded(session, session.transact(Change.from_plan(plan)), heard)


def test_the_replace_wizards_change_leaves_nothing_missing(heard):
    """The duty cycle linked the spare on its own; the wizard's transaction stores the
    configuration naming it: then the hand is replaced, not missing."""
    with open_session("sim:transradial", frame_events=False) as session:
        session.subscribe(heard.append)
        assert session.save_configuration().configurations
        _swap(session)
        assert _until(lambda: sum(lk.input.device == SPARE_HAND
                                  for lk in session.system().links) == 3)
        assert _missing(session.system()) == [HAND]  # linked on its own: still missing
        change = Change("replace a part", configuration=_stored_live(session.system()))
        _replaced_and_recorded(session, session.transact(change), heard)


def test_a_configuration_stored_naming_the_old_part_keeps_it_missing(heard):
    with open_session("sim:transradial", frame_events=False) as session:
        session.subscribe(heard.append)
        assert session.save_configuration().configurations
        stored = session.read_configuration()
        _swap(session)
        assert _until(lambda: sum(lk.input.device == SPARE_HAND
                                  for lk in session.system().links) == 3)
        both = ConfigCollection([*stored.configurations,
                                 *_stored_live(session.system()).configurations])
        assert session.transact(Change("store both", configuration=both)).written
        assert _missing(session.system()) == [HAND]
        assert not any(isinstance(e, ev.DeviceReplaced) for e in heard)


def test_a_change_that_is_not_the_replacement_leaves_the_part_missing(heard):
    with open_session("sim:transradial", frame_events=False) as session:
        session.subscribe(heard.append)
        assert session.save_configuration().configurations
        _swap(session)
        assert _until(lambda: sum(lk.input.device == SPARE_HAND
                                  for lk in session.system().links) == 3)
        value = P.encode_value(P.device_parameter(P.DEVICE_BEACON_INTERVAL), 120)
        result = session.transact(Change("set beacon interval", parameters=[
            ParameterWrite(SPARE_HAND, P.DEVICE_BEACON_INTERVAL, 0, value)]))
        assert result.ok, result.summary()
        assert _missing(session.system()) == [HAND]
        assert not any(isinstance(e, ev.DeviceReplaced) for e in heard)


def test_the_history_reads_the_replaced_parts_from_the_notes():
    notes = ["held 1 device", replaced_note(HAND, SPARE_HAND)]
    assert replaced_from_notes(notes) == [{"old": {**KEY, "serial": 301},
                                           "new": {**KEY, "serial": 302}}]
    assert replaced_from_notes([]) == []
