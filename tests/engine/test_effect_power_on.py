"""The next power-on predicted from the parts as they power on (issue 26, point 2).

Found by tests/bus/test_effect_property.py against the arbitrator's real start-up: the parts
come up unlinked and keep only their stored source fields, so start-up makes every link again
from nothing. A link the live bus keeps but start-up would not make from nothing (a second
input with sole access on one output) must be predicted to go.
"""

from __future__ import annotations

from pdcp_studio.bus.sim.rigs import resolve_prosthesis
from pdcp_studio.engine.effect import effect_of, predict_power_on
from pdcp_studio.engine.plan import set_links
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link

JOYSTICK = ChannelRef(2, 2, 4, 1)
LEDS_X = ChannelRef(2, 2, 5, 1)
LEDS_Y = ChannelRef(2, 2, 5, 2)  # type 0x5200: sole access


def _thesis_test1(links):
    system = resolve_prosthesis("thesis-test1").load()
    set_links(system, links)
    return system


def test_links_start_up_makes_again_are_predicted_to_stay():
    system = _thesis_test1([Link(JOYSTICK, LEDS_X)])
    po = predict_power_on(system, ConfigCollection([]), autoconfigure=True)
    assert (po.links_added, po.links_removed) == ([], [])
    assert po.configuration == "retrieved"


def test_a_second_sole_access_input_on_one_output_is_predicted_to_go():
    system = _thesis_test1([Link(JOYSTICK, LEDS_X), Link(JOYSTICK, LEDS_Y)])
    assert system.channel(LEDS_Y).sole_access
    po = predict_power_on(system, ConfigCollection([]), autoconfigure=True)
    assert po.links_removed == [Link(JOYSTICK, LEDS_Y)]
    assert po.links_added == []


def test_the_effect_of_adding_it_says_start_up_undoes_it():
    system = _thesis_test1([Link(JOYSTICK, LEDS_X)])
    effect = effect_of(system, links_after=[Link(JOYSTICK, LEDS_X), Link(JOYSTICK, LEDS_Y)])
    assert effect.links_added == [Link(JOYSTICK, LEDS_Y)]
    assert effect.next_power_on.links_removed == [Link(JOYSTICK, LEDS_Y)]
    assert effect.next_power_on.reverts
    assert any("is removed" in line for line in effect.power_on_lines())
