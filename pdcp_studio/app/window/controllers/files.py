"""Opening and saving the main window's document (dialogs, last folder, unsaved changes).

The file round trip in one place; reading and writing the formats themselves is
:mod:`pdcp_studio.app.documents.files`.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QFileDialog, QMessageBox, QWidget

from pdcp_studio.app.documents import files
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.live.live_bus import LiveController
from pdcp_studio.app.window.questions import LEAVE_COMPARE, LEAVE_DISCONNECT
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.app.window.support import FILE_FILTERS
from pdcp_studio.errors import PdcpError

_CTX = "WindowFiles"


def _t(text: str) -> str:
    return translate(_CTX, text)


def last_dir() -> str:
    """The folder the user last opened or saved in (home at first)."""
    return str(QSettings().value("files/last_dir", str(Path.home())))


def remember_dir(path: str) -> None:
    QSettings().setValue("files/last_dir", str(Path(path).parent))


class FileController:
    """Open, save, save as, and the ask-before-dropping-changes of one document.

    ``loaded()`` puts a new system on screen; ``open_config(path, collection)`` opens a
    stored configuration in a window of its own; ``compare(path)`` compares a file with
    the connected prosthesis; ``ask_leave_bus(path)`` and ``ask_save_changes()`` are the
    window's questions (tests answer them)."""

    def __init__(self, doc: Document, live: LiveController, status: StatusLine,
                 parent: QWidget, *, loaded: Callable[[], None],
                 is_ready: Callable[[], bool],
                 open_config: Callable[[Path, object], object],
                 compare: Callable[[Path], object],
                 ask_leave_bus: Callable[[Path | None], str],
                 ask_save_changes: Callable[[], QMessageBox.StandardButton]) -> None:
        self.doc = doc
        self.live = live
        self.status = status
        self.parent = parent
        self._loaded = loaded
        self._is_ready = is_ready
        self._open_config = open_config
        self._compare = compare
        self._ask_leave_bus = ask_leave_bus
        self._ask_save_changes = ask_save_changes

    def open_path(self, path: str | Path) -> bool:
        """Open a system file or a .pdcfg; errors go to a message box and return False.

        While connected, the connection is never dropped silently: the user chooses to
        compare the file with the prosthesis instead, to disconnect and open it, or to
        cancel (:meth:`confirm_leave_bus`). A stored configuration opens in a window of its
        own and leaves the connection alone.
        """
        if not files.is_config_path(Path(path)) and not self.confirm_leave_bus(Path(path)):
            return False
        try:
            opened = files.open_path(path)
        except (PdcpError, OSError) as err:
            self.status.error(_t("Cannot open"), str(err))
            return False
        self.show_opened(opened, Path(path))
        return True

    def show_opened(self, opened: files.Opened, path: Path | None) -> None:
        """Put a loaded file on screen (offline: ``open_path`` asked before leaving a bus).

        A stored configuration opens as its own document instead and leaves the bus alone."""
        if opened.kind == "config" and path is not None:
            self.show_configuration_document(opened, path)
            return
        self.live.disconnect_bus()
        self.doc.set_system(opened.system, path, None, positions=opened.positions,
                            kind=opened.kind, config=opened.config)
        what = "configuration" if opened.kind == "config" else "system"
        note = f" ({opened.note})" if opened.note else ""
        self.status.say(
            _t("Opened {what} {v1}: {n_devices} devices, {n_links} links{note}").format(
                what=what,
                v1=path.name if path else "",
                n_devices=len(opened.system.devices),
                n_links=len(opened.system.links),
                note=note,
            )
        )
        self._loaded()

    def show_configuration_document(self, opened: files.Opened, path: Path) -> None:
        """A .pdcfg opens as its own document window (configurations, checks, fit); this
        window stays on its prosthesis, which the configuration is fitted to."""
        self._open_config(path, opened.config)
        self.status.say(
            _t("Opened stored configurations {name} in their own window").format(
                name=path.name
            )
        )
        if not self._is_ready():
            self._loaded()

    def confirm_leave_bus(self, path: Path | None = None) -> bool:
        """True when it is fine to put another document on screen (not connected, or the
        user chose to disconnect); "compare" opens the comparison with the prosthesis."""
        if not self.live.is_live:
            return True
        answer = self._ask_leave_bus(path)
        if answer == LEAVE_COMPARE and path is not None:
            self._compare(path)
            return False
        if answer == LEAVE_DISCONNECT:
            self.live.disconnect_bus()
            return True
        return False

    def ask_open(self) -> None:
        if not self.maybe_save():
            return
        path, _ = QFileDialog.getOpenFileName(self.parent, _t("Open"), last_dir(),
                                              FILE_FILTERS)
        if path:
            remember_dir(path)
            self.open_path(path)

    def save(self) -> bool:
        if self.doc.path is None:
            return self.ask_save_as()
        return self.save_to(self.doc.path)

    def ask_save_as(self) -> bool:
        start = str(self.doc.path) if self.doc.path else str(Path(last_dir()) / "system.json")
        path, _ = QFileDialog.getSaveFileName(self.parent, _t("Save as"), start, FILE_FILTERS)
        if not path:
            return False
        remember_dir(path)
        return self.save_to(path)

    def save_to(self, path: str | Path) -> bool:
        """Save as a system file, or as a .pdcfg (links only) by the extension."""
        path = Path(path)
        try:
            if files.is_config_path(path):
                files.save_configuration(self.doc.system, path)
            else:
                files.save_system(self.doc.system, path, self.doc.positions)
        except (PdcpError, OSError, ValueError) as err:
            self.status.error(_t("Cannot save"), f"{path}: {err}")
            return False
        self.doc.kind = "config" if files.is_config_path(path) else "system"
        self.doc.mark_saved(path)
        self.status.say(_t("Saved {path}").format(path=path))
        return True

    def maybe_save(self) -> bool:
        """True when it is fine to drop the document (saved, discarded, or clean)."""
        self.doc.remember_layout()  # a live view's card positions: kept, never asked about
        if not self.doc.is_dirty:
            return True
        answer = self._ask_save_changes()
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard
