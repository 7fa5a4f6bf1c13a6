"""Pending changes: what the project (the document) would change on the prosthesis.

On a live bus every edit is staged in the document (one undo step each); the prosthesis as
last seen is ``Document.bus_system``. The difference between the two — links to make, links
to remove, parameters to write — is the list of pending changes, and Write to prosthesis
turns it into one :class:`~pdcp_studio.bus.transaction.Change` for the session's one
transaction road. Pure: no Qt, no bus I/O; tested without threads.

The inputs' source fields and the node IDs are never pending: the arbitrator keeps them in
step with the links. Data Transfer Enabled is pending only where it differs from what the
links imply (the arbitrator sets it with every link it makes or removes).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from pdcp_studio.model import param_fields
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System

#: Channel fields that can be staged on a live bus: field → catalog parameter ID.
CHANNEL_PARAMS = {name: param_fields.param_of_field(name, "input") for name in (
    "type", "profile", "descriptor", "data_enabled", "required_inputs", "desired_inputs",
    "terminal_profile")}
#: Device fields that can be staged on a live bus: field → catalog parameter ID.
DEVICE_PARAMS = {name: param_fields.param_of_field(name, "device") for name in (
    "descriptor", "beacon_interval", "ack_timeout", "bind_timeout")}
#: The action a written set of pending changes is recorded as.
WRITE_ACTION = "write to prosthesis"

ADD, REMOVE, PARAMETER = "add", "remove", "parameter"

#: A staged field → its name in ``model.param_names`` (the effect's parameter names).
FIELD_NAMES = {"type": "type", "profile": "profile", "descriptor": "descriptor",
               "data_enabled": "data-transfer", "required_inputs": "required-inputs",
               "desired_inputs": "desired-inputs", "terminal_profile": "terminal-profile",
               "beacon_interval": "beacon-interval", "ack_timeout": "ack-timeout",
               "bind_timeout": "bind-timeout"}

Translate = Callable[[str], str]


def _same(text: str) -> str:
    return text


@dataclass(frozen=True)
class PendingChange:
    """One staged change: a link to add or remove, or a parameter to write.

    ``key``/``index`` name the device and channel (index 0: the device itself) of a
    parameter; ``old`` is the prosthesis's value, ``new`` the project's.
    """

    kind: str
    link: Link | None = None
    key: DeviceKey | None = None
    index: int = 0
    field: str = ""
    old: Any = None
    new: Any = None
    reason: str = ""

    @property
    def ref(self) -> ChannelRef | None:
        """The channel of a channel parameter (None for a device parameter or a link)."""
        if self.key is None or not self.index:
            return None
        return ChannelRef(*self.key, self.index)

    def describe(self, bus: System | None, project: System | None = None,
                 names: Names | None = None, tr: Translate = _same) -> str:
        """One line in the words of a change's effect (``engine.effect``): a link by its
        channels' names, a parameter old → new as the confirmation will say it. ``bus`` is
        the prosthesis as it is, ``project`` the document; ``names`` and ``tr`` the app's
        (plain names and English without them)."""
        base = bus if bus is not None else project
        names = names or Names(base)
        if self.kind in (ADD, REMOVE) and self.link is not None:
            return names.link(self.link)
        if bus is not None and project is not None and self.key is not None:
            from pdcp_studio.engine.effect import parameter_words

            words = parameter_words(bus, [parameter_write(project, self)], names, tr,
                                    only=FIELD_NAMES.get(self.field))
            if words:
                return "; ".join(words)
        if self.key is None:
            return "?"
        where = (names.channel(self.ref) if self.ref is not None else names.part(self.key))
        return f"{where}: {self.field.replace('_', ' ')} {_value(self.old)} → {_value(self.new)}"


def _value(value: Any) -> str:
    if isinstance(value, bool):
        from pdcp_studio.app.i18n import translate  # Qt's translator: only for words

        return translate("Pending", "on") if value else translate("Pending", "off")
    if isinstance(value, str):
        return f"“{value}”"
    if isinstance(value, tuple):
        return "{" + ", ".join(str(v) for v in value) + "}"
    return str(value)


def pending_changes(bus: System | None, project: System,
                    reasons: dict[Link, str] | None = None) -> list[PendingChange]:
    """What writing ``project`` to the prosthesis ``bus`` changes: removals, additions, then
    parameters (the order a transaction makes them in). Empty offline (``bus`` None)."""
    if bus is None:
        return []
    reasons = reasons or {}
    out: list[PendingChange] = []
    old, new = set(bus.links), set(project.links)
    out += [PendingChange(REMOVE, link=lk, reason=reasons.get(lk, ""))
            for lk in sorted(old - new)]
    out += [PendingChange(ADD, link=lk, reason=reasons.get(lk, ""))
            for lk in sorted(new - old)]
    for key, mine in project.devices.items():
        theirs = bus.devices.get(key)
        if theirs is None or not theirs.present:
            continue  # a missing device cannot be written
        for name in DEVICE_PARAMS:
            if getattr(mine, name) != getattr(theirs, name):
                out.append(PendingChange(PARAMETER, key=key, field=name,
                                         old=getattr(theirs, name), new=getattr(mine, name)))
        for index, ch in sorted(mine.channels.items()):
            other = theirs.channels.get(index)
            if other is None:
                continue
            ref = ChannelRef(*key, index)
            for name in CHANNEL_PARAMS:
                a, b = getattr(other, name), getattr(ch, name)
                if a == b:
                    continue
                if name == "data_enabled" and b == _linked(project, ref, ch):
                    continue  # follows the staged links: the arbitrator sets it
                out.append(PendingChange(PARAMETER, key=key, index=index, field=name,
                                         old=a, new=b))
    return out


def _linked(system: System, ref: ChannelRef, ch: Any) -> bool:
    if ch.is_input:
        return system.source_of(ref) is not None
    return bool(system.inputs_fed_by(ref))


def parameter_write(project: System, change: PendingChange) -> Any:
    """The :class:`~pdcp_studio.bus.transaction.ParameterWrite` of a parameter change."""
    from pdcp_studio.bus.transaction import ParameterWrite

    assert change.key is not None
    device = project.devices[change.key]
    obj = device.channels[change.index] if change.index else device
    pid = (CHANNEL_PARAMS if change.index else DEVICE_PARAMS)[change.field]
    return ParameterWrite(change.key, pid, change.index,
                          param_fields.encode_field_value(obj, pid))


def change_for(changes: list[PendingChange], project: System,
               action: str = WRITE_ACTION, reason: str = "staged in PDCP Studio") -> Any:
    """The transaction's :class:`~pdcp_studio.bus.transaction.Change` for these pending
    changes: link removals, then additions (with their reasons), then parameter writes
    (type and profile share one parameter: written once)."""
    from pdcp_studio.bus.transaction import Change, LinkAction

    links = [LinkAction(c.kind, c.link, c.reason or reason)
             for c in changes if c.kind in (ADD, REMOVE) and c.link is not None]
    writes, seen = [], set()
    for c in changes:
        if c.kind != PARAMETER:
            continue
        write = parameter_write(project, c)
        ident = (write.device, write.param, write.channel)
        if ident not in seen:
            seen.add(ident)
            writes.append(write)
    return Change(action, links=links, parameters=writes)
