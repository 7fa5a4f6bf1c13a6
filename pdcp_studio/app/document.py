"""The open document: one system, its profile tree, undo stack, selection and preview.

Every widget wraps this object and subscribes to its signals (napari's habit); undo
commands (:mod:`pdcp_studio.app.commands`) change the model only through the mutators
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
"""

from __future__ import annotations

import json
import logging
from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, Signal
from PySide6.QtGui import QUndoStack

from pdcp_studio.errors import ModelError, ProfileError
from pdcp_studio.model import profile as prof
from pdcp_studio.model.profile_tree import ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link, System

log = logging.getLogger(__name__)

Selection = DeviceKey | ChannelRef | Link | None
Position = tuple[float, float]

#: Profile trees shipped in resources/profiles, merged in this order (first wins a name).
BUILTIN_TREES = ("thesis-fig4.6.json", "thesis-tests.json")

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


def user_profiles_dir() -> Path | None:
    """Where user and vendor profile trees live (the user's data folder, ``profiles``)."""
    from pdcp_studio.paths import user_profiles_dir as folder

    return folder()


def load_profile_tree(extra: Iterable[Path] = (), *, user_dir: bool = True) -> ProfileTree:
    """The built-in trees merged with user trees; a broken user file is logged, not fatal."""
    from pdcp_studio.paths import profiles_dir

    files = [profiles_dir() / name for name in BUILTIN_TREES]
    udir = user_profiles_dir() if user_dir else None
    if udir is not None and udir.is_dir():
        files += sorted(udir.glob("*.json"))
    files += list(extra)
    tree = ProfileTree("profiles")
    for path in files:
        try:
            part = ProfileTree.from_json(json.loads(Path(path).read_text("utf-8")), str(path))
        except (OSError, ValueError, ProfileError) as err:
            log.warning("profile tree %s skipped: %s", path, err)
            continue
        tree = tree.merged(part)
    return tree


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

    def __init__(self, system: System | None = None, *, tree: ProfileTree | None = None,
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.system: System = system if system is not None else System()
        self.tree: ProfileTree = tree if tree is not None else load_profile_tree()
        self.undo_stack = QUndoStack(self)
        self.path: Path | None = None
        self.session: Any = None
        self.preview_plan: Any = None
        #: Remembered card positions (scene coordinates), kept when a device leaves.
        self.positions: dict[DeviceKey, Position] = {}
        #: What kind of file ``path`` is: "system" or "config" (a .pdcfg opened as a view).
        self.kind = "system"
        #: The stored configuration plans use (an opened .pdcfg, or one read from a bus).
        self.config: Any = None
        self._selection: Selection = None
        self._extra_dirty = False
        self._was_dirty = False
        self.undo_stack.cleanChanged.connect(self._on_clean_changed)

    # -- whole document -----------------------------------------------------------
    def set_system(self, system: System, path: Path | str | None = None, session: Any = None,
                   *, dirty: bool = False, positions: dict[DeviceKey, Position] | None = None,
                   kind: str = "system", config: Any = None) -> None:
        """Show a different system: clears undo history, selection and preview.

        ``dirty`` marks a system that exists nowhere on disk yet (an autoconfigured
        default, a scan) so closing asks before dropping it.
        """
        self.system = system
        self.path = Path(path) if path is not None else None
        self.kind, self.config = kind, config
        session_changed = session is not self.session
        self.session = session
        self.preview_plan = None
        self._selection = None
        if positions is not None:
            self.positions = dict(positions)
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

    def sync_live(self, snapshot: System) -> None:
        """Follow the live bus: presence, node IDs, new devices and the links.

        Devices the snapshot lacks stay, marked missing (their card shows it); devices it
        has keep their objects (so local parameter edits survive) with presence and node
        IDs updated. Not an undo step: the bus changed, not the user.
        """
        system = self.system
        added = False
        for key, device in snapshot.devices.items():
            mine = system.devices.get(key)
            if mine is None:
                system.add_device(device)
                added = True
                continue
            changed = mine.present != device.present or mine.node_id != device.node_id
            mine.present, mine.node_id = device.present, device.node_id
            for index, ch in device.channels.items():
                own = mine.channels.get(index)
                if own is not None and own.node_id != ch.node_id:
                    own.node_id = ch.node_id
            if changed and not added:
                self.deviceChanged.emit(key)
        for key, mine in system.devices.items():
            if key not in snapshot.devices and mine.present:
                mine.present = False
                if not added:
                    self.deviceChanged.emit(key)
        links = [lk for lk in snapshot.links
                 if system.channel(lk.output) is not None and system.channel(lk.input)]
        if added:
            system.clear_links()
            for link in links:
                system.add_link(link, check=False)
            self.systemReset.emit()
        elif set(links) != set(system.links):
            self.set_links(links)

    def set_present(self, key: DeviceKey, present: bool) -> None:
        """A device joined or left the live bus (not an undo step)."""
        device = self.system.devices.get(key)
        if device is not None and device.present != present:
            device.present = present
            self.deviceChanged.emit(key)

    def set_session(self, session: Any) -> None:
        """Bind or unbind a live session without touching the system."""
        if session is not self.session:
            self.session = session
            self.sessionChanged.emit(session)

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
    def is_dirty(self) -> bool:
        try:
            clean = self.undo_stack.isClean()
        except RuntimeError:  # the stack is being destroyed with us and still signals
            return self._extra_dirty
        return self._extra_dirty or not clean

    def _on_clean_changed(self, _clean: bool) -> None:
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
        self.system.clear_links()
        for link in links:
            self.system.add_link(link, check=False)
        if isinstance(self._selection, Link) and not self.system.has_link(self._selection):
            self.select(None)
        self.linksChanged.emit()

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
