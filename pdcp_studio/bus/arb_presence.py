"""Presence: beacons, departures, twins on one node ID, and nodes bound by someone else.

A mixin of :class:`pdcp_studio.bus.arbitrator.Arbitrator`, run on its dispatch thread: the tick
judges presence and expires held and foreign node IDs; frames from unknown nodes keep their
IDs out of the pool and get the device reset.
"""

from __future__ import annotations

import logging
import time

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arb_claim import Decision
from pdcp_studio.bus.arb_common import (
    BEACON_WINDOW,
    BIND_HOLD_S,
    ECHOES_FOR_TWIN,
    FOREIGN_HOLD_S,
    MISSED_BEACONS,
    PRESENCE_GRACE,
    TWIN_BEACON_RATIO,
    UNKNOWN_RESET_S,
    _Foreign,
    _Node,
)
from pdcp_studio.errors import FrameError, PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    FunctionCode,
    Mode,
    Reset,
    ResponseCode,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
)

log = logging.getLogger("pdcp_studio.bus.arbitrator")  # one logger for the arbitrator


class PresenceMixin:
    """Presence, departures, duplicate devices and foreign nodes of the :class:`Arbitrator`."""

    # -- one arbitrator per bus (reference §5; the decisions are arb_claim's) ---------------
    def _hear_claim(self, arbitration_id: int, data: bytes, now: float) -> bool:
        """Feed a received frame to the claim; False once another arbitrator is on the bus
        (then nothing received is ours to handle)."""
        decision = self._claim.heard(arbitration_id, data, now)
        if decision is not None:
            self._claim_yielded(decision)
        return not self._claim.yielded

    # -- a pulled adapter (bus/reopen.py reopens it) ------------------------------------------
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
                for node in self._nodes.values():
                    node.last_seen = max(node.last_seen, now)
                self._jobs += 1
        self._emit(ev.BusState(state, line))
        if self._disconnected:
            return
        try:
            self._pool_exec.submit(self._reread_links)
        except RuntimeError:
            with self._lock:
                self._jobs -= 1

    def _reread_links(self) -> None:
        """After an outage: read each linked input's Source's Node Ids and Data Transfer
        Enabled back; re-make the links whose input does not say what the model says."""
        try:
            with self._plan_lock:
                with self._lock:
                    links = [lk for lk in self._system.links
                             if self._system.is_present(lk.output)
                             and self._system.is_present(lk.input)]
                for link in links:
                    with self._lock:
                        in_node = self._node_of.get(link.input.device)
                        out_node = self._node_of.get(link.output.device)
                        out_id = self._pool.id_of((link.output.device, link.output.index))
                    if None in (in_node, out_node, out_id):
                        continue
                    try:
                        sources = self.requests.get(in_node, P.IN_SOURCE_NODE_IDS,
                                                    link.input.index)
                        enabled = self.requests.get(in_node, P.CH_DATA_ENABLED,
                                                    link.input.index)
                        if sources != bytes([out_node, out_id]) or enabled != b"\x01":
                            log.info("%s: link %s was lost during the outage: re-making it",
                                     self.name, link)
                            self._wire_add(link)
                    except PdcpError as err:
                        self._error(f"link {link} could not be read back after the outage: "
                                    f"{err}", "transport")
        finally:
            with self._lock:
                self._jobs -= 1

    def _claim_tick(self, now: float) -> bool:
        """End the listening when it is due, beacon when due; True while arbitrating (and
        the adapter is there: presence is not judged while nobody can be heard)."""
        decision = self._claim.tick(now)
        if decision is not None:
            self._claim_started(decision)
        if self._claim.beacon_due(now):
            self._send_quiet(Beacon(0, mode=Mode.ARBITRATOR))
        return bool(self._claim.may_write) and not self._disconnected

    def _claim_started(self, decision: Decision | None) -> None:
        """The bus is ours: the start-up reset (a replaced arbitrator's devices bind again)."""
        if decision is not None:
            self.bus_message = decision.message
            log.info("%s: %s", self.name, decision.message)
            self._emit(ev.BusState("arbitrating", decision.message))
            with self._lock:
                self._unknown_reset.clear()  # resets skipped while listening may go now
        if self._reset_on_claim or (decision is not None and decision.takeover):
            self._broadcast_reset()

    def _claim_yielded(self, decision: Decision) -> None:
        """Another arbitrator is on the bus: stop writing at once and say so, once."""
        self.bus_message = decision.message
        # Info, not warning: the yield event is what callers show (the CLI's one error line);
        # a warning would reach stderr a second time through logging's last-resort handler.
        log.info("%s: %s", self.name, decision.message)
        with self._lock:
            nodes = list(self._nodes)
        for node_id in nodes:
            self.requests.abort(node_id, "another bus arbitrator is on the bus")
        self._emit(ev.BusState("yielded", decision.message))
        self._wake.set()

    # -- foreign nodes and twins ----------------------------------------------------------
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

    def _count_beacon(self, node: _Node, now: float, caught_up: bool = True) -> None:
        """Twins bound together beacon on one node ID at twice the device's rate.

        Judged only on frames handled as they come: after a backlog (a flood, a busy
        machine) a second's beacons are handled in a moment and would look like twins."""
        if not node.set_up or not caught_up:
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

