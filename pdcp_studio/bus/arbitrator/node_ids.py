"""The node-ID pool: 1–254, shared by devices and output channels (reference §1, §4.6.5).

Pure bookkeeping (no bus, no threads of its own; the arbitrator locks around it): who holds
which ID, what to suggest to a device asking for a taken one, and giving IDs back when a
device leaves. An empty pool raises NodeIdExhaustedError, which the arbitrator reports.
"""

from __future__ import annotations

from collections.abc import Hashable

from pdcp_studio.errors import NodeIdExhaustedError
from pdcp_studio.protocol.identifier import NODE_ID_MAX, NODE_ID_MIN

#: Who holds an ID: a DeviceKey for a device, (DeviceKey, channel index) for an output.
Owner = Hashable


class NodeIdPool:
    """IDs 1–254 → owner. Lowest free ID first, so the same bus gives the same IDs."""

    def __init__(self, low: int = NODE_ID_MIN, high: int = NODE_ID_MAX) -> None:
        self.low, self.high = low, high
        self._owner: dict[int, Owner] = {}
        self._by_owner: dict[Owner, int] = {}

    def __len__(self) -> int:
        return len(self._owner)

    @property
    def capacity(self) -> int:
        return self.high - self.low + 1

    @property
    def free_count(self) -> int:
        return self.capacity - len(self._owner)

    def owner(self, node_id: int) -> Owner | None:
        return self._owner.get(node_id)

    def id_of(self, owner: Owner) -> int | None:
        return self._by_owner.get(owner)

    def is_free(self, node_id: int) -> bool:
        return self.low <= node_id <= self.high and node_id not in self._owner

    def lowest_free(self) -> int:
        """The lowest free ID; NodeIdExhaustedError when none is left."""
        for node_id in range(self.low, self.high + 1):
            if node_id not in self._owner:
                return node_id
        raise NodeIdExhaustedError(
            f"all {self.capacity} node IDs are in use by devices and output channels "
            f"(reference §4.6.5); unplug a device to free some"
        )

    def take(self, owner: Owner, node_id: int | None = None) -> int:
        """Give ``owner`` an ID: the one it holds, ``node_id`` if free, else the lowest free."""
        held = self._by_owner.get(owner)
        if held is not None and (node_id is None or node_id == held):
            return held
        if node_id is None or not self.is_free(node_id):
            node_id = self.lowest_free()
        if held is not None:
            self.release(owner)
        self._owner[node_id] = owner
        self._by_owner[owner] = node_id
        return node_id

    def release(self, owner: Owner) -> int | None:
        """Give ``owner``'s ID back; returns it (None if it held none)."""
        node_id = self._by_owner.pop(owner, None)
        if node_id is not None:
            del self._owner[node_id]
        return node_id

    def release_where(self, predicate) -> list[int]:  # type: ignore[no-untyped-def]
        """Release every owner for which ``predicate(owner)`` is true (a departed device)."""
        gone = [o for o in self._by_owner if predicate(o)]
        return [nid for nid in (self.release(o) for o in gone) if nid is not None]

    def clear(self) -> None:
        self._owner.clear()
        self._by_owner.clear()
