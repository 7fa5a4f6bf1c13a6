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

The arbitrator is composed of parts, each with one job and its own state (as canopen composes
its ``Network`` from ``nmt``, ``lss`` and ``sdo``):

- ``claim`` (:class:`~pdcp_studio.bus.arb_claim.BusClaim`): may we write on this bus at all;
- ``nodes`` (:class:`~pdcp_studio.bus.arb_nodes.NodeTable`): who holds which node ID, and what
  to answer a bind request;
- ``presence`` (:class:`~pdcp_studio.bus.arb_presence.PresenceTracker`): who is gone at
  ``now``, twins on one node ID, nodes bound by someone else;
- ``setup`` (:class:`~pdcp_studio.bus.arb_setup.DeviceSetup`): reading a bound device with the
  device reader the scan shares (``bus/device_reader.py``) and installing it;
- ``links`` (:class:`~pdcp_studio.bus.arb_links.LinkWriter`): what to write for a link, and
  writing it;
- ``profile`` (:class:`~pdcp_studio.bus.arb_profile.ProfileDriver`): start-up, duty cycle, plans;
- ``transactions`` (:class:`~pdcp_studio.bus.arb_transaction.Transactions`): the change road.

The claim, node table and presence tracker decide from ``now`` and the frames heard and return
decisions (tested without threads); this class owns the bus, the threads, the lock and the
system, and carries the decisions out. ``arb_common`` holds the constants and node state.
"""


from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arb_claim import BusClaim, Decision, Phase
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
    UNREAD_BEACON_INTERVAL_S,
    _Node,
)
from pdcp_studio.bus.arb_links import LinkWriter
from pdcp_studio.bus.arb_nodes import BindDecision, NodeTable
from pdcp_studio.bus.arb_presence import PresenceTracker
from pdcp_studio.bus.arb_profile import ProfileDriver
from pdcp_studio.bus.arb_setup import DeviceSetup
from pdcp_studio.bus.arb_transaction import Transactions
from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.log_limit import LimitedLog, RepeatLimiter
from pdcp_studio.bus.memory import MemoryStore
from pdcp_studio.bus.node_ids import NodeIdPool
from pdcp_studio.bus.requests import RESPONSE_TIMEOUT_S, RequestEngine
from pdcp_studio.bus.signals import decode_sample
from pdcp_studio.bus.transaction import INTERLOCK_RENEW_S, Change, Policy, TransactionResult
from pdcp_studio.errors import FrameError, ModelError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.param_fields import learn_value, only_inputs
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    BindResponse,
    ChannelData,
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


class Arbitrator:
    """A headless PDCP bus arbitrator on ``bus`` (which it owns and shuts down on close)."""

    #: Seconds between two renewals of a transaction's interlock (tests shorten it).
    interlock_renew_s = INTERLOCK_RENEW_S

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
        self.frame_events = frame_events
        self.channel_events = channel_events
        self.memory = memory if isinstance(memory, MemoryStore) else MemoryStore(memory)
        if autoconfigure is not None and self.memory.read_policy()["autoconfigure"] != \
                autoconfigure:  # ``--no-autoconfigure``: the flag sets the stored policy
            self.memory.write_policy({"autoconfigure": autoconfigure})
        self.bad_frames = 0
        self.error_frames = 0
        self.data_frames = 0
        self.conn = Connection(bus, name=name, pace_s=pace_s, drop_own=drop_own)
        self._errors = RepeatLimiter(burst=ERROR_BURST)
        self._crashes = LimitedLog(log, f"{name}: ")
        self._disconnected = False  # the adapter was pulled (a ReopeningBus says so)
        if hasattr(bus, "on_state"):
            bus.on_state = self._adapter_state
        self.requests = RequestEngine(self._send, response_timeout=response_timeout,
                                      retries=retries)
        self._lock = threading.RLock()  # the parts' state and the system
        self._plan_lock = threading.RLock()  # wire work on links: plans, set-ups, transactions
        self._subscribers = ev.Subscribers(name)
        self._system = System()
        self._jobs = 0  # jobs in flight on the set-up pool besides set-ups (departures …)
        now = time.monotonic()
        # One arbitrator per bus (reference §5, arb_claim): on a can: bus it first listens
        # ``listen_s``; until then (and for good once another arbitrator is heard) it writes
        # nothing, not even the start-up reset.
        self.claim = BusClaim(now, listen_s, own_echoes=self.conn.drop_own)
        self._reset_on_claim = reset_on_start
        self.bus_message = ""  # the last BusState line (why it arbitrates or not)
        self.nodes = NodeTable(*node_ids)
        self.presence = PresenceTracker()
        self.setup = DeviceSetup(self)
        self.links = LinkWriter(self)
        # Without the start-up reset, devices bound by an earlier arbitrator keep their IDs:
        # hear them all (beacons) before handing any ID out; the device asking retries.
        listen_until = max(now if reset_on_start else now + FOREIGN_LISTEN_S,
                           self.claim.listen_until)
        self.profile = ProfileDriver(self, now, quiet_s=startup_quiet_s,
                                     duty_quiet_s=duty_quiet_s, max_wait_s=startup_max_wait_s,
                                     listen_until=listen_until)
        self.transactions = Transactions(self)
        self._decoder: Any = None
        if frame_events:
            from pdcp_studio.bus.monitor import FrameDecoder

            self._decoder = FrameDecoder()
        self._decoder_lock = threading.Lock()
        self._stop = threading.Event()
        self._wake = threading.Event()
        self._pool_exec = ThreadPoolExecutor(SETUP_WORKERS, thread_name_prefix=f"pdcp {name} setup")
        self._thread = threading.Thread(target=self._run, name=f"pdcp {name}", daemon=True)
        self._profile_thread = threading.Thread(target=self.profile.loop,
                                                name=f"pdcp {name} profile", daemon=True)
        self._closed = False
        self._thread.start()
        self._profile_thread.start()
        if self.claim.may_write:
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
            return self.nodes.node_of.get(DeviceKey(*key))

    def channel_node_id(self, ref: ChannelRef) -> int | None:
        """The node ID an output channel sends its data with (None if it has none)."""
        with self._lock:
            return self.nodes.output_id(ref)

    @property
    def channel_node_ids(self) -> frozenset[int]:
        """The node IDs output channels send their data with now (a frame's node ID in this
        set and mode 0 is channel data)."""
        return self.nodes.channel_set

    @property
    def duplicates(self) -> set[DeviceKey]:
        """Devices reported as twins (two on the bus with one VID/PID/serial)."""
        return self.presence.duplicates

    @property
    def stale_data_frames(self) -> int:
        """Data frames on channel node IDs from before the last reset (expected, counted)."""
        return self.presence.stale_data_frames

    @property
    def applied_plans(self) -> list[Plan]:
        return self.profile.applied_plans

    @property
    def _pool(self) -> NodeIdPool:  # (tests look at the pool's free IDs)
        return self.nodes.pool

    @property
    def _nodes(self) -> dict[int, _Node]:  # (tests look at a node's state)
        return self.nodes.by_id

    @property
    def bus_state(self) -> str:
        """``listening``, ``arbitrating`` or ``yielded`` (ev.BusState says when it changes)."""
        return self.claim.phase.value

    @property
    def yielded(self) -> bool:
        """True once another arbitrator was heard: this one writes nothing any more."""
        return self.claim.phase is Phase.YIELDED

    def wait_claimed(self, timeout: float) -> bool:
        """Wait until listening is over; True when this arbitrator arbitrates the bus."""
        deadline = time.monotonic() + timeout
        while self.claim.phase is Phase.LISTENING and time.monotonic() < deadline \
                and not self._closed:
            time.sleep(0.01)
        return self.claim.may_write

    @property
    def startup_done(self) -> bool:
        return self.profile.startup_done

    def _busy(self) -> bool:
        """Binds held or deferred, set-ups or jobs under way."""
        with self._lock:
            return bool(self.setup.in_flight or self.nodes.held or self.nodes.deferred
                         or self._jobs)

    def _settled(self) -> bool:
        with self._lock:
            busy = self._busy() or bool(self.profile.plan_running)
            if self.profile_layer:
                busy = busy or not self.profile.startup_done or self.profile.duty_needed
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

    # -- jobs on the set-up pool ----------------------------------------------------------
    def _submit_job(self, fn: Callable[..., None], *args: Any) -> None:
        """Run ``fn(*args)`` on the set-up pool, counted until it calls :meth:`_job_done`."""
        with self._lock:
            self._jobs += 1
        try:
            self._pool_exec.submit(fn, *args)
        except RuntimeError:  # closing
            self._job_done()

    def _job_done(self) -> None:
        with self._lock:
            self._jobs -= 1

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
                node = self.nodes.node(key)
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

    # -- links, plans, transactions (the parts do the work) -------------------------------
    def add_link(self, link: Link) -> None:
        """Make a link on the bus; ModelError for what the model refuses (a second source on
        an input, wrong directions) or an end that is not on the bus.

        A dead link (its output gone) on the same input is replaced.
        """
        self.links.add_link(link)

    def remove_link(self, link: Link) -> None:
        """Remove a link from the model and the bus (ModelError if there is no such link)."""
        self.links.remove_link(link)

    def apply_plan(self, plan: Plan, progress: Callable[[int, int, str], Any] | None = None,
                   cancel: threading.Event | None = None) -> TransactionResult:
        """Carry out an engine plan's actions on the bus, in order, with no interlock (the
        profile layer's own start-up and duty cycle); log it and return what came of it.

        An action that fails on the wire is reported and skipped, the others go on (status
        ``failed``, reason naming them). ``cancel`` stops between actions. Changes a person
        asks for go through :meth:`transact` instead (interlock, verify, all or nothing).
        """
        return self.profile.apply_plan(plan, progress, cancel)

    def run_startup(self) -> Plan:
        """Listing 4.1 / 5.1 with the memory's configuration (or the devices' own)."""
        return self.profile.run_startup()

    def run_duty_cycle(self) -> Plan:
        """Listing 4.2: replacements for channels that left, then autoconfigure."""
        return self.profile.run_duty_cycle()

    def read_policy(self) -> Policy:
        """The profile-layer policy kept in memory beside the stored configuration; an
        unreadable memory gives the thesis's default (autoconfigure on)."""
        return self.transactions.read_policy()

    def transact(self, change: Change, progress: Callable[[int, int, str], Any] | None = None,
                 cancel: threading.Event | None = None) -> TransactionResult:
        """Carry ``change`` out as one transaction (reference §5: interlock, write, verify,
        restore, release); never raises for a bus failure — the result says applied, failed
        or rolled back, at which step and why."""
        return self.transactions.transact(change, progress, cancel)

    def _do_link(self, op: str, link: Link) -> None:  # (a test slows a transaction down here)
        self.transactions.do_link(op, link)

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
        if not self.claim.may_write:
            raise TransportError(f"{self.name}: not writing to the bus ({self.bus_state}: "
                                 "another arbitrator is on it or it is still being heard)")
        arbitration_id, data = message.encode()
        if message.mode is Mode.ARBITRATOR and message.node_id:
            with self._lock:
                node = self.nodes.by_id.get(message.node_id)
                if node is not None:
                    node.last_request = time.monotonic()
        # On a bus that echoes, the claim accounts for the copies (arb_claim), not the
        # connection's filter: a copy later than the filter waits must not pass for another
        # arbitrator's frame.
        self.claim.sent(arbitration_id, data, time.monotonic())
        self.conn.send(arbitration_id, data, filter_echo=False)
        if self.frame_events:
            self._frame_event(arbitration_id, data, time.time())

    def _send_quiet(self, message: Message) -> None:
        if not self.claim.may_write or self._disconnected:
            return  # listening, another arbitrator on the bus, or no adapter: say nothing
        try:
            self._send(message)
        except TransportError as err:
            self._error(str(err), "transport")

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
                    self._on_frame(cast("can.Message", item))
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
        if self.claim.is_own_echo(msg.arbitration_id, data, now):
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
        if self.nodes.is_foreign(aid):
            self._foreign_frame(node_id, aid, data, now)
            return
        try:
            message = decode(aid, data, channel_node_ids=self.nodes.channel_set)
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
            node = self.nodes.by_id.get(node_id)
            if node is not None:
                node.last_seen = now
                if isinstance(message, Beacon):
                    node.last_beacon = now
        if node is None:  # node 0, or a device that left a moment ago
            return
        if isinstance(message, Beacon):
            why = self.presence.beacon(node, now, self.conn.inbound.empty())
            if why:
                self._twin(node.key, why)
            return
        if isinstance(message, UpdateDataChannel):
            self.links.on_update(node, message)
            return
        echo, why = self.presence.response(node, aid, data, now,
                                           2 * self.requests.response_timeout)
        if why:
            self._twin(node.key, why)
        if not echo:
            self.requests.feed(message)

    def _on_data(self, message: ChannelData, timestamp: float) -> None:
        self.data_frames += 1
        if not self.channel_events:
            return
        with self._lock:
            ref = self.nodes.channel_ids.get(message.node_id)
            ch = self._system.channel(ref) if ref else None
            kind = ch.type if ch else 0
        if ref is not None:
            self._emit(ev.ChannelValue(ref, decode_sample(kind, message.data), timestamp))

    # -- binding (the node table decides) -------------------------------------------------
    def _on_bind(self, req: BindRequest, now: float) -> None:
        key = DeviceKey(req.vid, req.pid, req.serial)
        with self._lock:
            if key not in self.presence.duplicates and key not in self.nodes.exhausted_reported:
                self.profile.last_bind = now
        if now < self.profile.listen_until:
            return  # still learning which IDs devices of an earlier arbitrator use
        with self._lock:
            decision = self.nodes.on_bind_request(req, now, self.presence.duplicates)
            if decision.kind == "grant":
                self._bound(decision.key, decision.node_id, now)
        self._answer(decision)

    def _answer_bind(self, req: BindRequest, now: float) -> None:
        with self._lock:
            decision = self.nodes.decide_bind(req, now)
            if decision.kind == "grant":
                self._bound(decision.key, decision.node_id, now)
        self._answer(decision)

    def _answer(self, decision: BindDecision) -> None:
        key = decision.key
        if decision.kind == "exhausted":
            if decision.report:  # once per device, not per retry
                self._error(decision.report, "node_ids_exhausted")
        elif decision.kind in ("grant", "suggest"):
            self._send_quiet(BindResponse(decision.asked, decision.node_id, key.vid, key.pid,
                                          key.serial))

    def _bound(self, key: DeviceKey, node_id: int, now: float) -> None:
        """Under the lock: ``key`` holds ``node_id``; start (or restart) its set-up."""
        device = self._system.device(key)
        interval = (max(device.beacon_interval, 1) / 1000.0 if device is not None
                    else max(DEFAULT_BEACON_INTERVAL_S, UNREAD_BEACON_INTERVAL_S))
        node, old = self.nodes.install(key, node_id, now, interval)
        if old is not None and old != node_id:
            self.requests.abort(old, "the device bound again with another node ID")
        self.profile.last_change = now
        self.setup.start(node)

    # -- presence (the presence tracker decides) ------------------------------------------
    def _tick(self, now: float, caught_up: bool = True) -> None:
        """Presence, held and foreign node IDs, deferred binds."""
        with self._lock:
            gone = self.presence.absent(list(self.nodes.by_id.values()), now) \
                if caught_up else []
            self.nodes.expire(now)
            resolved = self.nodes.resolve_deferred(now, self.presence.duplicates) \
                if caught_up else []
        for node in gone:
            self._depart(node, now)
        for req, twin in resolved:
            key = DeviceKey(req.vid, req.pid, req.serial)
            if twin:
                self._twin(key, "a second one asked to bind while the first kept beaconing")
            else:
                log.info("%s: device %s binds again (it restarted)", self.name, key)
                with self._lock:
                    again = self.nodes.node(key)
                    if again is not None:
                        again.set_up = False
                self._answer_bind(req, now)

    def _twin(self, key: DeviceKey, why: str) -> None:
        with self._lock:
            line = self.presence.report(key, why)
        self._error(line, "duplicate_device")

    def _depart(self, node: _Node, now: float) -> None:
        key = node.key
        with self._lock:
            if not self.nodes.remove(node):
                return
            self.setup.in_flight.pop(key, None)
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
                       for lk in self.links.links_from(ref)
                       if self._system.is_present(lk.input)]
            self.presence.duplicates.discard(key)
            self.profile.last_change = now
            if was_present:
                self.profile.duty_needed = True
        self.requests.abort(node.node_id, "the device left the bus")
        if not was_present:
            return
        log.info("%s: device %s left (node %d)", self.name, key, node.node_id)
        self._emit(ev.DeviceLeft(key))
        self._submit_job(self.links.silence_inputs, fed)
        self._wake.set()

    def _foreign_frame(self, node_id: int, aid: int, data: bytes, now: float) -> None:
        """A frame from a node ID nobody holds here: a device (or output) bound by an earlier
        arbitrator. Its ID is kept out of the pool while it is heard; a device is reset so
        it binds with us; undecodable frames are counted, and shown once per node."""
        with self._lock:
            self.nodes.hear_foreign(node_id, now)
        try:
            message = decode(aid, data)
        except FrameError as err:
            what = self.presence.bad_stranger_frame(node_id, now)
            if what == "stale":
                return  # data already on the wire when we reset
            self.bad_frames += 1
            if what == "show":
                self._error(f"undecodable frame #{self.bad_frames} 0x{aid:03X} "
                            f"[{data.hex(' ').upper()}] from node {node_id}, which is not "
                            f"bound here: {err} (further ones are counted, not shown)",
                            "bad_frame")
            return
        if isinstance(message, Beacon | UpdateDataChannel):
            with self._lock:
                stranger = node_id not in self.nodes.channel_ids
            if stranger and self.presence.may_reset_stranger(node_id, now):
                log.info("%s: node %d is not bound here: resetting it", self.name, node_id)
                self._send_quiet(Reset(node_id))
        if isinstance(message, UpdateDataChannel):
            self._send_quiet(UpdateDataChannelResponse(node_id, ResponseCode.FAILURE,
                                                       message.channel))

    # -- one arbitrator per bus (reference §5; the claim decides) -------------------------
    def _hear_claim(self, arbitration_id: int, data: bytes, now: float) -> bool:
        """Feed a received frame to the claim; False once another arbitrator is on the bus
        (then nothing received is ours to handle)."""
        decision = self.claim.heard(arbitration_id, data, now)
        if decision is not None:
            self._claim_yielded(decision)
        return not self.claim.yielded

    def _claim_tick(self, now: float) -> bool:
        """End the listening when it is due, beacon when due; True while arbitrating (and
        the adapter is there: presence is not judged while nobody can be heard)."""
        decision = self.claim.tick(now)
        if decision is not None:
            self._claim_started(decision)
        if self.claim.beacon_due(now):
            self._send_quiet(Beacon(0, mode=Mode.ARBITRATOR))
        return bool(self.claim.may_write) and not self._disconnected

    def _claim_started(self, decision: Decision | None) -> None:
        """The bus is ours: the start-up reset (a replaced arbitrator's devices bind again)."""
        if decision is not None:
            self.bus_message = decision.message
            log.info("%s: %s", self.name, decision.message)
            self._emit(ev.BusState("arbitrating", decision.message))
            with self._lock:
                self.presence.unknown_reset.clear()  # resets skipped while listening may go
        if self._reset_on_claim or (decision is not None and decision.takeover):
            self._send_quiet(Reset(0))

    def _claim_yielded(self, decision: Decision) -> None:
        """Another arbitrator is on the bus: stop writing at once and say so, once."""
        self.bus_message = decision.message
        # Info, not warning: the yield event is what callers show (the CLI's one error line);
        # a warning would reach stderr a second time through logging's last-resort handler.
        log.info("%s: %s", self.name, decision.message)
        with self._lock:
            nodes = list(self.nodes.by_id)
        for node_id in nodes:
            self.requests.abort(node_id, "another bus arbitrator is on the bus")
        self._emit(ev.BusState("yielded", decision.message))
        self._wake.set()

    # -- a pulled adapter (bus/reopen.py reopens it) --------------------------------------
    def _adapter_state(self, state: str, line: str) -> None:
        """Called on the Notifier's thread: hand it to the dispatch thread."""
        self.conn.post(lambda: self._on_adapter_state(state, line))

    def _on_adapter_state(self, state: str, line: str) -> None:
        """Disconnected: presence is not judged (nobody can be heard) and nothing is sent.
        Reconnected: every device gets its beacon intervals to be heard again, and the links
        are read back from the inputs and re-made where they differ."""
        now = time.monotonic()
        with self._lock:
            self._disconnected = state == "disconnected"
            if not self._disconnected:
                for node in self.nodes.by_id.values():
                    node.last_seen = max(node.last_seen, now)
        self._emit(ev.BusState(state, line))
        if not self._disconnected:
            self._submit_job(self.links.reread)

    # -- reset ----------------------------------------------------------------------------
    def reset(self, keep_memory: bool = True) -> None:
        """Restart the arbitrator: forget the bus, reset every device (they bind again) and
        run start-up again; ``keep_memory=False`` erases the stored configuration first."""
        with self._plan_lock:
            if not keep_memory:
                self.memory.erase()
            with self._lock:
                node_ids = list(self.nodes.by_id)
                now = time.monotonic()
                self.presence.forget(self.nodes.channel_ids, now)
                self.setup.forget()
                self._system = System()
                self.nodes.clear()
                self.profile.restart(now)
            for node_id in node_ids:
                self.requests.abort(node_id, "the arbitrator was reset")
            log.info("%s: reset (%s memory)", self.name, "kept" if keep_memory else "erased")
            self._send_quiet(Reset(0))
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
