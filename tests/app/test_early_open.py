"""The bus asked for on the command line opens while the window is made (issue 11, start-up).

``application.open_early`` starts opening the session on a thread of its own; the window's
connection takes that session instead of opening a second one, and a bus that cannot be
opened fails the connection exactly as a Connect does.
"""

from __future__ import annotations

import pytest

from pdcp_studio.app.application import open_early

pytestmark = pytest.mark.gui


def test_the_window_takes_the_session_opened_early(make_window, qtbot):
    opening = open_early("sim:transradial")
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial", opening)
    assert window.live.is_live
    assert window.live.bridge.session is opening.result(timeout=0)
    assert len(window.doc.system.devices) == 4
    window.live.disconnect_bus()
    qtbot.waitUntil(lambda: opening.result(timeout=0).closed, timeout=5000)


def test_a_bus_that_does_not_open_early_fails_as_a_connect_does(make_window, qtbot):
    failures = []
    for early in (False, True):
        window = make_window()
        window.live.failed.connect(lambda url, message: failures.append((url, message)))
        opening = open_early("sim:no-such-prosthesis") if early else None
        with qtbot.waitSignal(window.live.failed, timeout=20000):
            window.connect_bus("sim:no-such-prosthesis", opening)
        assert not window.live.is_live
    assert len(failures) == 2 and failures[0] == failures[1]
    assert "no-such-prosthesis" in failures[0][1]
