"""The status bar's word on the fitting history: which archive, who is signed in.

The window signs in once, just after it opens (``documents/sign_in.py``): on the clinic's
PostgreSQL archive the server is asked (a password dialog when libpq finds none); on the
default SQLite file nothing is opened. The label says "signed in as …" (or read only, or not
signed in, with why in its tooltip) for the rest of the session.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QLabel, QStatusBar, QWidget

from pdcp_studio.app.documents import sign_in as signing


class ArchiveStatus:
    """The archive's label in ``bar``; :meth:`sign_in` (run once, soon after start)."""

    def __init__(self, bar: QStatusBar, parent: QWidget,
                 signed_in: Callable[[], None] | None = None) -> None:
        self._parent = parent
        self._signed_in = signed_in  # who else shows the operator (the pending panel)
        self.label = QLabel()
        bar.addPermanentWidget(self.label)
        from pdcp_studio.storage.archive import archive_url, describe
        from pdcp_studio.storage.archive.open import is_postgres

        url = archive_url()
        if is_postgres(url):
            existing = signing.current()  # once per session: a second window reuses it
            if existing is not None and existing.role and existing.location == describe(url):
                self.show(existing)
            else:
                QTimer.singleShot(0, self.sign_in)
        else:
            self.show(signing.sign_in(parent))

    def sign_in(self) -> signing.SignedIn:
        state = signing.sign_in(self._parent)
        self.show(state)
        if self._signed_in is not None:
            self._signed_in()
        return state

    def show(self, state: signing.SignedIn) -> None:
        self.label.setText(state.status_text())
        self.label.setToolTip(state.tooltip())
        self.label.setStyleSheet("color: #b91c1c;" if state.error or not state.may_record
                                 else "")
