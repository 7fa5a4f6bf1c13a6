"""The PDCP bus arbitrator on any python-can bus (reference §1 and §2, issue 4 item 1).

It binds devices from one node-ID pool shared with their output channels, sets each device up
(§1 steps 1–6), answers Update Data Channel requests, keeps presence by beacons (gone after
3 missed intervals), makes and removes links on the wire, keeps the stored configuration in
its non-volatile memory and runs the profile layer's start-up and hot-swap duty cycle
through the engine's plans.

Threads, all owned here and stopped by :meth:`Arbitrator.close`:
- the *dispatch* thread drains the connection's queue (the Notifier only enqueues): it
  decodes frames, answers bind and Update Data Channel requests, feeds responses to the
  :class:`RequestEngine`, and checks presence on a tick. It never waits for the bus.
- a small *set-up pool* reads newly bound devices (requests to different devices overlap)
  and does the wire work of departures.
- the *profile* thread runs start-up once binding has been quiet for ``startup_quiet_s``,
  and the duty cycle after joins and leaves.
Link changes on the wire and plans are serialized by one lock, so a plan never races a
set-up re-making a link. Subscribers are called on these threads and must not block.

Decisions beyond the reference:
- A bind request asking for a free ID (or the one the device holds) is granted at once;
  otherwise the lowest free ID is suggested and held for that device for ``BIND_HOLD_S``.
- A device that is present and asks to bind again either rebooted or has a twin with the same
  VID/PID/serial. The answer waits ``DUPLICATE_WINDOW`` beacon intervals: a beacon from the
  bound node meanwhile means a twin (reported, never bound); silence means a reboot (set up
  again, links re-made). Twins that bound together (one answer binds both) are caught by
  their echoed responses (dropped, so requests still work) or their doubled beacon rate.
- A departed device stays in the system (``present`` false) with its links (dead links,
  as the engine expects); its node IDs go back to the pool, and inputs it fed stop listening.
- Traffic from a node ID the arbitrator does not hold (a device or output bound by an earlier
  arbitrator) keeps that ID out of the pool while it is heard; a beacon from such a node gets
  a Reset Device, so the device binds again; start and :meth:`reset` broadcast one.
"""

from __future__ import annotations

import itertools
import logging
import struct
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.memory import MemoryStore
from pdcp_studio.bus.node_ids import NodeIdPool
from pdcp_studio.bus.requests import (
    RESPONSE_TIMEOUT_S,
    DeviceRefusedError,
    RequestEngine,
)
from pdcp_studio.bus.signals import decode_sample
from pdcp_studio.errors import (
    FrameError,
    ModelError,
    NodeIdExhaustedError,
    ParameterError,
    PdcpError,
    TransportError,
)
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import NO_SOURCE, Channel, Device, Link, SourceInfo, System
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    BindResponse,
    ChannelData,
    FunctionCode,
    Message,
    Mode,
    Reset,
    ResponseCode,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
)
from pdcp_studio.protocol.identifier import NODE_ID_MAX, NODE_ID_MIN

if TYPE_CHECKING:
    import can

    from pdcp_studio.engine.plan import Plan

log = logging.getLogger(__name__)

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

_PAIR = struct.Struct("<HH")  # X, Y (VID/PID, type/profile)
_SN_INDEX = struct.Struct("<HB")  # serial, channel index
_OFF, _ON = b"\x00", b"\x01"
_NOT_CONNECTED = {
    P.IN_SOURCE_VID_PID: _PAIR.pack(0xFFFF, 0xFFFF),
    P.IN_SOURCE_SN_INDEX: _SN_INDEX.pack(0xFFFF, 0xFF),
    P.IN_SOURCE_TYPE_PROFILE: _PAIR.pack(0, 0),
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


class Arbitrator:
    """A headless PDCP bus arbitrator on ``bus`` (which it owns and shuts down on close)."""

    def __init__(self, bus: can.BusABC, *, memory: str | Path | MemoryStore | None = None,
                 profile_layer: bool = True, name: str = "arbitrator", pace_s: float = 0.0,
                 response_timeout: float = RESPONSE_TIMEOUT_S, retries: int = RETRIES,
                 startup_quiet_s: float = STARTUP_QUIET_S, duty_quiet_s: float = DUTY_QUIET_S,
                 startup_max_wait_s: float = STARTUP_MAX_WAIT_S,
                 node_ids: tuple[int, int] = (NODE_ID_MIN, NODE_ID_MAX),
                 frame_events: bool = False, channel_events: bool = True,
                 reset_on_start: bool = True) -> None:
        self.name = name
        self.profile_layer = profile_layer
        self.retries = retries
        self.startup_quiet_s = startup_quiet_s
        self.duty_quiet_s = duty_quiet_s
        self.startup_max_wait_s = startup_max_wait_s
        self.frame_events = frame_events
        self.channel_events = channel_events
        self.memory = memory if isinstance(memory, MemoryStore) else MemoryStore(memory)
        self.applied_plans: list[Plan] = []
        self.bad_frames = 0
        self.error_frames = 0
        self.data_frames = 0
        self.duplicates: set[DeviceKey] = set()
        self.conn = Connection(bus, name=name, pace_s=pace_s)
        self.requests = RequestEngine(self._send, response_timeout=response_timeout,
                                      retries=retries)
        self._lock = threading.RLock()
        self._plan_lock = threading.RLock()
        self._subscribers = ev.Subscribers(name)
        self._system = System()
        self._pool = NodeIdPool(*node_ids)
        self._nodes: dict[int, _Node] = {}
        self._node_of: dict[DeviceKey, int] = {}
        self._channel_ids: dict[int, ChannelRef] = {}
        self._channel_set: frozenset[int] = frozenset()
        self._held: dict[DeviceKey, float] = {}  # suggested, not yet granted: since when
        self._deferred: dict[DeviceKey, tuple[BindRequest, float, float]] = {}
        self._setups: dict[DeviceKey, tuple[int, int]] = {}  # in flight: (epoch, generation)
        self._jobs = 0  # departure jobs in flight
        self._exhausted_reported: set[DeviceKey] = set()
        self._setup_failures: dict[DeviceKey, int] = {}
        self._unknown_reset: dict[int, float] = {}
        self._foreign: dict[int, float] = {}  # node ID heard but not bound here: last heard
        self._foreign_shown: set[int] = set()
        # Channel node IDs given out before the last reset, and until when their in-flight data
        # frames are expected (counted in stale_data_frames, not reported as undecodable).
        self._stale_channels: frozenset[int] = frozenset()
        self._stale_until = 0.0
        self.stale_data_frames = 0
        self._other_arbitrator = False
        self._epoch = 0  # bumped by reset(): stale set-ups discard their results
        self._generations = itertools.count(1)
        self._plan_running = 0
        now = time.monotonic()
        self._started = now
        # Without the start-up reset, devices bound by an earlier arbitrator keep their IDs:
        # hear them all (beacons) before handing any ID out; the device asking retries.
        self._listen_until = now if reset_on_start else now + FOREIGN_LISTEN_S
        self._last_bind = now
        self._last_change = now
        self._startup_done = False
        self._duty_needed = False
        self._last_present: set[ChannelRef] = set()
        self._decoder: Any = None
        if frame_events:
            from pdcp_studio.bus.monitor import FrameDecoder

            self._decoder = FrameDecoder()
        self._decoder_lock = threading.Lock()
        self._stop = threading.Event()
        self._wake = threading.Event()
        self._pool_exec = ThreadPoolExecutor(SETUP_WORKERS, thread_name_prefix=f"pdcp {name} setup")
        self._thread = threading.Thread(target=self._run, name=f"pdcp {name}", daemon=True)
        self._profile_thread = threading.Thread(target=self._profile_loop,
                                                name=f"pdcp {name} profile", daemon=True)
        self._closed = False
        self._thread.start()
        self._profile_thread.start()
        if reset_on_start:
            self._broadcast_reset()

    # -- lifetime -------------------------------------------------------------------------
    def __enter__(self) -> Arbitrator:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Stop every thread, abort requests, shut the bus down. Idempotent."""
        if self._closed:
            return
        self._closed = True
        self._stop.set()
        self._wake.set()
        self.requests.close()
        self.conn.wake()
        self._pool_exec.shutdown(wait=False, cancel_futures=True)
        for thread in (self._thread, self._profile_thread):
            if thread is not threading.current_thread():
                thread.join(timeout=JOIN_S)
        self.conn.close()

    @property
    def closed(self) -> bool:
        return self._closed

    # -- events ---------------------------------------------------------------------------
    def subscribe(self, callback: Callable[[ev.Event], None]) -> Callable[[], None]:
        """Call ``callback(event)`` for every event; returns the unsubscribe function."""
        return self._subscribers.add(callback)

    def _emit(self, event: ev.Event) -> None:
        self._subscribers.emit(event)

    def _error(self, message: str, kind: str = "") -> None:
        log.warning("%s: %s", self.name, message)
        self._emit(ev.BusError(message, kind))

    # -- snapshot and look-ups ------------------------------------------------------------
    def system(self) -> System:
        """A copy of the bus as the arbitrator knows it (every device ever bound)."""
        with self._lock:
            return self._system.copy()

    def node_id_of(self, key: DeviceKey) -> int | None:
        """The node ID of a bound device (None if it is not bound)."""
        with self._lock:
            return self._node_of.get(DeviceKey(*key))

    def channel_node_id(self, ref: ChannelRef) -> int | None:
        """The node ID an output channel sends its data with (None if it has none)."""
        with self._lock:
            return self._pool.id_of((ref.device, ref.index))

    @property
    def startup_done(self) -> bool:
        return self._startup_done

    def _settled(self) -> bool:
        with self._lock:
            busy = bool(self._setups or self._held or self._deferred or self._plan_running
                        or self._jobs)
            if self.profile_layer:
                busy = busy or not self._startup_done or self._duty_needed
            return not busy

    def wait_settled(self, timeout: float) -> bool:
        """True once no bind, set-up or plan is in progress and start-up has run."""
        deadline = time.monotonic() + timeout
        while True:
            if self._settled():
                return True
            left = deadline - time.monotonic()
            if left <= 0 or self._closed:
                return False
            time.sleep(min(0.01, left))

    def _node_for(self, key: DeviceKey) -> int:
        node_id = self.node_id_of(key)
        if node_id is None:
            raise TransportError(f"{self.name}: device {DeviceKey(*key)} is not on the bus")
        return node_id

    # -- parameters -----------------------------------------------------------------------
    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        """Read one parameter (bulk transfer when the device asks for it)."""
        value = self.requests.get(self._node_for(key), param, channel, timeout=timeout)
        self._learn(DeviceKey(*key), param, channel, value)
        return value

    def set_parameter(self, key: DeviceKey, param: int, channel: int, value: bytes, *,
                      timeout: float | None = None) -> None:
        """Write one parameter (bulk transfer for values over 4 bytes).

        Node IDs (device, Channel Node Id, Source's Node Ids) belong to the arbitrator:
        use links for them. A new Beacon Interval takes effect for presence at once.
        """
        key = DeviceKey(*key)
        with self._lock:
            device = self._system.device(key)
            ch = device.channels.get(channel) if device and channel else None
        scope = "device" if channel == 0 else ch.direction.value if ch else ""
        if (param, scope) in _MANAGED:
            raise ModelError(f"parameter {param} of channel {channel} is managed by the "
                             "arbitrator (node IDs follow binding and links)")
        self.requests.set(self._node_for(key), param, channel, bytes(value), timeout=timeout)
        self._learn(key, param, channel, bytes(value))

    def _learn(self, key: DeviceKey, param: int, channel: int, value: bytes) -> None:
        with self._lock:
            device = self._system.device(key)
            if device is not None:
                learn_value(device, param, channel, value)
                _only_inputs(device)
            if channel == 0 and param == P.DEVICE_BEACON_INTERVAL and len(value) == 2:
                node = self._nodes.get(self._node_of.get(key, -1))
                if node is not None:
                    node.beacon_interval = max(int.from_bytes(value, "little"), 1) / 1000.0

    def suspend(self, key: DeviceKey, ms: int = 0) -> None:
        """Suspend Device: stop its data for ``ms`` milliseconds (0 = until released)."""
        self.requests.suspend(self._node_for(key), ms)

    def release(self, key: DeviceKey) -> None:
        """Release Device: a suspended device sends its data again."""
        self.requests.release(self._node_for(key))

    def reset_device(self, key: DeviceKey) -> None:
        """Reset Device: it answers, restarts and binds again (then is set up again)."""
        self.requests.reset(self._node_for(key))

    # -- memory ---------------------------------------------------------------------------
    def read_memory(self) -> ConfigCollection:
        """The stored configuration in non-volatile memory (empty when none is stored)."""
        return self.memory.read()

    def write_memory(self, configs: ConfigCollection) -> None:
        """Store ``configs`` (a power cut mid-write leaves the previous one; read back)."""
        self.memory.write(configs)

    def save_configuration(self) -> ConfigCollection:
        """Store the current links as the one configuration in memory (the thesis's save)."""
        from pdcp_studio.engine import configuration_from_system

        collection = ConfigCollection([configuration_from_system(self.system())])
        self.write_memory(collection)
        return collection

    # -- sending --------------------------------------------------------------------------
    def _send(self, message: Message) -> None:
        arbitration_id, data = message.encode()
        if message.mode is Mode.ARBITRATOR and message.node_id:
            with self._lock:
                node = self._nodes.get(message.node_id)
                if node is not None:
                    node.last_request = time.monotonic()
        self.conn.send(arbitration_id, data)
        if self.frame_events:
            self._frame_event(arbitration_id, data, time.time())

    def _send_quiet(self, message: Message) -> None:
        try:
            self._send(message)
        except TransportError as err:
            self._error(str(err), "transport")

    def _broadcast_reset(self) -> None:
        self._send_quiet(Reset(0))

    def _frame_event(self, arbitration_id: int, data: bytes, timestamp: float) -> None:
        with self._decoder_lock:
            line = self._decoder.decode(arbitration_id, data, timestamp).line
        self._emit(ev.FrameSeen(timestamp, arbitration_id, bytes(data), line))

    # -- the dispatch thread --------------------------------------------------------------
    def _run(self) -> None:
        next_tick = 0.0
        while not self._stop.is_set():
            item = self.conn.get(TICK_S)
            if self._stop.is_set():
                break
            try:
                if isinstance(item, Exception):
                    self._error(f"the bus reported {item}", "transport")
                elif callable(item):
                    item()
                elif item is not None:
                    self._on_frame(item)
                now = time.monotonic()
                if now >= next_tick:
                    next_tick = now + TICK_S
                    # Presence is judged only when every frame received so far is handled:
                    # a backlog (a busy machine) must not pass for silent devices.
                    self._tick(now, self.conn.inbound.empty())
            except Exception:  # one bad frame or bug must never stop the arbitrator
                log.exception("%s: dispatch failed", self.name)

    def _bad_frame(self, why: str) -> None:
        self.bad_frames += 1
        self._error(f"undecodable frame #{self.bad_frames}: {why}", "bad_frame")

    def _on_frame(self, msg: can.Message) -> None:
        data = bytes(msg.data)
        if self.frame_events:
            self._frame_event(msg.arbitration_id, data, msg.timestamp or time.time())
        if msg.is_error_frame:
            self.error_frames += 1
            self._error(f"error frame #{self.error_frames} on the bus", "error_frame")
            return
        if msg.is_extended_id or msg.is_remote_frame:
            kind = "extended identifier" if msg.is_extended_id else "remote frame"
            self._bad_frame(f"0x{msg.arbitration_id:X}: {kind} (PDCP uses base data frames)")
            return
        now = time.monotonic()
        aid = msg.arbitration_id
        node_id = aid & 0xFF
        if (not aid >> 8 & 1 and aid >> 9 != 3 and 0 < node_id <= NODE_ID_MAX
                and node_id not in self._nodes and node_id not in self._channel_set):
            self._foreign_frame(node_id, aid, data, now)
            return
        try:
            message = decode(aid, data, channel_node_ids=self._channel_set)
        except FrameError as err:
            self._bad_frame(f"0x{aid:03X} [{data.hex(' ').upper()}]: {err}")
            return
        if isinstance(message, ChannelData):
            self._on_data(message, msg.timestamp or time.time())
            return
        if message.mode is Mode.ARBITRATOR:
            if not self._other_arbitrator:
                self._other_arbitrator = True
                self._error(f"another bus arbitrator is sending ({message.CODE.label}); "
                            "two arbitrators on one bus do not work (thesis §B.5)",
                            "other_arbitrator")
            return
        if isinstance(message, BindRequest):
            self._on_bind(message, now)
            return
        with self._lock:
            node = self._nodes.get(node_id)
            if node is not None:
                node.last_seen = now
                if isinstance(message, Beacon):
                    node.last_beacon = now
        if node is None:  # node 0, or a device that left a moment ago
            return
        if isinstance(message, Beacon):
            self._count_beacon(node, now)
            return
        if isinstance(message, UpdateDataChannel):
            self._on_update(node, message)
            return
        if not self._is_echo(node, msg.arbitration_id, data, now):
            self.requests.feed(message)

    def _on_data(self, message: ChannelData, timestamp: float) -> None:
        self.data_frames += 1
        if not self.channel_events:
            return
        with self._lock:
            ref = self._channel_ids.get(message.node_id)
            ch = self._system.channel(ref) if ref else None
            kind = ch.type if ch else 0
        if ref is not None:
            self._emit(ev.ChannelValue(ref, decode_sample(kind, message.data), timestamp))

    def _foreign_frame(self, node_id: int, aid: int, data: bytes, now: float) -> None:
        """A frame from a node ID nobody holds here: a device (or output) bound by an earlier
        arbitrator. Its ID is kept out of the pool while it is heard; a device is reset so
        it binds with us; undecodable frames are counted, and shown once per node."""
        with self._lock:
            if self._pool.is_free(node_id):
                self._pool.take(_Foreign(node_id), node_id)
            if isinstance(self._pool.owner(node_id), _Foreign):
                self._foreign[node_id] = now
        try:
            message = decode(aid, data)
        except FrameError as err:
            if node_id in self._stale_channels and now < self._stale_until:
                self.stale_data_frames += 1  # data already on the wire when we reset
                return
            self.bad_frames += 1
            if node_id not in self._foreign_shown:
                self._foreign_shown.add(node_id)
                self._error(f"undecodable frame #{self.bad_frames} 0x{aid:03X} "
                            f"[{data.hex(' ').upper()}] from node {node_id}, which is not "
                            f"bound here: {err} (further ones are counted, not shown)",
                            "bad_frame")
            return
        if isinstance(message, Beacon | UpdateDataChannel):
            self._unknown_node(node_id, now)
        if isinstance(message, UpdateDataChannel):
            self._send_quiet(UpdateDataChannelResponse(node_id, ResponseCode.FAILURE,
                                                       message.channel))

    def _unknown_node(self, node_id: int, now: float) -> None:
        """A device bound by someone else: reset it so it binds with us (rate-limited)."""
        if now - self._unknown_reset.get(node_id, -UNKNOWN_RESET_S) < UNKNOWN_RESET_S:
            return
        with self._lock:
            if node_id in self._channel_ids:
                return
        self._unknown_reset[node_id] = now
        log.info("%s: node %d is not bound here: resetting it", self.name, node_id)
        self._send_quiet(Reset(node_id))

    def _is_echo(self, node: _Node, arbitration_id: int, data: bytes, now: float) -> bool:
        """A second identical answer to one request: twins bound to one node ID do that."""
        code = data[0] if data else 0
        if not code & 0x80 and code != FunctionCode.BULK_DATA:
            return False
        last = node.last_response
        window = 2 * self.requests.response_timeout
        echo = (last is not None and last[0] == arbitration_id and last[1] == data
                and node.last_request < last[2] and now - last[2] < window)
        node.last_response = None if echo else (arbitration_id, data, now)
        if echo:
            node.echoes += 1
        else:
            node.answers += 1
        if (node.echoes >= ECHOES_FOR_TWIN and node.echoes * 2 >= node.answers
                and node.key not in self.duplicates):
            self._report_duplicate(node.key, f"node {node.node_id} answers requests twice")
        return echo

    def _count_beacon(self, node: _Node, now: float) -> None:
        """Twins bound together beacon on one node ID at twice the device's rate."""
        if not node.set_up:
            node.window_start, node.window_beacons = now, 0
            return
        node.window_beacons += 1
        span = BEACON_WINDOW * node.beacon_interval
        if now - node.window_start < span:
            return
        if (node.window_beacons > TWIN_BEACON_RATIO * BEACON_WINDOW
                and node.key not in self.duplicates):
            self._report_duplicate(node.key, f"node {node.node_id} beacons "
                                             f"{node.window_beacons} times in {span:.2f} s")
        node.window_start, node.window_beacons = now, 0

    def _report_duplicate(self, key: DeviceKey, why: str) -> None:
        self.duplicates.add(key)
        self._error(f"two devices with VID {key.vid}, PID {key.pid}, serial {key.serial} "
                    f"are on the bus ({why}); only one can be bound", "duplicate_device")

    # -- binding --------------------------------------------------------------------------
    def _on_bind(self, req: BindRequest, now: float) -> None:
        key = DeviceKey(req.vid, req.pid, req.serial)
        with self._lock:
            if key not in self.duplicates and key not in self._exhausted_reported:
                self._last_bind = now
        if now < self._listen_until:
            return  # still learning which IDs devices of an earlier arbitrator use
        with self._lock:
            node = self._nodes.get(self._node_of.get(key, -1))
            if node is not None and node.set_up:
                if key in self.duplicates:
                    return  # the reported twin asks again: it is never bound
                pending = self._deferred.get(key)
                window = DUPLICATE_WINDOW * node.beacon_interval
                self._deferred[key] = (req, pending[1] if pending else now,
                                       pending[2] if pending else now + window)
                return
        self._answer_bind(req, now)

    def _answer_bind(self, req: BindRequest, now: float) -> None:
        key = DeviceKey(req.vid, req.pid, req.serial)
        asked = req.node_id
        exhausted: NodeIdExhaustedError | None = None
        first = False
        with self._lock:
            held = self._pool.id_of(key)
            if isinstance(self._pool.owner(asked), _Foreign):  # most likely that very device,
                self._pool.release(self._pool.owner(asked))  # reset and binding again
                self._foreign.pop(asked, None)
            if asked == held or self._pool.is_free(asked):
                grant = asked
            elif held is not None:
                grant = held
            else:
                try:
                    grant = self._pool.lowest_free()
                except NodeIdExhaustedError as err:
                    self._held.pop(key, None)
                    first = key not in self._exhausted_reported
                    self._exhausted_reported.add(key)
                    exhausted = err
            if exhausted is None:
                self._exhausted_reported.discard(key)
                self._pool.take(key, grant)
                if grant == asked:
                    self._held.pop(key, None)
                    self._bound(key, grant, now)
                else:
                    self._held[key] = now
        if exhausted is not None:
            if first:  # once per device, not per retry
                self._error(f"device {key} cannot bind: {exhausted}", "node_ids_exhausted")
            return
        self._send_quiet(BindResponse(asked, grant, key.vid, key.pid, key.serial))

    def _bound(self, key: DeviceKey, node_id: int, now: float) -> None:
        """Under the lock: ``key`` holds ``node_id``; start (or restart) its set-up."""
        old = self._node_of.get(key)
        if old is not None:
            self._nodes.pop(old, None)
        if old is not None and old != node_id:
            self.requests.abort(old, "the device bound again with another node ID")
        device = self._system.device(key)
        interval = (max(device.beacon_interval, 1) / 1000.0 if device is not None
                    else DEFAULT_BEACON_INTERVAL_S)
        node = _Node(key, node_id, now, beacon_interval=interval)
        node.generation = next(self._generations)  # unique: a stale set-up never matches
        self._nodes[node_id] = node
        self._node_of[key] = node_id
        self._setups[key] = (self._epoch, node.generation)
        self._last_change = now
        epoch = self._epoch
        try:
            self._pool_exec.submit(self._setup_job, key, node_id, node.generation, epoch)
        except RuntimeError:  # closing
            self._setups.pop(key, None)

    # -- the tick: presence, held IDs, deferred binds -------------------------------------
    def _tick(self, now: float, caught_up: bool = True) -> None:
        gone: list[_Node] = []
        resolved: list[tuple[BindRequest, bool]] = []
        with self._lock:
            for node in list(self._nodes.values()) if caught_up else ():
                limit = node.beacon_interval * (MISSED_BEACONS + PRESENCE_GRACE)
                if now - node.last_seen > limit:
                    gone.append(node)
            for node_id, seen in list(self._foreign.items()):
                if now - seen > FOREIGN_HOLD_S:
                    del self._foreign[node_id]
                    self._pool.release(_Foreign(node_id))
            for key, since in list(self._held.items()):
                if now - since > BIND_HOLD_S:
                    del self._held[key]
                    if key not in self._node_of:
                        self._pool.release(key)
            for key, (req, since, deadline) in list(self._deferred.items()) if caught_up else ():
                node = self._nodes.get(self._node_of.get(key, -1))
                if node is None:
                    del self._deferred[key]
                    resolved.append((req, False))
                elif node.last_beacon > since:
                    del self._deferred[key]
                    if key not in self.duplicates:
                        resolved.append((req, True))
                elif now >= deadline:
                    del self._deferred[key]
                    resolved.append((req, False))
        for node in gone:
            self._depart(node, now)
        for req, twin in resolved:
            key = DeviceKey(req.vid, req.pid, req.serial)
            if twin:
                self._report_duplicate(key, "a second one asked to bind while the first "
                                            "kept beaconing")
            else:
                log.info("%s: device %s binds again (it restarted)", self.name, key)
                with self._lock:
                    node = self._nodes.get(self._node_of.get(key, -1))
                    if node is not None:
                        node.set_up = False
                self._answer_bind(req, now)

    def _depart(self, node: _Node, now: float) -> None:
        key = node.key
        with self._lock:
            if self._nodes.get(node.node_id) is not node:
                return
            del self._nodes[node.node_id]
            del self._node_of[key]
            self._setups.pop(key, None)
            self._deferred.pop(key, None)
            self._pool.release(key)
            self._pool.release_where(lambda o: isinstance(o, tuple) and o[0] == key)
            self._refresh_channel_ids()
            device = self._system.device(key)
            was_present = device is not None and device.present
            fed: list[Link] = []
            if device is not None:
                device.present = False
                device.node_id = None
                for ch in device.channels.values():
                    ch.node_id = None
                    ch.data_enabled = False
                fed = [lk for ref in (device.ref(c.index) for c in device.outputs())
                       for lk in self._links_from(ref) if self._system.is_present(lk.input)]
            if key in self.duplicates:
                self.duplicates.discard(key)
            self._last_change = now
            if was_present:
                self._duty_needed = True
                self._jobs += 1
        self.requests.abort(node.node_id, "the device left the bus")
        if not was_present:
            return
        log.info("%s: device %s left (node %d)", self.name, key, node.node_id)
        self._emit(ev.DeviceLeft(key))
        try:
            self._pool_exec.submit(self._silence_inputs, fed)
        except RuntimeError:
            with self._lock:
                self._jobs -= 1
        self._wake.set()

    def _links_from(self, output: ChannelRef) -> list[Link]:
        return [Link(output, i) for i in self._system.inputs_fed_by(output)]

    def _silence_inputs(self, links: list[Link]) -> None:
        """Inputs fed by a departed output stop listening: its node ID may be reused."""
        try:
            with self._plan_lock:
                for link in links:
                    with self._lock:
                        node_id = self._node_of.get(link.input.device)
                        others = [s for s in self._system.sources_of(link.input)
                                  if s != link.output and self._system.is_present(s)]
                    if node_id is None or others:
                        continue
                    try:
                        self.requests.set(node_id, P.CH_DATA_ENABLED, link.input.index, _OFF)
                        self.requests.set(node_id, P.IN_SOURCE_NODE_IDS, link.input.index,
                                          b"\0\0")
                    except PdcpError as err:
                        self._error(f"input {link.input} could not be told its source left: "
                                    f"{err}", "transport")
                        continue
                    with self._lock:
                        ch = self._system.channel(link.input)
                        if ch is not None:
                            ch.data_enabled = False
        finally:
            with self._lock:
                self._jobs -= 1

    def _refresh_channel_ids(self) -> None:
        """Under the lock: channel node ID → output, from the pool (decode needs the set)."""
        ids: dict[int, ChannelRef] = {}
        for node_id in range(self._pool.low, self._pool.high + 1):
            owner = self._pool.owner(node_id)
            if isinstance(owner, tuple) and len(owner) == 2:
                ids[node_id] = ChannelRef(*owner[0], owner[1])
        self._channel_ids = ids
        self._channel_set = frozenset(ids)

    # -- Update Data Channel --------------------------------------------------------------
    def _on_update(self, node: _Node, msg: UpdateDataChannel) -> None:
        self._send_quiet(UpdateDataChannelResponse(node.node_id, ResponseCode.SUCCESS,
                                                   msg.channel))
        with self._lock:
            node.updates.add(msg.channel)
            if not node.set_up:
                return  # set-up (step 5) handles it
            ref = ChannelRef(*node.key, msg.channel)
            links = [Link(s, ref) for s in self._system.sources_of(ref)]
            self._jobs += 1
        try:
            self._pool_exec.submit(self._sync_links, links)
        except RuntimeError:
            with self._lock:
                self._jobs -= 1

    def _sync_links(self, links: list[Link]) -> None:
        try:
            with self._plan_lock:
                for link in links:
                    with self._lock:
                        live = (self._system.has_link(link) and self._system.is_present(link.output)
                                and self._system.is_present(link.input))
                    if live:
                        try:
                            self._wire_add(link)
                        except PdcpError as err:
                            self._error(f"link {link} could not be re-made: {err}", "transport")
        finally:
            with self._lock:
                self._jobs -= 1

    # -- set-up (reference §1 steps 1–6) --------------------------------------------------
    def _current(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> bool:
        with self._lock:
            node = self._nodes.get(node_id)
            return (epoch == self._epoch and node is not None and node.key == key
                    and node.generation == generation)

    def _setup_job(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> None:
        try:
            device = self._read_device(key, node_id)
            if self._current(key, node_id, generation, epoch):
                self._commit(key, node_id, generation, epoch, device)
        except PdcpError as err:
            if self._current(key, node_id, generation, epoch) and not self._stop.is_set():
                with self._lock:
                    failures = self._setup_failures[key] = self._setup_failures.get(key, 0) + 1
                again = failures < SETUP_ATTEMPTS
                self._error(f"set-up of device {key} (node {node_id}) failed: {err}"
                            + ("; resetting it to try again" if again else ""), "setup")
                if again:
                    self._send_quiet(Reset(node_id))
        except Exception:
            log.exception("%s: set-up of %s failed", self.name, key)
        finally:
            with self._lock:
                if self._setups.get(key) == (epoch, generation):
                    del self._setups[key]
                self._last_change = time.monotonic()
            self._wake.set()

    def _get(self, node_id: int, param: int, channel: int = 0) -> bytes | None:
        """A set-up read; None if the device refuses (a parameter it does not have)."""
        try:
            return self.requests.get(node_id, param, channel)
        except DeviceRefusedError:
            return None

    def _read_device(self, key: DeviceKey, node_id: int) -> Device:
        """Steps 1–3 and the reads of steps 4–5: the device and all its channels."""
        device = Device(key.vid, key.pid, key.serial)
        ident = self._get(node_id, P.DEVICE_VID_PID)
        if ident is not None and len(ident) == 4 and _PAIR.unpack(ident) != (key.vid, key.pid):
            self._error(f"device {key} reports VID/PID {ident.hex()} after binding", "setup")
        for param in _DEVICE_PARAMS:
            value = self._get(node_id, param)
            if value is not None:
                learn_value(device, param, 0, value)
        count = self._get(node_id, P.DEVICE_CHANNEL_COUNT) or b"\0"
        for index in range(1, count[0] + 1):
            transfer = self._get(node_id, P.CH_TRANSFER_TYPE, index)
            if not transfer:
                continue
            try:
                direction = Direction.from_transfer_type(transfer[0])
            except ValueError as err:
                self._error(f"device {key} channel {index}: {err}", "setup")
                continue
            ch = device.add_channel(Channel(index, direction))
            params = _CHANNEL_PARAMS + (_INPUT_PARAMS if ch.is_input else ())
            for param in params:
                value = self._get(node_id, param, index)
                if value is not None:
                    learn_value(device, param, index, value)
        _only_inputs(device)
        return device

    def _commit(self, key: DeviceKey, node_id: int, generation: int, epoch: int,
                device: Device) -> None:
        """Steps 4 (channel node IDs), 5 and 6: install the device, re-make its links."""
        with self._plan_lock:
            ids: dict[int, int] = {}
            refused: list[str] = []
            with self._lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                for ch in device.outputs():
                    try:
                        ids[ch.index] = self._pool.take((key, ch.index))
                    except NodeIdExhaustedError as err:
                        refused.append(f"output {device.ref(ch.index)} gets no node ID and "
                                       f"cannot be linked: {err}")
                self._refresh_channel_ids()
            for text in refused:
                self._error(text, "node_ids_exhausted")
            for index, channel_id in ids.items():
                self.requests.set(node_id, P.OUT_NODE_ID, index, bytes([channel_id]))
                device.channels[index].node_id = channel_id
            with self._lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                node = self._nodes[node_id]
                old = self._system.device(key)
                joined = old is None or not old.present
                device.present, device.node_id = True, node_id
                device.name = old.name if old is not None else ""
                node.beacon_interval = max(device.beacon_interval, 1) / 1000.0
                if old is None:
                    self._system.add_device(device)
                else:
                    self._system.devices[key] = device
                    for link in self._system.links:
                        if key in (link.output.device, link.input.device):
                            try:
                                self._system.check_link(link)
                            except ModelError:
                                self._system.remove_link(link)
                links = [lk for lk in self._system.links
                         if key in (lk.output.device, lk.input.device)
                         and self._system.is_present(lk.output)
                         and self._system.is_present(lk.input)]
                node.set_up = True
                node.updates.clear()
                self._setup_failures.pop(key, None)
                if joined:
                    self._duty_needed = True
                self._last_change = time.monotonic()
            for link in links:
                try:
                    self._wire_add(link)
                except PdcpError as err:
                    self._error(f"link {link} could not be re-made: {err}", "transport")
        if joined:
            log.info("%s: device %s joined (node %d, %d channels)", self.name, key, node_id,
                     len(device.channels))
            self._emit(ev.DeviceJoined(key))
        self._wake.set()

    # -- links on the wire ----------------------------------------------------------------
    def _wire_add(self, link: Link) -> None:
        """Input: Source's Node Ids, the redundant source fields, Data Transfer Enabled;
        output: Data Transfer Enabled (setup step 6). Updates the model's channels."""
        with self._lock:
            out_node = self._node_of.get(link.output.device)
            in_node = self._node_of.get(link.input.device)
            out_id = self._pool.id_of((link.output.device, link.output.index))
            out_ch = self._system.channel(link.output)
            in_ch = self._system.channel(link.input)
            if out_node is None or in_node is None or out_ch is None or in_ch is None:
                raise ModelError(f"link {link}: both devices must be on the bus")
            if out_id is None:
                raise NodeIdExhaustedError(f"link {link}: output {link.output} has no node ID")
            want = SourceInfo(link.output.vid, link.output.pid, link.output.serial,
                              link.output.index, out_ch.type, out_ch.profile)
            have = in_ch.source
        i = link.input.index
        self.requests.set(in_node, P.IN_SOURCE_NODE_IDS, i, bytes([out_node, out_id]))
        if (have.vid, have.pid) != (want.vid, want.pid):
            self.requests.set(in_node, P.IN_SOURCE_VID_PID, i, _PAIR.pack(want.vid, want.pid))
        if (have.serial, have.index) != (want.serial, want.index):
            self.requests.set(in_node, P.IN_SOURCE_SN_INDEX, i,
                              _SN_INDEX.pack(want.serial, want.index))
        if (have.type, have.profile) != (want.type, want.profile):
            self.requests.set(in_node, P.IN_SOURCE_TYPE_PROFILE, i,
                              _PAIR.pack(want.type, want.profile))
        with self._lock:
            in_ch.source = want
        self.requests.set(in_node, P.CH_DATA_ENABLED, i, _ON)
        with self._lock:
            in_ch.data_enabled = True
        self.requests.set(out_node, P.CH_DATA_ENABLED, link.output.index, _ON)
        with self._lock:
            out_ch.data_enabled = True

    def _wire_remove(self, link: Link) -> None:
        """After the model dropped ``link``: clear the input unless it has another source,
        and stop the output unless it still feeds a present input."""
        with self._lock:
            in_node = self._node_of.get(link.input.device)
            out_node = self._node_of.get(link.output.device)
            in_ch = self._system.channel(link.input)
            out_ch = self._system.channel(link.output)
            other = self._system.source_of(link.input)
            still_feeds = any(self._system.is_present(i)
                              for i in self._system.inputs_fed_by(link.output))
        if in_node is not None and in_ch is not None and other is None:
            i = link.input.index
            self.requests.set(in_node, P.CH_DATA_ENABLED, i, _OFF)
            self.requests.set(in_node, P.IN_SOURCE_NODE_IDS, i, b"\0\0")
            for param, value in _NOT_CONNECTED.items():
                self.requests.set(in_node, param, i, value)
            with self._lock:
                in_ch.source, in_ch.data_enabled = NO_SOURCE, False
        if out_node is not None and out_ch is not None and not still_feeds:
            self.requests.set(out_node, P.CH_DATA_ENABLED, link.output.index, _OFF)
            with self._lock:
                out_ch.data_enabled = False

    def add_link(self, link: Link) -> None:
        """Make a link on the bus; ModelError for what the model refuses (a second source on
        an input, wrong directions) or an end that is not on the bus.

        A dead link (its output gone) on the same input is replaced.
        """
        with self._plan_lock:
            with self._lock:
                system = self._system
                system.check_link(link)
                if system.has_link(link):
                    return
                for end in (link.output, link.input):
                    if not system.is_present(end):
                        raise ModelError(f"link {link}: {end} is not on the bus")
                dead = [Link(s, link.input) for s in system.sources_of(link.input)
                        if not system.is_present(s)]
                live = [s for s in system.sources_of(link.input) if system.is_present(s)]
                if live:
                    raise ModelError(f"link {link}: input {link.input} already has source "
                                     f"{live[0]}")
            for old in dead:
                self._remove(old)
            self._add(link)

    def remove_link(self, link: Link) -> None:
        """Remove a link from the model and the bus (ModelError if there is no such link)."""
        with self._plan_lock:
            with self._lock:
                if not self._system.has_link(link):
                    raise ModelError(f"link {link} is not in the system")
            self._remove(link)

    def _add(self, link: Link) -> None:
        with self._lock:
            present = (self._system.is_present(link.output)
                       and self._system.is_present(link.input))
        if present:
            self._wire_add(link)
        with self._lock:
            if not self._system.has_link(link):
                self._system.add_link(link, check=False)
        self._emit(ev.LinkMade(link))

    def _remove(self, link: Link) -> None:
        with self._lock:
            if self._system.has_link(link):
                self._system.remove_link(link)
        self._wire_remove(link)
        self._emit(ev.LinkRemoved(link))

    # -- plans ----------------------------------------------------------------------------
    def apply_plan(self, plan: Plan, progress: Callable[[int, int, str], Any] | None = None,
                   cancel: threading.Event | None = None) -> None:
        """Carry out an engine plan's actions on the bus, in order; log it.

        An action that fails on the wire is reported and skipped, the others go on; the
        failures are raised together at the end (TransportError). ``cancel`` stops between
        actions (noted in the plan).
        """
        from pdcp_studio.engine.plan import Op

        failures: list[str] = []
        with self._plan_lock:
            with self._lock:
                self._plan_running += 1
            try:
                total = len(plan.actions)
                for done, action in enumerate(plan.actions):
                    if cancel is not None and cancel.is_set():
                        plan.notes.append(f"cancelled after {done} of {total} actions")
                        break
                    if progress is not None:
                        progress(done, total, f"{action.op.value} {action.link}")
                    try:
                        if action.op is Op.ADD:
                            with self._lock:
                                self._system.check_link(action.link)
                                exists = self._system.has_link(action.link)
                            if not exists:
                                self._add(action.link)
                        else:
                            with self._lock:
                                exists = self._system.has_link(action.link)
                            if exists:
                                self._remove(action.link)
                    except PdcpError as err:
                        failures.append(f"{action.op.value} {action.link}: {err}")
                        self._error(f"plan {plan.mode}: {failures[-1]}", "plan")
                else:
                    if progress is not None:
                        progress(total, total, f"plan {plan.mode} applied")
                self.applied_plans.append(plan)
                log.info("%s: applied plan %s: %d added, %d removed%s", self.name, plan.mode,
                         len(plan.added), len(plan.removed),
                         f", {len(failures)} failed" if failures else "")
                for action in plan.actions:
                    log.info("%s:   %s %s (%s)", self.name, action.op.value, action.link,
                             action.reason)
            finally:
                with self._lock:
                    self._plan_running -= 1
        self._emit(ev.PlanApplied(plan))
        if failures:
            raise TransportError(f"plan {plan.mode}: {len(failures)} action(s) failed: "
                                 + "; ".join(failures[:5]))

    def run_startup(self) -> Plan:
        """Listing 4.1 / 5.1 with the memory's configuration (or the devices' own)."""
        from pdcp_studio.engine import plan_startup
        from pdcp_studio.engine.procedures import missing_devices

        with self._plan_lock:
            with self._lock:
                self._duty_needed = False
            try:
                stored = self.read_memory()
            except (OSError, PdcpError) as err:
                # An unreadable memory must not keep the prosthesis unlinked: say so once and
                # start up from what the devices themselves store (as a replaced arbitrator).
                self._error(f"stored configuration unreadable, starting up from the devices' "
                            f"own source fields: {err}", "plan")
                stored = ConfigCollection([])
            snapshot = self.system()
            config = stored if stored.configurations else None
            plan = plan_startup(snapshot, config)
            try:
                self.apply_plan(plan)
                # What the stored configuration names and the bus lacks is shown as missing.
                with self._lock:
                    for device in missing_devices(self._system, config):
                        if self._system.device(device.key) is None:
                            self._system.add_device(device)
            finally:
                with self._lock:
                    self._startup_done = True
                    self._last_present = self._present_refs()
        return plan

    def run_duty_cycle(self) -> Plan:
        """Listing 4.2: replacements for channels that left, then autoconfigure."""
        from pdcp_studio.engine import plan_duty_cycle

        with self._plan_lock:
            with self._lock:
                self._duty_needed = False
                before = set(self._last_present)
            snapshot = self.system()
            plan = plan_duty_cycle(snapshot, before)
            try:
                if plan.actions:
                    self.apply_plan(plan)
            finally:
                with self._lock:
                    self._last_present = self._present_refs()
        return plan

    def _present_refs(self) -> set[ChannelRef]:
        return {ref for ref, _ in self._system.channels() if self._system.is_present(ref)}

    def _busy(self) -> bool:
        with self._lock:
            return bool(self._setups or self._held or self._deferred or self._jobs)

    def _profile_loop(self) -> None:
        while not self._stop.is_set():
            self._wake.wait(0.02)
            self._wake.clear()
            if self._stop.is_set() or not self.profile_layer:
                continue
            now = time.monotonic()
            try:
                if not self._startup_done:
                    if self._startup_due(now):
                        self.run_startup()
                elif (self._duty_needed and not self._busy()
                      and now - self._last_change >= self.duty_quiet_s):
                    self.run_duty_cycle()
            except PdcpError as err:
                self._error(f"profile layer: {err}", "plan")
            except Exception:
                log.exception("%s: the profile layer failed", self.name)

    def _startup_due(self, now: float) -> bool:
        """Listing 4.1's wait: no bind request for ``startup_quiet_s`` and nothing being set
        up; but never longer than ``startup_max_wait_s`` (a device that keeps asking for a
        taken ID and ignores the suggestion must not hold the prosthesis up)."""
        with self._lock:
            setups = bool(self._setups)
        if now - self._started >= self.startup_max_wait_s and not setups:
            if not self._busy():
                return True
            self._error(f"start-up runs after {self.startup_max_wait_s:g} s although binding "
                        "has not settled (a device keeps asking for an ID it is not given)",
                        "setup")
            return True
        since = max(self._started, self._last_bind, self._listen_until)
        quiet = now - since >= self.startup_quiet_s
        return quiet and not self._busy() and self.conn.inbound.empty()

    # -- reset ----------------------------------------------------------------------------
    def reset(self, keep_memory: bool = True) -> None:
        """Restart the arbitrator: forget the bus, reset every device (they bind again) and
        run start-up again; ``keep_memory=False`` erases the stored configuration first."""
        with self._plan_lock:
            if not keep_memory:
                self.memory.erase()
            with self._lock:
                nodes = list(self._nodes)
                self._stale_channels = frozenset(self._channel_ids)
                self._stale_until = time.monotonic() + RESET_GRACE_S
                self._epoch += 1
                self._system = System()
                self._pool.clear()
                self._nodes.clear()
                self._node_of.clear()
                self._refresh_channel_ids()
                self._held.clear()
                self._deferred.clear()
                self._setups.clear()
                self.duplicates.clear()
                self._exhausted_reported.clear()
                self._setup_failures.clear()
                self._unknown_reset.clear()
                self._foreign.clear()
                self._foreign_shown.clear()
                self._startup_done = False
                self._duty_needed = False
                self._last_present = set()
                now = time.monotonic()
                self._started = self._last_bind = self._last_change = now
            for node_id in nodes:
                self.requests.abort(node_id, "the arbitrator was reset")
            log.info("%s: reset (%s memory)", self.name, "kept" if keep_memory else "erased")
            self._broadcast_reset()
        self._wake.set()

    def devices_present(self) -> list[DeviceKey]:
        """Keys of the devices on the bus and set up."""
        with self._lock:
            return [k for k, d in self._system.devices.items() if d.present]

    def wait_for(self, predicate: Callable[[], bool], timeout: float) -> bool:
        """Poll ``predicate`` until it is true or ``timeout`` passes (tests, scripts)."""
        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() >= deadline:
                return False
            time.sleep(0.005)
        return True

