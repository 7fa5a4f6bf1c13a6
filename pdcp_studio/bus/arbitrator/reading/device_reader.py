"""Reading one device's parameters: the one reader the arbitrator's set-up and the scan share.

A device is read one request after another (the request engine allows one transaction per
device): first its device parameters, then for each channel 1…N its Transfer Type and the
parameters of that direction. What is read is a :class:`ReadList` — the set-up reads what
the model needs (not the node IDs and enabled flags it is about to set), the scan reads
everything. The values come back raw; ``model/param_fields.py`` turns them into a Device.
A parameter the device refuses (it does not implement it) is None.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from pdcp_studio.bus.arbitrator.reading.requests import DeviceRefusedError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.param_fields import Values
from pdcp_studio.model.refs import DeviceKey, Direction


@dataclass(frozen=True)
class ReadList:
    """Which parameters to read: of the device (channel 0), and of each channel direction
    (after its Transfer Type, which is always read first)."""

    device: tuple[int, ...]
    input: tuple[int, ...]
    output: tuple[int, ...]

    def channel(self, direction: Direction) -> tuple[int, ...]:
        return self.input if direction is Direction.INPUT else self.output

    def count(self, directions: list[Direction]) -> int:
        """Reads of a device with channels of these directions."""
        return len(self.device) + sum(1 + len(self.channel(d)) for d in directions)


def _ids(scope: P.Scope | Direction, skip: tuple[int, ...] = ()) -> tuple[int, ...]:
    return tuple(s.id for s in P.parameters_for(scope) if s.id not in skip)


#: Everything the catalog has (the scan).
EVERYTHING = ReadList(_ids("device"), _ids(Direction.INPUT, (P.CH_TRANSFER_TYPE,)),
                      _ids(Direction.OUTPUT, (P.CH_TRANSFER_TYPE,)))
#: The set-up's reads (reference §1 steps 1–5): not the bus-session values it sets itself.
_SESSION = (P.CH_TRANSFER_TYPE, P.CH_DATA_ENABLED, P.IN_SOURCE_NODE_IDS)
SETUP = ReadList(_ids("device", (P.DEVICE_NODE_ID,)), _ids(Direction.INPUT, _SESSION),
                 _ids(Direction.OUTPUT, (*_SESSION, P.OUT_NODE_ID)))


class DeviceReader:
    """Reads devices through a request engine (``get(node, param, channel, …)``).

    ``before`` runs before each request (a pacer, a cancel check that raises); ``after``
    gets (key, param, channel) after each (progress). ``descriptor_bulk`` starts the device
    descriptor with Configure Get Bulk (the scan); the set-up asks inline first, as the
    worked example of 001 §3.3 does.
    """

    def __init__(self, requests: Any, *, timeout: float | None = None,
                 before: Callable[[], None] | None = None,
                 after: Callable[[DeviceKey, int, int], None] | None = None,
                 descriptor_bulk: bool = True) -> None:
        self.requests = requests
        self.timeout = timeout
        self.descriptor_bulk = descriptor_bulk
        self.before = before
        self.after = after

    def get(self, key: DeviceKey, node_id: int, param: int, channel: int = 0) -> bytes | None:
        """One read; None when the device refuses it (a parameter it does not have)."""
        if self.before is not None:
            self.before()
        # A device descriptor is long (the thesis's is 33 bytes): ask for bulk at once.
        # Channel descriptors are often short or empty, so they go inline first.
        long_value = self.descriptor_bulk and channel == 0 and param == P.DEVICE_DESCRIPTOR
        try:
            value: bytes | None = self.requests.get(node_id, param, channel, timeout=self.timeout,
                                                    bulk_first=long_value)
        except DeviceRefusedError:
            value = None
        if self.after is not None:
            self.after(key, param, channel)
        return value

    def read_device(self, key: DeviceKey, node_id: int, what: ReadList, values: Values) -> None:
        """The device parameters of ``what`` into ``values``."""
        for param in what.device:
            values[param, 0] = self.get(key, node_id, param)

    def read_channels(self, key: DeviceKey, node_id: int, what: ReadList, values: Values,
                      problem: Callable[[str], None] | None = None) -> None:
        """Every channel 1…N (Number of Data Channels, read before) into ``values``;
        ``problem`` hears of a Transfer Type that is no direction."""
        count = param_fields.decoded(values, P.DEVICE_CHANNEL_COUNT) or 0
        for index in range(1, count + 1):
            raw = values[P.CH_TRANSFER_TYPE, index] = self.get(key, node_id, P.CH_TRANSFER_TYPE,
                                                               index)
            direction = param_fields.channel_direction(values, index)
            if direction is None:
                if raw and raw != b"\0" and problem is not None:
                    problem(f"device {key} channel {index}: transfer type {raw.hex()} is "
                            "neither input (1) nor output (2)")
                continue
            for param in what.channel(direction):
                values[param, index] = self.get(key, node_id, param, index)

    def identity_problem(self, key: DeviceKey, node_id: int, values: Values) -> str:
        """Why the values read are not from device ``key`` ('' when they are, or unread)."""
        got = param_fields.decoded(values, P.DEVICE_VID_PID)
        serial = param_fields.decoded(values, P.DEVICE_SERIAL)
        if got is None or (tuple(got) == (key.vid, key.pid) and serial == key.serial):
            return ""
        return f"node {node_id} answered as {got[0]}/{got[1]}/{serial}, not {key}"


__all__ = ["EVERYTHING", "SETUP", "DeviceReader", "ReadList"]
