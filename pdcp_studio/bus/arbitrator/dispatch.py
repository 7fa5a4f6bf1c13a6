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
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, cast

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.claim import Decision
from pdcp_studio.bus.arbitrator.common import (
    DEFAULT_BEACON_INTERVAL_S,
    TICK_S,
    UNREAD_BEACON_INTERVAL_S,
    _Node,
)
from pdcp_studio.bus.arbitrator.nodes import BindDecision
from pdcp_studio.bus.sim.signals import decode_sample
from pdcp_studio.errors import FrameError
from pdcp_studio.model.refs import DeviceKey
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

    from pdcp_studio.bus.arbitrator.core import Arbitrator

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator

#: A dispatch loop that did not come round for this long was stalled (it runs every TICK_S)…
STALL_S = 0.15
#: … and then waits this long before judging presence: the frames received meanwhile may still
#: sit in the driver's or the socket's buffer, unseen, and silence would be misread.
STALL_GRACE_S = 0.3


class Dispatcher:
    """The dispatch thread of an :class:`Arbitrator` (its state is the parts')."""

    def __init__(self, arb: Arbitrator) -> None:
        self.arb = arb

    def run(self) -> None:
        """The thread: frames as they come, the claim's and presence's tick every TICK_S."""
        arb = self.arb
        next_tick = 0.0
        last = time.monotonic()
        hold_until = 0.0
        while not arb._stop.is_set():
            item = arb.conn.get(TICK_S)
            if arb._stop.is_set():
                break
            try:
                if isinstance(item, Exception):
                    arb._error(f"the bus reported {item}", "transport")
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
                    arb._flush_errors()
                    # Presence is judged only when every frame received so far is handled:
                    # a backlog (a busy machine) must not pass for silent devices.
                    self._tick(now, arb.conn.inbound.empty() and now >= hold_until)
            except Exception:  # one bad frame or bug must never stop the arbitrator
                arb._crashes.exception("dispatch", "dispatch failed")

    def _bad_frame(self, why: str) -> None:
        arb = self.arb
        arb.bad_frames += 1
        arb._error(f"undecodable frame #{arb.bad_frames}: {why}", "bad_frame")

    def _on_frame(self, msg: can.Message) -> None:
        arb = self.arb
        data = bytes(msg.data)
        now = time.monotonic()
        if arb.claim.is_own_echo(msg.arbitration_id, data, now):
            return  # our own frame, handed back by the bus (late or not)
        if arb.frame_events:
            arb._frame_event(msg.arbitration_id, data, msg.timestamp or time.time())
        if msg.is_error_frame:
            arb.error_frames += 1
            arb._error(f"error frame #{arb.error_frames} on the bus", "error_frame")
            return
        if msg.is_extended_id or msg.is_remote_frame:
            kind = "extended identifier" if msg.is_extended_id else "remote frame"
            self._bad_frame(f"0x{msg.arbitration_id:X}: {kind} (PDCP uses base data frames)")
            return
        aid = msg.arbitration_id
        node_id = aid & 0xFF
        if not self._hear_claim(aid, data, now):
            return  # another arbitrator is on the bus: nothing here is ours to answer
        if arb.nodes.is_foreign(aid):
            self._foreign_frame(node_id, aid, data, now)
            return
        try:
            message = decode(aid, data, channel_node_ids=arb.nodes.channel_set)
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
        with arb._lock:
            node = arb.nodes.by_id.get(node_id)
            if node is not None:
                node.last_seen = now
                if isinstance(message, Beacon):
                    node.last_beacon = now
        if node is None:  # node 0, or a device that left a moment ago
            return
        if isinstance(message, Beacon):
            why = arb.presence.beacon(node, now, arb.conn.inbound.empty())
            if why:
                self._twin(node.key, why)
            return
        if isinstance(message, UpdateDataChannel):
            arb.links.on_update(node, message)
            return
        echo, why = arb.presence.response(node, aid, data, now,
                                           2 * arb.requests.response_timeout)
        if why:
            self._twin(node.key, why)
        if not echo:
            arb.requests.feed(message)

    def _on_data(self, message: ChannelData, timestamp: float) -> None:
        arb = self.arb
        arb.data_frames += 1
        if not arb.channel_events:
            return
        with arb._lock:
            ref = arb.nodes.channel_ids.get(message.node_id)
            ch = arb._system.channel(ref) if ref else None
            kind = ch.type if ch else 0
        if ref is not None:
            arb._emit(ev.ChannelValue(ref, decode_sample(kind, message.data), timestamp))

    # -- binding (the node table decides) -------------------------------------------------
    def _on_bind(self, req: BindRequest, now: float) -> None:
        arb = self.arb
        key = DeviceKey(req.vid, req.pid, req.serial)
        with arb._lock:
            if (key not in arb.presence.duplicates
                    and key not in arb.nodes.exhausted_reported):
                arb.profile.last_bind = now
        if now < arb.profile.listen_until:
            return  # still learning which IDs devices of an earlier arbitrator use
        with arb._lock:
            decision = arb.nodes.on_bind_request(req, now, arb.presence.duplicates)
            set_up = self._bound(decision.key, decision.node_id, now) \
                if decision.kind == "grant" else None
        try:
            self._answer(decision)
        finally:
            if set_up is not None:
                set_up()  # after the answer: the set-up's first request must not overtake it

    def _answer_bind(self, req: BindRequest, now: float) -> None:
        arb = self.arb
        with arb._lock:
            decision = arb.nodes.decide_bind(req, now)
            set_up = self._bound(decision.key, decision.node_id, now) \
                if decision.kind == "grant" else None
        try:
            self._answer(decision)
        finally:
            if set_up is not None:
                set_up()

    def _answer(self, decision: BindDecision) -> None:
        arb = self.arb
        key = decision.key
        if decision.kind == "exhausted":
            if decision.report:  # once per device, not per retry
                arb._error(decision.report, "node_ids_exhausted")
        elif decision.kind in ("grant", "suggest"):
            arb._send_quiet(BindResponse(decision.asked, decision.node_id, key.vid, key.pid,
                                          key.serial))

    def _bound(self, key: DeviceKey, node_id: int, now: float) -> Callable[[], None]:
        """Under the lock: ``key`` holds ``node_id``; its set-up (or a new one) is in flight.
        Returns what starts it, called once the bind answer is sent."""
        arb = self.arb
        device = arb._system.device(key)
        interval = (max(device.beacon_interval, 1) / 1000.0 if device is not None
                    else max(DEFAULT_BEACON_INTERVAL_S, UNREAD_BEACON_INTERVAL_S))
        node, old = arb.nodes.install(key, node_id, now, interval)
        if old is not None and old != node_id:
            arb.requests.abort(old, "the device bound again with another node ID")
        arb.profile.last_change = now
        return arb.setup.start(node)

    # -- presence (the presence tracker decides) ------------------------------------------
    def _tick(self, now: float, caught_up: bool = True) -> None:
        """Presence, held and foreign node IDs, deferred binds."""
        arb = self.arb
        with arb._lock:
            gone = arb.presence.absent(list(arb.nodes.by_id.values()), now) \
                if caught_up else []
            arb.nodes.expire(now)
            resolved = arb.nodes.resolve_deferred(now, arb.presence.duplicates) \
                if caught_up else []
        for node in gone:
            self._depart(node, now)
        for req, twin in resolved:
            key = DeviceKey(req.vid, req.pid, req.serial)
            if twin:
                self._twin(key, "a second one asked to bind while the first kept beaconing")
            else:
                log.info("%s: device %s binds again (it restarted)", arb.name, key)
                with arb._lock:
                    again = arb.nodes.node(key)
                    if again is not None:
                        again.set_up = False
                self._answer_bind(req, now)

    def _twin(self, key: DeviceKey, why: str) -> None:
        arb = self.arb
        with arb._lock:
            line = arb.presence.report(key, why)
        arb._error(line, "duplicate_device")

    def _depart(self, node: _Node, now: float) -> None:
        arb = self.arb
        key = node.key
        with arb._lock:
            if not arb.nodes.remove(node):
                return
            arb.setup.in_flight.pop(key, None)
            device = arb._system.device(key)
            was_present = device is not None and device.present
            fed: list[Link] = []
            if device is not None:
                device.present = False
                device.node_id = None
                for ch in device.channels.values():
                    ch.node_id = None
                    ch.data_enabled = False
                fed = [lk for ref in (device.ref(c.index) for c in device.outputs())
                       for lk in arb.links.links_from(ref)
                       if arb._system.is_present(lk.input)]
            arb.presence.duplicates.discard(key)
            arb.profile.last_change = now
            if was_present:
                arb.profile.duty_needed = True
        arb.requests.abort(node.node_id, "the device left the bus")
        if not was_present:
            return
        log.info("%s: device %s left (node %d)", arb.name, key, node.node_id)
        arb._emit(ev.DeviceLeft(key))
        arb._submit_job(arb.links.silence_inputs, fed)
        arb._wake.set()

    def _foreign_frame(self, node_id: int, aid: int, data: bytes, now: float) -> None:
        """A frame from a node ID nobody holds here: a device (or output) bound by an earlier
        arbitrator. Its ID is kept out of the pool while it is heard; a device is reset so
        it binds with us; undecodable frames are counted, and shown once per node."""
        arb = self.arb
        with arb._lock:
            arb.nodes.hear_foreign(node_id, now)
        try:
            message = decode(aid, data)
        except FrameError as err:
            what = arb.presence.bad_stranger_frame(node_id, now)
            if what == "stale":
                return  # data already on the wire when we reset
            arb.bad_frames += 1
            if what == "show":
                arb._error(f"undecodable frame #{arb.bad_frames} 0x{aid:03X} "
                            f"[{data.hex(' ').upper()}] from node {node_id}, which is not "
                            f"bound here: {err} (further ones are counted, not shown)",
                            "bad_frame")
            return
        if isinstance(message, Beacon | UpdateDataChannel):
            with arb._lock:
                stranger = node_id not in arb.nodes.channel_ids
            if stranger and arb.presence.may_reset_stranger(node_id, now):
                log.info("%s: node %d is not bound here: resetting it", arb.name, node_id)
                arb._send_quiet(Reset(node_id))
        if isinstance(message, UpdateDataChannel):
            arb._send_quiet(UpdateDataChannelResponse(node_id, ResponseCode.FAILURE,
                                                       message.channel))

    # -- one arbitrator per bus (reference §5; the claim decides) -------------------------
    def _hear_claim(self, arbitration_id: int, data: bytes, now: float) -> bool:
        """Feed a received frame to the claim; False once another arbitrator is on the bus
        (then nothing received is ours to handle)."""
        arb = self.arb
        decision = arb.claim.heard(arbitration_id, data, now)
        if decision is not None:
            self._claim_yielded(decision)
        return not arb.claim.yielded

    def _claim_tick(self, now: float) -> bool:
        """End the listening when it is due, beacon when due; True while arbitrating (and
        the adapter is there: presence is not judged while nobody can be heard)."""
        arb = self.arb
        decision = arb.claim.tick(now)
        if decision is not None:
            self.claim_started(decision)
        if arb.claim.beacon_due(now):
            arb._send_quiet(Beacon(0, mode=Mode.ARBITRATOR))
        return bool(arb.claim.may_write) and not arb._disconnected

    def claim_started(self, decision: Decision | None) -> None:
        """The bus is ours: the start-up reset (a replaced arbitrator's devices bind again)."""
        arb = self.arb
        if decision is not None:
            arb.bus_message = decision.message
            log.info("%s: %s", arb.name, decision.message)
            arb._emit(ev.BusState("arbitrating", decision.message))
            with arb._lock:
                arb.presence.unknown_reset.clear()  # resets skipped while listening may go
        if arb._reset_on_claim or (decision is not None and decision.takeover):
            arb._send_quiet(Reset(0))

    def _claim_yielded(self, decision: Decision) -> None:
        """Another arbitrator is on the bus: stop writing at once and say so, once."""
        arb = self.arb
        arb.bus_message = decision.message
        # Info, not warning: the yield event is what callers show (the CLI's one error line);
        # a warning would reach stderr a second time through logging's last-resort handler.
        log.info("%s: %s", arb.name, decision.message)
        with arb._lock:
            nodes = list(arb.nodes.by_id)
        for node_id in nodes:
            arb.requests.abort(node_id, "another bus arbitrator is on the bus")
        arb._emit(ev.BusState("yielded", decision.message))
        arb._wake.set()

    # -- a pulled adapter (bus/reopen.py reopens it) --------------------------------------
    def adapter_state(self, state: str, line: str) -> None:
        """Called on the Notifier's thread: hand it to the dispatch thread."""
        arb = self.arb
        arb.conn.post(lambda: self._on_adapter_state(state, line))

    def _on_adapter_state(self, state: str, line: str) -> None:
        """Disconnected: presence is not judged (nobody can be heard) and nothing is sent.
        Reconnected: every device gets its beacon intervals to be heard again, and the links
        are read back from the inputs and re-made where they differ."""
        arb = self.arb
        now = time.monotonic()
        with arb._lock:
            arb._disconnected = state == "disconnected"
            if not arb._disconnected:
                for node in arb.nodes.by_id.values():
                    node.last_seen = max(node.last_seen, now)
        arb._emit(ev.BusState(state, line))
        if not arb._disconnected:
            arb._submit_job(arb.links.reread)


__all__ = ["STALL_GRACE_S", "STALL_S", "Dispatcher"]
