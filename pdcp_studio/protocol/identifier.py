"""The 11-bit CAN identifier of a PDCP frame: priority, mode and node ID.

Layout (001 §2.2, reference §1): bits 10–9 priority, bit 8 mode, bits 7–0 node ID, so
``arbitration_id = priority << 9 | mode << 8 | node_id``. Lower identifiers win arbitration:
at equal priority a device (mode 0) beats the arbitrator (mode 1).
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any, NamedTuple

from pdcp_studio.errors import FrameError

#: Node ID 0 addresses every device on the bus.
BROADCAST = 0
#: The range the arbitrator assigns to devices and output data channels.
NODE_ID_MIN = 1
NODE_ID_MAX = 254
#: The largest CAN 2.0A base identifier.
ARBITRATION_ID_MAX = 0x7FF

_PRIORITY_SHIFT = 9
_MODE_SHIFT = 8
_NODE_MASK = 0xFF


class Priority(IntEnum):
    """Bits 10–9. BINDING (3) is used only by the Bind Device Request (0x01)."""

    HIGH = 0
    NORMAL = 1
    LOW = 2
    BINDING = 3


class Mode(IntEnum):
    """Bit 8: who sent the frame."""

    DEVICE = 0
    ARBITRATOR = 1


class Identifier(NamedTuple):
    """A split arbitration ID; ``node_id`` is the target (mode 1) or the sender (mode 0)."""

    priority: Priority
    mode: Mode
    node_id: int

    @property
    def arbitration_id(self) -> int:
        return make_id(self.priority, self.mode, self.node_id)

    def __str__(self) -> str:
        return f"{self.priority.name}/{self.mode.name}/node {self.node_id}"


#: Priority and Mode by value, in value order (``split_id`` indexes them: the fields of an
#: 11-bit identifier are always in range).
_PRIORITIES: tuple[Priority, ...] = tuple(Priority)
_MODES: tuple[Mode, ...] = tuple(Mode)
_PRIORITY_OF: dict[int, Priority] = {p.value: p for p in Priority}
_MODE_OF: dict[int, Mode] = {m.value: m for m in Mode}


def _member(table: dict[int, Any], enum: type, value: object) -> Any:
    """``enum(value)``, by a dict look-up when ``value`` is one of its values (what Enum's
    own call does first, without its call machinery); otherwise ``enum(value)`` itself, so
    anything else raises (or converts) exactly as before."""
    try:
        return table[value]  # type: ignore[index]
    except (KeyError, TypeError):
        return enum(value)


def check_node_id(node_id: int, what: str = "node ID", *, allow_broadcast: bool = True) -> int:
    """Return ``node_id`` if it is a valid PDCP node ID (0–254, or 1–254), else raise FrameError."""
    low = BROADCAST if allow_broadcast else NODE_ID_MIN
    if not isinstance(node_id, int) or isinstance(node_id, bool):
        raise FrameError(f"{what} {node_id!r} is not an integer")
    if not low <= node_id <= NODE_ID_MAX:
        raise FrameError(f"{what} {node_id} is out of range ({low}–{NODE_ID_MAX})")
    return node_id


def make_id(priority: int, mode: int, node_id: int) -> int:
    """Compose an 11-bit arbitration ID; raises FrameError on an out-of-range field."""
    try:
        prio: Priority = _member(_PRIORITY_OF, Priority, priority)
    except ValueError:
        raise FrameError(f"priority {priority!r} is out of range (0–3)") from None
    try:
        mod: Mode = _member(_MODE_OF, Mode, mode)
    except ValueError:
        raise FrameError(f"mode {mode!r} is out of range (0 device, 1 arbitrator)") from None
    check_node_id(node_id)
    return prio << _PRIORITY_SHIFT | mod << _MODE_SHIFT | node_id


def split_id(arbitration_id: int) -> Identifier:
    """Split an arbitration ID into its fields; raises FrameError if it is not PDCP's."""
    if not isinstance(arbitration_id, int) or isinstance(arbitration_id, bool):
        raise FrameError(f"arbitration ID {arbitration_id!r} is not an integer")
    if not 0 <= arbitration_id <= ARBITRATION_ID_MAX:
        raise FrameError(
            f"arbitration ID 0x{arbitration_id:X} is not an 11-bit base identifier (0–0x7FF)"
        )
    node_id = arbitration_id & _NODE_MASK
    if node_id > NODE_ID_MAX:
        raise FrameError(
            f"arbitration ID 0x{arbitration_id:03X}: node ID {node_id} is out of range "
            f"(0–{NODE_ID_MAX})"
        )
    return Identifier(
        _PRIORITIES[arbitration_id >> _PRIORITY_SHIFT],
        _MODES[arbitration_id >> _MODE_SHIFT & 1],
        node_id,
    )
