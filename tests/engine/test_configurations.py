"""Several stored configurations (thesis B.2.1 case 4): a patient with two terminal devices.

The arbitrator stores one configuration per terminal device (a hand, an elbow). At start-up
it must pick the one that fits the hardware that is present — most links with both ends
present, then fewest missing channels — and the plan must say which and why.
"""

from __future__ import annotations

import pytest

from pdcp_studio.engine import (
    choose_configuration,
    configuration_from_system,
    plan_autoconfigure,
    plan_replacements,
    plan_startup,
    resolve_configuration,
)
from pdcp_studio.errors import EngineError
from pdcp_studio.model import ConfigCollection, StoredChannel, StoredConfiguration, StoredLink
from tests.engine.engine_builders import L, dev, inp, out, ref, system

HAND, ELBOW = 30, 31


def _prosthesis(terminal: int):
    """EMG sensor SN10 and control unit SN20, with the hand or the elbow plugged in."""
    return system(
        dev(10, out(1, 0x4220), out(2, 0x4240)),
        dev(20, inp(1, 0x4220, sole=True), inp(2, 0x4240, sole=True),
            out(3, 0x2220, req=[1, 2]), out(4, 0x2400, req=[1, 2])),
        dev(HAND, inp(1, 0x2220, sole=True, terminal=True), present=terminal == HAND),
        dev(ELBOW, inp(1, 0x2400, sole=True, terminal=True), present=terminal == ELBOW),
    )


def _stored_for(terminal: int, index: int) -> StoredConfiguration:
    s = _prosthesis(terminal)
    s.devices[ref(terminal, 1).device].present = True
    plan_autoconfigure(s).apply(s)
    cfg = configuration_from_system(s)
    cfg.index = index
    return cfg


@pytest.fixture
def collection() -> ConfigCollection:
    return ConfigCollection([_stored_for(HAND, 1), _stored_for(ELBOW, 2)])


def test_each_stored_configuration_is_for_one_terminal_device(collection):
    hand, elbow = collection.configurations
    assert L(20, 3, HAND, 1) in [L(*sl.output.ref[2:], *sl.input.ref[2:])
                                 for sl in hand.links]
    assert {sl.input.serial for sl in elbow.links} == {20, ELBOW}


@pytest.mark.parametrize(("present", "index"), [(HAND, 1), (ELBOW, 2)])
def test_the_configuration_of_the_present_terminal_device_is_chosen(collection, present, index):
    s = _prosthesis(present)
    cfg, why = choose_configuration(s, collection)
    assert cfg.index == index
    assert why.startswith(f"chose configuration {index}: 3 of 3 links with both ends present, "
                          "0 missing channel(s) — the best fit of 2")
    other = 3 - index
    assert f"configuration {other}: 2 of 3 links with both ends present, 1 missing" in why


def test_startup_says_which_configuration_and_why(collection):
    s = _prosthesis(ELBOW)
    plan = plan_startup(s, collection)
    assert plan.configuration.index == 2
    assert plan.final_links == [L(10, 1, 20, 1), L(10, 2, 20, 2), L(20, 4, ELBOW, 1)]
    doc = plan.to_json()["configuration"]
    assert (doc["index"], doc["source"]) == (2, "stored")
    assert "most links with both ends present, then fewest missing channels" in doc["reason"]
    assert "Configuration (stored): chose configuration 2" in plan.to_text()


def test_a_tie_on_present_links_goes_to_fewer_missing_channels():
    s = _prosthesis(HAND)
    hand_links = _stored_for(HAND, 1).links
    to_elbow = _stored_for(ELBOW, 0).links[2]  # SN20.O4 → elbow (missing)
    ghost = StoredChannel(9, 2, 2, 99, 0x5000, 0x2400)  # an output nobody has
    # Both keep the hand's three links; configuration 2 names one missing channel (the
    # elbow), configuration 3 two (the elbow and the ghost output).
    one_missing = StoredConfiguration(2, [*hand_links, to_elbow])
    two_missing = StoredConfiguration(3, [*hand_links, to_elbow,
                                          StoredLink(to_elbow.input, ghost)])
    cfg, why = choose_configuration(s, ConfigCollection([two_missing, one_missing]))
    assert cfg.index == 2, why
    assert why.startswith("chose configuration 2: 3 of 4 links with both ends present, "
                          "1 missing channel(s)")
    assert "configuration 3: 3 of 5 links with both ends present, 2 missing channel(s)" in why


def test_equal_fits_go_to_the_first_stored(collection):
    s = _prosthesis(HAND)
    s.devices[ref(HAND, 1).device].present = False
    cfg, _ = choose_configuration(s, collection)  # both: 2 links present, 1 missing
    assert cfg.index == 1


def test_replacements_use_the_chosen_configuration_too(collection):
    plan = plan_replacements(_prosthesis(ELBOW), collection)
    assert plan.configuration.index == 2
    assert L(20, 4, ELBOW, 1) in plan.final_links


def test_an_empty_collection_is_refused():
    with pytest.raises(EngineError, match="no configuration"):
        choose_configuration(_prosthesis(HAND), ConfigCollection([]))
    assert resolve_configuration(_prosthesis(HAND), ConfigCollection([]))[0] is None
