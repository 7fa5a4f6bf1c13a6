"""Channel Type flags, MSB-first numbering, checked against appendix D's values."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.model.channel_type import ChannelType, ControlMode, DataType


@pytest.mark.parametrize(
    ("value", "sole", "terminal"),
    [
        (0x5300, True, True),  # terminal device input 1, appendix D
        (0x7300, True, True),  # terminal device input 2
        (0x7200, True, False),  # control unit input 1: sole access only
        (0x5200, True, False),  # control unit input 2
        (0x5000, False, False),  # outputs
        (0x7000, False, False),
    ],
)
def test_appendix_d_flags(value, sole, terminal):
    t = ChannelType(value)
    assert t.sole_access is sole
    assert t.terminal is terminal


def test_thesis_bit0_is_msb_byte_size():
    assert ChannelType(0x0000).bits == 4
    assert ChannelType(0x4000).bits == 8
    assert ChannelType(0x8000).bits == 12
    assert ChannelType(0xC000).bits == 16


def test_data_type_and_control_mode_fields():
    t = ChannelType(0x5000)
    assert t.data_type is DataType.UNSIGNED
    assert t.control_mode is ControlMode.POSITION
    assert ChannelType(0x7000).data_type is DataType.BOOLEAN
    assert ChannelType(0x2000).data_type is DataType.FLOAT
    assert ChannelType(0x0400).control_mode is ControlMode.VELOCITY
    assert ChannelType(0x0800).control_mode is ControlMode.ACCELERATION
    assert ChannelType(0x0C00).control_mode is ControlMode.OTHER


def test_prescaler_is_a_raw_code_with_a_hint():
    t = ChannelType(0x00E0)
    assert t.prescaler == 7
    assert t.prescaler_hint == "1e6"
    assert ChannelType(0x0020).prescaler_hint == "1e-6"


def test_unused_bits_are_kept():
    t = ChannelType(0x531F)
    assert t.unused == 0x1F
    assert t.replace(terminal=False).value == 0x521F


def test_build_matches_appendix_d():
    assert ChannelType.build(bits=8, data_type=DataType.UNSIGNED, sole_access=True,
                             terminal=True).value == 0x5300
    assert ChannelType.build(bits=8, data_type=DataType.BOOLEAN, sole_access=True).value == 0x7200


def test_out_of_range_refused():
    with pytest.raises(ValueError, match="16-bit"):
        ChannelType(0x10000)
    with pytest.raises(ValueError, match="byte size"):
        ChannelType.build(bits=10)


@given(st.integers(0, 0xFFFF))
def test_build_round_trip(value):
    t = ChannelType(value)
    again = ChannelType.build(bits=t.bits, data_type=t.data_type, control_mode=t.control_mode,
                              sole_access=t.sole_access, terminal=t.terminal,
                              prescaler=t.prescaler, unused=t.unused)
    assert again == t
