"""The open document: one system, its profile tree, undo stack, selection and preview.

Every widget wraps this object and subscribes to its signals (napari's habit); undo
commands (:mod:`pdcp_studio.app.documents.commands`) change the model only through the mutators
here, which emit the matching signal, so views never drift from the model.

Signals
    ``systemReset()``          a different system was set (rebuild everything)
    ``linksChanged()``         links were added or removed
    ``deviceChanged(key)``     a device field changed (``DeviceKey``)
    ``channelChanged(ref)``    a channel field changed (``ChannelRef``)
    ``selectionChanged(obj)``  ``DeviceKey`` | ``ChannelRef`` | ``Link`` | None
    ``dirtyChanged(bool)``     unsaved changes appeared or were saved
    ``previewChanged(plan)``   a plan is previewed (or None: preview cleared)
    ``positionChanged(key)``   a device card's remembered position changed
    ``pathChanged(path)``      the file behind the document changed (Path or None)
    ``sessionChanged(obj)``    a live session was bound (or None: offline)
    ``busChanged()``           the prosthesis was seen anew and differs (``bus_system``; pending)
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, QTimer, Signal
from PySide6.QtGui import QUndoStack

from pdcp_studio.app.documents import live_sync
from pdcp_studio.errors import ModelError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.profile_tree import ProfileNames, ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link, System
from pdcp_studio.storage.profile_trees import load_profile_trees, tree_for

if TYPE_CHECKING:
    from pdcp_studio.app.live.session_bridge import SessionBridge

log = logging.getLogger(__name__)

Selection = DeviceKey | ChannelRef | Link | None
Position = tuple[float, float]

#: Undo commands that only move cards (a live view is not dirty for them).
MOVE_COMMANDS = frozenset({"MoveDeviceCommand", "MoveDevicesCommand"})
#: A live view's layout is remembered this long after the last move.
LAYOUT_SAVE_MS = 400

#: Channel fields an edit may change (``Channel`` dataclass attributes).
CHANNEL_FIELDS = frozenset({
    "type", "profile", "terminal_profile", "required_inputs", "desired_inputs",
    "descriptor", "source", "node_id", "data_enabled",
})
#: Device fields an edit may change (``Device`` dataclass attributes).
DEVICE_FIELDS = frozenset({
    "name", "present", "descriptor", "node_id", "beacon_interval", "ack_timeout",
    "bind_timeout", "fw_version", "hw_version", "device_type", "device_profile",
    "ean_low", "ean_high",
})


class Document(QObject):
    """The system being looked at and edited, and everything the views share about it."""

    systemReset = Signal()
    linksChanged = Signal()
    deviceChanged = Signal(object)
    channelChanged = Signal(object)
    selectionChanged = Signal(object)
    dirtyChanged = Signal(bool)
    previewChanged = Signal(object)
    positionChanged = Signal(object)
    pathChanged = Signal(object)
    sessionChanged = Signal(object)
    busChanged = Signal()
    #: The connected prosthesis's profile-layer policy was read (``Policy`` or None).
    policyChanged = Signal(object)

    def __init__(self, system: System | None = None, *, tree: ProfileTree | None = None,
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.system: System = system if system is not None else System()
        #: The named profile trees (prosthetic, thesis test rig, the user's and vendors').
        self.trees: list[ProfileTree] = [tree] if tree is not None else load_profile_trees()
        #: The tree that names this system's channels (one of ``trees``).
        self.tree: ProfileNames = tree_for(self.trees, self.system)
        self.undo_stack = QUndoStack(self)
        self.path: Path | None = None
        self.session: SessionBridge | None = None
        self.preview_plan: Any = None
        #: Remembered card positions (scene coordinates), kept when a device leaves.
        self.positions: dict[DeviceKey, Position] = {}
        #: What kind of file ``path`` is: "system" or "config" (a .pdcfg opened as a view).
        self.kind = "system"
        #: The stored configuration plans use (an opened .pdcfg, or one read from a bus).
        self.config: Any = None
        #: The prosthesis as last seen (live only): what the project's edits are staged
        #: against. None offline.
        self.bus_system: System | None = None
        #: Why a link was staged (a plan's reason, "linked by hand"): for the pending list.
        self.link_reasons: dict[Link, str] = {}
        #: The connected prosthesis's profile-layer policy as last read (None: offline or
        #: not read yet); the checks follow it.
        self.policy: Any = None
        self._selection: Selection = None
        self._extra_dirty = False
        self._was_dirty = False
        self.undo_stack.cleanChanged.connect(self._on_clean_changed)
        # A live view's moves do not make it dirty, other edits do: follow every step.
        self.undo_stack.indexChanged.connect(self._on_index_changed)
        self._layout_timer = QTimer(self)
        self._layout_timer.setSingleShot(True)
        self._layout_timer.setInterval(LAYOUT_SAVE_MS)
        self._layout_timer.timeout.connect(self.remember_layout)

    # -- whole document -----------------------------------------------------------
    def set_system(self, system: System, path: Path | str | None = None,
                   session: SessionBridge | None = None,
                   *, dirty: bool = False, positions: dict[DeviceKey, Position] | None = None,
                   kind: str = "system", config: Any = None) -> None:
        """Show a different system: clears undo history, selection and preview.

        ``dirty`` marks a system that exists nowhere on disk yet (an autoconfigured
        default, a scan) so closing asks before dropping it.
        """
        self.system = system
        self.tree = tree_for(self.trees, system)
        self.path = Path(path) if path is not None else None
        self.kind, self.config = kind, config
        session_changed = session is not self.session
        self.session = session
        self.bus_system = system.copy() if session is not None else None
        self.preview_plan = None
        self._selection = None
        if positions is not None:
            self.positions = dict(positions)
            if self.is_live_view:  # as this prosthesis was last laid out, where remembered
                from pdcp_studio.app.live import layout as live_layout

                self.positions = live_layout.restore(system, self.positions, self.live_url)
        self.undo_stack.clear()
        self.undo_stack.setClean()
        self._extra_dirty = dirty
        self.systemReset.emit()
        self.previewChanged.emit(None)
        self.selectionChanged.emit(None)
        self.pathChanged.emit(self.path)
        if session_changed:
            self.sessionChanged.emit(session)
        self._emit_dirty()

    def sync_live(self, snapshot: System) -> bool:
        """Follow the live bus: a three-way merge of the prosthesis into the project
        (:func:`~pdcp_studio.app.documents.live_sync.merge_snapshot`), then the signals.

        ``bus_system`` is the prosthesis as last seen. What the bus owns (presence, node IDs,
        the inputs' source fields, versions) always follows the snapshot; a link or a
        writable field follows it unless the user changed it here since (a staged change,
        kept). Not an undo step: the bus changed, not the user.

        Returns False, having sent no signal, when the snapshot is the prosthesis exactly
        as last seen and the project follows from it unchanged (a rescan that finds the
        same bus): the views then have nothing to redraw, so back-to-back scans cost the
        GUI thread a comparison, not a rebuild of every card, row and check.

        The snapshot becomes ``bus_system`` as it is (a fresh copy from the session, never
        changed afterwards: copying it again cost the GUI thread ~4 ms per 254 devices).
        """
        result = live_sync.merge_snapshot(self.system, self.bus_system, snapshot)
        if result.unchanged:
            return False  # bus_system stays: it equals the snapshot
        self.bus_system = snapshot
        if result.added:
            live_sync.apply_links(self.system, result.links)
            self.systemReset.emit()
            self.busChanged.emit()
            return True
        for key in dict.fromkeys(result.changed_devices):
            self.deviceChanged.emit(key)
        for ref in result.changed_channels:
            self.channelChanged.emit(ref)
        if result.links_changed:
            self.set_links(result.links)
        self.busChanged.emit()
        return True

    def set_present(self, key: DeviceKey, present: bool) -> None:
        """A device joined or left the live bus (not an undo step)."""
        device = self.system.devices.get(key)
        if device is not None and device.present != present:
            device.present = present
            self.deviceChanged.emit(key)

    @property
    def autoconfigure(self) -> bool:
        """May the prosthesis autoconfigure on its own? (True offline: the thesis default.)"""
        return self.policy is None or bool(self.policy.autoconfigure)

    def set_policy(self, policy: Any) -> None:
        """The live prosthesis's policy as read (None: unknown); the checks follow it."""
        if policy != self.policy:
            self.policy = policy
            self.policyChanged.emit(policy)

    def set_session(self, session: SessionBridge | None) -> None:
        """Bind or unbind a live session without touching the system."""
        if session is not self.session:
            self.session = session
            if session is None:
                self.bus_system = None
                self.set_policy(None)
            self.sessionChanged.emit(session)
            self.busChanged.emit()

    def set_path(self, path: Path | str | None) -> None:
        self.path = Path(path) if path is not None else None
        self.pathChanged.emit(self.path)

    def mark_saved(self, path: Path | str | None = None) -> None:
        """After a successful save: the current state is the clean state."""
        if path is not None:
            self.set_path(path)
        self._extra_dirty = False
        self.undo_stack.setClean()
        self._emit_dirty()

    def mark_dirty(self) -> None:
        """A change that is not on the undo stack (e.g. a card moved before any save)."""
        self._extra_dirty = True
        self._emit_dirty()

    @property
    def is_live_view(self) -> bool:
        """The bus itself is the document (connected, no project file)."""
        return self.path is None and self.session is not None and self.kind == "system"

    @property
    def live_url(self) -> str:
        return str(getattr(self.session, "url", "") or "")

    def remember_layout(self) -> None:
        """Keep a live view's card positions for the next time this prosthesis connects."""
        self._layout_timer.stop()
        if self.is_live_view:
            from pdcp_studio.app.live import layout as live_layout

            live_layout.save(self.system, self.positions, self.live_url)

    def _only_moves_since_clean(self) -> bool:
        stack = self.undo_stack
        clean, index = stack.cleanIndex(), stack.index()
        if clean < 0:
            return False
        low, high = sorted((clean, index))
        return all(type(stack.command(i)).__name__ in MOVE_COMMANDS for i in range(low, high))

    @property
    def is_dirty(self) -> bool:
        """Changes that would be lost: a live view's card moves are not (they are
        remembered per prosthesis, :mod:`live_layout`), any other edit is."""
        try:
            clean = self.undo_stack.isClean()
            if not clean and self.is_live_view and self._only_moves_since_clean():
                clean = True
        except RuntimeError:  # the stack is being destroyed with us and still signals
            return self._extra_dirty
        return self._extra_dirty or not clean

    def _on_clean_changed(self, _clean: bool) -> None:
        self._emit_dirty()

    def _on_index_changed(self, _index: int) -> None:
        self._emit_dirty()

    def _emit_dirty(self) -> None:
        dirty = self.is_dirty
        if dirty != self._was_dirty:
            self._was_dirty = dirty
            self.dirtyChanged.emit(dirty)

    @property
    def title(self) -> str:
        """The name shown in the window title."""
        if self.path is not None:
            return self.path.name
        if self.session is not None:
            return str(getattr(self.session, "url", "live bus"))
        return "untitled"

    # -- selection ----------------------------------------------------------------
    @property
    def selection(self) -> Selection:
        return self._selection

    def select(self, obj: Selection) -> None:
        """Select a device, channel or link (None clears); views follow the signal."""
        if obj == self._selection:
            return
        self._selection = obj
        self.selectionChanged.emit(obj)

    # -- preview ------------------------------------------------------------------
    def set_preview(self, plan: Any) -> None:
        """Show a plan on the views without changing the system (None clears it)."""
        self.preview_plan = plan
        self.previewChanged.emit(plan)

    # -- lookups ------------------------------------------------------------------
    def device(self, key: DeviceKey) -> Device:
        device = self.system.device(key)
        if device is None:
            raise ModelError(f"no device {key} in this system")
        return device

    def channel(self, ref: ChannelRef) -> Channel:
        channel = self.system.channel(ref)
        if channel is None:
            raise ModelError(f"no channel {ref} in this system")
        return channel

    def set_trees(self, trees: list[ProfileTree]) -> None:
        """The named trees changed (edited): name this system from them again."""
        self.trees = list(trees)
        self.tree = tree_for(self.trees, self.system)

    def profile_name(self, profile: int) -> str:
        """Short profile name from the tree (hex when the tree does not know it)."""
        try:
            return self.tree.short_name(profile)
        except ValueError:
            return prof.fmt(profile)

    # -- mutators (called by undo commands; each emits its signal) -------------------
    def add_link(self, link: Link) -> None:
        self.system.add_link(link, check=False)
        self.linksChanged.emit()

    def remove_link(self, link: Link) -> None:
        if not self.system.has_link(link):
            return  # already gone (the live bus removed it): undo/redo stays harmless
        self.system.remove_link(link)
        if self._selection == link:
            self.select(None)
        self.linksChanged.emit()

    def set_links(self, links: Iterable[Link]) -> None:
        """Replace every link at once (plan apply/undo): one signal, not hundreds."""
        live_sync.apply_links(self.system, links)
        if isinstance(self._selection, Link) and not self.system.has_link(self._selection):
            self.select(None)
        self.linksChanged.emit()

    def links_state(self, links: Iterable[Link]) -> tuple[list[Link], dict[ChannelRef, Any]]:
        """The links and the link-kept fields (source, Data Transfer Enabled) of every end
        of ``links`` — what :meth:`restore_links_state` puts back (an undo)."""
        refs = {r for lk in links for r in (lk.output, lk.input)}
        fields = {}
        for ref in refs:
            ch = self.system.channel(ref)
            if ch is not None:
                fields[ref] = (ch.source, ch.data_enabled)
        return list(self.system.links), fields

    def restore_links_state(self, state: tuple[list[Link], dict[ChannelRef, Any]]) -> None:
        """Put links back (through the one apply path), then the link-kept fields exactly
        as they were (an undo restores a file's own values too)."""
        from pdcp_studio.engine import set_links

        links, fields = state
        set_links(self.system, links)
        for ref, (source, enabled) in fields.items():
            ch = self.system.channel(ref)
            if ch is not None:
                ch.source, ch.data_enabled = source, enabled
        self._links_done(fields)

    def apply_plan_actions(self, plan: Any) -> None:
        """Carry a plan's actions out with the engine's ONE offline apply path
        (``engine.set_links``: links, the inputs' source fields, Data Transfer Enabled — the
        system the CLI's ``apply`` writes for the same plan)."""
        from pdcp_studio.engine import set_links

        set_links(self.system, live_sync.links_after(self.system.links, plan.actions))
        for a in plan.actions:
            self.link_reasons[a.link] = a.reason
        self._links_done({r for a in plan.actions for r in (a.link.output, a.link.input)})

    def _links_done(self, refs: Iterable[ChannelRef]) -> None:
        if isinstance(self._selection, Link) and not self.system.has_link(self._selection):
            self.select(None)
        self.linksChanged.emit()
        for ref in refs:
            self.channelChanged.emit(ref)

    def set_channel_field(self, ref: ChannelRef, name: str, value: Any) -> None:
        if name not in CHANNEL_FIELDS:
            raise ModelError(f"channel field {name!r} cannot be edited")
        channel = self.channel(ref)
        if name in ("required_inputs", "desired_inputs"):
            value = tuple(sorted(value))
        setattr(channel, name, value)
        self.channelChanged.emit(ref)

    def set_device_field(self, key: DeviceKey, name: str, value: Any) -> None:
        if name not in DEVICE_FIELDS:
            raise ModelError(f"device field {name!r} cannot be edited")
        setattr(self.device(key), name, value)
        self.deviceChanged.emit(key)

    def set_position(self, key: DeviceKey, pos: Position) -> None:
        self.positions[key] = (float(pos[0]), float(pos[1]))
        self.positionChanged.emit(key)
        if self.is_live_view:
            self._layout_timer.start()  # remembered once the drag has settled

    def add_device(self, device: Device) -> None:
        self.system.add_device(device)
        self.systemReset.emit()

    def remove_device(self, key: DeviceKey) -> Device:
        device = self.system.remove_device(key)
        if self._selection is not None and _device_of(self._selection) == key:
            self.select(None)
        self.systemReset.emit()
        return device

    def replace_device(self, device: Device) -> None:
        """Swap in a changed copy of a device (same key) — e.g. a rescan of one node."""
        self.system.devices[device.key] = device
        self.deviceChanged.emit(device.key)

    def copy_channel(self, ref: ChannelRef, **changes: Any) -> Channel:
        """A changed copy of a channel (for computing an edit without applying it)."""
        return replace(self.channel(ref), **changes)


def _device_of(obj: Selection) -> DeviceKey | None:
    if isinstance(obj, DeviceKey):
        return obj
    if isinstance(obj, ChannelRef):
        return obj.device
    if isinstance(obj, Link):
        return obj.input.device
    return None
