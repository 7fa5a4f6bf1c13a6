"""A plan's steps in plain words for a prosthetist: which link, why, and how similar.

The engine's plan (``engine/plan.py``) speaks the engineer's language: rule keys, channel
references, profile codes, similarity scores. The plan panel, the events list and the
fitting report show these words instead and keep the engineer's text (the engine's reason,
the score's breakdown) one hover away.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.model.refs import ChannelRef, DeviceKey

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Action, Plan, Refusal, Rule
    from pdcp_studio.engine.similarity import Similarity
    from pdcp_studio.model.system import System

#: ``profile_name(code) -> str``: what a profile code carries, by the profile tree's names.
ProfileName = Callable[[int], str]

_CTX = "PlanWords"

#: Engine mode → why the plan ran, in words.
MODE_WORDS = {
    "duty-cycle": QT_TRANSLATE_NOOP("PlanWords", "a part was replaced while the prosthesis "
                                                 "was running"),
    "startup": QT_TRANSLATE_NOOP("PlanWords", "the prosthesis started up"),
    "autoconfigure": QT_TRANSLATE_NOOP("PlanWords", "automatic set-up"),
    "replacements": QT_TRANSLATE_NOOP("PlanWords", "looking for replacements for missing "
                                                   "parts"),
    "implement": QT_TRANSLATE_NOOP("PlanWords", "putting the stored set-up in place"),
    "enforce": QT_TRANSLATE_NOOP("PlanWords", "making sure inputs that need a source for "
                                              "themselves have it alone"),
    "clear": QT_TRANSLATE_NOOP("PlanWords", "removing every link"),
    "manual": QT_TRANSLATE_NOOP("PlanWords", "a change made by hand"),
}

#: Engine rule (``Rule.value``) → why this step, in words.
RULE_WORDS = {
    "stored": QT_TRANSLATE_NOOP("PlanWords", "it is in the stored set-up"),
    "retrieved": QT_TRANSLATE_NOOP("PlanWords", "the devices remembered it"),
    "replacement": QT_TRANSLATE_NOOP("PlanWords", "it replaces a part that is missing"),
    "terminal": QT_TRANSLATE_NOOP("PlanWords", "it drives a part of the prosthesis"),
    "required": QT_TRANSLATE_NOOP("PlanWords", "another channel needs it"),
    "desired": QT_TRANSLATE_NOOP("PlanWords", "another channel works better with it"),
    "sole_access": QT_TRANSLATE_NOOP("PlanWords", "an input needs its source for itself"),
    "clear": QT_TRANSLATE_NOOP("PlanWords", "all links are removed"),
    "not_stored": QT_TRANSLATE_NOOP("PlanWords", "it is not in the stored set-up"),
    "replaced": QT_TRANSLATE_NOOP("PlanWords", "one of its parts is missing; a "
                                               "replacement takes its place"),
    "superseded": QT_TRANSLATE_NOOP("PlanWords", "the part sending to it is missing; a "
                                                 "replacement takes its place"),
}

#: Refusal kind (``Refusal.value``) → why a step was not taken, in words.
REFUSAL_WORDS = {
    "sole_access": QT_TRANSLATE_NOOP("PlanWords", "that output already feeds an input that "
                                                  "needs it for itself"),
    "input_taken": QT_TRANSLATE_NOOP("PlanWords", "that input already has a source"),
    "no_candidate": QT_TRANSLATE_NOOP("PlanWords", "no similar free channel was found"),
    "rolled_back": QT_TRANSLATE_NOOP("PlanWords", "undone: a channel it needs could not be "
                                                  "connected"),
    "already_tried": QT_TRANSLATE_NOOP("PlanWords", "already tried and refused"),
    "missing": QT_TRANSLATE_NOOP("PlanWords", "both of its parts are missing"),
    "not_input": QT_TRANSLATE_NOOP("PlanWords", "the device's description names a channel "
                                                "that is not an input"),
}


def tr(text: object) -> str:
    return translate(_CTX, str(text))


def mode_words(mode: str) -> str:
    text = MODE_WORDS.get(mode)
    return tr(text) if text else mode


def rule_words(rule: Rule | str) -> str:
    value = getattr(rule, "value", rule)
    text = RULE_WORDS.get(str(value))
    return tr(text) if text else str(getattr(rule, "label", value))


def refusal_words(kind: Refusal | str) -> str:
    value = getattr(kind, "value", kind)
    text = REFUSAL_WORDS.get(str(value))
    return tr(text) if text else str(value)


def device_words(system: System | None, key: DeviceKey) -> str:
    """The device's product name from the catalogue (its own name if it has one)."""
    from pdcp_studio.app.words.part_names import part_name

    return part_name(system, key)


def channel_words(system: System | None, ref: ChannelRef, profile_name: str = "") -> str:
    """``Multi-grip hand with wrist rotator, Power grip``: the channel's one name
    (``model/names.py``: its part, and its descriptor, else what it carries
    (``profile_name``), else "channel N")."""
    from pdcp_studio.app.words.part_names import channel_name

    return channel_name(system, ref, profile_name)


def link_words(system: System | None, output: ChannelRef, input_: ChannelRef,
               names: dict[ChannelRef, str] | None = None) -> str:
    names = names or {}
    return (f"{channel_words(system, output, names.get(output, ''))} → "
            f"{channel_words(system, input_, names.get(input_, ''))}")


def part_words(old: DeviceKey, new: DeviceKey) -> str:
    """How the new part relates to the one it replaces, from their identities."""
    if old == new:
        return tr("the same part")
    if (old.vid, old.pid) == (new.vid, new.pid):
        return tr("same product, other serial number")
    if old.vid == new.vid:
        return tr("same maker, another product")
    return tr("another maker's product")


def signal_words(similarity: Similarity | None, levels: int = 0) -> str:
    """How alike two channels' signals are (the similarity score in words).

    ``levels``: how many levels the profile compared with has (0 if unknown)."""
    if similarity is None:
        return ""
    depth = similarity.profile_depth
    same_form = similarity.control_mode and similarity.data_type and similarity.byte_size
    if levels and depth >= levels:
        kind = tr("same kind of signal")
    elif depth:
        kind = (tr("similar signal ({depth} of {levels} levels alike)").format(
            depth=depth, levels=levels) if levels else
            count("PlanWords", "similar signal (%n level(s) alike)", depth))
    else:
        kind = tr("another kind of signal")
    if same_form:
        return tr("{kind}, same form").format(kind=kind)
    differs = [name for flag, name in (
        (similarity.control_mode, tr("control mode")),
        (similarity.data_type, tr("value type")),
        (similarity.byte_size, tr("value size"))) if not flag]
    return tr("{kind}; other {what}").format(kind=kind, what=", ".join(differs))


def similarity_words(action: Action, plan: Plan) -> str:
    """How similar a step's two ends are; for a replacement, how similar the new part and
    channel are to the missing one (``same product, other serial number; same kind of
    signal, same form``)."""
    from pdcp_studio.model import profile as prof

    sim = action.similarity
    if sim is None:
        return ""
    cause = action.cause
    # A replacement's cause is the missing channel: the new one is compared with it.
    missing = (cause if action.rule.value == "replacement" and isinstance(cause, ChannelRef)
               else None)
    facts = plan.channels.get(missing if missing is not None else action.link.input)
    levels = prof.depth(facts.profile) if facts is not None else 0
    signal = signal_words(sim, levels)
    if missing is None:
        return signal
    was_input = any(lk.input == missing for lk in plan.links_before)
    new = action.link.input if was_input else action.link.output
    return f"{part_words(missing.device, new.device)}; {signal}"


def engineer_detail(action: Action) -> str:
    """The engine's own words for a step (for a tooltip): reason, rule and score."""
    parts = [f"{action.rule.value}: {action.reason}"]
    if action.similarity is not None:
        parts.append(f"similarity {action.similarity.describe()}")
    return "\n".join(parts)


def plan_channel_words(system: System | None, plan: Plan | None, ref: ChannelRef,
                       profile_name: ProfileName | None = None) -> str:
    """A channel of a plan in words: device, channel, what it carries; (missing) if gone.
    ``profile_name(code) -> str`` names what it carries (a hex code is left out)."""
    facts = plan.channels.get(ref) if plan is not None else None
    name = profile_name(facts.profile) if facts is not None and profile_name else ""
    if name.startswith("0x"):
        name = ""
    text = channel_words(system, ref, name)
    if facts is not None and not facts.present:
        text += tr(" (missing)")
    return text


def step_words(system: System | None, plan: Plan, action: Action,
               profile_name: ProfileName | None = None) -> str:
    """One plan step as the graph's tooltip on its dashed link says it: what the plan
    does, why, and how similar (the plan table's words; the engine's are in its detail)."""
    add = getattr(action.op, "value", action.op) == "add"
    link = (f"{plan_channel_words(system, plan, action.link.output, profile_name)} → "
            f"{plan_channel_words(system, plan, action.link.input, profile_name)}")
    lines = [(tr("The plan adds this link:") if add else tr("The plan removes this link:")),
             link, tr("Why: {0}").format(rule_words(action.rule))]
    similar = similarity_words(action, plan)
    if similar:
        lines.append(tr("How similar: {0}").format(similar))
    return "\n".join(lines)
