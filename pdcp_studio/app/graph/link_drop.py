"""What releasing a link drag over a port means: which output feeds which input, or why
not. Pure (no Qt): the scene's drag gesture asks it, tests ask it without a scene.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from pdcp_studio.app.graph.analysis import link_refusal
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link, System

#: Why a drag released away from every port links nothing.
NO_TARGET = "no target port"


@dataclass(frozen=True)
class LinkDrop:
    """The outcome of a drop: the ends (output first; None without a target port) and the
    refusal ("" when the link may be made)."""

    output: ChannelRef | None
    input: ChannelRef | None
    reason: str = ""

    @property
    def link(self) -> Link | None:
        """The link to make, None when refused."""
        if self.reason or self.output is None or self.input is None:
            return None
        return Link(self.output, self.input)


def link_ends(system: System, start: ChannelRef,
              target: ChannelRef) -> tuple[ChannelRef, ChannelRef]:
    """Output first: a drag may go either way between an output and an input."""
    start_ch, target_ch = system.channel(start), system.channel(target)
    start_is_output = start_ch is not None and start_ch.is_output
    target_is_output = target_ch is not None and target_ch.is_output
    if not start_is_output and target_is_output:
        return target, start
    return start, target


def decide_drop(system: System, start: ChannelRef, target: ChannelRef | None,
                name: Callable[[ChannelRef], str] = str) -> LinkDrop:
    """The drop of a drag that started at ``start`` over ``target`` (None: no port);
    a refusal names the channels by ``name``."""
    if target is None or target == start:
        return LinkDrop(None, None, NO_TARGET)
    out, into = link_ends(system, start, target)
    return LinkDrop(out, into, link_refusal(system, out, into, name) or "")
