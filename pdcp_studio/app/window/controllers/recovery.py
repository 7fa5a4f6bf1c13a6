"""Crash recovery for the main window: autosaving the document and offering it back.

The autosaver, the store and the dialog themselves are in
:mod:`pdcp_studio.app.documents.recovery`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtWidgets import QWidget

from pdcp_studio.app.documents import files
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.i18n import translate
from pdcp_studio.app.window.status import StatusLine
from pdcp_studio.errors import PdcpError

_CTX = "WindowRecovery"


class RecoveryController:
    """Autosave while editing into ``store`` (None: no recovery); after a crash, offer
    and restore what was autosaved. ``loaded()`` puts a restored system on screen."""

    def __init__(self, doc: Document, store: Any, status: StatusLine, parent: QWidget,
                 loaded: Callable[[], None]) -> None:
        self.doc = doc
        self.store = store
        self.status = status
        self.parent = parent
        self._loaded = loaded
        self.autosaver: Any = None
        if store is not None:
            self._start_autosave()

    def _start_autosave(self) -> None:
        from pdcp_studio.app.documents import recovery as mod

        doc = self.doc
        self.autosaver = mod.Autosaver(
            self.store, lambda: str(doc.path) if doc.path else "untitled",
            lambda: files.system_text(doc.system, doc.positions),
            path_fn=lambda: str(doc.path) if doc.path else None, parent=self.parent)
        self.autosaver.error.connect(self.status.say)
        self.autosaver.watch(doc)

    def offer_recovery(self) -> bool:
        """After a crash: offer the autosaved documents; True if one was restored."""
        from pdcp_studio.app.documents import recovery as mod

        if self.store is None:
            return False
        pending = self.store.pending()
        if not pending:
            return False
        dialog = mod.RecoveryDialog(pending, self.parent)
        chosen = dialog.chosen() if dialog.exec() == dialog.DialogCode.Accepted else []
        for entry in pending:
            if not chosen or entry is not chosen[0]:
                self.store.discard(entry.name)
        if not chosen:
            return False
        return self.restore(chosen[0])

    def restore(self, entry: Any) -> bool:
        """Show an autosaved document, marked unsaved (its file, if any, is older)."""
        try:
            opened = files.loads_system(entry.text, entry.name)
        except PdcpError as err:
            self.status.error(translate(_CTX, "Cannot recover"), str(err))
            return False
        self.doc.set_system(opened.system, entry.path, None, dirty=True,
                            positions=opened.positions)
        self._loaded()
        self.status.say(translate(_CTX, "Recovered unsaved work: {title}")
                        .format(title=entry.title))
        return True

    def clean(self) -> None:
        """Closed on purpose: nothing to recover next time."""
        if self.autosaver is not None:
            self.autosaver.clean()
