"""What a link drag's drop means, decided without Qt: output first whichever way the drag
went, refused with the reason the status line shows."""

from __future__ import annotations

from pdcp_studio.app.graph.link_drop import NO_TARGET, decide_drop, link_ends
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

SENSOR, HAND = Device(10, 1, 1).key, Device(10, 3, 1).key
OUT1, OUT2 = ChannelRef(*SENSOR, 1), ChannelRef(*SENSOR, 2)
IN = ChannelRef(*HAND, 1)


def _system() -> System:
    sensor = Device(10, 1, 1, name="EMG sensor")
    sensor.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222))
    sensor.add_channel(Channel(2, Direction.OUTPUT, type=0x9000, profile=0x4224))
    hand = Device(10, 3, 1, name="Hand")
    hand.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x4222))
    return System([sensor, hand])


def test_a_drop_on_an_input_links_the_output_to_it_either_way():
    system = _system()
    assert decide_drop(system, OUT1, IN).link == Link(OUT1, IN)
    assert decide_drop(system, IN, OUT1).link == Link(OUT1, IN)
    assert link_ends(system, IN, OUT1) == (OUT1, IN)


def test_a_drop_away_from_a_port_or_on_the_start_links_nothing():
    system = _system()
    for target in (None, OUT1):
        drop = decide_drop(system, OUT1, target)
        assert drop.link is None and drop.reason == NO_TARGET and drop.output is None


def test_refusals_say_why():
    system = _system()
    system.add_link(Link(OUT1, IN))
    second = decide_drop(system, OUT2, IN)
    assert second.link is None and "already has a source" in second.reason
    assert (second.output, second.input) == (OUT2, IN)
    assert "ends at an input" in decide_drop(system, OUT1, OUT2).reason
    system.devices[HAND].present = False
    system.remove_link(Link(OUT1, IN))
    assert "missing device" in decide_drop(system, OUT1, IN).reason
