"""Crash recovery: unsaved documents are autosaved to recovery files and offered on next start.

Public API
    ``Recovery(directory=None)`` — the store. ``directory`` defaults to
    ``QStandardPaths.AppDataLocation``/``recovery`` (tests pass a temporary directory).
    ``save(name, text, *, path=None, kind="system") -> Path`` writes one entry atomically
    (``storage.atomic``); ``pending() -> list[RecoveryEntry]`` lists entries left by processes
    that are no longer running (i.e. after a crash), newest first; ``entries()`` lists all;
    ``discard(name)`` removes one (after a clean save or close, or when the user declines).
    ``name`` identifies the document (its file path, or ``untitled`` for a new one).

    ``Autosaver(recovery, name_fn, text_fn, *, interval_ms=5000, parent=None)`` — a QObject
    that autosaves while a document is dirty. Call ``changed()`` after every edit (or
    ``watch(document)`` to connect a ``Document``'s signals); it saves at most once per
    ``interval_ms`` — the text is made on the GUI thread, the file is written on a worker.
    ``clean()`` discards the entry (a clean save or close). Signals: ``saved(Path)``,
    ``error(str)``.

    ``RecoveryDialog(entries, parent=None)`` — lists pending entries; ``chosen()`` gives the
    entries the user ticked to restore after ``Restore``.

    ``offer_recovery(recovery, parent=None, ask=None) -> list[RecoveryEntry]`` — at start-up:
    if there are pending entries, show the dialog (``ask(dialog) -> bool`` replaces the modal
    ``exec`` in tests), discard every entry not chosen and return the chosen ones; the caller
    opens each (``restore_system(entry)`` for a system) as an unsaved document, whose
    autosaver then takes the entry over (same name) and clears it on a clean save.

Entries are JSON (``pdcp-recovery/1``) with the text, the original path, the kind, the saving
process id and the time. A process never offers its own or a live process's entries, so two
running windows do not steal each other's autosaves.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import hashlib
import json
import logging
import os
import threading
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, QStandardPaths, Qt, QTimer, Signal
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.workers import Worker
from pdcp_studio.storage.atomic import atomic_write_text

log = logging.getLogger(__name__)

RECOVERY_FORMAT = "pdcp-recovery/1"
SUFFIX = ".recovery.json"
DEFAULT_INTERVAL_MS = 5000


def default_directory() -> Path:
    """``AppDataLocation/recovery`` (the application and organisation names pick the folder)."""
    base = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.AppDataLocation)
    return Path(base or Path.home() / ".pdcp-studio") / "recovery"


def _pid_alive(pid: int) -> bool:
    """Whether a process with this id runs (POSIX signal 0; elsewhere assume it died)."""
    if pid <= 0:
        return False
    if pid == os.getpid():
        return True
    if os.name != "posix":
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # someone else's process with that id: not ours to offer either
    except OSError:
        return False
    return True


@dataclass(frozen=True)
class RecoveryEntry:
    """One autosaved document."""

    name: str
    text: str
    path: str | None
    kind: str
    saved_at: str  # ISO 8601, UTC
    pid: int
    file: Path

    @property
    def title(self) -> str:
        """A line for the recovery dialog: file name and autosave time."""
        shown = Path(self.path).name if self.path else self.name
        when = self.saved_at.replace("T", " ")[:19]
        return f"{shown} — autosaved {when} UTC"


class Recovery:
    """The recovery files in one directory (created on the first save)."""

    def __init__(self, directory: str | Path | None = None) -> None:
        self.directory = Path(directory) if directory is not None else default_directory()
        self._lock = threading.Lock()  # saves may come from a worker thread

    def file_for(self, name: str) -> Path:
        """The recovery file of the document ``name``."""
        digest = hashlib.sha256(name.encode("utf-8")).hexdigest()[:20]
        return self.directory / f"{digest}{SUFFIX}"

    def save(self, name: str, text: str, *, path: str | Path | None = None,
             kind: str = "system") -> Path:
        """Write (replace) the entry for ``name`` atomically; returns its file."""
        doc = {
            "format": RECOVERY_FORMAT,
            "name": name,
            "path": None if path is None else str(path),
            "kind": kind,
            "saved_at": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
            "pid": os.getpid(),
            "text": text,
        }
        target = self.file_for(name)
        with self._lock:
            self.directory.mkdir(parents=True, exist_ok=True)
            atomic_write_text(target, json.dumps(doc, ensure_ascii=False))
        return target

    def _read(self, file: Path) -> RecoveryEntry | None:
        try:
            doc = json.loads(file.read_text("utf-8"))
            if doc.get("format") != RECOVERY_FORMAT:
                raise ValueError("not a recovery file")
            return RecoveryEntry(str(doc["name"]), str(doc["text"]), doc.get("path"),
                                 str(doc.get("kind", "system")), str(doc.get("saved_at", "")),
                                 int(doc.get("pid", 0)), file)
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as err:
            log.warning("ignoring unreadable recovery file %s: %s", file, err)
            return None

    def entries(self) -> list[RecoveryEntry]:
        """Every readable entry, newest first."""
        if not self.directory.is_dir():
            return []
        found = (self._read(f) for f in self.directory.glob(f"*{SUFFIX}"))
        return sorted((e for e in found if e is not None), key=lambda e: e.saved_at,
                      reverse=True)

    def pending(self) -> list[RecoveryEntry]:
        """Entries whose process has ended without discarding them: left by a crash."""
        return [e for e in self.entries() if not _pid_alive(e.pid)]

    def discard(self, name: str) -> bool:
        """Remove the entry for ``name``; True if there was one."""
        with self._lock:
            try:
                self.file_for(name).unlink()
            except FileNotFoundError:
                return False
        return True


class Autosaver(QObject):
    """Autosave one document while it is dirty (see the module docstring)."""

    saved = Signal(object)
    error = Signal(str)

    def __init__(self, recovery: Recovery, name_fn: Callable[[], str],
                 text_fn: Callable[[], str], *, interval_ms: int = DEFAULT_INTERVAL_MS,
                 path_fn: Callable[[], Any] | None = None,
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.recovery = recovery
        self._name_fn, self._text_fn, self._path_fn = name_fn, text_fn, path_fn
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(interval_ms)
        self._timer.timeout.connect(self.save_now)
        self._saved_name: str | None = None
        self._worker: Worker | None = None
        self._generation = 0  # bumped by clean(): a save in flight must not resurrect

    def changed(self) -> None:
        """The document changed: autosave within ``interval_ms`` (once per interval)."""
        if not self._timer.isActive():
            self._timer.start()

    def save_now(self) -> Worker | None:
        """Make the text now (GUI thread) and write it on a worker."""
        self._timer.stop()
        try:
            name, text = self._name_fn(), self._text_fn()
            path = self._path_fn() if self._path_fn else None
        except Exception as err:  # a model that cannot serialise must not break editing
            self.error.emit(self.tr("Autosave: {err}").format(err=err))
            return None
        if self._saved_name is not None and self._saved_name != name:
            self.recovery.discard(self._saved_name)  # the document was renamed
        self._saved_name = name
        generation = self._generation
        recovery = self.recovery

        def work(_p: Any, _c: threading.Event) -> Path:
            return recovery.save(name, text, path=path)

        worker = Worker(work, "Autosave")
        worker.finished.connect(lambda file: self._written(file, name, generation))
        worker.failed.connect(
            lambda msg: self.error.emit(self.tr("Autosave: {msg}").format(msg=msg))
        )
        self._worker = worker
        return worker.start()

    def _written(self, file: Path, name: str, generation: int) -> None:
        if generation != self._generation:  # cleaned while the write was in flight
            self.recovery.discard(name)
            return
        self.saved.emit(file)

    def clean(self) -> None:
        """The document was saved or closed cleanly: drop its recovery entry."""
        self._timer.stop()
        self._generation += 1
        if self._worker is not None:
            self._worker.wait(5.0)
        names = {self._saved_name}
        with contextlib.suppress(Exception):
            names.add(self._name_fn())
        for name in names - {None}:
            self.recovery.discard(str(name))
        self._saved_name = None

    def watch(self, document: Any) -> None:
        """Follow a ``Document``: autosave on edits while dirty, clean when it turns clean."""

        def on_change(*_args: Any) -> None:
            if document.is_dirty:
                self.changed()

        for name in ("linksChanged", "deviceChanged", "channelChanged", "systemReset"):
            getattr(document, name).connect(on_change)
        document.undo_stack.indexChanged.connect(on_change)
        document.dirtyChanged.connect(lambda dirty: self.changed() if dirty else self.clean())


class RecoveryDialog(QDialog):
    """Offer autosaved documents after a crash; ``chosen()`` after ``Restore``."""

    def __init__(self, entries: Iterable[RecoveryEntry], parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Recover unsaved work"))
        self.entries = list(entries)
        self.list = QListWidget()
        for entry in self.entries:
            item = QListWidgetItem(entry.title)
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
            item.setCheckState(Qt.CheckState.Checked)
            item.setToolTip(entry.path or entry.name)
            self.list.addItem(item)
        buttons = QDialogButtonBox()
        self.restore_button = buttons.addButton(self.tr("Restore"),
                                                QDialogButtonBox.ButtonRole.AcceptRole)
        self.discard_button = buttons.addButton(self.tr("Discard all"),
                                                QDialogButtonBox.ButtonRole.RejectRole)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(
            QLabel(
                self.tr(
                    "PDCP Studio did not close cleanly. These unsaved documents were autosaved:"
                )
            )
        )
        layout.addWidget(self.list)
        layout.addWidget(buttons)

    def chosen(self) -> list[RecoveryEntry]:
        """The ticked entries (meaningful after the dialog was accepted)."""
        return [e for i, e in enumerate(self.entries)
                if self.list.item(i).checkState() == Qt.CheckState.Checked]


def offer_recovery(recovery: Recovery, parent: QWidget | None = None,
                   ask: Callable[[RecoveryDialog], bool] | None = None) -> list[RecoveryEntry]:
    """Offer what a crash left behind; returns the entries to restore (see the module doc)."""
    entries = recovery.pending()
    if not entries:
        return []
    dialog = RecoveryDialog(entries, parent)
    try:
        accepted = ask(dialog) if ask is not None else (
            dialog.exec() == QDialog.DialogCode.Accepted)
        chosen = dialog.chosen() if accepted else []
    finally:
        dialog.deleteLater()
    for entry in entries:
        if entry not in chosen:
            recovery.discard(entry.name)
    return chosen


def restore_system(entry: RecoveryEntry) -> Any:
    """The ``System`` an entry holds (SystemFileError names the problem)."""
    from pdcp_studio.storage import system_file

    return system_file.loads(entry.text, entry.path or entry.name)
