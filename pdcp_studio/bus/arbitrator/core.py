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
its ``Network`` from ``nmt``, ``lss`` and ``sdo``, which see only ``send_message`` and
``subscribe``). No part sees the arbitrator: each gets in its constructor the few things it
needs — the shared :class:`~pdcp_studio.bus.arbitrator.state.SystemState` (the system, its
lock, the wire lock), the request engine, and callables to send a frame, emit an event,
report an error or submit a job — and asks another part through a call, never by writing its
fields. :meth:`Arbitrator._wire` connects them, in one place.

- ``claim`` (:class:`~pdcp_studio.bus.arbitrator.claim.BusClaim`): may we write on this bus at all;
- ``nodes`` (:class:`~pdcp_studio.bus.arbitrator.nodes.NodeTable`): who holds which node ID, and
  what to answer a bind request; the model's node IDs are stamped from it (``NodeTable.stamp``);
- ``presence`` (:class:`~pdcp_studio.bus.arbitrator.presence.PresenceTracker`): who is gone at
  ``now``, twins on one node ID, nodes bound by someone else;
- ``setup`` (:class:`~pdcp_studio.bus.arbitrator.setup.DeviceSetup`): reading a bound device with
  the device reader the scan shares (``bus/arbitrator/reading/device_reader.py``) and installing it;
- ``links`` (:class:`~pdcp_studio.bus.arbitrator.links.LinkWriter`): what to write for a link, and
  writing it;
- ``profile`` (:class:`~pdcp_studio.bus.arbitrator.profile.driver.ProfileDriver`): start-up, duty
  cycle, plans, and when they are due;
- ``transactions`` (:class:`~pdcp_studio.bus.arbitrator.change.transactions.Transactions`): the
  change road, holding devices through the motion interlock
  (``bus/arbitrator/change/interlock.py``);
- ``dispatch`` (:class:`~pdcp_studio.bus.arbitrator.dispatch.Dispatcher`): the dispatch thread,
  which hears every frame, asks the deciding parts and carries their decisions out.

The claim, node table and presence tracker decide from ``now`` and the frames heard and return
decisions (tested without threads); this class owns the bus, the threads (the profile
thread's body is ``bus/arbitrator/profile/thread.py``), the set-up pool
(``bus/arbitrator/jobs.py``), the state and the errors' limiter, sends, and keeps the public
API. ``bus/arbitrator/common.py`` holds the constants and node state.
"""


from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.change.interlock import Interlock
from pdcp_studio.bus.arbitrator.change.transactions import Transactions
from pdcp_studio.bus.arbitrator.claim import BusClaim, Phase
from pdcp_studio.bus.arbitrator.common import (
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
from pdcp_studio.bus.arbitrator.dispatch import Dispatcher
from pdcp_studio.bus.arbitrator.frame_events import FrameFeed
from pdcp_studio.bus.arbitrator.jobs import JobPool
from pdcp_studio.bus.arbitrator.links import LinkWriter
from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.bus.arbitrator.node_ids import NodeIdPool
from pdcp_studio.bus.arbitrator.nodes import NodeTable
from pdcp_studio.bus.arbitrator.presence import PresenceTracker
from pdcp_studio.bus.arbitrator.profile.driver import ProfileDriver, ProfilePorts
from pdcp_studio.bus.arbitrator.profile.thread import ProfileThread
from pdcp_studio.bus.arbitrator.reading.requests import RESPONSE_TIMEOUT_S, RequestEngine
from pdcp_studio.bus.arbitrator.setup import DeviceSetup
from pdcp_studio.bus.arbitrator.state import SystemState
from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.log_limit import LimitedLog, RepeatLimiter
from pdcp_studio.bus.transaction import INTERLOCK_RENEW_S, Change, Policy, TransactionResult
from pdcp_studio.errors import ModelError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.param_fields import learn_value, only_inputs
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.protocol import (
    Message,
    Mode,
    Reset,
)
from pdcp_studio.protocol.identifier import NODE_ID_MAX, NODE_ID_MIN

if TYPE_CHECKING:
    import can

    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.storage.archive.chain import Anchor

log = logging.getLogger(__name__)

#: ``wait_settled`` looks again at least this often; it is woken sooner by news of a set-up,
#: bind or plan (a second waiter may take the news: it then looks at its next poll).
SETTLE_POLL_S = 0.01
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

def _always() -> bool:
    return True


@runtime_checkable
class ReportsAdapterState(Protocol):
    """A bus that says when its adapter is pulled and back (``bus/reopen.py``'s ReopeningBus):
    ``on_state(state, line)``."""

    on_state: Callable[[str, str], None] | None


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
                 drop_own: bool | None = None, listen_s: float = 0.0,
                 direct: bool = False, take_back: bool = False) -> None:
        self.name = name
        self.profile_layer = profile_layer
        self.retries = retries
        self._frame_events = frame_events  # fixed for its life: sent frames here, heard
        # ones by the dispatcher (``show_frame``)
        self.memory = memory if isinstance(memory, MemoryStore) else MemoryStore(memory)
        if autoconfigure is not None and self.memory.read_policy()["autoconfigure"] != \
                autoconfigure:  # ``--no-autoconfigure``: the flag sets the stored policy
            self.memory.write_policy({"autoconfigure": autoconfigure})
        self.conn = Connection(bus, name=name, pace_s=pace_s, drop_own=drop_own, direct=direct)
        self._errors = RepeatLimiter(burst=ERROR_BURST)
        self.requests = RequestEngine(self._send, response_timeout=response_timeout,
                                      retries=retries)
        self._state = SystemState()
        self._subscribers = ev.Subscribers(name)
        self._jobs = JobPool(SETUP_WORKERS, name, self._state.lock)
        self._frames = FrameFeed(self._emit)
        self._stop = threading.Event()
        self._wake = threading.Event()
        #: Set whenever the bus may have settled (a set-up, a bind, a start-up or duty cycle
        #: ended): ``wait_settled`` looks again at once instead of at its next poll.
        self._news = threading.Event()
        now = time.monotonic()
        # One arbitrator per bus (reference §5, arb_claim): on a can: bus it first listens
        # ``listen_s``; until then (and while another arbitrator is heard) it writes nothing,
        # not even the start-up reset. ``take_back`` (the headless arbitrator): one that
        # appeared later is waited out, and the bus taken back when its beacons are gone.
        self.claim = BusClaim(now, listen_s, own_echoes=self.conn.drop_own,
                              take_back=take_back)
        self.nodes = NodeTable(*node_ids)
        self.presence = PresenceTracker()
        self._wire(now, reset_on_start=reset_on_start, startup_quiet_s=startup_quiet_s,
                   duty_quiet_s=duty_quiet_s, startup_max_wait_s=startup_max_wait_s,
                   channel_events=channel_events)
        if isinstance(bus, ReportsAdapterState):
            bus.on_state = self.dispatch.adapter_state
        self._thread = threading.Thread(target=self.dispatch.run, name=f"pdcp {name}",
                                        daemon=True)
        profile = ProfileThread(
            self.profile, stop=self._stop, wake=self._wake,
            may_run=lambda: self.profile_layer and self.claim.may_write, busy=self._busy,
            setting_up=self.setup.under_way, caught_up=self.conn.inbound.empty,
            present=self.devices_present, error=self._error, closed=lambda: self._closed,
            ran=self._news.set, name=name)
        self._profile_thread = threading.Thread(target=profile.run, name=f"pdcp {name} profile",
                                                daemon=True)
        self._closed = False
        self._thread.start()
        self._profile_thread.start()
        if self.claim.may_write:
            self.dispatch.claim_started(None)

    def _wire(self, now: float, *, reset_on_start: bool, startup_quiet_s: float,
              duty_quiet_s: float, startup_max_wait_s: float, channel_events: bool) -> None:
        """Make the parts and connect their ports: the one place they meet. Methods a test
        replaces on the instance (``read_memory``, ``_do_link`` and the ``add_link`` it calls,
        ``interlock_renew_s``) are asked each time, through a lambda."""
        state, name = self._state, self.name
        self.links = LinkWriter(state, self.nodes, self.requests, send=self._send_quiet,
                                submit=self._jobs.submit, error=self._error, emit=self._emit,
                                name=name)
        interlock = Interlock(suspend=self.suspend, release=self.release,
                              renew_s=lambda: self.interlock_renew_s, name=name)
        # Without the start-up reset, devices bound by an earlier arbitrator keep their IDs:
        # hear them all (beacons) before handing any ID out; the device asking retries.
        listen_until = max(now if reset_on_start else now + FOREIGN_LISTEN_S,
                           self.claim.listen_until)
        self.profile = ProfileDriver(
            ProfilePorts(state, add_link=self.links.add, remove_link=self.links.remove,
                         interlock=interlock, read_memory=lambda: self.read_memory(),
                         read_policy=lambda: self.read_policy(), error=self._error,
                         emit=self._emit, closed=lambda: self._closed, name=name,
                         verify_inputs=lambda refs: self.transactions.verify_inputs(refs)),
            now, quiet_s=startup_quiet_s, duty_quiet_s=duty_quiet_s,
            max_wait_s=startup_max_wait_s, listen_until=listen_until)
        self.setup = DeviceSetup(state, self.nodes, self.requests, run=self._jobs.run,
                                 wire_add=self.links.wire_add,
                                 note_change=self.profile.note_change, send=self._send_quiet,
                                 error=self._error, emit=self._emit, wake=self._stir,
                                 stopping=self._stop.is_set, name=name)
        self.transactions = Transactions(
            state, self.memory, self.links, interlock=interlock, running=self.profile.running,
            get_parameter=self.get_parameter, set_parameter=self.set_parameter,
            node_id_of=self.node_id_of, channel_node_id=self.channel_node_id,
            do_link=lambda op, link: self._do_link(op, link),
            read_memory=lambda: self.read_memory(), write_memory=self.write_memory,
            emit=self._emit, name=name)
        self.dispatch = Dispatcher(
            state, self.conn, self.claim, self.nodes, self.presence, self.requests,
            links=self.links, setup=self.setup, profile=self.profile,
            show_frame=self._frames.frame if self._frame_events else None,
            channel_events=channel_events, reset_on_claim=reset_on_start,
            send=self._send_quiet, error=self._error, flush_errors=self._flush_errors,
            crashes=LimitedLog(log, f"{name}: "), emit=self._emit, wake=self._stir,
            stop=self._stop, name=name)

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
        self._stir()
        self.requests.close()
        self.conn.wake()
        self._jobs.shutdown()
        for thread in (self._thread, self._profile_thread):
            if thread is not threading.current_thread():
                thread.join(timeout=JOIN_S)
        self.conn.close()

    @property
    def closed(self) -> bool:
        return self._closed

    # -- events ---------------------------------------------------------------------------
    def subscribe(self, callback: Callable[[ev.Event], None], *,
                  wants_frames: Callable[[], bool] | None = None) -> Callable[[], None]:
        """Call ``callback(event)`` for every event; returns the unsubscribe function.

        ``wants_frames`` (with ``frame_events``): asked before each frame whether this
        subscriber shows ``FrameSeen`` events now (a session: while it has subscribers of its
        own); without it, it always does. While no subscriber wants them, frames are not
        decoded for display: they wait (``FRAME_BACKLOG`` at most) and are decoded, in order,
        before the next frame one is shown, so the texts are the same, and the work is off
        the path of opening a simulated prosthesis, which nobody watches yet."""
        unwatch = self._frames.watch(wants_frames if wants_frames is not None else _always)
        remove = self._subscribers.add(callback)

        def unsubscribe() -> None:
            remove()
            unwatch()

        return unsubscribe

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
        return self._state.snapshot()

    def node_id_of(self, key: DeviceKey) -> int | None:
        """The node ID of a bound device (None if it is not bound)."""
        with self._state.lock:
            return self.nodes.node_of.get(DeviceKey(*key))

    def channel_node_id(self, ref: ChannelRef) -> int | None:
        """The node ID an output channel sends its data with (None if it has none)."""
        with self._state.lock:
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
    def _decoder(self) -> FrameDecoder | None:  # (tests look at the frame events' decoder …)
        return self._frames.decoder

    @property
    def _unshown(self) -> list[tuple[int, bytes, float]]:  # (… the frames waiting for it …)
        return self._frames.unshown

    @property
    def _frame_gates(self) -> list[Callable[[], bool]]:  # (… and who wants frames now)
        return self._frames.gates

    @property
    def _pool(self) -> NodeIdPool:  # (tests look at the pool's free IDs)
        return self.nodes.pool

    @property
    def _nodes(self) -> dict[int, _Node]:  # (tests look at a node's state)
        return self.nodes.by_id

    @property
    def bad_frames(self) -> int:
        """Frames heard that are not PDCP (undecodable, extended, remote)."""
        return self.dispatch.bad_frames

    @property
    def error_frames(self) -> int:
        return self.dispatch.error_frames

    @property
    def data_frames(self) -> int:
        """Channel data frames heard."""
        return self.dispatch.data_frames

    @property
    def bus_message(self) -> str:
        """The last BusState line (why it arbitrates or not)."""
        return self.dispatch.bus_message

    @property
    def bus_state(self) -> str:
        """``listening``, ``arbitrating`` or ``yielded`` (ev.BusState says when it changes)."""
        return self.claim.phase.value

    @property
    def yielded(self) -> bool:
        """True while another arbitrator is heard: this one writes nothing (with
        ``take_back`` until the other's beacons are gone; else for good)."""
        return self.claim.phase is Phase.YIELDED

    @property
    def read_only(self) -> bool:
        """Another arbitrator appeared after this one had started: it stays up, writes
        nothing, and takes the bus back when the other's beacons are gone (``take_back``)."""
        return self.yielded and self.claim.later and self.claim.take_back

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
        with self._state.lock:
            return bool(self.setup.under_way() or self.nodes.held or self.nodes.deferred
                        or self._jobs.busy())

    def _settled(self) -> bool:
        with self._state.lock:
            return not self._busy() and self.profile.settled(self.profile_layer)

    def wait_settled(self, timeout: float) -> bool:
        """True once no bind, set-up or plan is in progress and start-up has run."""
        deadline = time.monotonic() + timeout
        while True:
            self._news.clear()  # before looking: news from now on wakes the wait below
            if self._settled():
                return True
            left = deadline - time.monotonic()
            if left <= 0 or self._closed:
                return False
            self._news.wait(min(SETTLE_POLL_S, left))

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
        with self._state.lock:
            device = self._state.system.device(key)
            ch = device.channels.get(channel) if device and channel else None
        scope = "device" if channel == 0 else ch.direction.value if ch else ""
        if (param, scope) in _MANAGED:
            raise ModelError(f"parameter {param} of channel {channel} is managed by the "
                             "arbitrator (node IDs follow binding and links)")
        self.requests.set(self._node_for(key), param, channel, bytes(value), timeout=timeout)
        self._learn(key, param, channel, bytes(value))

    def _learn(self, key: DeviceKey, param: int, channel: int, value: bytes) -> None:
        with self._state.lock:
            device = self._state.system.device(key)
            if device is not None:
                learn_value(device, param, channel, value)
                only_inputs(device)
                self.nodes.stamp(device)  # node IDs are the node table's, not what was read
            if channel == 0 and param == P.DEVICE_BEACON_INTERVAL and len(value) == 2:
                self.nodes.beacons_every(key, max(int.from_bytes(value, "little"), 1) / 1000.0)

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
        """Carry out an engine plan's actions on the bus, in order; log it and return what
        came of it. The profile layer's own start-up and duty cycle call it inside their
        motion interlock (``arb_transaction.holding``); it holds nothing itself.

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

    def read_anchor(self) -> Anchor | None:
        """The fitting history's anchor kept in memory (issue 28); None when none is kept."""
        return self.transactions.read_anchor()

    def write_anchor(self, anchor: Anchor) -> Anchor | None:
        """Store the fitting history's anchor beside the configuration; returns it read back."""
        return self.transactions.write_anchor(anchor)

    def transact(self, change: Change, progress: Callable[[int, int, str], Any] | None = None,
                 cancel: threading.Event | None = None) -> TransactionResult:
        """Carry ``change`` out as one transaction (reference §5: interlock, write, verify,
        restore, release); never raises for a bus failure — the result says applied, failed
        or rolled back, at which step and why."""
        return self.transactions.transact(change, progress, cancel)

    def _do_link(self, op: str, link: Link) -> None:  # (a test slows a transaction down here)
        """One link action of a change (none when the link is already so)."""
        with self._state.lock:
            exists = self._state.system.has_link(link)
        if op == "add" and not exists:
            self.add_link(link)
        elif op == "remove" and exists:
            self.remove_link(link)

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
            with self._state.lock:
                self.nodes.asked(message.node_id, time.monotonic())
        # On a bus that echoes, the claim accounts for the copies (arb_claim), not the
        # connection's filter: a copy later than the filter waits must not pass for another
        # arbitrator's frame.
        self.claim.sent(arbitration_id, data, time.monotonic())
        self.conn.send(arbitration_id, data, filter_echo=False)
        if self._frame_events:
            self._frames.frame(arbitration_id, data, time.time())

    def _send_quiet(self, message: Message) -> None:
        if not self.claim.may_write or self.dispatch.disconnected:
            return  # listening, another arbitrator on the bus, or no adapter: say nothing
        try:
            self._send(message)
        except TransportError as err:
            self._error(str(err), "transport")

    # -- reset ----------------------------------------------------------------------------
    def reset(self, keep_memory: bool = True) -> None:
        """Restart the arbitrator: forget the bus, reset every device (they bind again) and
        run start-up again; ``keep_memory=False`` erases the stored configuration first."""
        with self._state.wire_lock:
            if not keep_memory:
                self.memory.erase()
            with self._state.lock:
                node_ids = list(self.nodes.by_id)
                now = time.monotonic()
                self.presence.forget(self.nodes.channel_ids, now)
                self.setup.forget()
                self._state.forget()
                self.nodes.clear()
                self.profile.restart(now)
            for node_id in node_ids:
                self.requests.abort(node_id, "the arbitrator was reset")
            log.info("%s: reset (%s memory)", self.name, "kept" if keep_memory else "erased")
            self._send_quiet(Reset(0))
        self._stir()

    def _stir(self) -> None:
        """Something changed: the profile thread and ``wait_settled`` look again now."""
        self._wake.set()
        self._news.set()

    def devices_present(self) -> list[DeviceKey]:
        """Keys of the devices on the bus and set up."""
        with self._state.lock:
            return [k for k, d in self._state.system.devices.items() if d.present]

    def wait_for(self, predicate: Callable[[], bool], timeout: float) -> bool:
        """Wait until ``predicate()`` is true or ``timeout`` passes (tests, scripts): asked
        again on news of a set-up, bind or plan, and every 5 ms at least."""
        deadline = time.monotonic() + timeout
        while True:
            self._news.clear()  # before asking: news from now on wakes the wait below
            if predicate():
                return True
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            self._news.wait(min(0.005, left))
