"""An open stored-configuration file (``.pdcfg``) as a document: its collection, the
configuration being looked at, undo, and lossless saving.

A configuration file is not a system: it holds links and each linked channel's type and
profile, several configurations of them, and records other tools wrote that PDCP Studio
does not understand (kept: reference §3). So it gets its own document instead of being
turned into a system. Every edit is a pure function of :mod:`pdcp_studio.model.config_edit`
pushed as one undo step holding the collection before and after; saving writes the
collection with the codec, atomically, unknown records in place.

Signals
    ``changed()``             the collection changed (an edit, undo or redo)
    ``currentChanged(int)``   another configuration is being looked at (position)
    ``dirtyChanged(bool)``    unsaved changes appeared or were saved
    ``pathChanged(object)``   the file behind the document (Path or None)
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QCoreApplication, QObject, Signal
from PySide6.QtGui import QUndoCommand, QUndoStack

from pdcp_studio.app.i18n import translate
from pdcp_studio.model import config_edit as edit
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
)
from pdcp_studio.model.refs import ChannelRef


def load_config_file(path: str | Path) -> ConfigCollection:
    """Read a ``.pdcfg`` file; the error names the file (ConfigFormatError, OSError)."""
    from pdcp_studio.errors import ConfigFormatError
    from pdcp_studio.storage import config_codec
    from pdcp_studio.storage.regular_file import NotARegularFile

    try:
        return config_codec.load_path(path)
    except NotARegularFile as err:  # a FIFO or a device: bad input, like a bad file
        raise ConfigFormatError(f"{path}: cannot read: {err.strerror}") from None
    except ConfigFormatError as err:
        named = ConfigFormatError(f"{path}: {err}")
        named.offset, named.reason = err.offset, err.reason
        raise named from None


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigDocument", text)


class CollectionCommand(QUndoCommand):
    """One edit: the collection (and the configuration looked at) before and after."""

    def __init__(self, doc: ConfigDocument, text: str, after: ConfigCollection,
                 current: int) -> None:
        super().__init__(text)
        self.doc = doc
        self.before, self.before_current = doc.collection, doc.current
        self.after, self.after_current = after, current

    def redo(self) -> None:
        self.doc._set(self.after, self.after_current)

    def undo(self) -> None:
        self.doc._set(self.before, self.before_current)


class ConfigDocument(QObject):
    """A stored-configuration collection being looked at and edited."""

    changed = Signal()
    currentChanged = Signal(int)
    dirtyChanged = Signal(bool)
    pathChanged = Signal(object)

    def __init__(self, collection: ConfigCollection | None = None,
                 path: str | Path | None = None, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.collection = collection if collection is not None else ConfigCollection()
        self.path = Path(path) if path is not None else None
        self.current = 0 if self.collection.configurations else -1
        self.undo_stack = QUndoStack(self)
        self.undo_stack.cleanChanged.connect(self._on_clean_changed)

    @classmethod
    def open(cls, path: str | Path, parent: QObject | None = None) -> ConfigDocument:
        """Read a ``.pdcfg`` file (ConfigFormatError naming it / OSError on failure)."""
        return cls(load_config_file(path), path, parent)

    def _on_clean_changed(self, clean: bool) -> None:
        self.dirtyChanged.emit(not clean)

    # -- state ----------------------------------------------------------------------
    @property
    def is_dirty(self) -> bool:
        return not self.undo_stack.isClean()

    @property
    def title(self) -> str:
        return (
            self.path.name
            if self.path is not None
            else translate("ConfigDocument", "untitled.pdcfg")
        )

    def configuration(self, position: int | None = None) -> StoredConfiguration | None:
        """Configuration ``position`` (default: the current one), or None."""
        pos = self.current if position is None else position
        configs = self.collection.configurations
        return configs[pos] if 0 <= pos < len(configs) else None

    def set_current(self, position: int) -> None:
        """Look at another configuration (not an undo step)."""
        n = len(self.collection.configurations)
        position = min(max(position, 0), n - 1) if n else -1
        if position != self.current:
            self.current = position
            self.currentChanged.emit(position)

    def _set(self, collection: ConfigCollection, current: int) -> None:
        self.collection = collection
        moved = current != self.current
        self.current = current
        self.changed.emit()
        if moved:
            self.currentChanged.emit(current)

    def _push(self, text: str, after: ConfigCollection, current: int | None = None) -> None:
        n = len(after.configurations)
        cur = self.current if current is None else current
        cur = min(max(cur, 0), n - 1) if n else -1
        self.undo_stack.push(CollectionCommand(self, text, after, cur))

    # -- edits (each one undo step) -------------------------------------------------
    def add_configuration(self) -> None:
        after = edit.add_configuration(self.collection)
        self._push(
            translate("ConfigDocument", "Add configuration"), after, len(after.configurations) - 1
        )

    def duplicate_configuration(self, position: int | None = None) -> None:
        pos = self.current if position is None else position
        if self.configuration(pos) is None:
            return
        self._push(
            translate("ConfigDocument", "Duplicate configuration %1").replace("%1", str(pos + 1)),
            edit.duplicate_configuration(self.collection, pos),
            pos + 1,
        )

    def remove_configuration(self, position: int | None = None) -> None:
        pos = self.current if position is None else position
        if self.configuration(pos) is None:
            return
        self._push(
            translate("ConfigDocument", "Remove configuration %1").replace("%1", str(pos + 1)),
            edit.remove_configuration(self.collection, pos),
            pos,
        )

    def move_configuration(self, delta: int, position: int | None = None) -> None:
        """Move a configuration up (-1) or down (+1): its priority at start-up."""
        pos = self.current if position is None else position
        to = pos + delta
        if self.configuration(pos) is None or not 0 <= to < len(self.collection.configurations):
            return
        self._push(translate("ConfigDocument", "Move configuration %1").replace("%1", str(pos + 1)),
                   edit.move_configuration(self.collection, pos, to), to)

    def add_link(self, output: StoredChannel, input: StoredChannel) -> None:
        if self.configuration() is None:
            return
        self._push(
            translate("ConfigDocument", "Add link"),
            edit.add_link(self.collection, self.current, output, input),
        )

    def remove_links(self, link_positions: list[int]) -> None:
        if self.configuration() is None or not link_positions:
            return
        text = (
            translate("ConfigDocument", "Remove link")
            if len(link_positions) == 1
            else translate("ConfigDocument", "Remove links")
        )
        self._push(text, edit.remove_links(self.collection, self.current, link_positions))

    def set_channel(self, ref: ChannelRef, *, type: int | None = None,
                    profile: int | None = None) -> None:
        """Change a stored channel's type and/or profile (ValueError when out of range)."""
        if self.configuration() is None:
            return
        after = edit.set_channel(self.collection, self.current, ref, type=type,
                                 profile=profile)
        self._push(translate("ConfigDocument", "Edit channel %1").replace("%1", str(ref)), after)

    # -- files ----------------------------------------------------------------------
    def save(self, path: str | Path | None = None) -> Path:
        """Write the collection atomically (unknown records in place); marks it saved."""
        from pdcp_studio.storage import config_codec

        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("no file to save to")
        config_codec.save_path(self.collection, target)
        if target != self.path:
            self.path = target
            self.pathChanged.emit(target)
        self.undo_stack.setClean()
        return target

    def mark_saved(self) -> None:
        self.undo_stack.setClean()
