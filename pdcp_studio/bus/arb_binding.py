"""Binding and node IDs: answering bind requests from the one pool shared with output channels.

A mixin of :class:`pdcp_studio.bus.arbitrator.Arbitrator` (it uses the arbitrator's state and
locks); kept apart so the bind decisions (grant, suggest and hold, defer a present device's
second request) read on their own.
"""

from __future__ import annotations

import logging

from pdcp_studio.bus.arb_common import DEFAULT_BEACON_INTERVAL_S, DUPLICATE_WINDOW, _Foreign, _Node
from pdcp_studio.errors import NodeIdExhaustedError
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.protocol import BindRequest, BindResponse

log = logging.getLogger("pdcp_studio.bus.arbitrator")  # one logger for the arbitrator

#: Per-device notes kept for devices that hold no node ID (refused binds, failed set-ups)
#: are bounded: a bind flood of made-up serial numbers must not grow them without end.
MAX_KEYS_REMEMBERED = 1024
#: Beacon interval assumed for presence until a newly bound device's own has been read: long
#: enough for a device beaconing every 500 ms (the full rig's) not to be declared gone, and
#: bound again, while it is still being set up.
UNREAD_BEACON_INTERVAL_S = 1.0


class BindingMixin:
    """Bind requests, node-ID grants and the channel node-ID map of the :class:`Arbitrator`."""

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
                    if first and len(self._exhausted_reported) >= MAX_KEYS_REMEMBERED:
                        self._exhausted_reported.clear()  # a bind flood of made-up keys
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
                    else max(DEFAULT_BEACON_INTERVAL_S, UNREAD_BEACON_INTERVAL_S))
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

    # -- channel node IDs -----------------------------------------------------------------
    def _refresh_channel_ids(self) -> None:
        """Under the lock: channel node ID → output, from the pool (decode needs the set)."""
        ids: dict[int, ChannelRef] = {}
        for node_id in range(self._pool.low, self._pool.high + 1):
            owner = self._pool.owner(node_id)
            if isinstance(owner, tuple) and len(owner) == 2:
                ids[node_id] = ChannelRef(*owner[0], owner[1])
        self._channel_ids = ids
        self._channel_set = frozenset(ids)
