"""A plan as readable text: what will change, why, and what was tried and refused.

Written for a prosthetist at a terminal: every link names both channels, given the system's
:class:`~pdcp_studio.model.names.Names` by the one name every other text uses ("Hand, Power
grip") with the engineer's numbers beside it in brackets (reference, profile code and name),
else by its reference, profile and descriptor; nested actions are indented by how deep in
``intelligently_connect`` they were made.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pdcp_studio.model.profile import fmt
from pdcp_studio.model.refs import ChannelRef

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.model.names import Names
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.model.system import Link


def _channel(plan: Plan, ref: ChannelRef, tree: ProfileTree | None,
             names: Names | None = None) -> str:
    facts = plan.channels.get(ref)
    if names is not None:
        profile = ""
        if facts is not None and tree is not None and tree.names_exactly(facts.profile):
            profile = tree.short_name(facts.profile)
        numbers = str(ref) if facts is None else f"{ref}, {fmt(facts.profile)}"
        if facts is not None and tree is not None:
            numbers += f" {tree.name_of(facts.profile)}"
        missing = " (missing)" if facts is not None and not facts.present else ""
        return f"{names.channel(ref, profile)}{missing} [{numbers}]"
    if facts is None:
        return str(ref)
    text = f"{ref} {fmt(facts.profile)}"
    if tree is not None:
        text += f" {tree.name_of(facts.profile)}"
    if facts.descriptor:
        text += f" “{facts.descriptor}”"
    if not facts.present:
        text += " [missing]"
    return text


def plan_to_text(plan: Plan, tree: ProfileTree | None = None,
                 names: Names | None = None) -> str:
    """The plan in words (see the module doc); ``names``: the system's one naming."""

    def _link(plan: Plan, link: Link, tree: ProfileTree | None) -> str:
        return (f"{_channel(plan, link.output, tree, names)} → "
                f"{_channel(plan, link.input, tree, names)}")

    final = plan.final_links
    lines = [
        f"Plan: {plan.mode} — add {len(plan.added)}, remove {len(plan.removed)} "
        f"({len(plan.links_before)} links before, {len(final)} after)"
    ]
    if plan.configuration_reason:
        lines.append(f"Configuration ({plan.configuration_source}): {plan.configuration_reason}")
    lines.append("")
    if plan.actions:
        lines.append("Actions:")
        width = len(str(len(plan.actions)))
        for n, a in enumerate(plan.actions, 1):
            pad = "  " * a.depth
            sign = "+" if a.op.value == "add" else "-"
            lines.append(f"  {n:>{width}}. {pad}{sign} {a.op.value:6} {_link(plan, a.link, tree)}")
            indent = " " * (width + 4) + pad + "  "
            lines.append(f"{indent}[{a.rule.value}] {a.reason}")
            if a.similarity is not None:
                lines.append(f"{indent}similarity {a.similarity.describe()}")
    else:
        lines.append("Actions: none — nothing to change.")
    if plan.rejections:
        lines += ["", "Tried and refused:"]
        for r in plan.rejections:
            at = r.attempt
            subject = (_link(plan, at.link, tree) if at.link is not None
                       else _channel(plan, at.channel, tree, names) if at.channel is not None
                       else "")
            lines.append(f"  - [{r.kind.value}] {subject}")
            lines.append(f"      {r.reason}")
            if r.rolled_back:
                undone = ", ".join(str(lk) for lk in r.rolled_back)
                lines.append(f"      rolled back: {undone}")
    if plan.notes:
        lines += ["", "Notes:"]
        lines += [f"  - {note}" for note in plan.notes]
    lines += ["", f"Links after the plan ({len(final)}):"]
    lines += [f"  {_link(plan, lk, tree)}" for lk in final] or ["  (none)"]
    return "\n".join(lines) + "\n"
