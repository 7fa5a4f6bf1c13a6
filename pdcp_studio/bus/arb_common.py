"""The arbitrator's shared vocabulary: its timing constants, per-node state and wire formats.

Split out of :mod:`pdcp_studio.bus.arbitrator` so each of its parts (binding, presence, set-up,
links, profile layer) can use them without importing the :class:`Arbitrator` itself; that
module re-exports every public name here. Each part imports the constants it reads, so a test
that patches one must patch it in the module that reads it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from pdcp_studio.errors import ParameterError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Device

#: Retries per request (so at most RETRIES + 1 attempts) unless the caller says otherwise.
RETRIES = 4
#: Beacon interval assumed until a device's own (parameter 10) has been read.
DEFAULT_BEACON_INTERVAL_S = 0.1
#: A device is gone after this many missed beacon intervals (reference §1 Decision) ...
MISSED_BEACONS = 3
#: ... plus this fraction of an interval for scheduling jitter.
PRESENCE_GRACE = 0.5
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
_DEVICE_PARAMS = (P.DEVICE_SERIAL, P.DEVICE_EAN_LOW, P.DEVICE_EAN_HIGH, P.DEVICE_VERSION,
                  P.DEVICE_TYPE_PROFILE, P.DEVICE_DESCRIPTOR, P.DEVICE_BEACON_INTERVAL,
                  P.DEVICE_ACK_TIMEOUT, P.DEVICE_BIND_TIMEOUT)
_CHANNEL_PARAMS = (P.CH_TYPE_PROFILE, P.CH_DESCRIPTOR, P.CH_REQUIRED_INPUTS, P.CH_DESIRED_INPUTS)
_INPUT_PARAMS = (P.IN_TERMINAL_PROFILE, P.IN_SOURCE_VID_PID, P.IN_SOURCE_SN_INDEX,
                 P.IN_SOURCE_TYPE_PROFILE)
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
    last_seen: float
    beacon_interval: float = DEFAULT_BEACON_INTERVAL_S
    last_beacon: float = 0.0
    generation: int = 0  # unique per binding: a set-up of an older one is discarded
    set_up: bool = False
    updates: set[int] = field(default_factory=set)  # inputs named in Update Data Channel
    last_response: tuple[int, bytes, float] | None = None
    last_request: float = 0.0
    echoes: int = 0
    answers: int = 0
    window_start: float = 0.0
    window_beacons: int = 0


def learn_value(device: Device, param: int, channel: int, value: bytes) -> None:
    """Store a parameter value read from (or written to) a device in its model ``Device``.

    Unknown parameters and values that do not fit their layout are ignored (a monitor shows
    them; the model keeps what it understands).
    """
    if channel == 0:
        spec = P.find_parameter(param, 0)
        ch = None
    else:
        ch = device.channels.get(channel)
        spec = None if ch is None else P.find_parameter(param, channel, ch.direction)
    if spec is None:
        return
    try:
        v = P.decode_value(spec, value)
    except ParameterError:
        return
    if ch is None:
        attrs = {P.DEVICE_EAN_LOW: "ean_low", P.DEVICE_EAN_HIGH: "ean_high",
                 P.DEVICE_DESCRIPTOR: "descriptor", P.DEVICE_BEACON_INTERVAL: "beacon_interval",
                 P.DEVICE_ACK_TIMEOUT: "ack_timeout", P.DEVICE_BIND_TIMEOUT: "bind_timeout"}
        if param in attrs:
            setattr(device, attrs[param], v)
        elif param == P.DEVICE_VERSION:
            device.fw_version, device.hw_version = v
        elif param == P.DEVICE_TYPE_PROFILE:
            device.device_type, device.device_profile = v
        elif param == P.DEVICE_NODE_ID:
            device.node_id = v or None
        return
    if param == P.CH_TYPE_PROFILE:
        ch.type, ch.profile = v
    elif param == P.CH_DESCRIPTOR:
        ch.descriptor = v
    elif param == P.CH_DATA_ENABLED:
        ch.data_enabled = bool(v)
    elif param == P.CH_REQUIRED_INPUTS:
        ch.required_inputs = tuple(v)
    elif param == P.CH_DESIRED_INPUTS:
        ch.desired_inputs = tuple(v)
    elif ch.is_input and param == P.IN_TERMINAL_PROFILE:
        ch.terminal_profile = v
    elif ch.is_input and param == P.IN_SOURCE_VID_PID:
        ch.source = replace(ch.source, vid=v[0], pid=v[1])
    elif ch.is_input and param == P.IN_SOURCE_SN_INDEX:
        ch.source = replace(ch.source, serial=v[0], index=v[1])
    elif ch.is_input and param == P.IN_SOURCE_TYPE_PROFILE:
        ch.source = replace(ch.source, type=v[0], profile=v[1])
    elif ch.is_output and param == P.OUT_NODE_ID:
        ch.node_id = v or None


def _only_inputs(device: Device) -> None:
    """Drop required/desired indices that are not input channels of the device."""
    inputs = {c.index for c in device.inputs()}
    for ch in device.channels.values():
        ch.required_inputs = tuple(i for i in ch.required_inputs if i in inputs)
        ch.desired_inputs = tuple(i for i in ch.desired_inputs if i in inputs)
