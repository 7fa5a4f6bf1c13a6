"""The System: identities, links, and the rules a link must keep."""

import pytest

from pdcp_studio.errors import ModelError
from pdcp_studio.model import Channel, ChannelRef, Device, Direction, Link, System


def _system():
    a = Device(2, 2, 4)
    a.add_channel(Channel(1, Direction.OUTPUT, 0x5000, 0x2120))
    b = Device(2, 2, 5)
    b.add_channel(Channel(1, Direction.INPUT, 0x7200, 0x2200))
    b.add_channel(Channel(2, Direction.INPUT, 0x5200, 0x2110))
    b.add_channel(Channel(3, Direction.OUTPUT, 0x5000, 0x1100, required_inputs=(2,)))
    return System([a, b])


def test_link_indexes():
    s = _system()
    lk = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))
    s.add_link(lk)
    assert s.source_of(ChannelRef(2, 2, 5, 2)) == ChannelRef(2, 2, 4, 1)
    assert s.inputs_fed_by(ChannelRef(2, 2, 4, 1)) == [ChannelRef(2, 2, 5, 2)]
    s.remove_link(lk)
    assert s.source_of(ChannelRef(2, 2, 5, 2)) is None
    assert s.links == []


def test_link_must_join_output_to_input():
    s = _system()
    with pytest.raises(ModelError, match="not an output"):
        s.add_link(Link(ChannelRef(2, 2, 5, 1), ChannelRef(2, 2, 5, 2)))
    with pytest.raises(ModelError, match="no channel"):
        s.add_link(Link(ChannelRef(2, 2, 4, 9), ChannelRef(2, 2, 5, 2)))


def test_input_with_a_source_refuses_a_second_one():
    s = _system()
    s.add_link(Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)))
    with pytest.raises(ModelError, match="already has source"):
        s.add_link(Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 5, 2)))


def test_duplicate_device_and_channel_refused():
    s = _system()
    with pytest.raises(ModelError, match="already"):
        s.add_device(Device(2, 2, 4))
    with pytest.raises(ModelError, match="already exists"):
        s.device((2, 2, 4)).add_channel(Channel(1, Direction.INPUT))
    with pytest.raises(ModelError, match="1…255"):
        s.device((2, 2, 4)).add_channel(Channel(256, Direction.INPUT))


def test_copy_is_independent():
    s = _system()
    c = s.copy()
    c.add_link(Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)))
    c.device((2, 2, 4)).name = "changed"
    assert s.links == [] and s.device((2, 2, 4)).name == ""


def test_remove_device_removes_its_links():
    s = _system()
    s.add_link(Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)))
    s.remove_device((2, 2, 4))
    assert s.links == []


def test_presence():
    s = _system()
    s.device((2, 2, 4)).present = False
    assert not s.is_present(ChannelRef(2, 2, 4, 1))
    assert s.is_present(ChannelRef(2, 2, 5, 1))
    assert not s.is_present(ChannelRef(9, 9, 9, 1))


def test_validate_refuses_required_index_that_is_not_an_input():
    s = _system()
    s.device((2, 2, 5)).channels[3].required_inputs = (3,)
    with pytest.raises(ModelError, match="not an input"):
        s.validate()
