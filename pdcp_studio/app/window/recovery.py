"""Crash recovery for the main window: autosaving the document and offering it back.

Kept apart from :mod:`main_window`; the autosaver and the dialog themselves are in
:mod:`pdcp_studio.app.documents.recovery`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pdcp_studio.app.documents import files
from pdcp_studio.errors import PdcpError


class RecoveryMixin:
    """Autosave while editing; after a crash, offer and restore what was autosaved."""

    if TYPE_CHECKING:  # a mixin of a QObject: Qt gives it tr()
        tr: Callable[[str], str]

    def _start_autosave(self, recovery: Any) -> None:
        from pdcp_studio.app.documents import recovery as mod

        doc = self.doc
        self.autosaver = mod.Autosaver(
            recovery, lambda: str(doc.path) if doc.path else "untitled",
            lambda: files.system_text(doc.system, doc.positions),
            path_fn=lambda: str(doc.path) if doc.path else None, parent=self)
        self.autosaver.error.connect(self.show_message)
        self.autosaver.watch(doc)

    def offer_recovery(self) -> bool:
        """After a crash: offer the autosaved documents; True if one was restored."""
        from pdcp_studio.app.documents import recovery as mod

        if self.recovery is None:
            return False
        pending = self.recovery.pending()
        if not pending:
            return False
        dialog = mod.RecoveryDialog(pending, self)
        chosen = dialog.chosen() if dialog.exec() == dialog.DialogCode.Accepted else []
        for entry in pending:
            if not chosen or entry is not chosen[0]:
                self.recovery.discard(entry.name)
        if not chosen:
            return False
        return self.restore(chosen[0])

    def restore(self, entry: Any) -> bool:
        """Show an autosaved document, marked unsaved (its file, if any, is older)."""
        try:
            opened = files.loads_system(entry.text, entry.name)
        except PdcpError as err:
            self.error_box(self.tr("Cannot recover"), str(err))
            return False
        self.doc.set_system(opened.system, entry.path, None, dirty=True,
                            positions=opened.positions)
        self._loaded()
        self.show_message(self.tr("Recovered unsaved work: {title}").format(title=entry.title))
        return True
