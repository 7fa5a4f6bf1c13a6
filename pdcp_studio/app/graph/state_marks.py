"""The findings and the staged changes marked on the graph's items, one item per step.

The scene runs the steps at once (an edit) or a slice per turn of the event loop (a live
snapshot of a large bus); what each card, port and link shows is decided here.
"""

from __future__ import annotations

from collections.abc import Iterator

from pdcp_studio.app.graph.analysis import SystemStates
from pdcp_studio.app.graph.items import DeviceItem
from pdcp_studio.app.graph.links import LinkItem
from pdcp_studio.app.graph.scene_words import SceneWords
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System


def pending_rows(bus: System | None, project: System) -> dict[DeviceKey, set[int]]:
    """Channels (0: the device) with a parameter staged but not yet written."""
    from pdcp_studio.app.documents.pending import PARAMETER, pending_changes

    marks: dict[DeviceKey, set[int]] = {}
    if bus is None:
        return marks
    for c in pending_changes(bus, project):
        if c.kind == PARAMETER and c.key is not None:
            marks.setdefault(c.key, set()).add(c.index)
    return marks


def mark_steps(cards: dict[DeviceKey, DeviceItem], link_items: dict[Link, LinkItem],
               system: System, bus: System | None, states: SystemStates,
               live: set[ChannelRef], pending: dict[DeviceKey, set[int]], dimmed: bool,
               words: SceneWords) -> Iterator[None]:
    """Show ``states`` on every card and link (``bus``: the prosthesis as last seen, its
    links not yet pending; ``dimmed``: a plan is previewed over them)."""
    for key, card in list(cards.items()):
        card.role = states.roles.get(key, card.role)
        card.problems = states.device_problems(key)
        card.pending_rows = pending.get(key, set())
        for port in card.ports.values():
            ref = port.ref
            if port.is_output:
                port.connected = bool(system.inputs_fed_by(ref))
                port.live = ref in live
            else:
                source = system.source_of(ref)
                port.connected = source is not None
                port.live = source in live
            port.unmet = ref in states.unmet_required
            port.setToolTip(words.port_advice(ref))
        card.refresh()
        yield
    on_bus = set(bus.links) if bus is not None else None
    for link, item in list(link_items.items()):
        item.pending = on_bus is not None and link not in on_bus
        item.conflict = link in states.conflict_links
        item.missing = link in states.missing_links
        item.setToolTip(words.link_advice(link))
        item.live = link.output in live
        item.setOpacity(0.35 if dimmed else 1.0)
        item.refresh()
        yield
