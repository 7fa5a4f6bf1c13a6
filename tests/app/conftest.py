"""Qt tests run headless: the platform must be chosen before any Qt import."""

from __future__ import annotations

import os

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")


@pytest.fixture
def make_window(qtbot):
    """``make_window(path=None, size=None)``: a quiet, shown MainWindow (``path`` opened);
    each is marked saved (no close prompt) and closed at teardown."""
    from pdcp_studio.app.main_window import MainWindow

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
