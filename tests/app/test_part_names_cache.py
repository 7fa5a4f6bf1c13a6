"""The naming cache of ``app/words/part_names.py`` answers for the system it is asked
about, never for another one that read the same when it was cached and was changed since
(a test run on a busy CI once named the hand's "Wrist rotation" "channel 3" that way)."""

from __future__ import annotations

from pdcp_studio.app.words import part_names
from pdcp_studio.bus.sim.rigs import HAND, load_prosthesis
from pdcp_studio.model.refs import ChannelRef


def test_a_system_changed_after_it_was_named_does_not_name_an_equal_one():
    first = load_prosthesis("transradial")
    fresh = first.copy()  # reads the same as ``first`` did
    assert part_names.channel_name(first, ChannelRef(*HAND, 3)).endswith("Wrist rotation")
    first.remove_device(HAND)  # changed in place after it was named (a document's edit)
    assert part_names.channel_name(fresh, ChannelRef(*HAND, 3)).endswith("Wrist rotation")
    assert part_names.names(fresh).system is fresh


def test_a_device_among_others_changed_after_naming_does_not_leak():
    system = load_prosthesis("transradial")
    shown = system.copy()
    hand = shown.devices[HAND]
    bus = system.copy()
    bus.remove_device(HAND)
    before = part_names.part_name(bus, HAND, [hand])
    hand.name = "Renamed in place"
    other = load_prosthesis("transradial").devices[HAND]
    assert part_names.part_name(bus, HAND, [other]) == before
