"""Channel Type: a 16-bit set of flags (reference §1 "Channel type").

The thesis numbers bits from the most significant end (thesis bit 0 = 0x8000);
appendix D confirms it (0x7300 = unsigned 16-bit position, sole access, terminal).
Unused bits 11–15 are kept as read.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from typing import Any

BYTE_SIZE_MASK = 0xC000
DATA_TYPE_MASK = 0x3000
CONTROL_MODE_MASK = 0x0C00
SOLE_ACCESS_MASK = 0x0200
TERMINAL_MASK = 0x0100
PRESCALER_MASK = 0x00E0
UNUSED_MASK = 0x001F


class DataType(IntEnum):
    SIGNED = 0
    UNSIGNED = 1
    FLOAT = 2
    BOOLEAN = 3

    @property
    def label(self) -> str:
        return ("signed int", "unsigned int", "float", "boolean")[self]


class ControlMode(IntEnum):
    POSITION = 0
    VELOCITY = 1
    ACCELERATION = 2
    OTHER = 3

    @property
    def label(self) -> str:
        return self.name.lower()


#: Byte-size code → bits of the value (4 and 8 take one byte; 12 and 16 take two).
BYTE_SIZE_BITS = (4, 8, 12, 16)

#: Prescaler code → the thesis's *suggested* factor (a hint only; nothing computes with it).
PRESCALER_HINTS = ("1", "1e-6", "1e-3", "1e-1", "1e1", "1e2", "1e3", "1e6")


@dataclass(frozen=True)
class ChannelType:
    """A decoded Channel Type value. ``ChannelType(0x7300).terminal`` is True."""

    value: int

    def __post_init__(self) -> None:
        if not 0 <= self.value <= 0xFFFF:
            raise ValueError(f"channel type 0x{self.value:X} is not a 16-bit value")

    @property
    def byte_size_code(self) -> int:
        return (self.value & BYTE_SIZE_MASK) >> 14

    @property
    def bits(self) -> int:
        return BYTE_SIZE_BITS[self.byte_size_code]

    @property
    def data_type(self) -> DataType:
        return DataType((self.value & DATA_TYPE_MASK) >> 12)

    @property
    def control_mode(self) -> ControlMode:
        return ControlMode((self.value & CONTROL_MODE_MASK) >> 10)

    @property
    def sole_access(self) -> bool:
        return bool(self.value & SOLE_ACCESS_MASK)

    @property
    def terminal(self) -> bool:
        return bool(self.value & TERMINAL_MASK)

    @property
    def prescaler(self) -> int:
        return (self.value & PRESCALER_MASK) >> 5

    @property
    def prescaler_hint(self) -> str:
        return PRESCALER_HINTS[self.prescaler]

    @property
    def unused(self) -> int:
        return self.value & UNUSED_MASK

    @classmethod
    def build(
        cls,
        *,
        bits: int = 8,
        data_type: DataType | int = DataType.UNSIGNED,
        control_mode: ControlMode | int = ControlMode.POSITION,
        sole_access: bool = False,
        terminal: bool = False,
        prescaler: int = 0,
        unused: int = 0,
    ) -> ChannelType:
        if bits not in BYTE_SIZE_BITS:
            raise ValueError(f"byte size {bits} bits is not one of {BYTE_SIZE_BITS}")
        if not 0 <= prescaler <= 7:
            raise ValueError(f"prescaler code {prescaler} is not 0…7")
        if not 0 <= unused <= UNUSED_MASK:
            raise ValueError(f"unused bits 0x{unused:X} do not fit in 5 bits")
        value = (
            BYTE_SIZE_BITS.index(bits) << 14
            | int(DataType(data_type)) << 12
            | int(ControlMode(control_mode)) << 10
            | (SOLE_ACCESS_MASK if sole_access else 0)
            | (TERMINAL_MASK if terminal else 0)
            | prescaler << 5
            | unused
        )
        return cls(value)

    def replace(self, **changes: object) -> ChannelType:
        """A copy with some fields changed (same keywords as :meth:`build`)."""
        fields: dict[str, Any] = {
            "bits": self.bits,
            "data_type": self.data_type,
            "control_mode": self.control_mode,
            "sole_access": self.sole_access,
            "terminal": self.terminal,
            "prescaler": self.prescaler,
            "unused": self.unused,
        }
        fields.update(changes)
        return ChannelType.build(**fields)

    def describe(self) -> str:
        flags = [f"{self.bits}-bit {self.data_type.label}", self.control_mode.label]
        if self.sole_access:
            flags.append("sole access")
        if self.terminal:
            flags.append("terminal")
        if self.prescaler:
            flags.append(f"prescaler {self.prescaler} (≈{self.prescaler_hint})")
        return ", ".join(flags)

    def __str__(self) -> str:
        return f"0x{self.value:04X}"
