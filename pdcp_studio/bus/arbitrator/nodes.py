"""The node table: who holds which node ID, and what to answer a bind request (reference §1).

One pool of node IDs is shared by devices and their output channels. A bind request asking for
a free ID (or the one the device holds) is granted at once; otherwise the lowest free ID is
suggested and held for that device for ``BIND_HOLD_S``. A device that is set up and asks to
bind again either rebooted or has a twin: its request is deferred ``DUPLICATE_WINDOW`` beacon
intervals (the presence tracker's beacons decide). Node IDs heard from devices bound by an
earlier arbitrator stay out of the pool while they are heard.

Pure: no threads, no bus, no clock. The arbitrator holds its lock around every call, passes
``now`` and carries the decisions out (the Bind Response, the set-up, the error line).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Literal

from pdcp_studio.bus.arbitrator.common import (
    BIND_HOLD_S,
    DUPLICATE_WINDOW,
    FOREIGN_HOLD_S,
    _Foreign,
    _Node,
)
from pdcp_studio.bus.arbitrator.node_ids import NodeIdPool
from pdcp_studio.errors import NodeIdExhaustedError
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device
from pdcp_studio.protocol import BindRequest
from pdcp_studio.protocol.identifier import NODE_ID_MAX

#: Per-device notes kept for devices that hold no node ID (refused binds, failed set-ups)
#: are bounded: a bind flood of made-up serial numbers must not grow them without end.
MAX_KEYS_REMEMBERED = 1024
#: Arbitration-ID priority bits of a bind request (``aid >> 9``).
_BINDING_PRIORITY = 3


@dataclass(frozen=True)
class BindDecision:
    """What to do with a bind request.

    ``grant``: answer with ``node_id`` (the ID asked for, or the one the device already holds:
    it is bound now); ``suggest``: answer with ``node_id``, held for the device until it asks
    for it; ``exhausted``: no answer, ``report`` is the error line (only the first time for a
    device); ``defer``: a set-up device asked again, wait for its twin's beacon; ``ignore``:
    a reported twin, never bound.
    """

    kind: Literal["grant", "suggest", "exhausted", "defer", "ignore"]
    key: DeviceKey
    asked: int = 0
    node_id: int = 0
    report: str = ""


def _key(req: BindRequest) -> DeviceKey:
    return DeviceKey(req.vid, req.pid, req.serial)


class NodeTable:
    """Node IDs of devices and outputs, bound nodes, held suggestions and deferred binds."""

    def __init__(self, low: int, high: int) -> None:
        self.pool = NodeIdPool(low, high)
        self.by_id: dict[int, _Node] = {}
        self.node_of: dict[DeviceKey, int] = {}
        self.channel_ids: dict[int, ChannelRef] = {}  # output node ID → output
        self.channel_set: frozenset[int] = frozenset()
        self.held: dict[DeviceKey, float] = {}  # suggested, not yet granted: since when
        self.deferred: dict[DeviceKey, tuple[BindRequest, float, float]] = {}  # req, since, until
        self.exhausted_reported: set[DeviceKey] = set()
        self.foreign: dict[int, float] = {}  # node ID heard but not bound here: last heard
        self._generations = itertools.count(1)

    # -- look-ups -------------------------------------------------------------------------
    def node(self, key: DeviceKey) -> _Node | None:
        return self.by_id.get(self.node_of.get(key, -1))

    def output_id(self, ref: ChannelRef) -> int | None:
        """The node ID an output channel sends its data with (None if it has none)."""
        return self.pool.id_of((ref.device, ref.index))

    def stamp(self, device: Device) -> None:
        """Write the node IDs this table holds for ``device`` and its outputs into the model
        (None where it holds none): the one place the model's node IDs are set, so they
        never disagree with the table."""
        device.node_id = self.node_of.get(device.key)
        for index, channel in device.channels.items():
            channel.node_id = self.output_id(device.ref(index))

    def is_foreign(self, arbitration_id: int) -> bool:
        """A device-mode frame (not a bind request) from a node ID nobody holds here."""
        node_id = arbitration_id & 0xFF
        return (not arbitration_id >> 8 & 1 and arbitration_id >> 9 != _BINDING_PRIORITY
                and 0 < node_id <= NODE_ID_MAX and node_id not in self.by_id
                and node_id not in self.channel_set)

    # -- bind decisions -------------------------------------------------------------------
    def on_bind_request(self, req: BindRequest, now: float,
                        duplicates: set[DeviceKey]) -> BindDecision:
        """A bind request: deferred when the device is set up already, else decided."""
        key = _key(req)
        node = self.node(key)
        if node is not None and node.set_up:
            if key in duplicates:
                return BindDecision("ignore", key)  # the reported twin asks again
            pending = self.deferred.get(key)
            window = DUPLICATE_WINDOW * node.beacon_interval
            self.deferred[key] = (req, pending[1] if pending else now,
                                  pending[2] if pending else now + window)
            return BindDecision("defer", key)
        return self.decide_bind(req, now)

    def decide_bind(self, req: BindRequest, now: float) -> BindDecision:
        """Grant, suggest (and hold) or refuse a node ID; the pool is updated."""
        key = _key(req)
        asked = req.node_id
        held = self.pool.id_of(key)
        owner = self.pool.owner(asked)
        if isinstance(owner, _Foreign):  # most likely that very device, reset and binding
            self.pool.release(owner)  # again
            self.foreign.pop(asked, None)
        if asked == held or self.pool.is_free(asked):
            grant = asked
        elif held is not None:
            grant = held
        else:
            try:
                grant = self.pool.lowest_free()
            except NodeIdExhaustedError as err:
                self.held.pop(key, None)
                first = key not in self.exhausted_reported
                if first and len(self.exhausted_reported) >= MAX_KEYS_REMEMBERED:
                    self.exhausted_reported.clear()  # a bind flood of made-up keys
                self.exhausted_reported.add(key)
                return BindDecision("exhausted", key, asked,
                                    report=f"device {key} cannot bind: {err}" if first else "")
        self.exhausted_reported.discard(key)
        self.pool.take(key, grant)
        if grant == asked:
            self.held.pop(key, None)
            return BindDecision("grant", key, asked, grant)
        self.held[key] = now
        return BindDecision("suggest", key, asked, grant)

    def install(self, key: DeviceKey, node_id: int, now: float, beacon_interval: float
                ) -> tuple[_Node, int | None]:
        """``key`` is bound to ``node_id``: its new node (a fresh generation, so a set-up of
        an older binding never matches) and the node ID it held before (None)."""
        old = self.node_of.get(key)
        if old is not None:
            self.by_id.pop(old, None)
        node = _Node(key, node_id, now, beacon_interval=beacon_interval)
        node.generation = next(self._generations)
        self.by_id[node_id] = node
        self.node_of[key] = node_id
        return node, old

    def resolve_deferred(self, now: float, duplicates: set[DeviceKey]
                         ) -> list[tuple[BindRequest, bool]]:
        """Deferred requests decided at ``now``: (request, True) when the bound node beaconed
        meanwhile (a twin), (request, False) when it kept silent or left (a reboot)."""
        resolved: list[tuple[BindRequest, bool]] = []
        for key, (req, since, deadline) in list(self.deferred.items()):
            node = self.node(key)
            if node is None:
                del self.deferred[key]
                resolved.append((req, False))
            elif node.last_beacon > since:
                del self.deferred[key]
                if key not in duplicates:
                    resolved.append((req, True))
            elif now >= deadline:
                del self.deferred[key]
                resolved.append((req, False))
        return resolved

    # -- what is known of a bound node ----------------------------------------------------
    def heard(self, node_id: int, now: float, *, beacon: bool = False,
              bus_time: float | None = None) -> _Node | None:
        """A frame (``beacon``: a beacon) from ``node_id`` handled at ``now`` and stamped
        ``bus_time`` by the bus; its node, or None when nobody holds that ID here."""
        node = self.by_id.get(node_id)
        if node is not None:
            node.last_seen = now
            if bus_time is not None:
                node.last_bus = bus_time
            if beacon:
                node.last_beacon = now
                if bus_time is not None:
                    node.prev_beacon_bus, node.last_beacon_bus = node.last_beacon_bus, bus_time
        return node

    def heard_all(self, now: float, bus_time: float | None = None) -> None:
        """The adapter is back (or the bus taken back): every node gets its beacon intervals
        to be heard again, by the clock and by the bus's (``bus_time``: the newest frame's)."""
        for node in self.by_id.values():
            node.last_seen = max(node.last_seen, now)
            if bus_time is not None:
                node.last_bus = max(node.last_bus, bus_time)

    def asked(self, node_id: int, now: float) -> None:
        """A request went to ``node_id`` at ``now`` (an echoed answer is judged by it)."""
        node = self.by_id.get(node_id)
        if node is not None:
            node.last_request = now

    def beacons_every(self, key: DeviceKey, interval_s: float) -> None:
        """``key``'s beacon interval is known (read, or just written)."""
        node = self.node(key)
        if node is not None:
            node.beacon_interval = interval_s

    def set_up(self, node: _Node, beacon_interval_s: float) -> None:
        """``node``'s device is read and installed: a bind request from it now means a
        reboot or a twin."""
        node.beacon_interval = beacon_interval_s
        node.set_up = True

    def binds_again(self, key: DeviceKey) -> None:
        """``key`` restarted: its bind request is answered as a fresh device's."""
        node = self.node(key)
        if node is not None:
            node.set_up = False

    # -- node IDs in use ------------------------------------------------------------------
    def give_outputs(self, key: DeviceKey, indices: list[int]
                     ) -> tuple[dict[int, int], list[int], str]:
        """Node IDs for a device's outputs: (index → ID, indices left without one, why)."""
        ids: dict[int, int] = {}
        refused: list[int] = []
        why = ""
        for index in indices:
            try:
                ids[index] = self.pool.take((key, index))
            except NodeIdExhaustedError as err:
                refused.append(index)
                why = str(err)
        self.refresh_channel_ids()
        return ids, refused, why

    def hear_foreign(self, node_id: int, now: float) -> None:
        """A frame from ``node_id``, bound elsewhere: keep the ID out of the pool a while."""
        if self.pool.is_free(node_id):
            self.pool.take(_Foreign(node_id), node_id)
        if isinstance(self.pool.owner(node_id), _Foreign):
            self.foreign[node_id] = now

    def expire(self, now: float) -> None:
        """Foreign IDs not heard for ``FOREIGN_HOLD_S`` and suggestions not taken up within
        ``BIND_HOLD_S`` go back to the pool."""
        for node_id, seen in list(self.foreign.items()):
            if now - seen > FOREIGN_HOLD_S:
                del self.foreign[node_id]
                self.pool.release(_Foreign(node_id))
        for key, since in list(self.held.items()):
            if now - since > BIND_HOLD_S:
                del self.held[key]
                if key not in self.node_of:
                    self.pool.release(key)

    def remove(self, node: _Node) -> bool:
        """``node`` left: its ID and its outputs' go back to the pool (False: it was not the
        current node of its device any more)."""
        if self.by_id.get(node.node_id) is not node:
            return False
        key = node.key
        del self.by_id[node.node_id]
        del self.node_of[key]
        self.deferred.pop(key, None)
        self.pool.release(key)
        self.pool.release_where(lambda o: isinstance(o, tuple) and o[0] == key)
        self.refresh_channel_ids()
        return True

    def clear(self) -> None:
        """Forget every binding (a reset); generations go on counting."""
        self.pool.clear()
        self.by_id.clear()
        self.node_of.clear()
        self.held.clear()
        self.deferred.clear()
        self.exhausted_reported.clear()
        self.foreign.clear()
        self.refresh_channel_ids()

    def refresh_channel_ids(self) -> None:
        """Channel node ID → output, from the pool (decoding needs the set)."""
        ids: dict[int, ChannelRef] = {}
        for node_id in range(self.pool.low, self.pool.high + 1):
            owner = self.pool.owner(node_id)
            if isinstance(owner, tuple) and len(owner) == 2:  # (device key, output index)
                key, index = owner
                ids[node_id] = ChannelRef(key.vid, key.pid, key.serial, index)
        self.channel_ids = ids
        self.channel_set = frozenset(ids)


__all__ = ["MAX_KEYS_REMEMBERED", "BindDecision", "NodeTable"]
