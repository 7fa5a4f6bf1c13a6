"""Who is signed in to the fitting history: once per session of the app.

On the clinic's PostgreSQL archive the operator recorded with a change is the role the
workstation signed in as (its full name where the clinic gave one), so the app signs in once,
when it starts: libpq's own sources first (the URL, ``$PGPASSWORD``, ``~/.pgpass``), else a
password dialog. A typed password lives in this process's memory only
(``storage.archive.postgres.remember_password``): PDCP Studio never writes it down. On the
default SQLite archive nobody signs in; the operator is asked once (``fitting.py``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtWidgets import QInputDialog, QLineEdit, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.model.safe_text import shown

#: ``ask(parent, location, why) -> password or None`` (tests answer for the dialog).
AskPassword = Callable[[QWidget | None, str, str], "str | None"]

#: Wrong passwords before the app stops asking.
TRIES = 3


def _t(text: str) -> str:
    return translate("SignIn", text)


@dataclass(frozen=True)
class SignedIn:
    """The archive in use and who records changes into it. ``role`` is None on SQLite;
    ``error`` says why the archive could not be opened (then nothing is signed in)."""

    engine: str
    location: str
    operator: str = ""
    role: str | None = None
    may_record: bool = True
    error: str = ""

    def status_text(self) -> str:
        """The status bar's words (the operator's name as the server gives it: shown,
        never run)."""
        return shown(self._status_text())

    def _status_text(self) -> str:
        if self.error:
            return _t("Fitting history: not signed in")
        if self.role is None:
            return _t("Fitting history: this computer")
        who = self.role if self.operator == self.role else f"{self.operator} ({self.role})"
        if not self.may_record:
            return _t("Fitting history: signed in as {0}, read only").format(who)
        return _t("Fitting history: signed in as {0}").format(who)

    def tooltip(self) -> str:
        text = self.location
        if self.error:
            text += "\n" + self.error
        return shown(text, newlines=True)


_current: SignedIn | None = None


def current() -> SignedIn | None:
    """This session's sign-in, once :func:`sign_in` ran."""
    return _current


def signed_in_operator() -> str:
    """The operator the clinic's archive records ("" when it is not a signed-in one)."""
    return _current.operator if _current is not None and _current.role else ""


def forget() -> None:
    """A new session (tests)."""
    global _current
    _current = None


def _ask_password(parent: QWidget | None, location: str, why: str) -> str | None:
    text, ok = QInputDialog.getText(
        parent, _t("Sign in to the fitting history"),
        _t("The clinic's fitting history at {0} asks for your password.\n{1}\n"
           "Password (kept only while PDCP Studio runs):").format(location, why),
        QLineEdit.EchoMode.Password, "")
    return text if ok else None


def sign_in(parent: QWidget | None = None, *, ask: AskPassword | None = None,
            url: str | None = None) -> SignedIn:
    """Open the archive in use once, asking for a password when the server wants one;
    the result is this session's :func:`current`."""
    global _current
    from pdcp_studio.storage.archive import HistoryError, archive_url, describe, open_archive
    from pdcp_studio.storage.archive.open import is_postgres

    chosen = archive_url(url)
    engine = "postgresql" if is_postgres(chosen) else "sqlite"
    try:
        location = describe(chosen)
    except HistoryError as err:
        _current = SignedIn(engine, chosen, error=str(err))
        return _current
    if engine == "sqlite":  # nobody signs in; the file is made by the first change
        _current = SignedIn(engine, location)
        return _current
    from pdcp_studio.storage.archive.postgres import ServerUnreachable, remember_password

    asker = ask or _ask_password
    for _attempt in range(TRIES + 1):
        try:
            with open_archive(chosen) as archive:
                try:
                    archive.check_can_record()
                    may = True
                except HistoryError:
                    may = False
                _current = SignedIn(engine, location, archive.operator(),
                                    archive.signed_in(), may)
                return _current
        except ServerUnreachable as err:
            if not err.needs_password or _attempt == TRIES:
                _current = SignedIn(engine, location, error=str(err))
                return _current
            password = asker(parent, location, err.why)
            if password is None:
                _current = SignedIn(engine, location, error=str(err))
                return _current
            remember_password(location, password)
        except HistoryError as err:
            _current = SignedIn(engine, location, error=str(err))
            return _current
    _current = SignedIn(engine, location, error="")
    return _current
