"""The GUI thread enters Python only for work of its own (issue 11: never blocked > 50 ms
while scans run). While the bus threads run Python, every entry waits for the interpreter
lock; an application-wide event filter written in Python made every event of every object
such an entry (three quarters of them during a scan)."""

from __future__ import annotations

import sys

import pytest
from PySide6.QtCore import QCoreApplication, QEvent, QObject

pytestmark = pytest.mark.gui


def test_events_of_plain_objects_do_not_enter_python(make_window, qtbot):
    make_window()  # installs the window's application-wide hooks
    target = QObject()
    entered: list[str] = []
    here = sys._getframe()

    def profile(frame, event, _arg):
        if event == "call" and frame.f_back is here:
            entered.append(frame.f_code.co_name)

    for _ in range(200):
        QCoreApplication.postEvent(target, QEvent(QEvent.Type.User))
    sys.setprofile(profile)
    try:
        QCoreApplication.sendPostedEvents(target, 0)
    finally:
        sys.setprofile(None)
    assert entered == []
