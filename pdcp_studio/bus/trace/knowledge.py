"""What a listener learns about a PDCP bus from its traffic.

Which node IDs are devices (bind responses, VID/PID/serial reads), which are output channels
(Channel Node Id writes and reads), which inputs listen to them (Source's Node Ids) and which
way each channel points. ``BusKnowledge`` owns these maps and changes them in place (the
decoder reads them on its fast path); it reports every change through the ``changed`` port,
so whoever cached texts made from it knows they are stale.
"""

from __future__ import annotations

from collections.abc import Callable

from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction

#: The owner of an output channel inferred from traffic (``inference.py``): its device and
#: index are not known, only that the node ID sends channel data.
INFERRED = (0, 0)
_NO_SOURCE = (0, 0xFF)  # a Source's Node Ids byte that means "not connected"
#: Parameters only an input channel has.
_INPUT_PARAMS = (P.IN_SOURCE_SN_INDEX, P.IN_SOURCE_NODE_IDS, P.IN_SOURCE_TYPE_PROFILE,
                 P.IN_TERMINAL_PROFILE)


class BusKnowledge:
    """Devices, output channels, their listeners and channel directions, learned as frames
    come; ``changed()`` is called on every change."""

    def __init__(self, changed: Callable[[], None]) -> None:
        self.changed = changed
        self.devices: dict[int, DeviceKey] = {}  # device node ID → identity
        self.outputs: dict[int, tuple[int, int]] = {}  # channel node → (device node, index)
        self.inputs: dict[int, set[tuple[int, int]]] = {}  # channel node → {(device node, index)}
        self.directions: dict[tuple[int, int], Direction] = {}
        self._partial: dict[int, dict[str, int]] = {}  # identities read in part, by node

    def ref(self, device_node: int, index: int) -> ChannelRef | str:
        """The channel ``index`` of the device at ``device_node``, named as well as known."""
        key = self.devices.get(device_node)
        return ChannelRef(*key, index) if key else f"node {device_node}#{index}"

    def bound(self, node: int, key: DeviceKey) -> None:
        """A device holds ``node`` now: forget its old node and any channel that used ``node``."""
        self.changed()
        for old in [n for n, k in self.devices.items() if k == key and n != node]:
            self._forget_device(old)
        self._forget_device(node)
        self.outputs.pop(node, None)
        self.devices[node] = key

    def _forget_device(self, node: int) -> None:
        self.changed()
        self.devices.pop(node, None)
        for chan_node in [c for c, (d, _) in self.outputs.items() if d == node]:
            del self.outputs[chan_node]
        for listeners in self.inputs.values():
            listeners.difference_update({x for x in listeners if x[0] == node})
        for gone in [k for k in self.directions if k[0] == node]:
            del self.directions[gone]

    def _moved(self, old: int, new: int) -> None:
        """The device at ``old`` was given node ID ``new``: its channels keep their node IDs."""
        if new == old or new in _NO_SOURCE:
            return
        self.changed()
        self.bound(new, self.devices.pop(old))
        # In place: the decoder holds these maps.
        outputs = {c: (new if d == old else d, i) for c, (d, i) in self.outputs.items()}
        self.outputs.clear()
        self.outputs.update(outputs)
        inputs = {c: {(new if d == old else d, i) for d, i in ins}
                  for c, ins in self.inputs.items()}
        self.inputs.clear()
        self.inputs.update(inputs)
        directions = {(new if d == old else d, i): v for (d, i), v in self.directions.items()}
        self.directions.clear()
        self.directions.update(directions)

    def direction(self, node: int, chan: int, param: int, value: bytes) -> Direction | None:
        """The channel's direction: learned, else implied by the parameter and value size."""
        if chan == 0:
            return None
        known = self.directions.get((node, chan))
        if known is not None:
            return known
        if param in _INPUT_PARAMS:
            return Direction.INPUT
        if param == P.OUT_NODE_ID and value:  # 1 byte: Channel Node Id; 4: Source's VID and PID
            return Direction.OUTPUT if len(value) == 1 else Direction.INPUT
        return None

    def learn(self, node: int, chan: int, param: int, value: bytes,
              direction: Direction | None) -> None:
        """Learn from a parameter value the device holds (written, or read back)."""
        if direction is not None and self.directions.get((node, chan)) is not direction:
            self.directions[node, chan] = direction
            self.changed()
        if chan == 0:
            if param == P.DEVICE_NODE_ID and len(value) == 1 and node in self.devices:
                self._moved(node, value[0])
            elif param in (P.DEVICE_VID_PID, P.DEVICE_SERIAL):
                self._learn_identity(node, param, value)
        elif param == P.CH_TRANSFER_TYPE and len(value) == 1 and value[0] in (1, 2):
            learned = Direction.from_transfer_type(value[0])
            if self.directions.get((node, chan)) is not learned:
                self.directions[node, chan] = learned
                self.changed()
        elif param == P.OUT_NODE_ID and direction is Direction.OUTPUT and len(value) == 1:
            self.changed()
            for chan_node in [c for c, owner in self.outputs.items() if owner == (node, chan)]:
                del self.outputs[chan_node]
            if value[0] not in _NO_SOURCE and value[0] not in self.devices:
                self.outputs[value[0]] = (node, chan)
        elif param == P.IN_SOURCE_NODE_IDS and len(value) == 2:
            self.changed()
            for listeners in self.inputs.values():
                listeners.discard((node, chan))
            if value[1] not in _NO_SOURCE:
                self.inputs.setdefault(value[1], set()).add((node, chan))

    def _learn_identity(self, node: int, param: int, value: bytes) -> None:
        partial = self._partial.setdefault(node, {})
        if param == P.DEVICE_VID_PID and len(value) == 4:
            partial["vid"] = int.from_bytes(value[:2], "little")
            partial["pid"] = int.from_bytes(value[2:], "little")
        elif param == P.DEVICE_SERIAL and len(value) == 2:
            partial["serial"] = int.from_bytes(value, "little")
        if len(partial) == 3 and node not in self.devices:
            self.bound(node, DeviceKey(**partial))
