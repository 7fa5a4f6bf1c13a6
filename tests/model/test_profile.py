"""Profiles as 16-bit nibble paths (reference §1)."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.model import profile as prof


def test_components_of_sensor_accelerometer_wrist():
    assert prof.components(0x4620) == (4, 6, 2)
    assert prof.depth(0x4620) == 3
    assert prof.from_components([4, 6, 2]) == 0x4620


def test_null_profile():
    assert prof.is_null(0x0000)
    assert prof.components(0) == ()
    assert not prof.is_well_formed(0)


def test_common_prefix_stops_at_first_difference_and_at_zero():
    assert prof.common_prefix_depth(0x1110, 0x1100) == 2
    assert prof.common_prefix_depth(0x2110, 0x2200) == 1
    assert prof.common_prefix_depth(0x1000, 0x2000) == 0
    assert prof.common_prefix_depth(0x1100, 0x1100) == 2


def test_parent_and_vendor_components():
    assert prof.parent(0x4620) == 0x4600
    assert prof.parent(0x4000) == 0
    assert prof.is_vendor_component(3)
    assert not prof.is_vendor_component(2)


def test_ill_formed_gap():
    assert not prof.is_well_formed(0x2020)
    assert prof.is_well_formed(0x2200)


def test_range_checks():
    with pytest.raises(ValueError):
        prof.components(0x10000)
    with pytest.raises(ValueError):
        prof.from_components([1, 2, 3, 4, 5])
    with pytest.raises(ValueError):
        prof.from_components([0x10])


@given(st.lists(st.integers(1, 15), max_size=4))
def test_components_round_trip(path):
    assert prof.components(prof.from_components(path)) == tuple(path)
