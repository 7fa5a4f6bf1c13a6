"""Fit a stored configuration to a prosthesis: what is there, what would be replaced, and
which configuration start-up would pick. Pure.

This only reads the engine's own decisions — ``plan_startup`` with this configuration as
the stored one (listing 4.1: drop links it does not have, make its links, find replacements
for its missing channels with listing 4.6, autoconfigure what is left) and
``choose_configuration`` for start-up's choice among several stored configurations (thesis
B.2.1 case 4) — so what the document shows is what the arbitrator would do.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pdcp_studio.engine.modes import plan_startup
from pdcp_studio.engine.plan import Action, Plan
from pdcp_studio.engine.procedures import choose_configuration
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import Link, System

PRESENT, MISSING = "present", "missing"


def end_state(system: System, ch: StoredChannel, want: Direction) -> str:
    """``present``; ``missing`` (device or channel absent); or why the channel does not
    fit as stored (it is there but the other direction)."""
    ref = ch.ref
    if not system.is_present(ref):
        return MISSING
    actual = system.channel(ref)
    if actual is not None and actual.direction is not want:
        return f"is an {actual.direction.value} on the prosthesis"
    return PRESENT


@dataclass
class LinkFit:
    """One stored link against the prosthesis, with the plan's actions about it."""

    position: int
    link: StoredLink
    output: str  # end_state of the output
    input: str  # end_state of the input
    actions: list[Action] = field(default_factory=list)

    @property
    def whole(self) -> bool:
        return self.output == PRESENT and self.input == PRESENT

    def summary(self) -> str:
        """Plain words: what happens to this link on this prosthesis."""
        if self.whole:
            return "both ends present: made as stored"
        parts = []
        for name, state in (("output", self.output), ("input", self.input)):
            if state != PRESENT:
                parts.append(f"{name} {state}")
        adds = [a for a in self.actions if a.op.value == "add"]
        if adds:
            made = "; ".join(f"replaced by {a.link.output} → {a.link.input} ({a.reason})"
                             for a in adds)
            return f"{', '.join(parts)}: {made}"
        return f"{', '.join(parts)}: no replacement found, the link is not made"


@dataclass
class ConfigFit:
    """A configuration of a collection against one prosthesis."""

    index: int
    links: list[LinkFit]
    plan: Plan  # start-up with this configuration stored (replacements included)
    chosen_index: int | None  # the configuration start-up would pick from the collection
    chosen_reason: str

    @property
    def whole(self) -> int:
        return sum(1 for lf in self.links if lf.whole)


def _about(action: Action, sl: StoredLink) -> bool:
    """Is this plan action the repair of stored link ``sl``?"""
    cause = action.cause
    ends = Link(sl.output.ref, sl.input.ref)
    if isinstance(cause, Link):
        return cause == ends
    if isinstance(cause, ChannelRef):
        return cause in (ends.output, ends.input)
    return False


def fit_configuration(system: System, collection: ConfigCollection, position: int
                      ) -> ConfigFit:
    """Configuration ``position`` (0-based) of ``collection`` against ``system``."""
    cfg: StoredConfiguration = collection.configurations[position]
    plan = plan_startup(system, cfg)
    fits = []
    for pos, sl in enumerate(cfg.links):
        lf = LinkFit(pos, sl, end_state(system, sl.output, Direction.OUTPUT),
                     end_state(system, sl.input, Direction.INPUT))
        if not lf.whole:
            lf.actions = [a for a in plan.actions if _about(a, sl)]
        fits.append(lf)
    chosen, why = choose_configuration(system, collection)
    return ConfigFit(cfg.index, fits, plan, chosen.index, why)
