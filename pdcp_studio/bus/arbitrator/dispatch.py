"""The arbitrator's dispatch thread: it hears every frame, asks the deciding parts and carries
their decisions out.

The thread drains the connection's queue (the Notifier only enqueues): it decodes frames,
feeds the claim (one arbitrator per bus), answers bind requests from the node table's
decisions, answers Update Data Channel requests through the link writer, feeds responses to
the request engine, and on a tick asks the presence tracker who is gone and the node table
which held IDs and deferred binds have run out. It never waits for the bus; wire work goes to
the arbitrator's set-up pool.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol, cast

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.claim import Decision, Stray
from pdcp_studio.bus.arbitrator.common import (
    DEFAULT_BEACON_INTERVAL_S,
    TICK_S,
    UNREAD_BEACON_INTERVAL_S,
    _Node,
)
from pdcp_studio.bus.arbitrator.nodes import BindDecision
from pdcp_studio.bus.arbitrator.state import Emit, ReportError, SendFrame, SystemState
from pdcp_studio.bus.log_limit import RepeatLimiter
from pdcp_studio.bus.sim.signals import decode_raw
from pdcp_studio.errors import FrameError
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    BindResponse,
    ChannelData,
    Mode,
    Reset,
    ResponseCode,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
)

if TYPE_CHECKING:
    import can

    from pdcp_studio.bus.arbitrator.claim import BusClaim
    from pdcp_studio.bus.arbitrator.nodes import NodeTable
    from pdcp_studio.bus.arbitrator.presence import PresenceTracker
    from pdcp_studio.bus.arbitrator.reading.requests import RequestEngine
    from pdcp_studio.bus.connection import Connection
    from pdcp_studio.bus.log_limit import LimitedLog

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator

#: A dispatch loop that did not come round for this long was stalled (it runs every TICK_S)…
STALL_S = 0.15
#: … and then waits this long before judging presence: the frames received meanwhile may still
#: sit in the driver's or the socket's buffer, unseen, and silence would be misread.
STALL_GRACE_S = 0.3


class LinkPort(Protocol):
    """What the dispatch thread asks of the link writer."""

    def on_update(self, node: _Node, msg: UpdateDataChannel) -> None: ...
    def links_from(self, output: ChannelRef) -> list[Link]: ...
    def silence_inputs(self, links: list[Link]) -> None: ...
    def reread(self) -> None: ...


class SetupPort(Protocol):
    """What the dispatch thread asks of the device set-up."""

    def start(self, node: _Node) -> Callable[[], None]: ...
    def cancel(self, key: DeviceKey) -> None: ...


class ProfilePort(Protocol):
    """What the dispatch thread tells the profile driver."""

    def listening(self, now: float) -> bool: ...
    def note_bind(self, now: float) -> None: ...
    def note_change(self, now: float, *, duty: bool = False) -> None: ...


class Dispatcher:
    """The dispatch thread. It owns the frame counters, whether the adapter is there and the
    last bus-state line; the rest of what it decides on is the deciding parts' (claim, node
    table, presence tracker), which it gets in its constructor with the other parts' ports.

    ``show_frame``: a frame heard, for the frame events (None: they are off)."""

    def __init__(self, state: SystemState, conn: Connection, claim: BusClaim, nodes: NodeTable,
                 presence: PresenceTracker, requests: RequestEngine, *, links: LinkPort,
                 setup: SetupPort, profile: ProfilePort,
                 show_frame: Callable[[int, bytes, float], None] | None,
                 channel_events: bool, reset_on_claim: bool, send: SendFrame,
                 error: ReportError, flush_errors: Callable[[], None], crashes: LimitedLog,
                 emit: Emit, wake: Callable[[], None], stop: threading.Event,
                 name: str) -> None:
        self._state = state
        self._conn = conn
        self._claim = claim
        self._nodes = nodes
        self._presence = presence
        self._requests = requests
        self._links = links
        self._setup = setup
        self._profile = profile
        self._show_frame = show_frame
        self._channel_events = channel_events
        self._reset_on_claim = reset_on_claim
        self._send = send
        self._error = error
        self._flush_errors = flush_errors
        self._crashes = crashes
        self._emit = emit
        self._wake = wake
        self._stop = stop
        self._name = name
        self.bad_frames = 0
        self.error_frames = 0
        self.data_frames = 0
        self.disconnected = False  # the adapter was pulled (a ReopeningBus says so)
        self.bus_message = ""  # the last BusState line (why it arbitrates or not)
        self._hold_until = 0.0  # after a stall: frames may still wait in the driver till then
        self._last_stall = float("-inf")  # when this loop last found it had not run
        #: The bus time (the frame's own timestamp) of the newest frame received from anyone,
        #: and when it was handled: presence is judged by the bus's clock (issue 28 item 6).
        self._bus_now = 0.0
        self._bus_now_at = 0.0
        #: Stray mode-1 frames: the first told, then one a second and a summary (log_limit).
        self._strays = RepeatLimiter(burst=1)

    def run(self) -> None:
        """The thread: frames as they come, the claim's and presence's tick every TICK_S."""
        next_tick = 0.0
        last = time.monotonic()
        while not self._stop.is_set():
            item = self._conn.get(TICK_S)
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
                    self._hold_until = now + STALL_GRACE_S  # frames may still wait in the driver
                    self._last_stall = now
                last = now
                if now >= next_tick and self._claim_tick(now):
                    next_tick = now + TICK_S
                    self._flush_strays(now)
                    self._flush_errors()
                    # Presence is judged only when every frame received so far is handled:
                    # a backlog (a busy machine) must not pass for silent devices.
                    self._tick(now, self._caught_up(now))
            except Exception:  # one bad frame or bug must never stop the arbitrator
                self._crashes.exception("dispatch", "dispatch failed")

    def _caught_up(self, now: float) -> bool:
        """Every frame received so far is handled: none queued, none left in the driver
        after a stall."""
        return self._conn.inbound.empty() and now >= self._hold_until

    def _bad_frame(self, why: str) -> None:
        self.bad_frames += 1
        self._error(f"undecodable frame #{self.bad_frames}: {why}", "bad_frame")

    def _on_frame(self, msg: can.Message) -> None:
        data = bytes(msg.data)
        now = time.monotonic()
        if self._claim.is_own_echo(msg.arbitration_id, data, now):
            return  # our own frame, handed back by the bus (late or not)
        stamp = msg.timestamp or time.time()
        if stamp >= self._bus_now:
            self._bus_now, self._bus_now_at = stamp, now
        if self._show_frame is not None:
            self._show_frame(msg.arbitration_id, data, stamp)
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
        if not self._hear_claim(aid, data, now, stamp):
            return  # another arbitrator is on the bus: nothing here is ours to answer
        if aid >> 8 & 1:
            return  # a mode-1 frame is never ours to handle (the claim has judged it)
        if self._nodes.is_foreign(aid):
            self._foreign_frame(node_id, aid, data, now)
            return
        try:
            message = decode(aid, data, channel_node_ids=self._nodes.channel_set)
        except FrameError as err:
            self._bad_frame(f"0x{aid:03X} [{data.hex(' ').upper()}]: {err}")
            return
        if isinstance(message, ChannelData):
            self._on_data(message, msg.timestamp or time.time())
            return
        if message.mode is Mode.ARBITRATOR:
            return  # (never reached: the claim has judged it)
        if isinstance(message, BindRequest):
            self._on_bind(message, now)
            return
        with self._state.lock:
            node = self._nodes.heard(node_id, now, beacon=isinstance(message, Beacon),
                                     bus_time=stamp)
        if node is None:  # node 0, or a device that left a moment ago
            return
        if isinstance(message, Beacon):
            why = self._presence.beacon(node, now, self._caught_up(now))
            if why:
                self._twin(node.key, why)
            return
        if isinstance(message, UpdateDataChannel):
            self._links.on_update(node, message)
            return
        echo, why = self._presence.response(node, aid, data, now,
                                           2 * self._requests.response_timeout)
        if why:
            self._twin(node.key, why)
        if not echo:
            self._requests.feed(message)

    def _on_data(self, message: ChannelData, timestamp: float) -> None:
        self.data_frames += 1
        if not self._channel_events:
            return
        with self._state.lock:
            ref = self._nodes.channel_ids.get(message.node_id)
            ch = self._state.system.channel(ref) if ref else None
            kind = ch.type if ch else 0
        if ref is not None:
            self._emit(ev.ChannelValue(ref, decode_raw(kind, message.data), timestamp))

    # -- binding (the node table decides) -------------------------------------------------
    def _on_bind(self, req: BindRequest, now: float) -> None:
        key = DeviceKey(req.vid, req.pid, req.serial)
        with self._state.lock:
            if (key not in self._presence.duplicates
                    and key not in self._nodes.exhausted_reported):
                self._profile.note_bind(now)
        if self._profile.listening(now):
            return  # still learning which IDs devices of an earlier arbitrator use
        if not self._claim_tick(now):
            return  # not ours to answer (yet): the device asks again
        with self._state.lock:
            decision = self._nodes.on_bind_request(req, now, self._presence.duplicates)
            set_up = self._bound(decision.key, decision.node_id, now) \
                if decision.kind == "grant" else None
        try:
            self._answer(decision)
        finally:
            if set_up is not None:
                set_up()  # after the answer: the set-up's first request must not overtake it

    def _answer_bind(self, req: BindRequest, now: float) -> None:
        with self._state.lock:
            decision = self._nodes.decide_bind(req, now)
            set_up = self._bound(decision.key, decision.node_id, now) \
                if decision.kind == "grant" else None
        try:
            self._answer(decision)
        finally:
            if set_up is not None:
                set_up()

    def _answer(self, decision: BindDecision) -> None:
        key = decision.key
        if decision.kind == "exhausted":
            if decision.report:  # once per device, not per retry
                self._error(decision.report, "node_ids_exhausted")
        elif decision.kind in ("grant", "suggest"):
            self._send(BindResponse(decision.asked, decision.node_id, key.vid, key.pid,
                                    key.serial))

    def _bound(self, key: DeviceKey, node_id: int, now: float) -> Callable[[], None]:
        """Under the lock: ``key`` holds ``node_id``; its set-up (or a new one) is in flight.
        Returns what starts it, called once the bind answer is sent."""
        device = self._state.system.device(key)
        interval = (max(device.beacon_interval, 1) / 1000.0 if device is not None
                    else max(DEFAULT_BEACON_INTERVAL_S, UNREAD_BEACON_INTERVAL_S))
        node, old = self._nodes.install(key, node_id, now, interval)
        node.last_bus = self._bus_estimate(now)
        if old is not None and old != node_id:
            self._requests.abort(old, "the device bound again with another node ID")
        self._profile.note_change(now)
        return self._setup.start(node)

    # -- presence (the presence tracker decides) ------------------------------------------
    def _bus_estimate(self, now: float) -> float:
        """The bus's clock now: the newest frame's bus time plus the time since it was
        handled (a node given a fresh start is stamped with it)."""
        return self._bus_now + max(0.0, now - self._bus_now_at) if self._bus_now_at else 0.0

    def _tick(self, now: float, caught_up: bool = True) -> None:
        """Presence (judged by the bus's clock, see the presence tracker), held and foreign
        node IDs, deferred binds."""
        with self._state.lock:
            gone = self._presence.absent(self._nodes.by_id.values(), now,
                                         now - self._last_stall) if caught_up else []
            self._nodes.expire(now)
            resolved = self._nodes.resolve_deferred(now, self._presence.duplicates) \
                if caught_up else []
        for node, why, silent_s in gone:
            self._depart(node, now, why, silent_s)
        for req, twin in resolved:
            key = DeviceKey(req.vid, req.pid, req.serial)
            if twin:
                self._twin(key, "a second one asked to bind while the first kept beaconing")
            else:
                log.info("%s: device %s binds again (it restarted)", self._name, key)
                with self._state.lock:
                    self._nodes.binds_again(key)
                self._answer_bind(req, now)

    def _twin(self, key: DeviceKey, why: str) -> None:
        with self._state.lock:
            line = self._presence.report(key, why)
        self._error(line, "duplicate_device")

    def _depart(self, node: _Node, now: float, why: str = "", silent_s: float = 0.0) -> None:
        key = node.key
        with self._state.lock:
            if not self._nodes.remove(node):
                return
            self._setup.cancel(key)
            device = self._state.system.device(key)
            was_present = device is not None and device.present
            fed: list[Link] = []
            if device is not None:
                device.present = False
                self._nodes.stamp(device)  # none: its IDs went back to the pool
                for ch in device.channels.values():
                    ch.data_enabled = False
                fed = [lk for ref in (device.ref(c.index) for c in device.outputs())
                       for lk in self._links.links_from(ref)
                       if self._state.system.is_present(lk.input)]
            self._presence.left(key)
            self._profile.note_change(now, duty=was_present)
        self._requests.abort(node.node_id, "the device left the bus")
        if not was_present:
            return
        log.info("%s: device %s left (node %d)%s", self._name, key, node.node_id,
                 f": {why}" if why else "")
        self._emit(ev.DeviceLeft(key, why=why, silent_s=silent_s,
                                 interval_s=node.beacon_interval))
        self._links.silence_inputs(fed)
        self._wake()

    def _foreign_frame(self, node_id: int, aid: int, data: bytes, now: float) -> None:
        """A frame from a node ID nobody holds here: a device (or output) bound by an earlier
        arbitrator. Its ID is kept out of the pool while it is heard; a device is reset so
        it binds with us; undecodable frames are counted, and shown once per node."""
        with self._state.lock:
            self._nodes.hear_foreign(node_id, now)
        try:
            message = decode(aid, data)
        except FrameError as err:
            what = self._presence.bad_stranger_frame(node_id, now)
            if what == "stale":
                return  # data already on the wire when we reset
            self.bad_frames += 1
            # While listening, the traffic may be another arbitrator's session, heard before
            # its beacons decide: counted, not shown (a taken bus ends in one line).
            if what == "show" and not self._claim.listening:
                self._error(f"undecodable frame #{self.bad_frames} 0x{aid:03X} "
                            f"[{data.hex(' ').upper()}] from node {node_id}, which is not "
                            f"bound here: {err} (further ones are counted, not shown)",
                            "bad_frame")
            return
        if isinstance(message, Beacon | UpdateDataChannel):
            with self._state.lock:
                stranger = node_id not in self._nodes.channel_ids
            if stranger and self._presence.may_reset_stranger(node_id, now):
                log.info("%s: node %d is not bound here: resetting it", self._name, node_id)
                self._send(Reset(node_id))
        if isinstance(message, UpdateDataChannel):
            self._send(UpdateDataChannelResponse(node_id, ResponseCode.FAILURE,
                                                 message.channel))

    # -- one arbitrator per bus (reference §5; the claim decides) -------------------------
    def _hear_claim(self, arbitration_id: int, data: bytes, now: float,
                    bus_time: float | None = None) -> bool:
        """Feed a received frame to the claim; False once another arbitrator is on the bus
        (then nothing received is ours to handle)."""
        decision = self._claim.heard(arbitration_id, data, now, bus_time)
        if isinstance(decision, Decision):
            self._claim_yielded(decision)
        elif isinstance(decision, Stray):
            self._stray(decision, now)
        return not self._claim.yielded

    def _stray(self, stray: Stray, now: float) -> None:
        """A stray arbitrator-mode frame: told (rate-limited), then ignored."""
        told, summary = self._strays.admit("stray_frame", stray.message, now)
        if summary is not None:
            self._error(summary.text("stray arbitrator-mode frames, ignored"), "stray_frame")
        if told:
            self._error(stray.message, "stray_frame")

    def _flush_strays(self, now: float) -> None:
        lone = self._claim.lone_beacon(now)
        if lone is not None:
            self._stray(lone, now)
        for summary in self._strays.due(now):
            self._error(summary.text("stray arbitrator-mode frames, ignored"), "stray_frame")

    def _claim_tick(self, now: float) -> bool:
        """End the listening when it is due, beacon when due; True while arbitrating (and
        the adapter is there: presence is not judged while nobody can be heard). A bind
        request asks it first: one handled after the listening ended but before the loop's
        next tick would be granted while every write is still refused, and the set-up of
        the device it binds would fail on its first request."""
        decision = self._claim.tick(now, self._caught_up(now))
        if decision is not None:
            self.claim_started(decision)
        if self._claim.beacon_due(now):
            self._send(Beacon(0, mode=Mode.ARBITRATOR))
        return bool(self._claim.may_write) and not self.disconnected

    def claim_started(self, decision: Decision | None) -> None:
        """The bus is ours: the start-up reset (a replaced arbitrator's devices bind again).
        Taken back after another arbitrator's beacons were gone: no reset (the prosthesis
        keeps working); every device gets its beacon intervals to be heard again, the links
        are read back and re-made where they differ, and devices the other bound are reset
        one by one when they beacon (strangers)."""
        if decision is not None:
            self.bus_message = decision.message
            log.info("%s: %s", self._name, decision.message)
            self._emit(ev.BusState("arbitrating", decision.message))
            with self._state.lock:
                self._presence.claimed()
                if decision.taken_back:
                    now = time.monotonic()
                    self._nodes.heard_all(now, self._bus_estimate(now))
            if decision.taken_back:
                self._links.reread()
                self._wake()
                return
        if self._reset_on_claim or (decision is not None and decision.takeover):
            self._send(Reset(0))

    def _claim_yielded(self, decision: Decision) -> None:
        """Another arbitrator is on the bus: stop writing at once and say so, once."""
        self.bus_message = decision.message
        # Info, not warning: the yield event is what callers show (the CLI's one error line);
        # a warning would reach stderr a second time through logging's last-resort handler.
        log.info("%s: %s", self._name, decision.message)
        with self._state.lock:
            nodes = list(self._nodes.by_id)
        for node_id in nodes:
            self._requests.abort(node_id, "another bus arbitrator is on the bus")
        self._emit(ev.BusState("yielded", decision.message))
        self._wake()

    # -- a pulled adapter (bus/reopen.py reopens it) --------------------------------------
    def adapter_state(self, state: str, line: str) -> None:
        """Called on the Notifier's thread: hand it to the dispatch thread."""
        self._conn.post(lambda: self._on_adapter_state(state, line))

    def _on_adapter_state(self, state: str, line: str) -> None:
        """Disconnected: presence is not judged (nobody can be heard) and nothing is sent.
        Reconnected: every device gets its beacon intervals to be heard again, and the links
        are read back from the inputs and re-made where they differ."""
        now = time.monotonic()
        with self._state.lock:
            self.disconnected = state == "disconnected"
            if not self.disconnected:
                self._nodes.heard_all(now, self._bus_estimate(now))
        self._emit(ev.BusState(state, line))
        if not self.disconnected:
            self._links.reread()


__all__ = ["STALL_GRACE_S", "STALL_S", "Dispatcher"]
