"""A scan says when it finishes (issue 11 item 5: feedback for Scan)."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.gui


def test_scan_finished_is_said_in_the_status_bar(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    window.act_scan.trigger()
    assert window.statusBar().currentMessage() == "Scanning the bus…"
    qtbot.waitUntil(lambda: window.statusBar().currentMessage().startswith("Scan finished"),
                    timeout=20000)
    assert window.statusBar().currentMessage() == "Scan finished: 4 device(s), 5 link(s)"
    window.live.disconnect_bus()
