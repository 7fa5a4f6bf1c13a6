"""Qt tests run headless: the platform must be chosen before any Qt import."""

from __future__ import annotations

import os

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")


@pytest.fixture(autouse=True, scope="session")
def interpreter_shared_as_in_the_app():
    """The app sets the interpreter's switch interval once at start-up (``run_app``); these
    tests build its windows and docks without it, so they set it the same way."""
    from pdcp_studio.app.application import share_the_interpreter

    share_the_interpreter()


@pytest.fixture(autouse=True)
def fitting_environment(tmp_path, monkeypatch):
    """Every app test records into its own fitting history, as a named operator, with its
    own settings: nothing is asked, nothing reaches the user's files."""
    from PySide6.QtCore import QSettings

    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "history.sqlite3"))
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "Test Prosthetist")
    QSettings.setDefaultFormat(QSettings.Format.IniFormat)
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope,
                      str(tmp_path / "settings"))
    return tmp_path


@pytest.fixture(autouse=True)
def no_shown_system_left():
    """A wizard left open at a test's end must not name the next test's parts by its
    window's system (``app/wizards/words.shown_system``, a module's hook); nor may one
    whose window set it late, after its test's end (before and after every test)."""
    from pdcp_studio.app.wizards import words

    words.shown_system = None
    yield
    words.shown_system = None


@pytest.fixture
def make_window(qtbot):
    """``make_window(path=None, size=None)``: a quiet, shown MainWindow (``path`` opened);
    each is marked saved (no close prompt) and closed at teardown."""
    from pdcp_studio.app.window.main_window import MainWindow

    made = []

    def make(path=None, size=None):
        w = MainWindow()
        w.quiet = True
        if size is not None:
            w.resize(*size)
        w.show()
        if path is not None:
            assert w.open_path(path)
        made.append(w)
        return w

    yield make
    for w in made:
        w.doc.mark_saved()
        w.close()
        w.deleteLater()
