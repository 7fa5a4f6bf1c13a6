"""Undo commands: every edit is one ``QUndoCommand`` that changes the model via Document.

``QUndoStack.push`` runs ``redo()`` — callers never apply the change themselves, and a
no-op edit is never pushed (:func:`push_channel_field` and friends check). Commands touch
the :class:`~pdcp_studio.app.document.Document`, never graphics items: the views follow
the document's signals.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from PySide6.QtGui import QUndoCommand

from pdcp_studio.app.document import Document, Position
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link

#: Command ids for ``mergeWith`` (consecutive moves of one drag merge into one step).
MOVE_ID = 1001


class AddLinkCommand(QUndoCommand):
    def __init__(self, doc: Document, link: Link, parent: QUndoCommand | None = None) -> None:
        super().__init__(f"Link {link.output} → {link.input}", parent)
        self.doc, self.link = doc, link

    def redo(self) -> None:
        self.doc.add_link(self.link)

    def undo(self) -> None:
        self.doc.remove_link(self.link)


class RemoveLinkCommand(QUndoCommand):
    def __init__(self, doc: Document, link: Link, parent: QUndoCommand | None = None) -> None:
        super().__init__(f"Remove link {link.output} → {link.input}", parent)
        self.doc, self.link = doc, link

    def redo(self) -> None:
        self.doc.remove_link(self.link)

    def undo(self) -> None:
        self.doc.add_link(self.link)


class SetLinksCommand(QUndoCommand):
    """Replace the whole link set (a plan's result): one signal each way."""

    def __init__(self, doc: Document, links: Iterable[Link], text: str,
                 parent: QUndoCommand | None = None) -> None:
        super().__init__(text, parent)
        self.doc = doc
        self.before = list(doc.system.links)
        self.after = sorted(links)

    def redo(self) -> None:
        self.doc.set_links(self.after)

    def undo(self) -> None:
        self.doc.set_links(self.before)


#: Channel fields a user may write to a live device: field → catalog parameter ID.
#: (Node IDs and the input's source fields are the arbitrator's: they follow the links.)
LIVE_CHANNEL_PARAMS = {"type": 1, "profile": 1, "descriptor": 2, "data_enabled": 4,
                       "required_inputs": 9, "desired_inputs": 10, "terminal_profile": 11}
LIVE_DEVICE_PARAMS = {"descriptor": 7, "beacon_interval": 10, "ack_timeout": 11,
                      "bind_timeout": 12}


def live_write_refusal(doc: Document, name: str, *, device: bool) -> str | None:
    """Why a field may not be edited on a live bus (None: it may, and will be written)."""
    if _live(doc) is None:
        return None
    table = LIVE_DEVICE_PARAMS if device else LIVE_CHANNEL_PARAMS
    if name in table or name == "name":
        return None
    if name == "node_id":
        return "node IDs are assigned by the arbitrator on a live bus"
    return f"{name.replace('_', ' ')} cannot be written to a live device"


def _write_live(doc: Document, key: DeviceKey, index: int, name: str) -> None:
    """Write the model's current value of one field to the live device (worker thread)."""
    from pdcp_studio.model import parameters as params

    bridge = _live(doc)
    if bridge is None or not hasattr(bridge.session, "set_parameter"):
        return
    device = doc.device(key)
    if index == 0:
        pid = LIVE_DEVICE_PARAMS.get(name)
        if pid is None:
            return
        spec = params.device_parameter(pid)
        value: Any = getattr(device, name)
    else:
        pid = LIVE_CHANNEL_PARAMS.get(name)
        if pid is None:
            return
        ch = device.channels[index]
        spec = params.channel_parameter(pid, ch.direction)
        value = (ch.type, ch.profile) if pid == 1 else getattr(ch, name)
        if pid == 4:
            value = int(bool(value))
    data = params.encode_value(spec, value)
    session = bridge.session
    bridge.run(lambda _p, _c: session.set_parameter(key, pid, index, data),
               f"Write {spec.name} of {key}" + (f" #{index}" if index else ""))


class SetChannelFieldCommand(QUndoCommand):
    """One channel field; on a live bus also written to the device (redo and undo)."""

    def __init__(self, doc: Document, ref: ChannelRef, name: str, value: Any,
                 text: str = "", parent: QUndoCommand | None = None) -> None:
        super().__init__(text or f"Set {name.replace('_', ' ')} of {ref}", parent)
        self.doc, self.ref, self.name, self.value = doc, ref, name, value
        self.old = getattr(doc.channel(ref), name)

    def redo(self) -> None:
        self.doc.set_channel_field(self.ref, self.name, self.value)
        _write_live(self.doc, self.ref.device, self.ref.index, self.name)

    def undo(self) -> None:
        self.doc.set_channel_field(self.ref, self.name, self.old)
        _write_live(self.doc, self.ref.device, self.ref.index, self.name)


class SetDeviceFieldCommand(QUndoCommand):
    """One device field; on a live bus also written to the device (redo and undo)."""

    def __init__(self, doc: Document, key: DeviceKey, name: str, value: Any,
                 text: str = "", parent: QUndoCommand | None = None) -> None:
        super().__init__(text or f"Set {name.replace('_', ' ')} of {key}", parent)
        self.doc, self.key, self.name, self.value = doc, key, name, value
        self.old = getattr(doc.device(key), name)

    def redo(self) -> None:
        self.doc.set_device_field(self.key, self.name, self.value)
        _write_live(self.doc, self.key, 0, self.name)

    def undo(self) -> None:
        self.doc.set_device_field(self.key, self.name, self.old)
        _write_live(self.doc, self.key, 0, self.name)


class MoveDeviceCommand(QUndoCommand):
    """A card moved. Consecutive moves of the same drag merge (``drag_id``)."""

    def __init__(self, doc: Document, key: DeviceKey, old: Position | None, new: Position,
                 drag_id: int = 0, parent: QUndoCommand | None = None) -> None:
        super().__init__(f"Move {doc.system.devices[key].label}" if key in doc.system.devices
                         else f"Move {key}", parent)
        self.doc, self.key, self.old, self.new, self.drag_id = doc, key, old, new, drag_id

    def id(self) -> int:
        return MOVE_ID

    def mergeWith(self, other: QUndoCommand) -> bool:
        if not isinstance(other, MoveDeviceCommand):
            return False
        if other.key != self.key or other.drag_id != self.drag_id or not self.drag_id:
            return False
        self.new = other.new
        return True

    def redo(self) -> None:
        self.doc.set_position(self.key, self.new)

    def undo(self) -> None:
        if self.old is not None:
            self.doc.set_position(self.key, self.old)


class MoveDevicesCommand(QUndoCommand):
    """Several cards moved by one drag (a multi-selection): one undo step."""

    def __init__(self, doc: Document, moves: dict[DeviceKey, tuple[Position, Position]],
                 parent: QUndoCommand | None = None) -> None:
        n = len(moves)
        super().__init__(f"Move {n} device{'s' if n != 1 else ''}", parent)
        self.doc, self.moves = doc, dict(moves)

    def redo(self) -> None:
        for key, (_old, new) in self.moves.items():
            self.doc.set_position(key, new)

    def undo(self) -> None:
        for key, (old, _new) in self.moves.items():
            self.doc.set_position(key, old)


# -- helpers that push only real changes -------------------------------------------------
def push_channel_field(doc: Document, ref: ChannelRef, name: str, value: Any,
                       text: str = "") -> bool:
    """Push one channel edit unless it changes nothing; True if pushed."""
    current = getattr(doc.channel(ref), name)
    if name in ("required_inputs", "desired_inputs"):
        value = tuple(sorted(value))
    if current == value:
        return False
    doc.undo_stack.push(SetChannelFieldCommand(doc, ref, name, value, text))
    return True


def push_device_field(doc: Document, key: DeviceKey, name: str, value: Any,
                      text: str = "") -> bool:
    if getattr(doc.device(key), name) == value:
        return False
    doc.undo_stack.push(SetDeviceFieldCommand(doc, key, name, value, text))
    return True


def manual_plan(doc: Document, adds: Iterable[Link] = (), removes: Iterable[Link] = ()) -> Any:
    """Edits by hand as an engine ``Plan``, for a live bus (the session applies plans)."""
    from pdcp_studio.engine import Action, ChannelFacts, Op, Plan, Rule

    system = doc.system
    actions = [Action(Op.REMOVE, lk, Rule.NOT_STORED, "removed by hand") for lk in removes]
    actions += [Action(Op.ADD, lk, Rule.STORED, "linked by hand") for lk in adds]
    channels = {}
    for a in actions:
        for ref in (a.link.output, a.link.input):
            ch = system.channel(ref)
            if ch is not None:
                channels[ref] = ChannelFacts(ch.type, ch.profile, ch.terminal_profile,
                                             ch.descriptor, system.is_present(ref))
    return Plan("manual", actions=actions, links_before=list(system.links), channels=channels)


def _live(doc: Document) -> Any:
    """The session bridge when the document shows a live bus (edits go to the bus)."""
    bridge = doc.session
    return bridge if bridge is not None and hasattr(bridge, "apply_plan") else None


def push_add_link(doc: Document, link: Link) -> bool:
    """Add a link: one undo step offline; on a live bus a one-action plan for the session."""
    if doc.system.has_link(link):
        return False
    bridge = _live(doc)
    if bridge is not None:
        bridge.apply_plan(manual_plan(doc, adds=[link]))
        return True
    doc.undo_stack.push(AddLinkCommand(doc, link))
    return True


def push_remove_links(doc: Document, links: Iterable[Link]) -> int:
    """Remove links as one undo step; returns how many."""
    links = [lk for lk in links if doc.system.has_link(lk)]
    if not links:
        return 0
    bridge = _live(doc)
    if bridge is not None:
        bridge.apply_plan(manual_plan(doc, removes=links))
        return len(links)
    if len(links) == 1:
        doc.undo_stack.push(RemoveLinkCommand(doc, links[0]))
        return 1
    doc.undo_stack.beginMacro(f"Remove {len(links)} links")
    try:
        for link in links:
            doc.undo_stack.push(RemoveLinkCommand(doc, link))
    finally:
        doc.undo_stack.endMacro()
    return len(links)


def push_plan(doc: Document, plan: Any, text: str = "") -> bool:
    """Apply a plan's actions to the document as one undo macro; False if it does nothing.

    Each action becomes an add/remove command in order, so undo steps back through
    exactly what the plan did; inputs' redundant ``source`` fields follow the links
    when the plan's result says so (``plan.final_links``).
    """
    actions = list(getattr(plan, "actions", ()))
    if not actions:
        return False
    mode = getattr(plan, "mode", "plan")
    stack = doc.undo_stack
    stack.beginMacro(text or f"Apply {mode} ({len(actions)} action{'s' * (len(actions) != 1)})")
    try:
        for action in actions:
            link = action.link
            if action.op == "add" and not doc.system.has_link(link):
                stack.push(AddLinkCommand(doc, link))
            elif action.op == "remove" and doc.system.has_link(link):
                stack.push(RemoveLinkCommand(doc, link))
        final = getattr(plan, "final_links", None)
        if final is not None and set(final) != set(doc.system.links):
            stack.push(SetLinksCommand(doc, final, "Match the plan's final links"))
    finally:
        stack.endMacro()
    return True
