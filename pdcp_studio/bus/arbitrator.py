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

This module keeps the class, its threads and its public API; the parts are mixins next to it:
``arb_binding`` (bind requests, node IDs), ``arb_presence`` (beacons, departures, twins, foreign
nodes), ``arb_setup`` (set-up after binding), ``arb_links`` (links on the wire), ``arb_profile``
(start-up, duty cycle, plans), ``arb_transaction`` (the change road: interlock, write, verify,
restore, release; the policy) and ``arb_common`` (constants, node state, wire formats).
"""


from __future__ import annotations

import itertools
import logging
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arb_binding import BindingMixin
from pdcp_studio.bus.arb_claim import BusClaim, Phase
from pdcp_studio.bus.arb_common import (
    _MANAGED,
    BEACON_WINDOW,
    BIND_HOLD_S,
    DEFAULT_BEACON_INTERVAL_S,
    DUPLICATE_WINDOW,
    DUTY_QUIET_S,
    ECHOES_FOR_TWIN,
    FOREIGN_HOLD_S,
    FOREIGN_LISTEN_S,
    JOIN_S,
    MISSED_BEACONS,
    PRESENCE_GRACE,
    RESET_GRACE_S,
    RETRIES,
    SETUP_ATTEMPTS,
    SETUP_WORKERS,
    STARTUP_MAX_WAIT_S,
    STARTUP_QUIET_S,
    TICK_S,
    TWIN_BEACON_RATIO,
    UNKNOWN_RESET_S,
    _Node,
)
from pdcp_studio.bus.arb_links import LinksMixin
from pdcp_studio.bus.arb_presence import PresenceMixin
from pdcp_studio.bus.arb_profile import ProfileMixin
from pdcp_studio.bus.arb_setup import SetupMixin
from pdcp_studio.bus.arb_transaction import TransactionMixin
from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.log_limit import LimitedLog, RepeatLimiter
from pdcp_studio.bus.memory import MemoryStore
from pdcp_studio.bus.node_ids import NodeIdPool
from pdcp_studio.bus.requests import RESPONSE_TIMEOUT_S, RequestEngine
from pdcp_studio.bus.signals import decode_sample
from pdcp_studio.errors import FrameError, ModelError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.param_fields import learn_value, only_inputs
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import System
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    ChannelData,
    Message,
    Mode,
    Reset,
    UpdateDataChannel,
    decode,
)
from pdcp_studio.protocol.identifier import NODE_ID_MAX, NODE_ID_MIN

if TYPE_CHECKING:
    import can

    from pdcp_studio.engine.plan import Plan

log = logging.getLogger(__name__)

#: Errors of one kind (undecodable frames, error frames …) told in full before the limit:
#: then one a second, and the rest as one summary a second (``bus/log_limit.py``).
ERROR_BURST = 8

__all__ = [
    "BEACON_WINDOW",
    "BIND_HOLD_S",
    "DEFAULT_BEACON_INTERVAL_S",
    "DUPLICATE_WINDOW",
    "DUTY_QUIET_S",
    "ECHOES_FOR_TWIN",
    "FOREIGN_HOLD_S",
    "FOREIGN_LISTEN_S",
    "JOIN_S",
    "MISSED_BEACONS",
    "PRESENCE_GRACE",
    "RESET_GRACE_S",
    "RETRIES",
    "SETUP_ATTEMPTS",
    "SETUP_WORKERS",
    "STARTUP_MAX_WAIT_S",
    "STARTUP_QUIET_S",
    "TICK_S",
    "TWIN_BEACON_RATIO",
    "UNKNOWN_RESET_S",
    "Arbitrator",
    "learn_value",
]


#: A dispatch loop that did not come round for this long was stalled (it runs every TICK_S)…
STALL_S = 0.15
#: … and then waits this long before judging presence: the frames received meanwhile may still
#: sit in the driver's or the socket's buffer, unseen, and silence would be misread.
STALL_GRACE_S = 0.3

#: How a summary names the errors of a kind.
_ERROR_WORDS = {"bad_frame": "undecodable frames", "error_frame": "error frames",
                "transport": "transport errors"}


class Arbitrator(BindingMixin, PresenceMixin, SetupMixin, LinksMixin, ProfileMixin,
                 TransactionMixin):
    """A headless PDCP bus arbitrator on ``bus`` (which it owns and shuts down on close)."""

    def __init__(self, bus: can.BusABC, *, memory: str | Path | MemoryStore | None = None,
                 profile_layer: bool = True, name: str = "arbitrator", pace_s: float = 0.0,
                 response_timeout: float = RESPONSE_TIMEOUT_S, retries: int = RETRIES,
                 startup_quiet_s: float = STARTUP_QUIET_S, duty_quiet_s: float = DUTY_QUIET_S,
                 startup_max_wait_s: float = STARTUP_MAX_WAIT_S,
                 node_ids: tuple[int, int] = (NODE_ID_MIN, NODE_ID_MAX),
                 frame_events: bool = False, channel_events: bool = True,
                 reset_on_start: bool = True, autoconfigure: bool | None = None,
                 drop_own: bool | None = None, listen_s: float = 0.0) -> None:
        self.name = name
        self.profile_layer = profile_layer
        self.retries = retries
        self.startup_quiet_s = startup_quiet_s
        self.duty_quiet_s = duty_quiet_s
        self.startup_max_wait_s = startup_max_wait_s
        self.frame_events = frame_events
        self.channel_events = channel_events
        self.memory = memory if isinstance(memory, MemoryStore) else MemoryStore(memory)
        if autoconfigure is not None and self.memory.read_policy()["autoconfigure"] != \
                autoconfigure:  # ``--no-autoconfigure``: the flag sets the stored policy
            self.memory.write_policy({"autoconfigure": autoconfigure})
        self.applied_plans: list[Plan] = []
        self.bad_frames = 0
        self.error_frames = 0
        self.data_frames = 0
        self.duplicates: set[DeviceKey] = set()
        self.conn = Connection(bus, name=name, pace_s=pace_s, drop_own=drop_own)
        self._errors = RepeatLimiter(burst=ERROR_BURST)
        self._crashes = LimitedLog(log, f"{name}: ")
        self._disconnected = False  # the adapter was pulled (a ReopeningBus says so)
        if hasattr(bus, "on_state"):
            bus.on_state = self._adapter_state
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
        self._epoch = 0  # bumped by reset(): stale set-ups discard their results
        self._generations = itertools.count(1)
        self._plan_running = 0
        now = time.monotonic()
        self._started = now
        # Without the start-up reset, devices bound by an earlier arbitrator keep their IDs:
        # hear them all (beacons) before handing any ID out; the device asking retries.
        self._listen_until = now if reset_on_start else now + FOREIGN_LISTEN_S
        # One arbitrator per bus (reference §5, arb_claim): on a can: bus it first listens
        # ``listen_s``; until then (and for good once another arbitrator is heard) it writes
        # nothing, not even the start-up reset.
        self._claim = BusClaim(now, listen_s, own_echoes=self.conn.drop_own)
        self._listen_until = max(self._listen_until, self._claim.listen_until)
        self._reset_on_claim = reset_on_start
        self.bus_message = ""  # the last BusState line (why it arbitrates or not)
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
        if self._claim.may_write:
            self._claim_started(None)

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
        """Log and show a bus error; repeats of one kind are limited, then summarised."""
        told, summary = self._errors.admit(kind or message, message)
        if summary is not None:
            self._tell_error(summary.text(_ERROR_WORDS.get(summary.kind, "")), summary.kind)
        if told:
            self._tell_error(message, kind)

    def _tell_error(self, message: str, kind: str) -> None:
        log.warning("%s: %s", self.name, message)
        self._emit(ev.BusError(message, kind))

    def _flush_errors(self) -> None:
        for summary in self._errors.due():
            self._tell_error(summary.text(_ERROR_WORDS.get(summary.kind, "")), summary.kind)

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
    def bus_state(self) -> str:
        """``listening``, ``arbitrating`` or ``yielded`` (ev.BusState says when it changes)."""
        return self._claim.phase.value

    @property
    def yielded(self) -> bool:
        """True once another arbitrator was heard: this one writes nothing any more."""
        return self._claim.phase is Phase.YIELDED

    def wait_claimed(self, timeout: float) -> bool:
        """Wait until listening is over; True when this arbitrator arbitrates the bus."""
        deadline = time.monotonic() + timeout
        while self._claim.phase is Phase.LISTENING and time.monotonic() < deadline \
                and not self._closed:
            time.sleep(0.01)
        return self._claim.may_write

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
                only_inputs(device)
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
        if not self._claim.may_write:
            raise TransportError(f"{self.name}: not writing to the bus ({self.bus_state}: "
                                 "another arbitrator is on it or it is still being heard)")
        arbitration_id, data = message.encode()
        if message.mode is Mode.ARBITRATOR and message.node_id:
            with self._lock:
                node = self._nodes.get(message.node_id)
                if node is not None:
                    node.last_request = time.monotonic()
        # On a bus that echoes, the claim accounts for the copies (arb_claim), not the
        # connection's filter: a copy later than the filter waits must not pass for another
        # arbitrator's frame.
        self._claim.sent(arbitration_id, data, time.monotonic())
        self.conn.send(arbitration_id, data, filter_echo=False)
        if self.frame_events:
            self._frame_event(arbitration_id, data, time.time())

    def _send_quiet(self, message: Message) -> None:
        if not self._claim.may_write or self._disconnected:
            return  # listening, another arbitrator on the bus, or no adapter: say nothing
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
        last = time.monotonic()
        hold_until = 0.0
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
                if now - last > STALL_S:  # this process did not run (a loaded PC, a pause):
                    hold_until = now + STALL_GRACE_S  # frames may still wait in the driver
                last = now
                if now >= next_tick and self._claim_tick(now):
                    next_tick = now + TICK_S
                    self._flush_errors()
                    # Presence is judged only when every frame received so far is handled:
                    # a backlog (a busy machine) must not pass for silent devices.
                    self._tick(now, self.conn.inbound.empty() and now >= hold_until)
            except Exception:  # one bad frame or bug must never stop the arbitrator
                self._crashes.exception("dispatch", "dispatch failed")

    def _bad_frame(self, why: str) -> None:
        self.bad_frames += 1
        self._error(f"undecodable frame #{self.bad_frames}: {why}", "bad_frame")

    def _on_frame(self, msg: can.Message) -> None:
        data = bytes(msg.data)
        now = time.monotonic()
        if self._claim.is_own_echo(msg.arbitration_id, data, now):
            return  # our own frame, handed back by the bus (late or not)
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
        aid = msg.arbitration_id
        node_id = aid & 0xFF
        if not self._hear_claim(aid, data, now):
            return  # another arbitrator is on the bus: nothing here is ours to answer
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
            return  # (the claim has already yielded)
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
            self._count_beacon(node, now, self.conn.inbound.empty())
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

