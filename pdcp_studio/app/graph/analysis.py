"""What the graph shows about a system: device roles, problem states, link rules. Pure.

Kept free of Qt so the rules can be tested (and reused by the inspector and the status
bar) without a scene.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device, Link, System

SENSOR, CONTROL, TERMINAL = "sensor", "control", "terminal"
#: Left-to-right order of the layers.
ROLE_LAYER = {SENSOR: 0, CONTROL: 1, TERMINAL: 2}


def device_role(device: Device) -> str:
    """Only outputs → sensor; a terminal input → terminal device; anything else → control."""
    inputs = device.inputs()
    if not inputs:
        return SENSOR if device.outputs() else CONTROL
    if any(ch.terminal for ch in inputs):
        return TERMINAL
    return CONTROL


@dataclass
class SystemStates:
    """Every problem the graph marks, computed once per change."""

    roles: dict[DeviceKey, str] = field(default_factory=dict)
    unmet_required: set[ChannelRef] = field(default_factory=set)
    conflict_links: set[Link] = field(default_factory=set)
    missing_links: set[Link] = field(default_factory=set)
    unconnected_terminals: set[ChannelRef] = field(default_factory=set)

    def device_problems(self, key: DeviceKey) -> list[str]:
        out = []
        unmet = sorted(r.index for r in self.unmet_required if r.device == key)
        if unmet:
            out.append("required input" + "s" * (len(unmet) > 1) + " not connected: "
                       + ", ".join(f"#{i}" for i in unmet))
        term = sorted(r.index for r in self.unconnected_terminals if r.device == key)
        if term:
            out.append("terminal input" + "s" * (len(term) > 1) + " not connected: "
                       + ", ".join(f"#{i}" for i in term))
        if any(key in (lk.output.device, lk.input.device) for lk in self.conflict_links):
            out.append("sole-access conflict")
        return out


def required_inputs_of(device: Device) -> set[int]:
    """Input indices some channel of ``device`` lists as required."""
    req: set[int] = set()
    for ch in device.channels.values():
        req.update(ch.required_inputs)
    return {i for i in req if i in device.channels and device.channels[i].is_input}


def compute_states(system: System) -> SystemStates:
    """The graph's marks, by the same rules as the Checks list (``engine/checks.py``): only
    links whose both ends are on the bus count; a required input is unmet only when a
    channel that requires it is in use (linked), as ``required-unmet`` says; a terminal
    input is unconnected when no live link feeds it; a sole-access conflict is an output
    feeding several sole-access inputs over live links."""
    states = SystemStates()
    live: list[Link] = []
    for link in system.links:
        if system.is_present(link.output) and system.is_present(link.input):
            live.append(link)
        else:
            states.missing_links.add(link)
    fed = {lk.input for lk in live}
    in_use = {r for lk in live for r in (lk.output, lk.input)}
    for ref in in_use:
        ch = system.channel(ref)
        for index in ch.required_inputs if ch is not None else ():
            target = ChannelRef(*ref.device, index)
            tch = system.channel(target)
            if tch is not None and tch.is_input and target not in fed:
                states.unmet_required.add(target)
    for key, device in system.devices.items():
        states.roles[key] = device_role(device)
        if not device.present:
            continue
        for ch in device.inputs():
            ref = device.ref(ch.index)
            if ch.terminal and ref not in fed:
                states.unconnected_terminals.add(ref)
    by_output: dict[ChannelRef, list[Link]] = {}
    for link in live:
        inp = system.channel(link.input)
        if inp is not None and inp.sole_access:
            by_output.setdefault(link.output, []).append(link)
    for links in by_output.values():
        if len(links) > 1:
            states.conflict_links.update(links)
    return states


def link_refusal(system: System, a: ChannelRef, b: ChannelRef,
                 name: Callable[[ChannelRef], str] = str) -> str | None:
    """Why ``a → b`` may not be linked (None: allowed). ``a`` is where the drag started;
    ``name`` names a channel in words (the scene's names; refs when not given)."""
    from pdcp_studio.app.i18n import translate

    def tr(text: str) -> str:
        return translate("LinkRefusal", text)

    out_ch, in_ch = system.channel(a), system.channel(b)
    if out_ch is None or in_ch is None:
        return tr("that channel is not in the system")
    if not out_ch.is_output:
        return tr("a link starts at an output: {0} is an input").format(name(a))
    if not in_ch.is_input:
        return tr("a link ends at an input: {0} is an output").format(name(b))
    if a.device == b.device:
        return tr("a device must not send to itself (same-device link)")
    if not system.is_present(a) or not system.is_present(b):
        return tr("a channel of a missing device cannot be linked")
    link = Link(a, b)
    if system.has_link(link):
        return tr("these channels are already linked")
    source = system.source_of(b)
    if source is not None:
        return tr("input {0} already has a source ({1}); remove that link first").format(
            name(b), name(source))
    if in_ch.sole_access:
        for other in system.inputs_fed_by(a):
            other_ch = system.channel(other)
            if other_ch is not None and other_ch.sole_access:
                return tr("sole access: output {0} already feeds the sole-access input "
                          "{1}").format(name(a), name(other))
    return None
