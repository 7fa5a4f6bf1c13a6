"""The one effect of a change (engine/effect.py): words, codes only in the technical detail,
the next power-on predicted by the engine's start-up, and a JSON form that reads back the same."""

from __future__ import annotations

import re
from dataclasses import dataclass

from pdcp_studio.engine import configuration_from_system
from pdcp_studio.engine.effect import TEMPLATES, Effect, effect_of
from pdcp_studio.model import param_names
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.storage.profile_trees import load_profile_trees, tree_for
from tests.engine.engine_builders import load

HEX = re.compile(r"0x[0-9A-Fa-f]+|\b\d+/\d+/\d+\b|[0-9a-f]{8,}")
HAND = DeviceKey(2641, 769, 301)


@dataclass(frozen=True)
class Write:
    device: DeviceKey
    param: int
    channel: int
    value: bytes


def linked():
    """The transradial prosthesis as the simulator sets it up: autoconfigured."""
    from pdcp_studio.engine.modes import plan_autoconfigure

    system = load("transradial")
    plan_autoconfigure(system).apply(system)
    assert len(system.links) == 5
    return system


def _names(system):
    return Names(system, profiles=tree_for(load_profile_trees(user_dir=False), system))


def _writes(system, key, channel, **named):
    obj = system.device(key).channels[channel] if channel else system.device(key)
    return [Write(key, p, channel, v)
            for p, v in param_names.writes_for(obj, {k.replace("_", "-"): v
                                                    for k, v in named.items()})]


def test_a_type_change_reads_as_its_control_mode_with_codes_only_in_the_detail():
    system = linked()
    writes = _writes(system, HAND, 1, type="0x9700")
    effect = effect_of(system, links_after=system.links, parameters=writes,
                       names=_names(system))
    [change] = effect.parameters
    assert (change.name, change.before, change.after) == ("type", "0x9300", "0x9700")
    words = effect.lines()
    assert any("control mode position → velocity" in ln for ln in words)
    assert not [ln for ln in words + effect.power_on_lines() if HEX.search(ln)], words
    assert any("0x9300 → 0x9700" in ln for ln in effect.technical())


def test_a_profile_change_is_named_from_the_profile_tree():
    system = linked()
    writes = _writes(system, HAND, 1, profile="0x2240")
    effect = effect_of(system, links_after=system.links, parameters=writes,
                       names=_names(system))
    text = effect.parameter_text(effect.parameters[0])
    assert "0x22" not in text and "Pinch" in text, text


def test_descriptor_flag_and_interval_in_words():
    system = linked()
    writes = (_writes(system, HAND, 1, descriptor="Power grip (fast)", data_transfer="off")
              + _writes(system, HAND, 0, beacon_interval="250"))
    effect = effect_of(system, links_after=system.links, parameters=writes)
    texts = [effect.parameter_text(p) for p in effect.parameters]
    assert any("“Power grip” → “Power grip (fast)”" in t for t in texts), texts
    assert any("data transfer on → off" in t for t in texts), texts
    assert any("beacon interval" in t and "→ 250 ms" in t for t in texts), texts


def test_an_unstored_link_removal_comes_back_at_the_next_power_on():
    system = linked()
    stored = ConfigCollection([configuration_from_system(system)])
    gone = system.links[2]
    effect = effect_of(system, links_after=[lk for lk in system.links if lk != gone],
                       config_before=stored, policy_before=False)
    assert effect.links_removed == [gone]
    assert effect.next_power_on.links_added == [gone] and effect.next_power_on.reverts
    assert any("not stored" in ln for ln in effect.power_on_lines())


def test_a_stored_link_removal_with_autoconfigure_off_stays_removed():
    system = linked()
    gone = system.links[2]
    after = system.copy()
    after.remove_link(gone)
    stored = ConfigCollection([configuration_from_system(after)])
    effect = effect_of(system, links_after=after.links, config_after=stored,
                       policy_before=False)
    assert effect.stored_changed
    assert not effect.next_power_on.changes
    assert any("nothing changes" in ln for ln in effect.power_on_lines())


def test_turning_autoconfigure_off_says_which_links_stay():
    system = linked()
    effect = effect_of(system, links_after=system.links, policy_before=True,
                       policy_after=False)
    assert any("removes nothing" in ln and str(len(system.links)) in ln
               for ln in effect.lines())


def test_nothing_to_change_is_said_so():
    system = linked()
    effect = effect_of(system, links_after=system.links)
    assert effect.empty and effect.lines()[0] == "Nothing changes on the prosthesis."


def test_the_json_form_reads_back_to_the_same_words():
    system = linked()
    writes = _writes(system, HAND, 1, type="0x9700")
    effect = effect_of(system, links_after=system.links[1:], parameters=writes,
                       names=_names(system))
    doc, po = effect.to_json(), effect.power_on_json()
    again = Effect.from_json(doc, po)
    assert again.lines() == effect.lines()
    assert again.power_on_lines() == effect.power_on_lines()
    assert doc["parameters"][0]["text"] and doc["text"] == effect.lines()
    assert set(po) >= {"links_added", "links_removed", "text"}


def test_every_template_is_listed_for_translation():
    import pdcp_studio.engine.effect as module

    named = {v for k, v in vars(module).items() if k.startswith("T_")}
    assert named == set(TEMPLATES)


def test_a_translation_reaches_every_word():
    system = linked()
    effect = effect_of(system, links_after=system.links[1:],
                       parameters=_writes(system, HAND, 1, type="0x9700"))
    def shout(text: str) -> str:  # upper case outside the {placeholders}
        return re.sub(r"[^{}]+(?=\{|$)|(?<=\})[^{}]+", lambda m: m.group(0).upper(), text)

    shouted = effect.lines(shout) + effect.power_on_lines(shout)
    assert any("LINK REMOVED" in ln for ln in shouted)
    assert any("CONTROL MODE POSITION → VELOCITY" in ln for ln in shouted), shouted


def test_names_are_the_parts_and_channels_names():
    system = linked()
    effect = effect_of(system, links_after=system.links[1:])
    ref = ChannelRef(*HAND, 1)
    assert effect.name(ref) == Names(system).channel(ref)


def test_turning_autoconfigure_off_lists_the_links_that_stay():
    system = linked()
    effect = effect_of(system, links_after=system.links, policy_before=True,
                       policy_after=False)
    stays = [ln for ln in effect.lines() if ln.strip().startswith("stays:")]
    assert len(stays) == len(system.links)


def test_data_transfer_off_at_a_linked_channel_says_the_link_goes_silent():
    """The truth trial: a linked input with data transfer off stays listed as a link but
    carries nothing; the effect says so."""
    system = linked()
    writes = _writes(system, HAND, 1, data_transfer="off")
    effect = effect_of(system, links_after=system.links, parameters=writes)
    muted = [ln for ln in effect.lines() if "carries no data" in ln]
    assert len(muted) == 1 and "Power grip" in muted[0]
