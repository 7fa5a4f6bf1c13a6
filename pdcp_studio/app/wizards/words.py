"""The guided tasks' sentences: parts, links, plans and similarity in a prosthetist's words.

The engine's reasons and the preview's lines are the engineer's (channel references,
profile codes, rule names); a wizard shows these sentences instead and keeps the
engineer's text one click away. Everything goes through Qt's translation (context
``Wizards``); nothing here needs a running application.
"""

from __future__ import annotations

from collections.abc import Callable

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words import part_names as names
from pdcp_studio.bus.session.api import ChangePreview
from pdcp_studio.engine import Action, Plan, Rule, Similarity
from pdcp_studio.engine.similarity import MAX_TYPE_SCORE, PROFILE_STEP
from pdcp_studio.model import profile as prof
from pdcp_studio.model.config_diff import ConfigDiff
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device, Link, System

_CTX = "Wizards"


def _t(text: str) -> str:
    return translate(_CTX, text)


def count(text: str, n: int) -> str:
    """``text`` with ``%n`` for ``n`` things: "1 link", "2 links" (Qt's plural forms)."""
    from pdcp_studio.app.words.plural import count as plural

    return plural(_CTX, text, n)


#: ``() -> System | None``: the main window's system while a wizard is open (set by
#: :func:`pdcp_studio.app.wizards.open_wizard`): its parts are named among the graph's, so
#: a fresh scan that no longer sees the hand still calls the spare what the graph calls it.
shown_system: Callable[[], System | None] | None = None


def _shown() -> list[Device]:
    system = shown_system() if shown_system is not None else None
    return list(system.devices.values()) if system is not None else []


def part_names(system: System) -> dict[DeviceKey, str]:
    """Every part's words (:func:`part_words`) at once: one pass, for long lists."""
    return names.part_names(system, _shown())


def part_words(system: System, key: DeviceKey) -> str:
    """The part's one name in every panel (``app/words/part_names.py``): its own name, else its
    product from the device catalogue; two parts that would read alike (a hand and its
    spare) get their serial numbers."""
    return names.part_name(system, key, _shown())


def channel_phrase(system: System, ref: ChannelRef, own: str = "") -> str:
    """``Multi-grip hand (serial 301), Power grip``: the channel's one name (``model/
    names.py``, as every panel says it: its part as :func:`part_words`, then its
    descriptor, "channel N" only where it has none). ``own``: what names a channel no
    longer in ``system`` (a missing part's, as the plan remembers it)."""
    return names.names(system, _shown()).channel(ref, own)


def link_words(system: System, link: Link) -> str:
    return f"{channel_phrase(system, link.output)} → {channel_phrase(system, link.input)}"


def similarity_words(similarity: Similarity | None, wanted_profile: int = 0) -> str:
    """How alike a replacement is to the channel it stands in for, in words and points."""
    if similarity is None:
        return ""
    levels = prof.depth(wanted_profile) if wanted_profile else similarity.profile_depth
    top = max(levels, similarity.profile_depth) * PROFILE_STEP + MAX_TYPE_SCORE
    data = (similarity.control_mode, similarity.data_type, similarity.byte_size)
    if similarity.profile_depth == 0:
        kind = _t("nothing in common in what it does")
    elif similarity.profile_depth >= levels:
        kind = _t("it does the same job")
    else:
        kind = _t("it does a related job ({0} of {1} levels of its kind alike)").format(
            similarity.profile_depth, levels)
    if all(data):
        how = _t("and sends its data the same way")
    elif not any(data):
        how = _t("but sends its data differently")
    else:
        how = _t("and sends its data partly the same way")
    if similarity.profile_depth >= levels and all(data):
        grade = _t("Exact match")
    elif similarity.profile_depth >= max(1, levels - 1):
        grade = _t("Close match")
    else:
        grade = _t("Distant match")
    return _t("{grade}: {kind} {how} ({total} of {top} points).").format(
        grade=grade, kind=kind, how=how, total=similarity.total, top=top)


def _missing_profile(plan: Plan, action: Action) -> int:
    cause = action.cause
    if isinstance(cause, ChannelRef):
        facts = plan.channels.get(cause)
        return facts.profile if facts is not None else 0
    return 0


def _plan_channel(system: System, plan: Plan, ref: ChannelRef) -> str:
    """A channel of a plan by its one name; one no longer on the bus by what the plan
    remembers of it (its descriptor)."""
    facts = plan.channels.get(ref)
    return channel_phrase(system, ref, facts.descriptor if facts is not None else "")


def _plan_link(system: System, plan: Plan, link: Link) -> str:
    return f"{_plan_channel(system, plan, link.output)} → {_plan_channel(system, plan, link.input)}"


def _cause_words(system: System, plan: Plan, cause: object) -> str:
    if isinstance(cause, Link):
        return _plan_link(system, plan, cause)
    if isinstance(cause, ChannelRef):
        return _plan_channel(system, plan, cause)
    return ""


def why_words(system: System, plan: Plan, action: Action) -> str:
    """Why the plan makes or removes this link, for a prosthetist."""
    cause = _cause_words(system, plan, action.cause)
    rule = action.rule
    if rule is Rule.TERMINAL:
        return _t("It drives a part of the prosthesis that nothing fed.")
    if rule is Rule.REQUIRED:
        return _t("{0} needs it to work.").format(cause) if cause else _t(
            "A channel in use needs it to work.")
    if rule is Rule.DESIRED:
        return _t("{0} works better with it.").format(cause) if cause else _t(
            "A channel in use works better with it.")
    if rule is Rule.REPLACEMENT:
        words = _t("It takes the place of {0}, which is gone.").format(cause)
        sim = similarity_words(action.similarity, _missing_profile(plan, action))
        return f"{words} {sim}" if sim else words
    if rule is Rule.REPLACED:
        return _t("One end is gone; the new part takes this link over.")
    if rule is Rule.SUPERSEDED:
        return _t("The output that fed it is gone.")
    if rule is Rule.STORED:
        return _t("It is in the configuration.")
    if rule is Rule.RETRIEVED:
        return _t("The parts remember this link.")
    if rule is Rule.SOLE_ACCESS:
        return _t("An input needs this output for itself alone.")
    if rule is Rule.NOT_STORED:
        return _t("It is not in the configuration.")
    if rule is Rule.CLEAR:
        return _t("Every link is cleared.")
    return action.reason


def action_words(action: str) -> str:
    """A fitting-history action in words (the wizards' own and restores; others as
    recorded)."""
    from pdcp_studio.app.wizards import logic

    if action == logic.ACTION_FITTING:
        return _t("New fitting: links written")
    if action == logic.ACTION_STORE:
        return _t("New fitting: configuration stored")
    if action == logic.ACTION_REPLACE:
        return _t("Part replaced")
    if action.startswith(logic.ACTION_RESTORE_FILE + " "):
        return _t("Configuration restored from {0}").format(
            action[len(logic.ACTION_RESTORE_FILE) + 1:])
    if action.startswith("history restore "):
        return _t("Fitting history entry {0} restored").format(
            action[len("history restore "):])
    return action


def plan_lines(system: System, plan: Plan) -> list[str]:
    """The plan, one sentence per link made or removed, with why (and how similar)."""
    out = []
    for action in plan.actions:
        verb = _t("Connect") if action.op.value == "add" else _t("Disconnect")
        out.append(f"{verb} {_plan_link(system, plan, action.link)}\n"
                   f"{why_words(system, plan, action)}")
    if plan.rejections:
        out.append(count("%n link(s) could not be made (the engineer's detail says why).",
                         len(plan.rejections)))
    return out


def config_lines(system: System, diff: ConfigDiff | None) -> list[str]:
    """How the stored configuration changes, in words (empty: it stays as it is)."""
    if diff is None:
        return []
    out = []
    for c in diff.configurations:
        for sl in c.only_in_b:
            out.append(_t("Will be stored: {0}").format(
                link_words(system, Link(sl.output.ref, sl.input.ref))))
        for sl in c.only_in_a:
            out.append(_t("No longer stored: {0}").format(
                link_words(system, Link(sl.output.ref, sl.input.ref))))
        for ch in c.changed:
            out.append(_t("Stored again with updated details: {0}").format(
                link_words(system, Link(*ch.ends))))
    if diff.unknown is not None and not out:
        out.append(_t("The stored configuration's extra records change."))
    return out


def preview_lines(system: System, preview: ChangePreview, links: bool = True) -> list[str]:
    """What the transaction will do on the prosthesis and what the next power-on does, in
    the words of the change's effect (``links`` False: without the links made and removed,
    when the plan above already says them)."""
    effect = preview.effect
    if effect is None:  # a preview made without one: the older words
        return _preview_lines_without_effect(system, preview, links)
    from pdcp_studio.app.words.effect_words import effect_tr
    from pdcp_studio.engine import effect as E

    out = effect.lines(effect_tr)
    if not links:
        said = {effect_tr(E.T_LINK_ADDED).format(link=effect.name(lk))
                for lk in effect.links_added}
        said |= {effect_tr(E.T_LINK_REMOVED).format(link=effect.name(lk))
                 for lk in effect.links_removed}
        out = [line for line in out if line not in said]
    return [*out, *effect.power_on_lines(effect_tr)]


def _preview_lines_without_effect(system: System, preview: ChangePreview,
                                  links: bool = True) -> list[str]:
    out = []
    current = set(preview.links_before)
    for a in preview.change.links if links else ():
        if (a.op == "add") == (a.link in current):
            continue
        verb = _t("Connect") if a.op == "add" else _t("Disconnect")
        out.append(f"{verb} {link_words(system, a.link)}")
    out += config_lines(system, preview.config_diff)
    if preview.change.policy is not None and preview.change.policy != preview.policy_before:
        out.append(_t("Automatic linking of new parts: on") if
                   preview.change.policy.autoconfigure else
                   _t("Automatic linking of new parts: off"))
    if preview.empty:
        out.append(_t("Nothing changes: the prosthesis already holds this."))
    elif preview.change.moves and preview.held:
        names = ", ".join(part_words(system, k) for k in preview.held)
        out.append(_t("Held still meanwhile, so the prosthesis cannot move: {0}.").format(names))
    return out
