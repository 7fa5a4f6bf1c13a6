"""Following the live bus: a three-way merge of the prosthesis into the project.

The document is the project, the prosthesis is what the session last saw. What the bus
owns (presence, node IDs, versions) always follows a fresh snapshot; a link or a field a
user may stage follows it unless the user changed it in the project since the last
snapshot (a staged change, kept). Pure: no Qt, no signals — :meth:`Document.sync_live`
applies :func:`merge_snapshot` and tells the views what changed, and tests run it without
a ``QApplication``.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.app.documents.pending import CHANNEL_PARAMS, DEVICE_PARAMS
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System

#: Fields the bus owns: on a live bus they always follow the prosthesis.
BUS_CHANNEL_FIELDS = ("node_id",)
BUS_DEVICE_FIELDS = ("present", "node_id", "fw_version", "hw_version", "device_type",
                     "device_profile", "ean_low", "ean_high")
#: Fields a user may stage on a live bus: they follow the prosthesis unless changed here.
#: (The inputs' source fields are merged the same way: a staged link changes them here.)
WRITABLE_CHANNEL_FIELDS = ("type", "profile", "terminal_profile", "required_inputs",
                           "desired_inputs", "descriptor", "data_enabled", "source")
WRITABLE_DEVICE_FIELDS = ("descriptor", "beacon_interval", "ack_timeout", "bind_timeout")


@dataclass
class SyncResult:
    """What a merge changed in the project (the views' to-do list)."""

    #: The snapshot is the prosthesis exactly as last seen.
    same_bus: bool = False
    #: A device new to the project was added (the views rebuild).
    added: bool = False
    changed_devices: list[DeviceKey] = field(default_factory=list)
    changed_channels: list[ChannelRef] = field(default_factory=list)
    #: The project's links once merged (sorted; both ends in the project).
    links: list[Link] = field(default_factory=list)
    links_changed: bool = False

    @property
    def unchanged(self) -> bool:
        """Nothing to show: the same bus, and the project follows from it unchanged."""
        return self.same_bus and not (self.added or self.changed_devices
                                      or self.changed_channels or self.links_changed)


def same_system(a: System, b: System) -> bool:
    """The same devices (every field, every channel) and the same links."""
    return a.devices == b.devices and set(a.links) == set(b.links)


def merge_snapshot(system: System, last_seen: System | None, snapshot: System) -> SyncResult:
    """Merge ``snapshot`` into the project ``system`` in place, against ``last_seen`` (the
    prosthesis as last seen, None before the first snapshot); returns what changed.

    Devices the snapshot lacks stay, marked missing; devices it has keep their objects
    (views and undo commands keep pointing at them). The links are computed, not set:
    the caller sets them (:func:`apply_links`, or its own mutator that signals).
    """
    base = last_seen or System()
    result = SyncResult(same_bus=last_seen is not None and same_system(snapshot, last_seen))
    for key, device in snapshot.devices.items():
        mine = system.devices.get(key)
        if mine is None:
            system.add_device(copy.deepcopy(device))
            result.added = True
            continue
        if mine == device:
            continue  # every field and channel as on the bus: nothing to merge
        old = base.devices.get(key)
        if merge_fields(mine, device, old, BUS_DEVICE_FIELDS, WRITABLE_DEVICE_FIELDS):
            result.changed_devices.append(key)
        for index, ch in device.channels.items():
            own = mine.channels.get(index)
            if own is None:
                continue
            was = old.channels.get(index) if old is not None else None
            if merge_fields(own, ch, was, BUS_CHANNEL_FIELDS, WRITABLE_CHANNEL_FIELDS):
                result.changed_channels.append(ChannelRef(*key, index))
    for key, mine in system.devices.items():
        if key not in snapshot.devices and mine.present:
            mine.present = False
            result.changed_devices.append(key)
    result.links = merged_links(system, base, snapshot)
    result.links_changed = set(result.links) != set(system.links)
    return result


def merged_links(system: System, base: System, snapshot: System) -> list[Link]:
    """The bus's links, plus the links staged in ``system``, minus the ones removed there
    (staged against ``base``); only links whose both ends ``system`` has."""
    base_links, mine_links = set(base.links), set(system.links)
    staged_add, staged_remove = mine_links - base_links, base_links - mine_links
    merged = (set(snapshot.links) | staged_add) - staged_remove
    return [lk for lk in sorted(merged)
            if system.channel(lk.output) is not None and system.channel(lk.input)]


def apply_links(system: System, links: Iterable[Link]) -> None:
    """Replace ``system``'s links (unchecked: they were merged from a checked bus)."""
    system.clear_links()
    for link in links:
        system.add_link(link, check=False)


def merge_fields(mine: Any, theirs: Any, base: Any, owned: Iterable[str],
                 writable: Iterable[str]) -> bool:
    """Three-way merge of one device or channel's fields; True if any changed here."""
    changed = False
    for name in owned:
        value = getattr(theirs, name)
        if getattr(mine, name) != value:
            setattr(mine, name, value)
            changed = True
    for name in writable:
        value = getattr(theirs, name)
        current = getattr(mine, name)
        if current == value:
            continue
        if base is None or current == getattr(base, name):  # not staged here: follow the bus
            setattr(mine, name, value)
            changed = True
    return changed


def staging_refusal(name: str, *, device: bool) -> str | None:
    """Why a field may not be staged on a live bus (None: it may; Write to prosthesis
    writes it). Node IDs and the inputs' source fields are the arbitrator's."""
    table = DEVICE_PARAMS if device else CHANNEL_PARAMS
    if name in table or name == "name":
        return None
    if name == "node_id":
        return "node IDs are assigned by the arbitrator on a live bus"
    return f"{name.replace('_', ' ')} cannot be written to a live device"


def links_after(links: Iterable[Link], actions: Iterable[Any]) -> list[Link]:
    """The links once ``actions`` (add/remove, in order) are carried out on ``links``."""
    out = set(links)
    for a in actions:
        (out.add if getattr(a.op, "value", a.op) == "add" else out.discard)(a.link)
    return sorted(out)
