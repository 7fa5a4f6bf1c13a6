"""What a channel's values are and the range they can take, from its channel type. Pure.

A channel sends raw values: the type's data type and byte size bound them (an unsigned
12-bit value is 0…4095, a signed 8-bit one −128…127, a boolean 0 or 1; a float has no
fixed bound) and its control mode says which quantity they are (position, velocity,
acceleration, or another value). The live plot scales its value axis to this range and
names it so, never "0…1" for an EMG envelope whose values run to 4095; no physical unit
is known (reference §2), so none is claimed, and the prescaler's factor is a hint only.
"""

from __future__ import annotations

from dataclasses import dataclass

from pdcp_studio.model.channel_type import ChannelType, ControlMode, DataType


@dataclass(frozen=True)
class ValueAxis:
    """The value axis of one channel: its quantity, form and range."""

    mode: ControlMode | None
    data_type: DataType | None
    bits: int
    #: The least and greatest value the type can carry (None: a float, or type unknown).
    lo: float | None
    hi: float | None
    #: The prescaler's suggested factor (``1e-3``), a hint only.
    hint: str = "1"

    @property
    def boolean(self) -> bool:
        return self.data_type is DataType.BOOLEAN

    @property
    def bounded(self) -> bool:
        return self.lo is not None and self.hi is not None


def type_range(ctype: ChannelType) -> tuple[float, float] | None:
    """The values ``ctype`` can carry: (least, greatest); None for a float."""
    bits = ctype.bits
    if ctype.data_type is DataType.BOOLEAN:
        return 0.0, 1.0
    if ctype.data_type is DataType.UNSIGNED:
        return 0.0, float(2 ** bits - 1)
    if ctype.data_type is DataType.SIGNED:
        return float(-(2 ** (bits - 1))), float(2 ** (bits - 1) - 1)
    return None


def value_axis(ctype: int | None) -> ValueAxis:
    """The value axis of a channel whose type value is ``ctype`` (None: not known)."""
    if ctype is None:
        return ValueAxis(None, None, 0, None, None)
    t = ChannelType(ctype)
    bounds = type_range(t)
    lo, hi = bounds if bounds is not None else (None, None)
    return ValueAxis(t.control_mode, t.data_type, t.bits, lo, hi, t.prescaler_hint)
