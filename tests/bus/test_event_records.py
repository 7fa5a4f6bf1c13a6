"""Bus events, transactions' parts and the log limiter's records share their equality, hash
and repr (``protocol/records.py``, issue 11) and behave exactly as ``dataclass`` made them
before."""

from __future__ import annotations

import copy
import dataclasses

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus import log_limit
from pdcp_studio.bus import transaction as tr
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol.records import Record
from tests.protocol.test_records import _reference

REF = ChannelRef(2, 2, 4, 1)
EVENTS = [
    ev.DeviceJoined(DeviceKey(2, 2, 4)), ev.DeviceLeft(DeviceKey(2, 2, 4)),
    ev.DeviceReplaced(DeviceKey(2, 2, 4), DeviceKey(2, 2, 7)),
    ev.LinkMade(Link(REF, ChannelRef(2, 2, 5, 2))), ev.LinkRemoved(Link(REF, REF)),
    ev.FrameSeen(1.5, 0x123, b"\x01", "a frame"), ev.BusError("bad", "bad_frame"),
    ev.BusState("arbitrating", "ours"), ev.PlanApplied("a plan"),
    ev.TerminalsUnconnected((REF,), "why"), ev.TransactionDone("a result"),
    ev.ChannelValue(REF, 0.5, 2.0), ev.Progress(1, 3, "scan"),
]


def test_every_event_class_is_covered():
    assert {type(e) for e in EVENTS} == {c for c in vars(ev).values() if isinstance(c, type)
                                         and issubclass(c, Record) and c is not Record}


@pytest.mark.parametrize("event", EVENTS, ids=lambda e: type(e).__name__)
def test_repr_hash_and_equality_are_a_frozen_dataclasss(event):
    ref = _reference(event)
    assert repr(event) == repr(ref) and hash(event) == hash(ref)
    twin = copy.copy(event)
    assert twin == event and hash(twin) == hash(event) and event != ref
    with pytest.raises(dataclasses.FrozenInstanceError):
        event.anything = 1  # type: ignore[attr-defined]
    for f in dataclasses.fields(event):
        other = copy.copy(event)
        object.__setattr__(other, f.name, "something else")
        # (a field declared compare=False — a departure's words, a plan's result — is not
        # compared, exactly as dataclass leaves it out)
        assert (other != event) is f.compare


def test_an_unhashable_field_makes_the_event_unhashable_as_before():
    with pytest.raises(TypeError):
        hash(ev.PlanApplied(["a", "list"]))
    with pytest.raises(TypeError):
        hash(_reference(ev.PlanApplied(["a", "list"])))


LINK = Link(REF, ChannelRef(2, 2, 5, 2))
FROZEN = [tr.LinkAction("add", LINK, "why"), tr.ParameterWrite(DeviceKey(2, 2, 4), 3, 0, b"\x01"),
          tr.Policy(False), log_limit.Summary("bad_frame", 3, 1.0, "last")]
MUTABLE = [tr.Change("links", [tr.LinkAction("add", LINK)], policy=tr.Policy()),
           tr.TransactionResult(tr.Status.APPLIED, "apply", links_after=[LINK], notes=["n"]),
           log_limit._Kind(1.0, 2.0, 3)]


@pytest.mark.parametrize("obj", FROZEN, ids=lambda o: type(o).__name__)
def test_frozen_bus_records_behave_as_before(obj):
    ref = _reference(obj)
    assert repr(obj) == repr(ref) and hash(obj) == hash(ref)
    assert copy.copy(obj) == obj and obj != ref
    with pytest.raises(dataclasses.FrozenInstanceError):
        obj.anything = 1  # type: ignore[attr-defined]


@pytest.mark.parametrize("obj", MUTABLE, ids=lambda o: type(o).__name__)
def test_mutable_bus_records_compare_and_show_as_before_and_stay_unhashable(obj):
    ref = _reference(obj)
    assert repr(obj) == repr(ref)
    twin = copy.deepcopy(obj)
    assert twin == obj and obj != ref
    for f in dataclasses.fields(obj):
        setattr(twin, f.name, "something else")
        assert twin != obj
        setattr(twin, f.name, getattr(obj, f.name))
        assert twin == obj
    with pytest.raises(TypeError):
        hash(obj)
    with pytest.raises(TypeError):
        hash(ref)
