"""Undo commands: every edit is one ``QUndoCommand`` that changes the model via Document.

Offline or live, an edit changes the document only: on a live bus it is a staged change
(the document is the project, the prosthesis the target) until Write to prosthesis runs
one transaction (:mod:`pdcp_studio.app.documents.pending`).

``QUndoStack.push`` runs ``redo()`` — callers never apply the change themselves, and a
no-op edit is never pushed (:func:`push_channel_field` and friends check). Commands touch
the :class:`~pdcp_studio.app.documents.document.Document`, never graphics items: the views follow
the document's signals.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable
from typing import Any

from PySide6.QtGui import QUndoCommand

from pdcp_studio.app.documents import live_sync, pending
from pdcp_studio.app.documents.document import Document, Position
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.effect_words import app_names, effect_tr
from pdcp_studio.app.words.part_names import part_name
from pdcp_studio.app.words.plural import count
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link


def _tr(text: str) -> str:
    return translate("Commands", text)


def _names(doc: Document) -> Names:
    """The names the undo texts use (the same as every other text about a change)."""
    return app_names(doc.system, doc.tree)


def field_words(doc: Document, key: DeviceKey, index: int, name: str, value: Any) -> str:
    """An edit of one field in the words of a change's effect ("Hand, Power grip: control
    mode position → velocity"), for the undo and redo texts."""
    from pdcp_studio.bus.transaction import ParameterWrite
    from pdcp_studio.engine.effect import parameter_words
    from pdcp_studio.model import param_fields

    names = _names(doc)
    device = doc.system.device(key)
    obj: Any = device.channels.get(index) if device is not None and index else device
    params = pending.CHANNEL_PARAMS if index else pending.DEVICE_PARAMS
    where = names.channel(ChannelRef(*key, index)) if index else names.part(key)
    if obj is not None and name in params:
        changed = copy.copy(obj)
        setattr(changed, name, value)
        try:
            data = param_fields.encode_field_value(changed, params[name])
        except (PdcpError, ValueError, AssertionError, ArithmeticError):
            data = b""
        if data:
            words = parameter_words(doc.system, [ParameterWrite(key, params[name], index, data)],
                                    names, effect_tr, only=pending.FIELD_NAMES.get(name))
            if words:
                return "; ".join(words)
    return _tr("{0}: {1} changed").format(where, name.replace("_", " "))

#: Command ids for ``mergeWith`` (consecutive moves of one drag merge into one step).
MOVE_ID = 1001


class LinksCommand(QUndoCommand):
    """Link actions in order, carried out by the engine's one apply path (``Plan.apply``):
    the inputs' source fields and Data Transfer Enabled follow the links exactly as the CLI's
    ``apply`` leaves them. Undo puts the links and those fields back as they were."""

    def __init__(self, doc: Document, actions: Iterable[Any], text: str,
                 mode: str = "manual", parent: QUndoCommand | None = None) -> None:
        super().__init__(text, parent)
        self.doc, self.mode = doc, mode
        self.actions = list(actions)
        self.before = doc.links_state([a.link for a in self.actions])

    def redo(self) -> None:
        from pdcp_studio.engine import Plan

        self.doc.apply_plan_actions(Plan(self.mode, actions=self.actions))

    def undo(self) -> None:
        self.doc.restore_links_state(self.before)


def _action(op: str, link: Link, reason: str) -> Any:
    from pdcp_studio.engine import Action, Op, Rule

    if op == "add":
        return Action(Op.ADD, link, Rule.STORED, reason)
    return Action(Op.REMOVE, link, Rule.NOT_STORED, reason)


class AddLinkCommand(LinksCommand):
    def __init__(self, doc: Document, link: Link, parent: QUndoCommand | None = None) -> None:
        super().__init__(doc, [_action("add", link, "linked by hand")],
                         _tr("Link {0}").format(_names(doc).link(link)), parent=parent)
        self.link = link


class RemoveLinkCommand(LinksCommand):
    def __init__(self, doc: Document, link: Link, parent: QUndoCommand | None = None) -> None:
        super().__init__(doc, [_action("remove", link, "removed by hand")],
                         _tr("Remove link {0}").format(_names(doc).link(link)), parent=parent)
        self.link = link


#: Fields a user may stage for a live device (node IDs and the inputs' source fields are
#: the arbitrator's: they follow the links).
LIVE_CHANNEL_PARAMS = pending.CHANNEL_PARAMS
LIVE_DEVICE_PARAMS = pending.DEVICE_PARAMS


def live_write_refusal(doc: Document, name: str, *, device: bool) -> str | None:
    """Why a field may not be staged on a live bus (None: it may; Write to prosthesis
    writes it)."""
    if doc.session is None:
        return None
    return live_sync.staging_refusal(name, device=device)


class SetChannelFieldCommand(QUndoCommand):
    """One channel field (on a live bus: staged, written by Write to prosthesis)."""

    def __init__(self, doc: Document, ref: ChannelRef, name: str, value: Any,
                 text: str = "", parent: QUndoCommand | None = None) -> None:
        super().__init__(text or field_words(doc, ref.device, ref.index, name, value), parent)
        self.doc, self.ref, self.name, self.value = doc, ref, name, value
        self.old = getattr(doc.channel(ref), name)

    def redo(self) -> None:
        self.doc.set_channel_field(self.ref, self.name, self.value)

    def undo(self) -> None:
        self.doc.set_channel_field(self.ref, self.name, self.old)


class SetDeviceFieldCommand(QUndoCommand):
    """One device field (on a live bus: staged, written by Write to prosthesis)."""

    def __init__(self, doc: Document, key: DeviceKey, name: str, value: Any,
                 text: str = "", parent: QUndoCommand | None = None) -> None:
        super().__init__(text or field_words(doc, key, 0, name, value), parent)
        self.doc, self.key, self.name, self.value = doc, key, name, value
        self.old = getattr(doc.device(key), name)

    def redo(self) -> None:
        self.doc.set_device_field(self.key, self.name, self.value)

    def undo(self) -> None:
        self.doc.set_device_field(self.key, self.name, self.old)


class MoveDeviceCommand(QUndoCommand):
    """A card moved. Consecutive moves of the same drag merge (``drag_id``)."""

    def __init__(self, doc: Document, key: DeviceKey, old: Position | None, new: Position,
                 drag_id: int = 0, parent: QUndoCommand | None = None) -> None:
        super().__init__(_tr("Move {0}").format(part_name(doc.system, key)), parent)
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
        super().__init__(count("Commands", "Move %n part(s)", n), parent)
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


def push_add_link(doc: Document, link: Link) -> bool:
    """Add a link as one undo step (on a live bus: a staged change)."""
    if doc.system.has_link(link):
        return False
    doc.undo_stack.push(AddLinkCommand(doc, link))
    return True


def push_remove_links(doc: Document, links: Iterable[Link]) -> int:
    """Remove links as one undo step; returns how many."""
    links = [lk for lk in links if doc.system.has_link(lk)]
    if not links:
        return 0
    text = (_tr("Remove link {0}").format(_names(doc).link(links[0])) if len(links) == 1
            else _tr("Remove {0} links").format(len(links)))
    doc.undo_stack.push(LinksCommand(
        doc, [_action("remove", lk, "removed by hand") for lk in links], text))
    return len(links)


def push_plan(doc: Document, plan: Any, text: str = "") -> bool:
    """A plan's actions as one undo step, in order, through the engine's one apply path
    (the same system the CLI's ``apply`` produces, source fields included); False if it
    does nothing."""
    actions = list(getattr(plan, "actions", ()))
    if not actions:
        return False
    mode = getattr(plan, "mode", "plan")
    doc.undo_stack.push(LinksCommand(
        doc, actions, text or count("Commands", "Apply the plan (%n step(s))", len(actions)),
        mode=mode))
    return True
