"""Messages share their equality, hash and repr (``protocol/records.py``,
issue 11) and behave exactly as ``dataclass(frozen=True)`` made them before: each instance is
compared with one of a plain frozen dataclass of the same fields."""

from __future__ import annotations

import copy
import dataclasses
from typing import Any

import pytest

from pdcp_studio.protocol import (
    MESSAGE_TYPES,
    Beacon,
    BindRequest,
    BindResponse,
    BulkData,
    BulkDataResponse,
    ChannelData,
    ConfigureGetBulk,
    ConfigureGetBulkResponse,
    ConfigureSetBulk,
    ConfigureSetBulkResponse,
    GetParameter,
    GetParameterResponse,
    Mode,
    Release,
    ReleaseResponse,
    Reset,
    ResetResponse,
    ResponseCode,
    SetParameter,
    SetParameterResponse,
    Suspend,
    SuspendResponse,
    UpdateDataChannel,
    UpdateDataChannelResponse,
)

OK = ResponseCode.SUCCESS
MESSAGES = [
    BindRequest(5, 2, 2, 4), BindResponse(5, 6, 2, 2, 4), GetParameter(5, 3, 1),
    GetParameterResponse(5, OK, 3, 1, b"\x01\x02"), SetParameter(5, 3, 1, b"\x01"),
    SetParameterResponse(5, OK, 3, 1, b"\x01"), Suspend(5, 100), SuspendResponse(5, OK, 100),
    Release(5), ReleaseResponse(5, OK), Beacon(5), Beacon(0, mode=Mode.ARBITRATOR), Reset(0),
    ResetResponse(5, OK), ConfigureGetBulk(5, 3, 0), ConfigureGetBulkResponse(5, OK, 3, 0, 12),
    ConfigureSetBulk(5, 3, 0, 12), ConfigureSetBulkResponse(5, OK, 3, 0, 12),
    BulkData(5, 1, b"abc", mode=Mode.DEVICE), BulkDataResponse(5, OK, mode=Mode.ARBITRATOR),
    UpdateDataChannel(5, 2), UpdateDataChannelResponse(5, OK, 2), ChannelData(9, b"\x01\x02"),
]


def _reference(obj: Any) -> Any:
    """The same values in a plain dataclass of the same name, fields and frozenness."""
    cls = type(obj)
    spec = [(f.name, Any, dataclasses.field(compare=f.compare, hash=f.hash, repr=f.repr))
            for f in dataclasses.fields(cls)]
    frozen = cls.__dataclass_params__.frozen  # type: ignore[attr-defined]
    plain = dataclasses.make_dataclass(cls.__name__, spec, frozen=frozen)
    return plain(**{f.name: getattr(obj, f.name) for f in dataclasses.fields(cls)})


def test_every_message_class_is_covered():
    assert {type(m) for m in MESSAGES} == {*MESSAGE_TYPES.values(), ChannelData}


@pytest.mark.parametrize("obj", MESSAGES, ids=lambda o: type(o).__name__)
def test_repr_hash_and_equality_are_a_frozen_dataclasss(obj):
    ref = _reference(obj)
    assert repr(obj) == repr(ref)
    assert hash(obj) == hash(ref)
    twin = copy.copy(obj)
    assert twin == obj and not twin != obj and hash(twin) == hash(obj)
    assert obj.__eq__(object()) is NotImplemented and obj != ref  # another class
    with pytest.raises(dataclasses.FrozenInstanceError):
        obj.anything = 1  # type: ignore[attr-defined]
    for f in dataclasses.fields(obj):
        other = copy.copy(obj)
        object.__setattr__(other, f.name, "something else")
        ref_other = copy.copy(ref)
        object.__setattr__(ref_other, f.name, "something else")
        assert (other == obj) == (ref_other == ref)


def test_messages_of_two_functions_with_equal_fields_differ():
    assert GetParameter(5, 3, 1) != ConfigureGetBulk(5, 3, 1)
    assert len({GetParameter(5, 3, 1), GetParameter(5, 3, 1), ConfigureGetBulk(5, 3, 1)}) == 2


def test_replace_and_asdict_work_as_on_any_dataclass():
    msg = dataclasses.replace(GetParameter(5, 3, 1), channel=2)
    assert msg == GetParameter(5, 3, 2)
    assert dataclasses.asdict(GetParameter(5, 3, 1))["param"] == 3
