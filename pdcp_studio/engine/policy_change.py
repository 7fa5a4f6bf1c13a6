"""What switching the autoconfigure policy changes on the prosthesis (issue 26 item 5).

One decision for the CLI (``policy``) and the app (Bus ▸ Autoconfigure): turning
autoconfigure on makes, in the same transaction, the links the duty cycle (listing 4.2) would
make now that it may — otherwise nothing would link them until the next swap; turning it off
removes nothing, and says which links stay. Pure: the system as read in, a plan and words out.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from pdcp_studio.engine.modes import plan_duty_cycle
from pdcp_studio.engine.plan import Plan
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link, System

#: Names a channel for the words (the app and the CLI may pass their own part names).
NameFn = Callable[[ChannelRef], str]
#: Puts a headline with ``%n`` in the reader's language for ``n`` things (-1: no count).
SayFn = Callable[[str, int], str]


#: The headline of :func:`kept_words` (``%n`` and ``(s)`` as Qt's plurals: the app translates
#: it with the same text).
KEPT = ("Every link stays as it is (%n link(s)); from now on unconnected hand, wrist or elbow "
        "channels stay unconnected until you link them:")
NONE_KEPT = ("No link is removed (there are none); from now on unconnected hand, wrist or "
             "elbow channels stay unconnected until you link them.")


def english(text: str, n: int) -> str:
    """``%n link(s)`` → ``1 link`` / ``2 links``."""
    return re.sub(r"\((s|es)\)", "" if n == 1 else r"\1", text.replace("%n", str(n)))


def kept_words(kept: list[Link], name: NameFn = str, say: SayFn = english) -> list[str]:
    """"Which links stay" when autoconfigure is turned off: all of them (nothing is removed),
    one line each; ``say(text, n)`` puts the headline in the reader's language."""
    if not kept:
        return [say(NONE_KEPT, -1)]  # -1: no count (as Qt's translate takes it)
    return [say(KEPT, len(kept)), *(f"  {name(lk.output)} → {name(lk.input)}" for lk in kept)]


@dataclass(frozen=True)
class PolicySwitch:
    """The change a policy switch makes: ``plan`` holds the link actions to carry out in
    the same transaction as the policy (none when turning it off or leaving it); ``kept``
    the links that stay as they are, and ``words`` say so (turning it off)."""

    before: bool
    after: bool
    plan: Plan
    kept: list[Link] = field(default_factory=list)
    words: list[str] = field(default_factory=list)

    @property
    def action(self) -> str:
        """The history's name for the change ("policy autoconfigure on")."""
        return f"policy autoconfigure {'on' if self.after else 'off'}"

    @property
    def switches(self) -> bool:
        return self.before != self.after


def policy_switch(system: System, before: bool, after: bool, *,
                  name: NameFn = str, say: SayFn = english) -> PolicySwitch:
    """What turning autoconfigure from ``before`` to ``after`` changes on ``system`` (the
    prosthesis as read). Turning it on plans the duty cycle with nothing gone since the last
    one (every present channel counts as previously present): only the autoconfiguration of
    unconnected terminal channels, exactly what the arbitrator would do at the next swap."""
    if after and not before:
        present = {ref for ref, _ in system.channels() if system.is_present(ref)}
        return PolicySwitch(before, after, plan_duty_cycle(system, present, autoconfigure=True))
    plan = Plan("policy", links_before=list(system.links))
    if before and not after:
        kept = sorted(system.links)
        return PolicySwitch(before, after, plan, kept, kept_words(kept, name, say))
    return PolicySwitch(before, after, plan)


__all__ = ["KEPT", "NONE_KEPT", "NameFn", "PolicySwitch", "SayFn", "english", "kept_words",
           "policy_switch"]
