"""The thesis's five hardware tests (chapter 6) and the appendix D rig, as scenarios.

Each test follows the thesis's description step by step on the shipped systems
(``resources/systems/thesis-test1..5.json``, ``appendix-d.json``): plan, apply, change the
hardware, plan again, and compare with the final configuration the thesis reports.
"""

from __future__ import annotations

from pdcp_studio.engine import (
    Rule,
    configuration_from_system,
    plan_autoconfigure,
    plan_duty_cycle,
    plan_replacements,
    plan_startup,
    retrieve_configuration,
)
from pdcp_studio.model import Channel, ConfigCollection, Direction, System
from pdcp_studio.storage import config_codec
from tests.engine.engine_builders import L, load, ref

#: Appendix D's links, which autoconfigure must reproduce exactly.
APPENDIX_D = [L(4, 1, 5, 2), L(5, 3, 6, 1), L(5, 5, 6, 2)]


def _unplug(system: System, serial: int) -> None:
    system.devices[ref(serial, 1).device].present = False


def _plug(system: System, serial: int) -> None:
    system.devices[ref(serial, 1).device].present = True


def _power_cycle(system: System) -> None:
    """A reset: the arbitrator forgets every link; devices keep their stored source fields."""
    system.clear_links()


# -- appendix D -------------------------------------------------------------------------
def test_appendix_d_autoconfigure_gives_exactly_the_printed_links():
    s = load("appendix-d")
    s.clear_links()
    plan = plan_autoconfigure(s)
    assert plan.final_links == APPENDIX_D
    # Worked through as the reference says: SN6.I1 first (terminal profile 0x1110 < 0x1220);
    # SN5.O3 scores 23 against it; its required input 2 then takes SN4.O1 (23); SN6.I2 last.
    steps = [(a.link, a.rule, a.similarity.total) for a in plan.actions]
    assert steps == [(L(5, 3, 6, 1), Rule.TERMINAL, 23),
                     (L(4, 1, 5, 2), Rule.REQUIRED, 23),
                     (L(5, 5, 6, 2), Rule.TERMINAL, 31)]
    assert plan.actions[1].cause == ref(5, 3)  # required by the bar-graph output


def test_appendix_d_push_button_stays_unlinked_because_fader_a_feeds_nothing():
    s = load("appendix-d")
    s.clear_links()
    plan = plan_autoconfigure(s)
    linked_inputs = {lk.input for lk in plan.final_links}
    assert ref(5, 1) not in linked_inputs  # SN5.I1 is required only by output 4
    assert all(lk.output != ref(5, 4) for lk in plan.final_links)


def test_appendix_d_as_printed_is_fully_configured_already():
    plan = plan_autoconfigure(load("appendix-d"))
    assert plan.is_empty()
    assert plan.final_links == APPENDIX_D


# -- test 1: replacement of a missing input ------------------------------------------------
def test_thesis_test1_missing_input_is_replaced_by_device_3():
    s = load("thesis-test1")  # device 3 (SN6) not yet plugged in
    first = plan_autoconfigure(s)
    assert first.final_links == [L(4, 1, 5, 1)]  # D1's and D2's channels connected
    first.apply(s)
    stored = configuration_from_system(s)

    _unplug(s, 5)
    _plug(s, 6)  # device 2 replaced by device 3
    plan = plan_startup(s, ConfigCollection([stored]))
    assert plan.final_links == [L(4, 1, 6, 1)]  # the thesis's final configuration
    (added,) = plan.added
    assert added.rule is Rule.REPLACEMENT
    assert added.cause == ref(5, 1)  # it stands in for the missing input
    # The link to the missing input is removed, so the input has one live source only.
    assert [a.link for a in plan.removed] == [L(4, 1, 5, 1)]


def test_thesis_test1_duty_cycle_repairs_the_same_way_while_running():
    s = load("thesis-test1")
    plan_autoconfigure(s).apply(s)
    before = {r for r, _ in s.channels() if s.is_present(r)}
    _unplug(s, 5)
    _plug(s, 6)
    plan = plan_duty_cycle(s, before)
    assert plan.final_links == [L(4, 1, 6, 1)]


# -- test 2: autoconfigure with no configuration ------------------------------------------
def test_thesis_test2_autoconfigure_from_nothing():
    s = load("thesis-test2")
    plan = plan_startup(s, None)  # powered on without any configuration
    assert plan.configuration_source == "retrieved"
    assert plan.configuration is not None and plan.configuration.links == []
    assert plan.final_links == APPENDIX_D
    assert {a.rule for a in plan.actions} == {Rule.TERMINAL, Rule.REQUIRED}


def test_thesis_test2_as_the_reference_table_lists_it():
    """Reference §4 lists device 1 with two outputs (O1 0x2120, O2 0x2110); the shipped rig
    follows appendix D (one output). With O2 present, SN5.I2 takes the exact match O2."""
    s = load("thesis-test2")
    s.devices[ref(4, 1).device].add_channel(Channel(2, Direction.OUTPUT, 0x5000, 0x2110))
    plan = plan_autoconfigure(s)
    assert plan.final_links == [L(4, 2, 5, 2), L(5, 3, 6, 1), L(5, 5, 6, 2)]
    assert plan.actions[1].similarity.total == 31


# -- test 3: recall the stored configuration -------------------------------------------------
def test_thesis_test3_stored_configuration_is_recalled_after_a_reset(tmp_path):
    s = load("thesis-test3")
    plan_autoconfigure(s).apply(s)
    before = s.links
    saved = tmp_path / "arbitrator.pdcfg"
    config_codec.save_path(ConfigCollection([configuration_from_system(s)]), saved)

    _power_cycle(s)
    plan = plan_startup(s, config_codec.load_path(saved))
    assert plan.configuration_source == "stored"
    assert plan.final_links == before
    assert {a.rule for a in plan.actions} <= {Rule.STORED, Rule.REQUIRED, Rule.DESIRED}


# -- test 4: replacement of a missing output ---------------------------------------------------
def test_thesis_test4_missing_output_is_replaced_by_device_2():
    s = load("thesis-test4")  # device 2 (SN5) not yet plugged in
    first = plan_autoconfigure(s)
    assert first.final_links == [L(4, 1, 6, 2)]  # D1's channel and D3's channel no. 2
    first.apply(s)
    stored = ConfigCollection([configuration_from_system(s)])

    _unplug(s, 4)
    _plug(s, 5)  # device 1 replaced by device 2
    plan = plan_replacements(s, stored)
    assert plan.final_links == [L(5, 2, 6, 2)]
    added = plan.added[-1]
    # 0x2120 shares two components with the missing 0x2110 (23); 0x2200 only one (15).
    assert (added.link, added.rule, added.similarity.total) == (L(5, 2, 6, 2),
                                                               Rule.REPLACEMENT, 23)


# -- test 5: a replaced arbitrator rebuilds from the devices -----------------------------------
def test_thesis_test5_configuration_rebuilt_from_the_devices_source_fields():
    s = load("thesis-test5")
    plan_autoconfigure(s).apply(s)
    before = s.links
    assert s.channel(ref(6, 1)).source.ref == ref(5, 3)  # redundant storage (§4.3.2)

    _power_cycle(s)  # a new arbitrator: nothing stored centrally
    retrieved = retrieve_configuration(s)
    assert [(sl.output.ref, sl.input.ref) for sl in retrieved.links] == [
        (lk.output, lk.input) for lk in sorted(before, key=lambda lk: lk.input)]
    plan = plan_startup(s, None)
    assert plan.configuration_source == "retrieved"
    assert plan.final_links == before
    assert all(a.rule is Rule.RETRIEVED for a in plan.actions)
