"""Devices, channels, links and the ``System`` that holds them.

A ``System`` is the whole bus as data: which devices are there (and which are known
but missing), their channels and parameters, and the output → input links. It is
mutable so that undoable edits and plans can change it; ``copy()`` gives an
independent one for previews.
"""

from __future__ import annotations

import copy as _copy
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.errors import ModelError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.channel_type import SOLE_ACCESS_MASK, TERMINAL_MASK, ChannelType
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction

NO_VID_PID = 0xFFFF
NO_SERIAL = 0xFFFF
NO_INDEX = 0xFF


@dataclass(frozen=True)
class SourceInfo:
    """What an input channel itself stores about its source output (redundant storage).

    ``0xFFFF`` / ``0xFF`` mean "not connected" (appendix D: ``source vid: FFFF``).
    """

    vid: int = NO_VID_PID
    pid: int = NO_VID_PID
    serial: int = NO_SERIAL
    index: int = NO_INDEX
    type: int = 0
    profile: int = 0

    @property
    def connected(self) -> bool:
        return not (
            self.vid == NO_VID_PID and self.pid == NO_VID_PID and self.serial == NO_SERIAL
        ) and self.index != NO_INDEX

    @property
    def ref(self) -> ChannelRef | None:
        return ChannelRef(self.vid, self.pid, self.serial, self.index) if self.connected else None


NO_SOURCE = SourceInfo()


@dataclass
class Channel:
    """An input or output data channel and its profile-layer parameters."""

    index: int
    direction: Direction
    type: int = 0x5000
    profile: int = 0
    terminal_profile: int = 0
    required_inputs: tuple[int, ...] = ()
    desired_inputs: tuple[int, ...] = ()
    descriptor: str = ""
    source: SourceInfo = NO_SOURCE
    node_id: int | None = None
    data_enabled: bool = False

    @property
    def is_input(self) -> bool:
        return self.direction is Direction.INPUT

    @property
    def is_output(self) -> bool:
        return self.direction is Direction.OUTPUT

    @property
    def ctype(self) -> ChannelType:
        return ChannelType(self.type)

    @property
    def terminal(self) -> bool:
        return self.is_input and bool(self.type & TERMINAL_MASK)

    @property
    def sole_access(self) -> bool:
        return self.is_input and bool(self.type & SOLE_ACCESS_MASK)


@dataclass
class Device:
    """A device on the bus, identified by (VID, PID, serial)."""

    vid: int
    pid: int
    serial: int
    name: str = ""
    present: bool = True
    channels: dict[int, Channel] = field(default_factory=dict)
    node_id: int | None = None
    descriptor: str = ""
    fw_version: int = 0
    hw_version: int = 0
    device_type: int = 0
    device_profile: int = 0
    beacon_interval: int = 100
    ack_timeout: int = 50
    bind_timeout: int = 200
    ean_low: int = 0
    ean_high: int = 0

    @property
    def key(self) -> DeviceKey:
        return DeviceKey(self.vid, self.pid, self.serial)

    @property
    def label(self) -> str:
        return self.name or self.descriptor or f"Device {self.key}"

    def ref(self, index: int) -> ChannelRef:
        return ChannelRef(self.vid, self.pid, self.serial, index)

    def inputs(self) -> list[Channel]:
        return [c for c in self.channels.values() if c.is_input]

    def outputs(self) -> list[Channel]:
        return [c for c in self.channels.values() if c.is_output]

    def add_channel(self, channel: Channel) -> Channel:
        if not 1 <= channel.index <= 255:
            raise ModelError(f"device {self.key}: channel index {channel.index} is not 1…255")
        if channel.index in self.channels:
            raise ModelError(f"device {self.key}: channel {channel.index} already exists")
        self.channels[channel.index] = channel
        return channel


def _copy_device(device: Device) -> Device:
    """A copy of ``device`` with copies of its channels (every other field is immutable)."""
    new = _copy.copy(device)
    new.channels = {index: _copy.copy(ch) for index, ch in device.channels.items()}
    return new


@dataclass(frozen=True, order=True)
class Link:
    """An output channel feeding an input channel."""

    output: ChannelRef
    input: ChannelRef

    def as_json(self) -> dict[str, Any]:
        return {"output": self.output.as_json(), "input": self.input.as_json()}

    def __str__(self) -> str:
        return f"{self.output} → {self.input}"


class System:
    """The bus: devices by key, in insertion order, and the set of links."""

    def __init__(self, devices: Iterable[Device] = (), links: Iterable[Link] = ()) -> None:
        self.devices: dict[DeviceKey, Device] = {}
        self._links: set[Link] = set()
        self._by_input: dict[ChannelRef, set[Link]] = {}
        self._by_output: dict[ChannelRef, set[Link]] = {}
        for d in devices:
            self.add_device(d)
        for link in links:
            self.add_link(link, check=False)

    # -- devices and channels ---------------------------------------------------
    def add_device(self, device: Device) -> Device:
        if device.key in self.devices:
            raise ModelError(f"device {device.key} is already in the system")
        self.devices[device.key] = device
        return device

    def remove_device(self, key: DeviceKey) -> Device:
        """Remove a device and every link touching it."""
        device = self.devices.pop(key)
        for link in [lk for lk in self._links if key in (lk.output.device, lk.input.device)]:
            self.remove_link(link)
        return device

    def device(self, key: DeviceKey) -> Device | None:
        return self.devices.get(key)

    def channel(self, ref: ChannelRef) -> Channel | None:
        device = self.devices.get(ref.device)
        return device.channels.get(ref.index) if device else None

    def is_present(self, ref: ChannelRef) -> bool:
        """The channel exists and its device is on the bus."""
        device = self.devices.get(ref.device)
        return device is not None and device.present and ref.index in device.channels

    def channels(self) -> Iterator[tuple[ChannelRef, Channel]]:
        for device in self.devices.values():
            for ch in device.channels.values():
                yield device.ref(ch.index), ch

    # -- links ------------------------------------------------------------------
    @property
    def links(self) -> list[Link]:
        """All links, sorted by output then input reference."""
        return sorted(self._links)

    def has_link(self, link: Link) -> bool:
        return link in self._links

    def sources_of(self, input_ref: ChannelRef) -> list[ChannelRef]:
        return sorted(lk.output for lk in self._by_input.get(input_ref, ()))

    def source_of(self, input_ref: ChannelRef) -> ChannelRef | None:
        links = self._by_input.get(input_ref)
        return min(links).output if links else None

    def inputs_fed_by(self, output_ref: ChannelRef) -> list[ChannelRef]:
        return sorted(lk.input for lk in self._by_output.get(output_ref, ()))

    def check_link(self, link: Link) -> None:
        """Raise ModelError unless ``link`` joins an existing output to an existing input."""
        out = self.channel(link.output)
        inp = self.channel(link.input)
        if out is None:
            raise ModelError(f"link {link}: no channel {link.output}")
        if inp is None:
            raise ModelError(f"link {link}: no channel {link.input}")
        if not out.is_output:
            raise ModelError(f"link {link}: {link.output} is not an output channel")
        if not inp.is_input:
            raise ModelError(f"link {link}: {link.input} is not an input channel")

    def add_link(self, link: Link, *, check: bool = True) -> None:
        """Add a link. With ``check``, also refuse an input that already has a source."""
        self.check_link(link)
        if link in self._links:
            return
        if check and self._by_input.get(link.input):
            raise ModelError(
                f"link {link}: input {link.input} already has source {self.source_of(link.input)}"
            )
        self._links.add(link)
        self._by_input.setdefault(link.input, set()).add(link)
        self._by_output.setdefault(link.output, set()).add(link)

    def remove_link(self, link: Link) -> None:
        if link not in self._links:
            raise ModelError(f"link {link} is not in the system")
        self._links.discard(link)
        self._by_input[link.input].discard(link)
        self._by_output[link.output].discard(link)

    def clear_links(self) -> None:
        self._links.clear()
        self._by_input.clear()
        self._by_output.clear()

    # -- whole system -----------------------------------------------------------
    def copy(self) -> System:
        """An independent copy. Devices and channels hold only immutable values besides the
        channel table, so each is copied one level deep: ~20× faster than ``deepcopy``
        (a 254-node-ID bus is copied on the GUI thread at every live snapshot)."""
        return System((_copy_device(d) for d in self.devices.values()), self._links)

    def validate(self) -> None:
        """Raise ModelError on the first structural problem (see the loader for paths)."""
        for key, device in self.devices.items():
            for ch in device.channels.values():
                prof.check_profile(ch.profile)
                for idx in (*ch.required_inputs, *ch.desired_inputs):
                    target = device.channels.get(idx)
                    if target is None or not target.is_input:
                        raise ModelError(
                            f"device {key} channel {ch.index}: required/desired index {idx} "
                            "is not an input channel of that device"
                        )
        for link in self._links:
            self.check_link(link)

    def __repr__(self) -> str:
        return f"System({len(self.devices)} devices, {len(self._links)} links)"
