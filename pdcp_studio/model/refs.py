"""Identities: a device is (VID, PID, serial); a channel is its device plus an index."""

from __future__ import annotations

from enum import StrEnum
from typing import Any, NamedTuple


class DeviceKey(NamedTuple):
    """A device's identity on any bus: vendor ID, product ID, serial number."""

    vid: int
    pid: int
    serial: int

    def __str__(self) -> str:
        return f"{self.vid}/{self.pid}/{self.serial}"


class ChannelRef(NamedTuple):
    """A channel's identity: its device's key and its channel index (1…255)."""

    vid: int
    pid: int
    serial: int
    index: int  # type: ignore[assignment]  # the channel index; shadows tuple.index on purpose

    @property
    def device(self) -> DeviceKey:
        return DeviceKey(self.vid, self.pid, self.serial)

    def as_json(self) -> dict[str, Any]:
        return {"vid": self.vid, "pid": self.pid, "serial": self.serial, "index": self.index}

    def __str__(self) -> str:
        return f"{self.vid}/{self.pid}/{self.serial}#{self.index}"


class Direction(StrEnum):
    """Transfer Type of a channel: 1 = input, 2 = output (parameter 3)."""

    INPUT = "input"
    OUTPUT = "output"

    @property
    def transfer_type(self) -> int:
        return 1 if self is Direction.INPUT else 2

    @classmethod
    def from_transfer_type(cls, value: int) -> Direction:
        if value == 1:
            return cls.INPUT
        if value == 2:
            return cls.OUTPUT
        raise ValueError(f"transfer type {value} is neither 1 (input) nor 2 (output)")
