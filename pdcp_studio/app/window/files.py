"""Opening and saving documents from the main window (dialogs, last folder, unsaved changes).

Kept apart from :mod:`main_window` so the file round trip reads in one place; reading and
writing the formats themselves is :mod:`pdcp_studio.app.documents.files`.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QFileDialog, QMessageBox

from pdcp_studio.app.documents import files
from pdcp_studio.app.window.support import FILE_FILTERS
from pdcp_studio.errors import PdcpError


class FileHandlingMixin:
    """Open, save, save as, and the ask-before-dropping-changes of :class:`MainWindow`."""

    if TYPE_CHECKING:  # a mixin of a QObject: Qt gives it tr()
        tr: Callable[[str], str]

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
            self.error_box(self.tr("Cannot open"), str(err))
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
        self.show_message(
            self.tr("Opened {what} {v1}: {n_devices} devices, {n_links} links{note}").format(
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
        from pdcp_studio.app.documents.config_view import open_config_window

        open_config_window(self, path, opened.config)
        self.show_message(
            self.tr("Opened stored configurations {name} in their own window").format(
                name=path.name
            )
        )
        if not self.is_ready:
            self._loaded()
    #: ``ask_leave_bus`` answers.
    LEAVE_COMPARE, LEAVE_DISCONNECT, LEAVE_CANCEL = "compare", "disconnect", "cancel"

    def confirm_leave_bus(self, path: Path | None = None) -> bool:
        """True when it is fine to put another document on screen (not connected, or the
        user chose to disconnect); "compare" opens the comparison with the prosthesis."""
        if not self.live.is_live:
            return True
        answer = self.ask_leave_bus(path)
        if answer == self.LEAVE_COMPARE and path is not None:
            self.compare_with_prosthesis(path)
            return False
        if answer == self.LEAVE_DISCONNECT:
            self.live.disconnect_bus()
            return True
        return False

    def ask_leave_bus(self, path: Path | None) -> str:
        """Compare, disconnect or cancel (tests replace this method)."""
        box = QMessageBox(self)
        box.setIcon(QMessageBox.Icon.Question)
        box.setWindowTitle(self.tr("Connected to a prosthesis"))
        name = path.name if path is not None else self.tr("another document")
        box.setText(self.tr("This window is connected to the prosthesis on {0}.\n"
                            "Opening {1} ends that connection.").format(self.live.url, name))
        box.setInformativeText(self.tr("You can compare the file with the prosthesis "
                                       "instead, and stay connected."))
        compare = box.addButton(self.tr("Compare with the prosthesis"),
                                QMessageBox.ButtonRole.AcceptRole)
        leave = box.addButton(self.tr("Disconnect and open"),
                              QMessageBox.ButtonRole.DestructiveRole)
        box.addButton(QMessageBox.StandardButton.Cancel)
        if path is None:
            compare.setEnabled(False)
        box.setDefaultButton(compare if path is not None else leave)
        box.exec()
        clicked = box.clickedButton()
        if clicked is compare:
            return self.LEAVE_COMPARE
        if clicked is leave:
            return self.LEAVE_DISCONNECT
        return self.LEAVE_CANCEL

    def ask_open(self) -> None:
        if not self.maybe_save():
            return
        path, _ = QFileDialog.getOpenFileName(self, self.tr("Open"), self._last_dir(), FILE_FILTERS)
        if path:
            self._remember_dir(path)
            self.open_path(path)

    def save(self) -> bool:
        if self.doc.path is None:
            return self.ask_save_as()
        return self.save_to(self.doc.path)

    def ask_save_as(self) -> bool:
        start = str(self.doc.path) if self.doc.path else str(Path(self._last_dir())
                                                             / "system.json")
        path, _ = QFileDialog.getSaveFileName(self, self.tr("Save as"), start, FILE_FILTERS)
        if not path:
            return False
        self._remember_dir(path)
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
            self.error_box(self.tr("Cannot save"), f"{path}: {err}")
            return False
        self.doc.kind = "config" if files.is_config_path(path) else "system"
        self.doc.mark_saved(path)
        self.show_message(self.tr("Saved {path}").format(path=path))
        return True

    def maybe_save(self) -> bool:
        """True when it is fine to drop the document (saved, discarded, or clean)."""
        self.doc.remember_layout()  # a live view's card positions: kept, never asked about
        if not self.doc.is_dirty:
            return True
        answer = self.ask_save_changes()
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard

    def ask_save_changes(self) -> QMessageBox.StandardButton:
        """Save, Discard or Cancel (tests replace this method)."""
        SB = QMessageBox.StandardButton
        return QMessageBox.question(
            self,
            self.tr("Unsaved changes"),
            self.tr("Save the changes to {title}?").format(title=self.doc.title),
            SB.Save | SB.Discard | SB.Cancel,
            SB.Save,
        )

    def _last_dir(self) -> str:
        return str(QSettings().value("files/last_dir", str(Path.home())))

    def _remember_dir(self, path: str) -> None:
        QSettings().setValue("files/last_dir", str(Path(path).parent))
