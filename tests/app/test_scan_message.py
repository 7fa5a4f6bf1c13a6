"""A scan says when it finishes (issue 11 item 5: feedback for Scan)."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.gui


def test_scan_finished_is_said_in_the_status_bar(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    said: list[str] = []
    window.statusBar().messageChanged.connect(said.append)  # later messages may follow
    window.act_scan.trigger()
    assert said and said[0] == "Scanning the bus…"
    qtbot.waitUntil(lambda: any(m.startswith("Scan finished") for m in said), timeout=30000)
    assert "Scan finished: 4 devices, 5 links" in said
    window.live.disconnect_bus()
