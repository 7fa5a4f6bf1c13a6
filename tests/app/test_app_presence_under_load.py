"""The app's parts under load (issue 28 item 6): a busy machine is no part leaving, and a part
that does leave is listed in Bus events with why ("No beacon for 1.9 s: 3 beacon intervals of
500 ms"), in words, the engineer's line one hover away."""

from __future__ import annotations

import re
import time

import pytest

from pdcp_studio.model.refs import DeviceKey
from tests.bus.test_presence_by_bus import BURN_S, burners

pytestmark = pytest.mark.gui

HAND = DeviceKey(2641, 769, 301)


@pytest.fixture
def live(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=30000):
        window.connect_bus("sim:transradial")
    yield window, window._leaf_docks["events"].widget()
    window.live.disconnect_bus()


def _left(panel) -> list[tuple[str, str, str]]:
    return [r for r in panel.rows() if "left the bus" in r[0]]


def test_a_part_that_leaves_says_why_in_bus_events(live, qtbot):
    window, panel = live
    session = window.live.bridge.session
    session.host.call(lambda: time.sleep(2.0), timeout=30.0)  # the devices' side starved
    qtbot.wait(500)
    assert _left(panel) == []
    window.live.bridge.unplug(HAND)
    qtbot.waitUntil(lambda: bool(_left(panel)), timeout=20000)
    ((_what, why, _similar),) = _left(panel)
    assert re.fullmatch(r"No beacon for \d+\.\d s: \d+ beacon intervals of \d+ ms", why), why
    row = next(i for i in range(panel.view.rowCount())
               if "left the bus" in panel.view.item(i, 1).text())
    assert "no beacon for" in panel.view.item(row, 1).toolTip()  # the arbitrator's line


@pytest.mark.slow
def test_cpu_burners_beside_the_app_make_no_part_leave(live, qtbot):
    window, panel = live
    with burners():
        deadline = time.monotonic() + BURN_S
        while time.monotonic() < deadline:
            qtbot.wait(200)  # the GUI thread busy too: events, repaints
    qtbot.wait(1000)
    assert _left(panel) == [], _left(panel)
    assert all(d.present for d in window.doc.system.devices.values())
