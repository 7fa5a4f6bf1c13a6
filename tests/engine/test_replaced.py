"""Which absent parts are replaced, not missing (issue 26 item 6): pure."""

from __future__ import annotations

import dataclasses

from pdcp_studio.engine.replaced import Replaced, replaced_parts
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file

HAND, SPARE = DeviceKey(2641, 769, 301), DeviceKey(2641, 769, 302)


def _swapped(systems_dir, *, move: int = 3):
    """transradial with the hand gone and ``move`` of its three links moved to a spare."""
    system = system_file.load_path(systems_dir / "transradial.json")
    cu = DeviceKey(2641, 513, 201)
    for n in (1, 2):
        system.add_link(Link(system.devices[DeviceKey(2641, 257, 100 + n)].ref(1),
                             system.devices[cu].ref(n)))
    for n in (1, 2, 3):
        system.add_link(Link(system.devices[cu].ref(2 + n), system.devices[HAND].ref(n)))
    roles = set(system.links)
    hand = system.devices[HAND]
    system.add_device(dataclasses.replace(
        hand, serial=SPARE.serial, name="Spare hand",
        channels={i: dataclasses.replace(c) for i, c in hand.channels.items()}))
    hand.present = False
    for link in sorted(lk for lk in roles if lk.input.device == HAND)[:move]:
        system.remove_link(link)
        system.add_link(Link(link.output, system.devices[SPARE].ref(link.input.index)))
    return system, roles


def test_a_part_whose_every_role_a_present_part_holds_is_replaced_by_it(systems_dir):
    system, roles = _swapped(systems_dir)
    assert replaced_parts(system, roles) == [Replaced(HAND, SPARE)]


def test_a_part_with_a_role_nobody_holds_is_still_missing(systems_dir):
    system, roles = _swapped(systems_dir, move=2)
    dead = [lk for lk in system.links if lk.input.device == HAND]
    for link in dead:  # its last link is gone too, but nobody took that role
        system.remove_link(link)
    assert replaced_parts(system, roles) == []


def test_a_role_still_only_on_a_dead_link_is_not_held(systems_dir):
    system, roles = _swapped(systems_dir, move=2)
    assert any(lk.input.device == HAND for lk in system.links)
    assert replaced_parts(system, roles) == []


def test_dead_links_left_beside_the_new_ones_do_not_keep_it_missing(systems_dir):
    """The duty cycle may link the spare (autoconfigure) and leave the hand's dead links."""
    system, roles = _swapped(systems_dir)
    for link in sorted(lk for lk in roles if lk.input.device == HAND):
        system.add_link(link, check=False)
    assert replaced_parts(system, roles) == [Replaced(HAND, SPARE)]


def test_a_part_without_roles_or_present_is_neither(systems_dir):
    system, roles = _swapped(systems_dir)
    assert replaced_parts(system, set()) == []  # no role known: cannot be judged
    system.devices[HAND].present = True
    assert replaced_parts(system, roles) == []
