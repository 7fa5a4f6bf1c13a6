"""The guided tasks' decisions and words, without Qt or a bus: missing and new parts, the
replacement plan and its change, restoring a file, the read-back check, similarity in words."""

from __future__ import annotations

import pytest

from pdcp_studio.app.wizards import logic, words
from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND, load_prosthesis
from pdcp_studio.engine import Similarity, plan_autoconfigure
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link

CONTROL = DeviceKey(2641, 513, 201)


@pytest.fixture
def fitted():
    """sim:transradial's system as start-up leaves it, with its links stored."""
    system = load_prosthesis("transradial")
    for device in system.devices.values():
        device.name = ""  # as the bus reports them: no names, only descriptors
    plan_autoconfigure(system).apply(system)
    return system, logic.configuration_of(system, system.links)


def _swap(system):
    """The hand gone, the spare plugged in (not linked yet)."""
    swapped = system.copy()
    swapped.devices[HAND].present = False
    swapped.devices[SPARE_HAND].present = True
    return swapped


def test_missing_parts_are_absent_parts_that_links_still_reach(fitted):
    system, stored = fitted
    assert logic.missing_parts(system, stored) == []  # the unplugged spare is not missing
    swapped = _swap(system)
    assert logic.missing_parts(swapped, stored) == [logic.MissingPart(HAND, 3)]
    # Without a stored configuration the links on the bus say it; a part the configuration
    # names that the bus never saw is missing too.
    assert logic.missing_parts(swapped, None) == [logic.MissingPart(HAND, 3)]
    gone = swapped.copy()
    gone.remove_device(HAND)
    assert logic.missing_parts(gone, stored) == [logic.MissingPart(HAND, 3)]


def test_new_parts_are_present_parts_not_known_before(fitted):
    system, _stored = fitted
    assert logic.new_parts(_swap(system), set(system.devices) - {SPARE_HAND}) == [SPARE_HAND]
    assert logic.new_parts(system, set()) == sorted(k for k, d in system.devices.items()
                                                    if d.present)


def test_the_replacement_plan_moves_every_link_to_the_spare_with_its_similarity(fitted):
    system, stored = fitted
    swapped = _swap(system)
    # The arbitrator may have linked the spare on its own already: the plan is the same.
    on_its_own = swapped.copy()
    from pdcp_studio.engine import set_links

    set_links(on_its_own, [*on_its_own.links,
                           Link(ChannelRef(*CONTROL, 3), ChannelRef(*SPARE_HAND, 1))])
    for bus in (swapped, on_its_own):
        plan = logic.replacement_plan(bus, stored, [SPARE_HAND])
        final = plan.final_links
        assert len(final) == 5 and not any(lk.input.device == HAND for lk in final)
        assert sorted(lk.input.index for lk in final if lk.input.device == SPARE_HAND) == \
            [1, 2, 3]
        change = logic.replacement_change(bus, plan)
        assert change.links_after(bus.links) == final
        assert change.configuration is not None
        stored_inputs = {sl.input.ref.device for sl in change.configuration.configurations[0]
                         .links}
        assert SPARE_HAND in stored_inputs and HAND not in stored_inputs
    lines = words.plan_lines(swapped, plan)
    assert any("It takes the place of Multi-grip hand with wrist rotator (serial 301), "
               "Power grip"
               in line and "Exact match" in line for line in lines)
    assert not any("0x" in line for line in lines)


def test_restoring_a_file_makes_its_links_and_stores_it(fitted):
    system, stored = fitted
    bare = system.copy()
    from pdcp_studio.engine import set_links

    set_links(bare, [])
    change = logic.restore_file_change(bare, stored, "fitted.pdcfg")
    assert change.action == "restore configuration from file fitted.pdcfg"
    assert set(change.links_after(bare.links)) == set(system.links)
    assert change.configuration is stored
    assert all(a.op == "add" and a.reason for a in change.links)


def test_verify_names_every_way_the_prosthesis_differs(fitted):
    system, stored = fitted
    assert logic.verify(system, stored, system.links, stored) == []
    links = sorted(system.links)
    problems = logic.verify(system, ConfigCollection(), links[:4], stored)
    assert [p.kind for p in problems] == ["link-extra", "config-differs"]
    swapped = _swap(system)
    kinds = [p.kind for p in logic.verify(swapped, stored, links, None)]
    assert kinds == ["part-missing"]
    assert [p.link for p in logic.verify(system, stored, [*links,
            Link(ChannelRef(*CONTROL, 3), ChannelRef(*SPARE_HAND, 1))], None)
            if p.kind == "link-missing"]


@pytest.mark.parametrize(("sim", "profile", "expected"), [
    (Similarity(31, 3, True, True, True), 0x2220,
     "Exact match: it does the same job and sends its data the same way (31 of 31 points)."),
    (Similarity(23, 2, True, True, True), 0x2600,
     "Exact match: it does the same job and sends its data the same way (23 of 23 points)."),
    (Similarity(20, 2, True, False, False), 0x2220,
     "Close match: it does a related job (2 of 3 levels of its kind alike) and sends its "
     "data partly the same way (20 of 31 points)."),
    (Similarity(8, 1, False, False, False), 0x2220,
     "Distant match: it does a related job (1 of 3 levels of its kind alike) but sends its "
     "data differently (8 of 31 points)."),
])
def test_similarity_in_words(sim, profile, expected):
    assert words.similarity_words(sim, profile) == expected


def test_parts_are_named_from_the_catalogue_and_kept_apart_by_serial(fitted):
    """Each part by its own name (what it tells the bus); the hand and its spare read
    alike, so they get their serial numbers; a part with no name of its own by its
    product from the catalogue, without a serial number when no other part reads so."""
    system, _stored = fitted
    bus = system.copy()
    assert words.part_words(bus, HAND) == "Multi-grip hand with wrist rotator (serial 301)"
    assert words.part_words(bus, SPARE_HAND) == \
        "Multi-grip hand with wrist rotator (serial 302)"
    assert words.part_words(bus, CONTROL) == "Pattern-recognition control unit"
    assert words.part_words(bus, DeviceKey(9, 9, 9)) == "unknown device (9/9/9)"
    assert words.channel_phrase(bus, ChannelRef(*HAND, 3)) == \
        "Multi-grip hand with wrist rotator (serial 301), Wrist rotation"
    bus.devices[CONTROL].descriptor = ""
    assert words.part_words(bus, CONTROL) == "Control unit"


def test_without_a_stored_configuration_the_links_on_the_bus_are_repaired(fitted):
    system, _stored = fitted
    swapped = _swap(system)  # the arbitrator keeps the links to the missing hand
    plan = logic.replacement_plan(swapped, None, [SPARE_HAND])
    assert sorted(lk.input.index for lk in plan.final_links
                  if lk.input.device == SPARE_HAND) == [1, 2, 3]
    assert not any(lk.input.device == HAND for lk in plan.final_links)
    assert logic.replacement_plan(swapped, ConfigCollection(), [SPARE_HAND]).final_links == \
        plan.final_links  # an empty stored configuration is none


def test_two_parts_that_would_read_alike_get_their_serial_numbers(fitted):
    system, _stored = fitted
    bus = _swap(system)
    bus.devices[HAND].present = True
    bus.devices[HAND].name = bus.devices[SPARE_HAND].name = "Hand"  # two hands named alike
    names = words.part_names(bus)
    assert names[HAND] == "Hand (serial 301)" and names[SPARE_HAND] == "Hand (serial 302)"
    assert names[CONTROL] == "Pattern-recognition control unit"  # its own name
    assert words.part_words(bus, HAND) == "Hand (serial 301)"
    bus.devices[SPARE_HAND].name = "Spare hand"  # no longer alike: no serial added
    assert words.part_words(bus, HAND) == "Hand"


def test_restoring_an_empty_stored_configuration_over_a_stored_one_is_flagged(fitted):
    from pdcp_studio.bus.transaction import Change

    system, stored = fitted
    empty = Change.links_to(system.links, system.links, "history restore 1")
    empty.configuration = ConfigCollection()
    assert logic.clears_stored(empty, stored)
    assert not logic.clears_stored(empty, ConfigCollection())  # nothing stored: nothing lost
    assert not logic.clears_stored(empty, None)
    kept = Change.links_to(system.links, system.links, "history restore 2")
    assert not logic.clears_stored(kept, stored)  # no configuration written
    kept.configuration = stored
    assert not logic.clears_stored(kept, stored)
