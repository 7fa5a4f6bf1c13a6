"""The protocol's enum look-ups by value (issue 11: every frame converts two or three fields)
give exactly what calling the enum gives, and fail exactly as it fails."""

from __future__ import annotations

import pytest

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import identifier
from pdcp_studio.protocol.codes import FUNCTION_CODES, FunctionCode
from pdcp_studio.protocol.identifier import Mode, Priority, make_id, split_id
from pdcp_studio.protocol.messages import decode


def _call(fn, *args):
    try:
        return "ok", fn(*args)
    except Exception as err:  # the outcome compared: value or exception type
        return "raised", type(err)


def test_function_codes_by_byte_are_the_enums_own():
    for byte in range(256):
        expected = _call(FunctionCode, byte)
        got = FUNCTION_CODES.get(byte)
        assert (("ok", got) if got is not None else ("raised", ValueError)) == expected


def test_labels_are_code_and_title():
    for code in FunctionCode:
        assert code.label == f"0x{code.value:02X} {code.title}"


@pytest.mark.parametrize("value", [0, 1, 2, 3, 4, -1, True, False, 1.0, 2.5, "1", None,
                                   Priority.LOW, Mode.ARBITRATOR, [1]])
def test_members_by_value_match_calling_the_enum(value):
    assert _call(identifier._member, identifier._PRIORITY_OF, Priority, value) == \
        _call(Priority, value)
    assert _call(identifier._member, identifier._MODE_OF, Mode, value) == _call(Mode, value)


@pytest.mark.parametrize("priority,mode", [(0, 0), (3, 1), (Priority.LOW, Mode.DEVICE),
                                           (4, 0), (0, 2), (-1, 0), ("1", 0), (None, 1)])
def test_make_id_accepts_and_refuses_as_before(priority, mode):
    try:
        prio, mod = Priority(priority), Mode(mode)
    except (ValueError, TypeError):
        with pytest.raises(FrameError):
            make_id(priority, mode, 5)
        return
    assert make_id(priority, mode, 5) == prio << 9 | mod << 8 | 5


def test_split_id_gives_enum_members_for_every_identifier():
    for aid in range(0x800):
        if aid & 0xFF == 0xFF:
            with pytest.raises(FrameError):
                split_id(aid)
            continue
        ident = split_id(aid)
        assert ident.priority is Priority(aid >> 9) and ident.mode is Mode(aid >> 8 & 1)
        assert ident.node_id == aid & 0xFF and ident.arbitration_id == aid


def test_an_unknown_function_code_is_still_named_in_the_error():
    with pytest.raises(FrameError, match="function code 0x05 deprecated command"):
        decode(0x205, b"\x05")
    with pytest.raises(FrameError, match="0x42"):
        decode(0x205, b"\x42")
