"""Plans as data: ordered actions with rules and similarity, apply, diff, text and JSON."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.engine import (
    Op,
    Rule,
    plan_autoconfigure,
    plan_clear,
    plan_enforce,
    plan_for,
    plan_startup,
)
from pdcp_studio.errors import EngineError
from pdcp_studio.model import NO_SOURCE, ProfileTree
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.storage import system_file
from tests.engine.engine_builders import ROOT, L, dev, inp, load, out, ref, shuffled, system

ROOT_PROFILES = ROOT / "resources" / "profiles" / "thesis-tests.json"


def _rig():
    s = load("appendix-d")
    s.clear_links()
    return s


def test_plan_never_changes_the_system_it_reads():
    s = _rig()
    before = system_file.dumps(s)
    plan_autoconfigure(s)
    plan_startup(s, None)
    assert system_file.dumps(s) == before


def test_actions_carry_rule_similarity_breakdown_and_cause():
    plan = plan_autoconfigure(_rig())
    a = plan.actions[1]
    assert (a.op, a.rule, a.depth) == (Op.ADD, Rule.REQUIRED, 1)
    assert a.similarity.describe() == (
        "23 = profile 2 levels (16) + control mode (4) + data type (2) + byte size (1)")
    assert a.reason == "required by 2/2/5#3 (0x1100): most similar free output"


def test_apply_makes_the_links_and_the_redundant_storage():
    s = _rig()
    plan = plan_autoconfigure(s)
    plan.apply(s)
    assert s.links == plan.final_links
    src = s.channel(ref(5, 2)).source
    assert (src.ref, src.type, src.profile) == (ref(4, 1), 0x5000, 0x2120)
    assert s.channel(ref(5, 2)).data_enabled and s.channel(ref(4, 1)).data_enabled
    assert not s.channel(ref(5, 4)).data_enabled  # fader A feeds nothing

    plan_clear(s).apply(s)
    assert s.links == []
    assert s.channel(ref(5, 2)).source == NO_SOURCE
    assert not s.channel(ref(4, 1)).data_enabled


def test_apply_refuses_a_plan_made_for_another_state_and_changes_nothing():
    s = _rig()
    plan = plan_autoconfigure(s)
    s.add_link(L(4, 1, 5, 2))  # the system moved on since the plan was made
    with pytest.raises(EngineError, match="action 2"):
        plan.apply(s)
    assert s.links == [L(4, 1, 5, 2)]


def test_diff_against_the_current_links():
    s = load("appendix-d")
    plan = plan_clear(s)
    add, remove = plan.diff(s)
    assert add == [] and remove == s.links
    add, remove = plan_autoconfigure(_rig()).diff(s)
    assert add == [] and remove == []  # appendix D already has exactly those links


def test_json_is_the_contract_document():
    plan = plan_autoconfigure(_rig())
    doc = json.loads(json.dumps(plan.to_json()))
    assert doc["mode"] == "autoconfigure"
    first = doc["actions"][0]
    assert {k: first[k] for k in ("op", "output", "input", "similarity", "reason")} == {
        "op": "add",
        "output": {"vid": 2, "pid": 2, "serial": 5, "index": 3},
        "input": {"vid": 2, "pid": 2, "serial": 6, "index": 1},
        "similarity": 23,
        "reason": "terminal channel 0x1110: most similar free output",
    }
    keys = [(lk["output"]["serial"], lk["output"]["index"], lk["input"]["serial"],
             lk["input"]["index"]) for lk in doc["links"]]
    assert keys == [(4, 1, 5, 2), (5, 3, 6, 1), (5, 5, 6, 2)]  # sorted by output, then input


def test_json_lists_rejections_and_rollbacks():
    s = system(dev(4, out(1, 0x2100)),
               dev(5, out(1, 0x1100, req=[2, 3]), inp(2, 0x2100), inp(3, 0x3100)),
               dev(6, inp(1, 0x1100, terminal=True)))
    doc = plan_autoconfigure(s).to_json()
    assert doc["actions"] == [] and doc["links"] == []
    kinds = [r["kind"] for r in doc["rejections"]]
    assert kinds == ["no_candidate", "rolled_back"]
    assert len(doc["rejections"][1]["rolled_back"]) == 2


def test_text_reads_as_an_explanation():
    tree = ProfileTree.from_json(json.loads(ROOT_PROFILES.read_text()))
    text = plan_autoconfigure(_rig()).to_text(tree)
    assert text.startswith("Plan: autoconfigure — add 3, remove 0 (0 links before, 3 after)")
    assert "[terminal] terminal channel 0x1110: most similar free output" in text
    assert "[required] required by 2/2/5#3 (0x1100)" in text
    assert "similarity 31 = profile 3 levels (24)" in text
    assert "“Bar graph LEDs”" in text
    assert "Bar Graph" in text  # the profile's name from the tree
    assert "Links after the plan (3):" in text


def test_text_shows_refusals_and_what_was_rolled_back():
    s = system(dev(4, out(1, 0x2100)),
               dev(5, out(1, 0x1100, req=[2, 3]), inp(2, 0x2100), inp(3, 0x3100)),
               dev(6, inp(1, 0x1100, terminal=True)))
    text = plan_autoconfigure(s).to_text()
    assert "Actions: none" in text
    assert "Tried and refused:" in text
    assert "[rolled_back]" in text and "rolled back: 2/2/5#1 → 2/2/6#1, 2/2/4#1 → 2/2/5#2" in text


@pytest.mark.parametrize("mode", ["autoconfigure", "startup", "replacements", "enforce",
                                  "clear", "duty-cycle"])
@pytest.mark.parametrize("name", ["appendix-d", "thesis-test1", "thesis-test4", "transradial"])
def test_same_plan_whatever_order_devices_and_channels_are_listed_in(mode, name):
    s = load(name)
    if mode in ("autoconfigure", "startup"):
        s.clear_links()
    want = plan_for(mode, s).to_json()
    for seed in range(3):
        assert plan_for(mode, shuffled(s, seed)).to_json() == want
        assert plan_for(mode, shuffled(s, seed)).to_text() == plan_for(mode, s).to_text()


def test_enforce_keeps_one_sole_access_input_per_output():
    s = system(dev(4, out(1, 0x1000)),
               dev(6, inp(1, 0x1200, sole=True), inp(2, 0x1100, sole=True, terminal=True),
                   inp(3, 0x1000, sole=True), inp(4, 0x1000)),
               links=[L(4, 1, 6, 1), L(4, 1, 6, 2), L(4, 1, 6, 3), L(4, 1, 6, 4)])
    plan = plan_enforce(s)
    assert [(a.op, a.link, a.rule) for a in plan.actions] == [
        (Op.REMOVE, L(4, 1, 6, 1), Rule.SOLE_ACCESS), (Op.REMOVE, L(4, 1, 6, 3), Rule.SOLE_ACCESS)]
    # The terminal channel is kept; the input without the flag was never in conflict.
    assert plan.final_links == [L(4, 1, 6, 2), L(4, 1, 6, 4)]


def test_clear_removes_every_link():
    plan = plan_clear(load("appendix-d"))
    assert [a.op for a in plan.actions] == [Op.REMOVE] * 3
    assert {a.rule for a in plan.actions} == {Rule.CLEAR}
    assert plan.final_links == []


def test_unknown_mode_is_an_engine_error():
    with pytest.raises(EngineError, match="unknown mode"):
        plan_for("reboot", _rig())


def test_implement_without_a_configuration_implements_the_systems_own_links():
    # Appendix D without SN4.O1 → SN5.I2: intelligently connecting the terminal link
    # SN5.O3 → SN6.I1 brings back the input its output requires.
    s = load("appendix-d")
    full = s.links
    s.remove_link(full[0])
    plan = plan_for("implement", s, None)
    assert plan.configuration_source == "system"
    assert [a.link for a in plan.actions] == [full[0]]
    assert plan.final_links == full


def test_an_empty_stored_collection_is_nothing_to_implement_not_an_error():
    rig = _rig()
    for mode in ("implement", "replacements"):
        plan = plan_for(mode, rig, ConfigCollection([]))
        assert plan.actions == [] and plan.final_links == rig.links
        assert "holds no configuration" in plan.configuration_reason
