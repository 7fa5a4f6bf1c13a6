"""The arbitrator's shared vocabulary: its timing constants, per-node state and wire formats.

Split out of :mod:`pdcp_studio.bus.arbitrator.core` so each of its parts (node table, presence,
set-up, links, profile layer) can use them without importing the :class:`Arbitrator` itself;
that module re-exports every public name here. Each part imports the constants it reads, so a test
that patches one must patch it in the module that reads it.
"""

from __future__ import annotations

from dataclasses import dataclass

from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction

#: Retries per request (so at most RETRIES + 1 attempts) unless the caller says otherwise.
RETRIES = 4
#: Beacon interval assumed until a device's own (parameter 10) has been read.
DEFAULT_BEACON_INTERVAL_S = 0.1
#: A device is gone after this many missed beacon intervals (reference §1 Decision) ...
MISSED_BEACONS = 3
#: ... plus this fraction of an interval for scheduling jitter.
PRESENCE_GRACE = 0.5
#: When nothing at all was received from anyone past a device's deadline (a starved process,
#: or a bus gone quiet), it is gone only after this many times its limit …
SILENT_BUS_FACTOR = 2.0
#: … and never before this many seconds of silence, the checker running throughout.
SILENT_BUS_S = 3.0
#: A present device asking to bind again: wait this many beacon intervals for a twin's beacon.
DUPLICATE_WINDOW = 1.5
#: Beacons are counted over this many intervals; more than TWIN_BEACON_RATIO times the
#: expected number reveals two devices beaconing on one node ID.
BEACON_WINDOW = 10
TWIN_BEACON_RATIO = 1.5
#: Echoed responses (a second identical answer to one request) that reveal bound twins.
ECHOES_FOR_TWIN = 4
#: How long a suggested node ID stays reserved for the device it was suggested to.
BIND_HOLD_S = 2.0
#: Start-up runs when no bind request came for this long (listing 4.1's "x ms").
STARTUP_QUIET_S = 0.5
#: ... but at the latest this long after the arbitrator started.
STARTUP_MAX_WAIT_S = 10.0
#: The duty cycle runs this long after the last join or leave.
DUTY_QUIET_S = 0.05
#: Devices set up at the same time.
SETUP_WORKERS = 8
#: Set-up attempts per device (after a failed one the device is reset and binds again).
SETUP_ATTEMPTS = 3
#: How often the dispatch thread checks presence and pending binds, at most.
TICK_S = 0.01
#: The least time between two Resets sent to one unknown beaconing node.
UNKNOWN_RESET_S = 1.0
#: A node ID heard from a device bound elsewhere stays out of the pool this long after.
FOREIGN_HOLD_S = 1.0
#: After a reset, channel data frames still arriving on the old channel node IDs are expected
#: for this long (devices finish what they queued before the Reset reached them).
RESET_GRACE_S = 1.0
#: Without a reset at start, binding waits this long while node IDs in use are heard.
FOREIGN_LISTEN_S = 3.5 * DEFAULT_BEACON_INTERVAL_S
#: Beacon interval assumed for presence until a newly bound device's own has been read: long
#: enough for a device beaconing every 500 ms (the full rig's) not to be declared gone, and
#: bound again, while it is still being set up.
UNREAD_BEACON_INTERVAL_S = 1.0
#: How long close() waits for each thread.
JOIN_S = 2.0

_OFF, _ON = b"\x00", b"\x01"


def _input_value(param: int, value: object) -> bytes:
    """An input channel's parameter value in the catalog's layout."""
    return P.encode_value(P.channel_parameter(param, Direction.INPUT), value)


_NOT_CONNECTED = {
    P.IN_SOURCE_VID_PID: _input_value(P.IN_SOURCE_VID_PID, (0xFFFF, 0xFFFF)),
    P.IN_SOURCE_SN_INDEX: _input_value(P.IN_SOURCE_SN_INDEX, (0xFFFF, 0xFF)),
    P.IN_SOURCE_TYPE_PROFILE: _input_value(P.IN_SOURCE_TYPE_PROFILE, (0, 0)),
}
#: Parameters only the arbitrator sets (changing them behind its back breaks the routing).
_MANAGED = {(P.DEVICE_NODE_ID, "device"), (P.OUT_NODE_ID, "output"),
            (P.IN_SOURCE_NODE_IDS, "input")}


@dataclass(frozen=True)
class _Foreign:
    """Pool owner of a node ID heard on the bus but not bound here."""

    node_id: int


@dataclass
class _Node:
    """A bound device's live state (the model Device lives in the system)."""

    key: DeviceKey
    node_id: int
    last_seen: float  # when its last frame was handled (monotonic)
    beacon_interval: float = DEFAULT_BEACON_INTERVAL_S
    last_beacon: float = 0.0
    generation: int = 0  # unique per binding: a set-up of an older one is discarded
    set_up: bool = False
    last_response: tuple[int, bytes, float] | None = None
    last_request: float = 0.0
    echoes: int = 0
    answers: int = 0
    window_start: float | None = None  # the open beacon-count window's start (None: none)
    window_beacons: int = 0
    last_bus: float = 0.0  # the bus time (the frame's own timestamp) of its last frame
    prev_beacon_bus: float = float("-inf")  # the bus times of its two latest beacons
    last_beacon_bus: float = float("-inf")
