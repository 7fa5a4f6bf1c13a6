"""The 11-bit identifier: priority << 9 | mode << 8 | node ID (001 §2.2)."""

from __future__ import annotations

import pytest

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.identifier import (
    BROADCAST,
    NODE_ID_MAX,
    NODE_ID_MIN,
    Identifier,
    Mode,
    Priority,
    check_node_id,
    make_id,
    split_id,
)


def test_constants() -> None:
    assert (BROADCAST, NODE_ID_MIN, NODE_ID_MAX) == (0, 1, 254)
    assert [p.value for p in Priority] == [0, 1, 2, 3]
    assert (Mode.DEVICE, Mode.ARBITRATOR) == (0, 1)


@pytest.mark.parametrize(
    ("priority", "mode", "node", "expected"),
    [
        (Priority.BINDING, Mode.DEVICE, 1, 0x601),  # 001 §3.3.1 bind request from node 1
        (Priority.NORMAL, Mode.ARBITRATOR, 5, 0x305),  # arbitrator → node 5
        (Priority.NORMAL, Mode.DEVICE, 5, 0x205),  # node 5 → arbitrator
        (Priority.HIGH, Mode.DEVICE, 5, 0x005),  # 001 §3.3.4 beacon
        (Priority.LOW, Mode.ARBITRATOR, 254, 0x5FE),
        (Priority.HIGH, Mode.ARBITRATOR, BROADCAST, 0x100),
    ],
)
def test_make_and_split(priority: Priority, mode: Mode, node: int, expected: int) -> None:
    assert make_id(priority, mode, node) == expected
    ident = split_id(expected)
    assert ident == Identifier(priority, mode, node)
    assert isinstance(ident.priority, Priority) and isinstance(ident.mode, Mode)
    assert ident.arbitration_id == expected


def test_plain_ints_are_accepted() -> None:
    assert make_id(1, 1, 5) == 0x305


def test_every_identifier_round_trips() -> None:
    for arbitration_id in range(0x800):
        if arbitration_id & 0xFF == 0xFF:
            with pytest.raises(FrameError, match="node ID 255"):
                split_id(arbitration_id)
        else:
            assert split_id(arbitration_id).arbitration_id == arbitration_id


def test_device_beats_arbitrator_at_equal_priority() -> None:
    assert make_id(1, Mode.DEVICE, 200) < make_id(1, Mode.ARBITRATOR, 1)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ((4, 0, 1), "priority 4 is out of range"),
        ((-1, 0, 1), "priority -1"),
        ((0, 2, 1), "mode 2 is out of range"),
        ((0, 0, 255), "node ID 255 is out of range"),
        ((0, 0, -1), "node ID -1 is out of range"),
        ((0, 0, "5"), "not an integer"),
    ],
)
def test_make_id_rejects(args: tuple, message: str) -> None:
    with pytest.raises(FrameError, match=message):
        make_id(*args)


@pytest.mark.parametrize("bad", [-1, 0x800, 0x1FFFFFFF])
def test_split_id_rejects_non_base_ids(bad: int) -> None:
    with pytest.raises(FrameError, match="11-bit"):
        split_id(bad)


def test_split_id_rejects_non_int() -> None:
    with pytest.raises(FrameError, match="not an integer"):
        split_id("0x305")  # type: ignore[arg-type]


def test_check_node_id() -> None:
    assert check_node_id(0) == 0
    assert check_node_id(254) == 254
    with pytest.raises(FrameError, match=r"granted node ID 0 is out of range \(1–254\)"):
        check_node_id(0, "granted node ID", allow_broadcast=False)
    with pytest.raises(FrameError):
        check_node_id(True)  # type: ignore[arg-type]


def test_identifier_str() -> None:
    assert str(split_id(0x305)) == "NORMAL/ARBITRATOR/node 5"
