"""Each **Decision** of reference §2 (the device profile layer), one test each.

Systems are tiny and built inline so that each test shows the one rule it is about.
Serial numbers stand for devices (VID 2, PID 2); ``L(5, 3, 6, 1)`` is SN5.O3 → SN6.I1.
"""

from __future__ import annotations

from pdcp_studio.engine import (
    Refusal,
    Rule,
    configuration_from_system,
    plan_autoconfigure,
    plan_duty_cycle,
    plan_implement,
    plan_replacements,
    plan_startup,
    retrieve_configuration,
)
from pdcp_studio.engine.layer import Connected, ProfileLayer
from pdcp_studio.model import (
    ChannelRef,
    ConfigCollection,
    Direction,
    Link,
    SourceInfo,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from tests.engine.engine_builders import L, dev, inp, out, ref, system


def stored(*links: tuple[Link, int, int, int, int]) -> StoredConfiguration:
    """A configuration from (link, out type, out profile, in type, in profile)."""
    out_ = []
    for n, (lk, ot, op, it, ip) in enumerate(links, 1):
        o, i = lk.output, lk.input
        out_.append(StoredLink(StoredChannel(i.index, i.vid, i.pid, i.serial, it, ip),
                               StoredChannel(o.index, o.vid, o.pid, o.serial, ot, op), n))
    return StoredConfiguration(1, out_)


# -- find_similar_channel (listing 4.8) ----------------------------------------------------
def test_same_device_links_are_not_candidates():
    s = system(dev(5, out(1, 0x1100), inp(2, 0x1100, terminal=True)),
               dev(6, out(1, 0x1200)))
    plan = plan_autoconfigure(s)
    # SN5.O1 matches two components (23) but is on the input's own device.
    assert plan.final_links == [L(6, 1, 5, 2)]


def test_a_candidate_must_share_the_root_component():
    # Identical type (7 points) never links a set-point input to a sensor output.
    s = system(dev(4, out(1, 0x2100)), dev(6, inp(1, 0x1100, terminal=True)))
    plan = plan_autoconfigure(s)
    assert plan.final_links == []
    (rej,) = plan.rejections
    assert rej.kind is Refusal.NO_CANDIDATE and rej.attempt.channel == ref(6, 1)
    assert "root component" in rej.reason


def test_for_a_sole_access_input_an_output_feeding_one_is_not_free():
    s = system(dev(4, out(1, 0x1000)),
               dev(6, inp(1, 0x1000, sole=True, terminal=True, terminal_profile=0x1100),
                   inp(2, 0x1000, sole=True, terminal=True, terminal_profile=0x1200)))
    plan = plan_autoconfigure(s)
    assert plan.final_links == [L(4, 1, 6, 1)]
    assert [r.attempt.channel for r in plan.rejections] == [ref(6, 2)]
    assert "sole-access" in plan.rejections[0].reason


def test_for_an_input_without_the_flag_any_output_is_free():
    s = system(dev(4, out(1, 0x1000)),
               dev(6, inp(1, 0x1000, sole=True, terminal=True, terminal_profile=0x1100),
                   inp(2, 0x1000, terminal=True, terminal_profile=0x1200)))
    assert plan_autoconfigure(s).final_links == [L(4, 1, 6, 1), L(4, 1, 6, 2)]


def test_an_input_candidate_is_free_only_without_a_source():
    # Stored: SN4.O1 → SN9.I1 (missing). SN6.I1 would match better but already has a source.
    s = system(dev(3, out(1, 0x4000)), dev(4, out(1, 0x1100)),
               dev(6, inp(1, 0x1100), inp(2, 0x1000)),
               links=[L(3, 1, 6, 1)])
    cfg = stored((L(4, 1, 9, 1), 0x5000, 0x1100, 0x5000, 0x1100))
    plan = plan_replacements(s, cfg)
    assert [a.link for a in plan.added] == [L(4, 1, 6, 2)]


def test_a_channel_of_a_missing_device_is_never_a_candidate():
    s = system(dev(3, out(1, 0x1110), present=False), dev(4, out(1, 0x1200)),
               dev(6, inp(1, 0x1110, terminal=True)))
    assert plan_autoconfigure(s).final_links == [L(4, 1, 6, 1)]


def test_ties_go_to_the_lower_profile_first():
    # Both outputs match two components and the whole type (23): 0x1110 < 0x1120 wins,
    # although its device comes later.
    s = system(dev(3, out(1, 0x1120)), dev(4, out(1, 0x1110)),
               dev(6, inp(1, 0x1100, terminal=True)))
    assert plan_autoconfigure(s).final_links == [L(4, 1, 6, 1)]


def test_then_ties_go_to_the_lower_vid_pid_serial_index():
    def winner(*devices):
        s = system(*devices, dev(6, inp(1, 0x1100, terminal=True)))
        return plan_autoconfigure(s).final_links[0].output

    assert winner(dev(7, out(1, 0x1100)), dev(3, out(2, 0x1100))) == ref(3, 2)
    assert winner(dev(3, out(2, 0x1100), out(1, 0x1100))) == ref(3, 1)
    assert winner(dev(1, out(1, 0x1100), vid=2, pid=9),
                  dev(9, out(1, 0x1100), vid=2, pid=3)) == ChannelRef(2, 3, 9, 1)
    assert winner(dev(9, out(1, 0x1100), vid=1), dev(1, out(1, 0x1100), vid=2)) == \
        ChannelRef(1, 2, 9, 1)


# -- connect (listing 4.4) ------------------------------------------------------------------
def test_connect_refuses_an_input_that_has_another_source():
    s = system(dev(3, out(1, 0x1000)), dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000)),
               links=[L(3, 1, 6, 1)])
    layer = ProfileLayer(s)
    assert layer.connect(L(4, 1, 6, 1), Rule.STORED, "test") is Connected.REFUSED
    assert layer.plan.rejections[0].kind is Refusal.INPUT_TAKEN
    assert layer.connect(L(3, 1, 6, 1), Rule.STORED, "test") is Connected.EXISTS
    assert layer.plan.actions == []


def test_connect_refuses_a_link_that_violates_sole_access():
    s = system(dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000, sole=True),
                                          inp(2, 0x1000, sole=True), inp(3, 0x1000)),
               links=[L(4, 1, 6, 1)])
    layer = ProfileLayer(s)
    assert layer.connect(L(4, 1, 6, 2), Rule.STORED, "test") is Connected.REFUSED
    assert layer.plan.rejections[0].kind is Refusal.SOLE_ACCESS
    # An input without the flag may share the output.
    assert layer.connect(L(4, 1, 6, 3), Rule.STORED, "test") is Connected.MADE


# -- intelligently_connect (listing 4.5) ------------------------------------------------------
def _sources(serial: int, *profiles: int):
    return dev(serial, *(out(n, p) for n, p in enumerate(profiles, 1)))


def test_required_and_desired_are_taken_in_the_decided_order():
    # The output's required, the input's required, the output's desired, the input's
    # desired — each by ascending channel index.
    s = system(
        dev(5, inp(1, 0x2100), inp(2, 0x2200), inp(3, 0x2300),
            out(9, 0x1000, req=[3, 1], des=[2])),
        dev(6, inp(1, 0x1000, terminal=True, req=[4], des=[5]), inp(4, 0x2400), inp(5, 0x2500)),
        _sources(7, 0x2100, 0x2200, 0x2300, 0x2400, 0x2500),
    )
    plan = plan_autoconfigure(s)
    assert [a.link.input for a in plan.actions] == [
        ref(6, 1), ref(5, 1), ref(5, 3), ref(6, 4), ref(5, 2), ref(6, 5)]
    assert [a.rule for a in plan.actions] == [Rule.TERMINAL, Rule.REQUIRED, Rule.REQUIRED,
                                              Rule.REQUIRED, Rule.DESIRED, Rule.DESIRED]
    assert [a.cause for a in plan.actions[1:]] == [ref(5, 9), ref(5, 9), ref(6, 1), ref(5, 9),
                                                   ref(6, 1)]
    assert all(a.depth == 1 for a in plan.actions[1:])


def test_an_input_that_already_has_a_source_counts_as_connected():
    s = system(dev(5, inp(1, 0x2100), out(9, 0x1000, req=[1])),
               dev(6, inp(1, 0x1000, terminal=True)),
               _sources(7, 0x2100), _sources(8, 0x2100),
               links=[L(8, 1, 5, 1)])
    plan = plan_autoconfigure(s)
    assert [a.link for a in plan.actions] == [L(5, 9, 6, 1)]
    assert plan.rejections == []


def test_mutual_references_terminate():
    # "channels 1 and 2 … reference each other"
    s = system(dev(5, inp(1, 0x1000, terminal=True, req=[2]), inp(2, 0x2000, req=[1])),
               _sources(4, 0x1000, 0x2000))
    plan = plan_autoconfigure(s)
    assert plan.final_links == [L(4, 1, 5, 1), L(4, 2, 5, 2)]


def test_mutual_references_through_two_devices_terminate():
    # SN5.O1 needs SN5.I2, fed by SN6.O1, which needs SN6.I2, fed by SN5.O3, which needs SN5.I2.
    s = system(dev(5, out(1, 0x1000, req=[2]), inp(2, 0x2000), out(3, 0x3000, req=[2])),
               dev(6, out(1, 0x2000, req=[2]), inp(2, 0x3000)),
               dev(7, inp(1, 0x1000, terminal=True)))
    plan = plan_autoconfigure(s)
    assert plan.final_links == [L(5, 1, 7, 1), L(5, 3, 6, 2), L(6, 1, 5, 2)]


def _rollback_rig():
    return system(
        dev(4, out(1, 0x2100)),
        dev(5, out(1, 0x1100, req=[2, 3]), inp(2, 0x2100, sole=True), inp(3, 0x3100)),
        dev(6, inp(1, 0x1100, terminal=True),
            inp(2, 0x1200, terminal=True, terminal_profile=0x1000)),
        dev(7, out(1, 0x4000)), dev(8, inp(1, 0x4000)),
        dev(9, out(1, 0x1200)),
        links=[L(7, 1, 8, 1)],
    )


def test_an_unmet_required_input_rolls_back_exactly_what_the_call_made():
    plan = plan_autoconfigure(_rollback_rig())
    # SN6.I2 (terminal profile 0x1000) came first and stays; the link that was there stays.
    assert plan.final_links == [L(7, 1, 8, 1), L(9, 1, 6, 2)]
    rolled = [r for r in plan.rejections if r.kind is Refusal.ROLLED_BACK]
    assert len(rolled) == 1
    assert rolled[0].attempt.link == L(5, 1, 6, 1)
    assert rolled[0].rolled_back == (L(5, 1, 6, 1), L(4, 1, 5, 2))
    assert "required input 2/2/5#3" in rolled[0].reason
    # Rolled-back links are not actions; what was tried is kept in the rejections.
    assert [a.link for a in plan.actions] == [L(9, 1, 6, 2)]
    kinds = [r.kind for r in plan.rejections]
    assert kinds == [Refusal.NO_CANDIDATE, Refusal.ROLLED_BACK]


def test_an_unmet_desired_input_rolls_back_only_its_own_sub_call():
    s = system(
        dev(4, out(1, 0x2100, req=[2]), inp(2, 0x3100)),
        dev(5, out(1, 0x1100, des=[2]), inp(2, 0x2100)),
        dev(6, inp(1, 0x1100, terminal=True)),
    )
    plan = plan_autoconfigure(s)
    assert plan.final_links == [L(5, 1, 6, 1)]
    rolled = [r for r in plan.rejections if r.kind is Refusal.ROLLED_BACK]
    assert [r.rolled_back for r in rolled] == [(L(4, 1, 5, 2),)]
    assert rolled[0].attempt.rule is Rule.DESIRED


# -- implement_configuration (listing 4.3) -----------------------------------------------------
def test_implement_uses_intelligently_connect_for_terminal_inputs_only():
    s = system(
        _sources(4, 0x2100, 0x2200),
        dev(5, inp(1, 0x2100), inp(2, 0x2200), out(3, 0x1100, req=[2]), out(4, 0x1200, req=[1])),
        dev(6, inp(1, 0x1100, terminal=True)), dev(7, inp(1, 0x1200)),
    )
    cfg = stored((L(5, 3, 6, 1), 0x5000, 0x1100, 0x5300, 0x1100),
                 (L(5, 4, 7, 1), 0x5000, 0x1200, 0x5000, 0x1200))
    plan = plan_implement(s, cfg)
    assert plan.final_links == [L(4, 2, 5, 2), L(5, 3, 6, 1), L(5, 4, 7, 1)]
    # SN7.I1 is not terminal: connect only, so SN5.O4's required input 1 stays unlinked.
    assert ref(5, 1) not in {lk.input for lk in plan.final_links}


# -- find_replacements (listing 4.6) ----------------------------------------------------------
def test_replacements_compare_with_the_stored_type_and_profile_of_the_missing_channel():
    s = system(dev(3, out(1, 0x2200), out(2, 0x2120)), dev(6, inp(1, 0x2110, terminal=True)))
    cfg = stored((L(4, 1, 6, 1), 0x5000, 0x2110, 0x5300, 0x2110))  # SN4 is not in the system
    plan = plan_replacements(s, cfg)
    (a,) = plan.added
    assert a.link == L(3, 2, 6, 1) and a.rule is Rule.REPLACEMENT
    assert "replaces missing output 2/2/4#1" in a.reason


def test_repaired_links_are_connected_most_similar_first():
    # Both missing inputs would be replaced by SN6.I1; the repaired link with the higher
    # input–output similarity (23 > 15) is connected first and wins it.
    s = system(dev(3, out(1, 0x1200)), dev(4, out(1, 0x1100)), dev(6, inp(1, 0x1100)))
    cfg = stored((L(3, 1, 9, 2), 0x5000, 0x1200, 0x5000, 0x1200),
                 (L(4, 1, 9, 1), 0x5000, 0x1100, 0x5000, 0x1100))
    plan = plan_replacements(s, cfg)
    assert [a.link for a in plan.added] == [L(4, 1, 6, 1)]
    taken = [r for r in plan.rejections if r.kind is Refusal.INPUT_TAKEN]
    assert [r.attempt.link for r in taken] == [L(3, 1, 6, 1)]


def test_repaired_links_with_equal_similarity_go_by_output_then_input():
    s = system(dev(3, out(1, 0x1200)), dev(4, out(1, 0x1100)), dev(6, inp(1, 0x1000)))
    cfg = stored((L(4, 1, 9, 1), 0x5000, 0x1100, 0x5000, 0x1100),
                 (L(3, 1, 9, 2), 0x5000, 0x1200, 0x5000, 0x1200))
    plan = plan_replacements(s, cfg)  # both repaired links score 15
    assert [a.link for a in plan.added] == [L(3, 1, 6, 1)]


def test_plan_replacements_first_implements_the_links_whose_ends_are_present():
    s = system(dev(3, out(1, 0x1100), out(2, 0x1200)), dev(6, inp(1, 0x1100), inp(2, 0x1200)))
    cfg = stored((L(3, 1, 6, 1), 0x5000, 0x1100, 0x5000, 0x1100),
                 (L(9, 1, 6, 2), 0x5000, 0x1200, 0x5000, 0x1200))
    plan = plan_replacements(s, cfg)
    assert [(a.link, a.rule) for a in plan.added] == [(L(3, 1, 6, 1), Rule.STORED),
                                                     (L(3, 2, 6, 2), Rule.REPLACEMENT)]
    assert plan.rejections == []  # the broken link is repaired, not refused


# -- autoconfigure (listing 4.7) -----------------------------------------------------------
def test_autoconfigure_serves_lower_terminal_profiles_first():
    s = system(dev(4, out(1, 0x1000)),
               dev(5, inp(1, 0x1000, sole=True, terminal=True, terminal_profile=0x1200)),
               dev(6, inp(1, 0x1000, sole=True, terminal=True, terminal_profile=0x1100)))
    assert plan_autoconfigure(s).final_links == [L(4, 1, 6, 1)]


def test_autoconfigure_ties_go_by_vid_pid_serial_index():
    def first(*devices):
        s = system(dev(4, out(1, 0x1000)), *devices)
        return plan_autoconfigure(s).final_links[0].input

    t = {"sole": True, "terminal": True, "terminal_profile": 0x1100}
    assert first(dev(6, inp(1, 0x1000, **t)), dev(5, inp(2, 0x1000, **t))) == ref(5, 2)
    assert first(dev(6, inp(2, 0x1000, **t), inp(1, 0x1000, **t))) == ref(6, 1)
    assert first(dev(1, inp(1, 0x1000, **t), vid=3), dev(9, inp(1, 0x1000, **t), vid=2)) == \
        ChannelRef(2, 2, 9, 1)


def test_autoconfigure_matches_on_the_channels_own_profile_not_its_terminal_profile():
    # A sensor input on a combined control + terminal device (reference §1).
    s = system(dev(4, out(1, 0x4200), out(2, 0x2200)),
               dev(6, inp(1, 0x4200, terminal=True, terminal_profile=0x2200)))
    assert plan_autoconfigure(s).final_links == [L(4, 1, 6, 1)]


def test_fully_configured_system_gives_an_empty_autoconfigure_plan():
    s = system(dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000, terminal=True)),
               links=[L(4, 1, 6, 1)])
    plan = plan_autoconfigure(s)
    assert plan.is_empty() and plan.rejections == []


# -- start-up (listings 4.1 / 5.1) ----------------------------------------------------------------
def _startup_rig(links):
    return system(dev(3, out(1, 0x1100), out(2, 0x1200), out(3, 0x1300)),
                  dev(6, inp(1, 0x1100), inp(2, 0x1200), inp(3, 0x1300)), links=links)


def test_startup_drops_links_the_stored_configuration_does_not_have_and_keeps_the_rest():
    s = _startup_rig([L(3, 1, 6, 1), L(3, 3, 6, 3)])
    cfg = stored((L(3, 1, 6, 1), 0x5000, 0x1100, 0x5000, 0x1100),
                 (L(3, 2, 6, 2), 0x5000, 0x1200, 0x5000, 0x1200))
    plan = plan_startup(s, cfg)
    assert [(a.op.value, a.link, a.rule) for a in plan.actions] == [
        ("remove", L(3, 3, 6, 3), Rule.NOT_STORED),
        ("add", L(3, 2, 6, 2), Rule.STORED),
    ]  # SN3.O1 → SN6.I1 is in both: kept, not re-made
    assert plan.final_links == [L(3, 1, 6, 1), L(3, 2, 6, 2)]


def test_the_stored_configuration_wins_over_the_devices_own():
    s = _startup_rig([])
    # A device configured in another prosthesis remembers a different source.
    s.channel(ref(6, 1)).source = SourceInfo(2, 2, 3, 3, 0x5000, 0x1300)
    cfg = stored((L(3, 1, 6, 1), 0x5000, 0x1100, 0x5000, 0x1100))
    plan = plan_startup(s, cfg)
    assert plan.configuration_source == "stored"
    assert plan.final_links == [L(3, 1, 6, 1)]


def test_without_a_stored_configuration_startup_retrieves_the_devices_own():
    s = _startup_rig([])
    s.channel(ref(6, 1)).source = SourceInfo(2, 2, 3, 3, 0x5000, 0x1300)
    plan = plan_startup(s, None)
    assert plan.configuration_source == "retrieved"
    assert plan.final_links == [L(3, 3, 6, 1)]
    assert plan.actions[0].rule is Rule.RETRIEVED


def test_retrieve_takes_the_inputs_stored_sources_in_ascending_input_order():
    s = system(dev(6, inp(2, 0x1200), inp(1, 0x1100)), dev(5, inp(1, 0x1300)),
               dev(3, out(1, 0x1100), out(2, 0x1200), out(3, 0x1300)))
    for (serial, index), src in {(6, 2): 2, (5, 1): 3, (6, 1): 1}.items():
        s.channel(ref(serial, index)).source = SourceInfo(2, 2, 3, src, 0x5000, 0x1000 + src)
    cfg = retrieve_configuration(s)
    assert [sl.input.ref for sl in cfg.links] == [ref(5, 1), ref(6, 1), ref(6, 2)]
    assert [sl.output.ref for sl in cfg.links] == [ref(3, 3), ref(3, 1), ref(3, 2)]
    assert cfg.links[0].output.profile == 0x1003  # the source profile the input stored


def test_startup_replaces_missing_channels_then_autoconfigures():
    s = system(dev(3, out(1, 0x1100), present=False), dev(4, out(1, 0x1120), out(2, 0x1200)),
               dev(6, inp(1, 0x1110, terminal=True),
                   inp(2, 0x1200, terminal=True, terminal_profile=0x1200)),
               links=[L(3, 1, 6, 1)])
    cfg = configuration_from_system(s)
    plan = plan_startup(s, ConfigCollection([cfg]))
    rules = [(a.op.value, a.rule) for a in plan.actions]
    assert rules == [("remove", Rule.SUPERSEDED), ("add", Rule.REPLACEMENT),
                     ("add", Rule.TERMINAL)]
    assert plan.final_links == [L(4, 1, 6, 1), L(4, 2, 6, 2)]


# -- duty cycle (listing 4.2) ---------------------------------------------------------------
def test_duty_cycle_does_nothing_when_nothing_changed():
    s = system(dev(4, out(1, 0x1000)), dev(6, inp(1, 0x1000, terminal=True)),
               links=[L(4, 1, 6, 1)])
    present = {r for r, _ in s.channels()}
    plan = plan_duty_cycle(s, present)
    assert plan.is_empty() and plan.notes == []


def test_duty_cycle_replaces_a_channel_that_disappeared():
    s = system(dev(4, out(1, 0x1100)), dev(5, out(1, 0x1200)),
               dev(6, inp(1, 0x1100, terminal=True)), links=[L(4, 1, 6, 1)])
    present = {r for r, _ in s.channels()}
    s.devices[ref(4, 1).device].present = False
    plan = plan_duty_cycle(s, present)
    assert plan.final_links == [L(5, 1, 6, 1)]
    assert plan.actions[-1].rule is Rule.REPLACEMENT
    assert "disappeared" in plan.notes[0]


def test_duty_cycle_autoconfigures_a_new_terminal_channel():
    s = system(dev(4, out(1, 0x1100)), dev(6, inp(1, 0x1100, terminal=True)))
    plan = plan_duty_cycle(s, {ref(4, 1)})
    assert [(a.link, a.rule) for a in plan.actions] == [(L(4, 1, 6, 1), Rule.TERMINAL)]


def test_find_similar_channel_on_the_layer_respects_direction():
    s = system(dev(4, out(1, 0x1100)), dev(6, inp(1, 0x1100)))
    layer = ProfileLayer(s)
    assert layer.find_similar_channel(Direction.INPUT, 0x5000, 0x1100)[0] == ref(6, 1)
    assert layer.find_similar_channel(Direction.OUTPUT, 0x5000, 0x1100)[0] == ref(4, 1)
